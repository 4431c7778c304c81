#include "scene/scene.h"

#include <algorithm>

#include <cmath>
#include <cstring>
#include <vector>
#include <unordered_set>

#include "core/error.h"
#include "core/huge_pages.h"
#include "core/rng.h"
#include "geometry/triangle.h"
#include "scene/material_desc.h"

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
  accel_.build(meshes, quadrics, grids, prototypes, instances, progress, accel_options);
  huge_pages::release_cached();  // the build's freed scratch, kept for its own reuse (core/huge_pages.h)
  bounds_ = accel_.bounds();

  const Bounds3f b = bounds_;
  center_ = b.empty() ? Vec3f{} : b.center();
  radius_ = b.empty() ? 1.0f : std::max(1e-3f, 0.5f * length(b.diagonal()));

  // Area lights: total area and, on meshes, a distribution over triangles by area.
  for (Light& light : lights) {
    if (light.kind != LightKind::Area) continue;
    if (light.object < meshes.size()) {
      if (!prepare_mesh_light(meshes[light.object], &light))
        throw Error(light_name(light) + ": the emitting mesh has zero area");
    } else {
      light.area = area(quadrics[light.object - meshes.size()]);
      prepare_sphere_light(quadrics[light.object - meshes.size()], &light);
    }
  }
  // Escaped rays look at these only: a loop over every light per escaped ray cost 10,000 tests on
  // scenes/many-lights.lua (three quarters of its render time).
  infinite_lights.clear();
  for (size_t i = 0; i < lights.size(); ++i)
    if (is_infinite_light(lights[i])) infinite_lights.push_back(uint32_t(i));
  std::vector<float> power(lights.size());
  for (size_t i = 0; i < lights.size(); ++i) {
    power[i] = light_power(*this, lights[i]);
    if (!(power[i] >= 0) || !std::isfinite(power[i]))
      throw Error(light_name(lights[i]) + ": its emitted power is " + (std::isnan(power[i]) ? "not a number" : "infinite") +
                  " in float; lower its intensity (or the emitter's size)");
  }
  light_selection = lights.empty() ? Distribution1D() : Distribution1D(power);
  light_bvh = LightBvh(*this, lights, power);  // before release_positions: it reads emitting triangles
  light_bvh.weigh_visibility(*this, lights, [this](const Ray& r) { return occluded(r); });
  release_positions();
}

// The geometry sets' leaves hold every triangle's vertices, and shading reads them there: a mesh keeps its own
// positions only when an area light samples it. This is what brings a mesh to 64 bytes per triangle in all.
void Scene::release_positions() {
  auto release = [](TriangleMesh& m) {
    free_storage(m.x);
    free_storage(m.y);
    free_storage(m.z);
  };
  for (size_t i = 0; i < meshes.size(); ++i)
    if (objects[i].area_light < 0) release(meshes[i]);
  for (const auto& proto : prototypes)  // area lights are never instanced
    for (TriangleMesh& m : proto->meshes) release(m);
}

bool Scene::intersect(Ray& ray, Hit* hit) const {
  Hit h;
  const SingleRay one(ray);
  accel_.intersect(one.soa(), 1, &h, TraceKernel::kSingle);
  if (!alpha_masks.empty()) pass_cut_outs(one.soa(), 1, &h);
  if (h.prim == kNoHit) return false;
  *hit = h;
  ray.t_max = h.t;
  return true;
}

bool Scene::intersect(Ray& ray, Hit* hit, TraversalCost* cost) const {
  if (!cost) return intersect(ray, hit);
  Hit h;
  accel_.intersect_counted(ray, &h, cost);
  if (!alpha_masks.empty()) {
    const SingleRay one(ray);
    pass_cut_outs(one.soa(), 1, &h);
  }
  if (h.prim == kNoHit) return false;
  *hit = h;
  ray.t_max = h.t;
  return true;
}

bool Scene::occluded(const Ray& ray) const {
  uint8_t blocked = 0;
  const SingleRay one(ray);
  accel_.occluded(one.soa(), 1, &blocked, TraceKernel::kSingle);
  if (!alpha_masks.empty()) occluded_past_cut_outs(one.soa(), 1, &blocked);
  return blocked != 0;
}

void Scene::intersect(const RaySoA& rays, size_t count, Hit* hits, bool coherent) const {
  accel_.intersect(rays, count, hits, coherent ? TraceKernel::kPacket8 : TraceKernel::kSingle);
  if (!alpha_masks.empty()) pass_cut_outs(rays, count, hits);
}

void Scene::occluded(const RaySoA& rays, size_t count, uint8_t* blocked, bool coherent) const {
  accel_.occluded(rays, count, blocked, coherent ? TraceKernel::kPacket8 : TraceKernel::kSingle);
  if (!alpha_masks.empty()) occluded_past_cut_outs(rays, count, blocked);
}

