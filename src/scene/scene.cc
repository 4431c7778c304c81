#include "scene/scene.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "core/error.h"
#include "geometry/triangle.h"
#include "scene/material_desc.h"
#include "traverse.h"

namespace torte {

void Scene::finalize(ProgressCounter* progress) {
  uint32_t object_base = uint32_t(meshes.size() + quadrics.size() + grids.size());
  for (const auto& proto : prototypes)
    object_base += uint32_t(proto->meshes.size() + proto->quadrics.size() + proto->grids.size());
  if (objects.size() != object_base) throw Error("internal: scene objects do not match its shapes");
  validate_material_tables(materials);
  if (progress) {
    uint64_t triangles = 0;
    for (const TriangleMesh& m : meshes) triangles += m.triangle_count();
    for (const auto& proto : prototypes)
      for (const TriangleMesh& m : proto->meshes) triangles += m.triangle_count();
    progress->total = GeometrySet::kProgressPerTriangle * triangles;
  }
  root_.build(meshes, quadrics, grids, 0, progress);
  object_base = uint32_t(meshes.size() + quadrics.size() + grids.size());
  for (const auto& proto : prototypes) {
    proto->geometry.build(proto->meshes, proto->quadrics, proto->grids, object_base, progress);
    object_base += uint32_t(proto->meshes.size() + proto->quadrics.size() + proto->grids.size());
  }
  // The instance level: a BVH2 over the instances' world bounds (the bottom levels are the prototypes').
  std::vector<Bounds3f> instance_bounds(instances.size());
  for (size_t i = 0; i < instances.size(); ++i) {
    if (instances[i].prototype >= prototypes.size()) throw Error("internal: instance of a missing prototype");
    instance_bounds[i] = instances[i].to_world.apply(prototypes[instances[i].prototype]->geometry.bounds());
    if (!instance_bounds[i].empty() && (!in_coordinate_range(instance_bounds[i].lo) || !in_coordinate_range(instance_bounds[i].hi)))
      throw Error("instance " + std::to_string(i) + " (after unrolling the nesting of groups) places its group beyond "
                  "+-1e18, the range the scene supports");
  }
  instance_bvh_.build(instance_bounds);
  bounds_ = merge(root_.bounds(), instance_bvh_.bounds());

  const Bounds3f b = bounds_;
  center_ = b.empty() ? Vec3f{} : b.center();
  radius_ = b.empty() ? 1.0f : std::max(1e-3f, 0.5f * length(b.diagonal()));

  // Area lights: total area and, on meshes, a distribution over triangles by area.
  for (Light& light : lights) {
    if (light.kind != LightKind::Area) continue;
    if (light.object < meshes.size()) {
      const TriangleMesh& mesh = meshes[light.object];
      std::vector<float> areas(mesh.triangle_count());
      double total = 0;
      for (size_t t = 0; t < areas.size(); ++t) total += areas[t] = mesh.triangle_area(t);
      if (!(total > 0)) throw Error(light_name(light) + ": the emitting mesh has zero area");
      light.triangles = Distribution1D(areas);
      light.area = float(total);
    } else {
      light.area = area(quadrics[light.object - meshes.size()]);
      prepare_sphere_light(quadrics[light.object - meshes.size()], &light);
    }
  }
  std::vector<float> power(lights.size());
  for (size_t i = 0; i < lights.size(); ++i) {
    power[i] = light_power(*this, lights[i]);
    if (!(power[i] >= 0) || !std::isfinite(power[i]))
      throw Error(light_name(lights[i]) + ": its emitted power is " + (std::isnan(power[i]) ? "not a number" : "infinite") +
                  " in float; lower its intensity (or the emitter's size)");
  }
  light_selection = lights.empty() ? Distribution1D() : Distribution1D(power);
  release_positions();
}

// The geometry sets' leaves hold every triangle's vertices, and shading reads them there: a mesh keeps its own
// positions only when an area light samples it. This is what brings a mesh to 64 bytes per triangle in all.
void Scene::release_positions() {
  auto release = [](TriangleMesh& m) {
    m.x = {};
    m.y = {};
    m.z = {};
  };
  for (size_t i = 0; i < meshes.size(); ++i)
    if (objects[i].area_light < 0) release(meshes[i]);
  for (const auto& proto : prototypes)  // area lights are never instanced
    for (TriangleMesh& m : proto->meshes) release(m);
}

bool Scene::intersect(Ray& ray, Hit* hit) const {
  Hit h;
  root_.intersect_one(ray, &h);
  if (!instances.empty()) {
    const float t[7] = {ray.o.x, ray.o.y, ray.o.z, ray.d.x, ray.d.y, ray.d.z, ray.t_max};
    intersect_instances({&t[0], &t[1], &t[2], &t[3], &t[4], &t[5], &t[6]}, 1, &h);
  }
  if (h.prim == kNoHit) return false;
  *hit = h;
  ray.t_max = h.t;
  return true;
}

bool Scene::occluded(const Ray& ray) const {
  const float t[7] = {ray.o.x, ray.o.y, ray.o.z, ray.d.x, ray.d.y, ray.d.z, ray.t_max};
  uint8_t blocked = 0;
  occluded({&t[0], &t[1], &t[2], &t[3], &t[4], &t[5], &t[6]}, 1, &blocked, false);
  return blocked != 0;
}

void Scene::intersect(const RaySoA& rays, size_t count, Hit* hits, bool coherent) const {
  root_.intersect(rays, count, hits, coherent);
  if (!instances.empty()) intersect_instances(rays, count, hits);
}

namespace {
// The ray in an instance's space: the direction is mapped but not renormalized, so t means the same distance
// along the ray in both spaces and hits compare directly.
Ray to_instance(const Instance& inst, const Ray& world) {
  const Transform& m = inst.to_world;
  return m.apply_inverse(world);
}
}  // namespace

void Scene::intersect_instances(const RaySoA& rays, size_t count, Hit* hits) const {
  for (size_t i = 0; i < count; ++i) {
    Ray r = ray_at(rays, i, std::min(rays.t_max[i], hits[i].t));
    if (!(r.t_max > 0)) continue;
    instance_bvh_.intersect(r, [&](uint32_t k, Ray& ray) {
      const Instance& inst = instances[k];
      Hit h = hits[i];
      h.instance = k;
      if (!prototypes[inst.prototype]->geometry.intersect_one(to_instance(inst, ray), &h)) return false;
      hits[i] = h;
      ray.t_max = h.t;
      return true;
    });
  }
}

void Scene::occluded(const RaySoA& rays, size_t count, uint8_t* blocked, bool coherent) const {
  root_.occluded(rays, count, blocked, coherent);
  if (instances.empty()) return;
  for (size_t i = 0; i < count; ++i) {
    if (blocked[i]) continue;
    const Ray r = ray_at(rays, i);
    blocked[i] = instance_bvh_.occluded(r, [&](uint32_t k, const Ray& ray) {
      const Instance& inst = instances[k];
      return prototypes[inst.prototype]->geometry.occluded_one(to_instance(inst, ray));
    });
  }
}

size_t Scene::accel_bytes() const {
  size_t bytes = root_.accel_bytes() + instance_bvh_.nodes().size() * sizeof(Bvh2Node) +
                 instance_bvh_.prim_indices().size() * sizeof(uint32_t);
  for (const auto& proto : prototypes) bytes += proto->geometry.accel_bytes();
  return bytes;
}

namespace {
size_t mesh_bytes(const TriangleMesh& m) {
  return (m.x.size() + m.y.size() + m.z.size() + m.nx.size() + m.ny.size() + m.nz.size() + m.u.size() + m.v.size()) *
             sizeof(float) +
         m.indices.size() * sizeof(uint32_t);
}
}  // namespace

size_t Scene::geometry_bytes() const {
  size_t bytes = quadrics.size() * sizeof(Quadric) + instances.size() * sizeof(Instance);
  for (const TriangleMesh& m : meshes) bytes += mesh_bytes(m);
  for (const auto& proto : prototypes) {
    bytes += proto->quadrics.size() * sizeof(Quadric);
    for (const TriangleMesh& m : proto->meshes) bytes += mesh_bytes(m);
  }
  return bytes;
}

SurfaceHit Scene::surface(const Ray& ray, const Hit& hit) const {
  if (hit.instance == kNoHit) return root_.surface(hit, &ray);
  const Instance& inst = instances[hit.instance];
  const Ray local = to_instance(inst, ray);
  SurfaceHit s = prototypes[inst.prototype]->geometry.surface(hit, &local);
  const Transform& m = inst.to_world;
  s.p = m.apply_point(s.p);
  // Normals map by the inverse transpose, which keeps them on the front side even under mirroring.
  s.ng = normalize(m.apply_normal(s.ng));
  s.ns = normalize(m.apply_normal(s.ns));
  s.dpdu = m.apply_vector(s.dpdu);
  s.dpdv = m.apply_vector(s.dpdv);
  return s;
}

std::string black_image_reason(const Scene& scene) {
  const bool shapes = scene.primitive_count() > 0 || !scene.instances.empty();
  if (!shapes && scene.lights.empty()) return "the scene is empty (no shapes, no lights): the image is black";
  if (scene.lights.empty()) return "the scene has no lights and no emitting shapes: the image is black";
  bool at_infinity = false, power = false;
  for (const Light& l : scene.lights) {
    at_infinity |= is_infinite_light(l);
    power |= light_power(scene, l) > 0;
  }
  if (!power) return "every light of the scene has zero power: the image is black";
  if (!shapes && !at_infinity)
    return "the scene has no shapes and no light at infinity (infinite, environment, sky): the image is black";
  return "";
}

}  // namespace torte