// ---- alpha masks ----------------------------------------------------------------------------------------------
// The SIMD kernels test triangles without callbacks, so cut-outs are applied to their results: a hit on a cut-out
// point is traced again from just past it, and a blocked shadow ray is checked by closest hits through the
// cut-outs. Scenes without masks never get here.

namespace {

constexpr int kMaxAlphaLayers = 64;  // cut-out layers a ray passes; the next hit counts as opaque

uint32_t float_bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

}  // namespace

bool Scene::cut_out(const Ray& r, const Hit& h) const {
  const SurfaceHit s = surface(r, h);
  const int32_t m = objects[s.object].alpha_mask;
  if (m < 0) return false;
  const AlphaMask& a = alpha_masks[size_t(m)];
  const float alpha = textures.eval(a.alpha, TextureContext{s.p, s.ns, s.uv, s.dpdu, s.dpdv, 0});
  if (!a.stochastic) return alpha < a.cutoff;
  uint64_t key = 0;
  for (float f : {s.p.x, s.p.y, s.p.z, r.d.x, r.d.y, r.d.z}) key = mix_bits(key ^ float_bits(f));
  const float u = float(key >> 40) * 0x1p-24f;
  return u >= alpha;
}

void Scene::pass_cut_outs(const RaySoA& rays, size_t count, Hit* hits) const {
  std::vector<uint32_t> pending;
  for (size_t i = 0; i < count; ++i)
    if (hits[i].prim != kNoHit && cut_out(ray_at(rays, i), hits[i])) pending.push_back(uint32_t(i));
  RayArrays next;
  std::vector<float> start;  // where each continuation starts along its original ray
  std::vector<Hit> found;
  for (int layer = 0; layer < kMaxAlphaLayers && !pending.empty(); ++layer) {
    next.clear();
    start.clear();
    for (uint32_t i : pending) {
      const Ray r = ray_at(rays, i);
      const SurfaceHit s = surface(Ray{r.o, r.d, hits[i].t}, hits[i]);
      const Vec3f o = offset_origin(s.p, s.ng, r.d);  // just past the surface, on the side the ray goes on to
      const float t0 = dot(o - r.o, r.d) / dot(r.d, r.d);
      start.push_back(t0);
      next.push({o, r.d, std::max(0.0f, r.t_max - t0)});
    }
    found.assign(pending.size(), Hit{});
    accel_.intersect(next.soa(), pending.size(), found.data(), TraceKernel::kSingle);
    std::vector<uint32_t> still;
    for (size_t k = 0; k < pending.size(); ++k) {
      Hit& h = hits[pending[k]];
      if (found[k].prim == kNoHit || !(next.t_max[k] > 0)) {
        h = Hit{};
        continue;
      }
      h = found[k];
      h.t += start[k];
      if (cut_out(ray_at(rays, pending[k]), h)) still.push_back(pending[k]);
    }
    pending.swap(still);
  }
}

void Scene::occluded_past_cut_outs(const RaySoA& rays, size_t count, uint8_t* blocked) const {
  RayArrays blocked_rays;
  std::vector<uint32_t> index;
  for (size_t i = 0; i < count; ++i)
    if (blocked[i]) {
      blocked_rays.push(ray_at(rays, i));
      index.push_back(uint32_t(i));
    }
  if (index.empty()) return;
  std::vector<Hit> hits(index.size());
  accel_.intersect(blocked_rays.soa(), index.size(), hits.data(), TraceKernel::kSingle);
  pass_cut_outs(blocked_rays.soa(), index.size(), hits.data());
  for (size_t k = 0; k < index.size(); ++k) blocked[index[k]] = hits[k].prim != kNoHit;
}

size_t Scene::accel_bytes() const { return accel_.accel_bytes(); }

namespace {
// A placed mesh's own arrays and, once per scene, the source it shares (which its shape holds anyway).
size_t mesh_bytes(const TriangleMesh& m, std::unordered_set<const TriangleMesh*>& sources) {
  size_t bytes = m.own_bytes();
  if (m.placed() && sources.insert(m.source.get()).second) bytes += m.source->own_bytes();
  return bytes;
}
}  // namespace

size_t Scene::geometry_bytes() const {
  size_t bytes = quadrics.size() * sizeof(Quadric) + instances.size() * sizeof(Instance);
  std::unordered_set<const TriangleMesh*> sources;
  for (const TriangleMesh& m : meshes) bytes += mesh_bytes(m, sources);
  for (const auto& proto : prototypes) {
    bytes += proto->quadrics.size() * sizeof(Quadric);
    for (const TriangleMesh& m : proto->meshes) bytes += mesh_bytes(m, sources);
  }
  return bytes;
}

SurfaceHit Scene::surface(const Ray& ray, const Hit& hit) const { return accel_.surface(ray, hit); }

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
