#include "scene/scene.h"

#include <cmath>

#include "core/error.h"
#include "geometry/triangle.h"

namespace torte {

void Scene::finalize() {
  if (objects.size() != meshes.size() + quadrics.size())
    throw Error("internal: scene objects do not match its shapes");
  tri_mesh_.clear();
  mesh_first_.clear();
  for (uint32_t m = 0; m < meshes.size(); ++m) {
    mesh_first_.push_back(uint32_t(tri_mesh_.size()));
    tri_mesh_.insert(tri_mesh_.end(), meshes[m].triangle_count(), m);
  }
  // World-space vertices of every triangle in one array: the trace loop reads 36 contiguous bytes per test
  // instead of chasing mesh -> index -> position (the wide BVH will keep its own SoA leaf copy instead).
  tri_vertices_.resize(size_t(triangle_count()) * 3);
  for (uint32_t m = 0; m < meshes.size(); ++m)
    for (size_t t = 0; t < meshes[m].triangle_count(); ++t)
      for (int k = 0; k < 3; ++k)
        tri_vertices_[3 * (mesh_first_[m] + t) + k] = meshes[m].position(meshes[m].indices[3 * t + k]);
  std::vector<Bounds3f> bounds(primitive_count());
  for (uint32_t m = 0; m < meshes.size(); ++m)
    for (size_t t = 0; t < meshes[m].triangle_count(); ++t) bounds[mesh_first_[m] + t] = meshes[m].triangle_bounds(t);
  for (size_t q = 0; q < quadrics.size(); ++q) bounds[triangle_count() + q] = world_bounds(quadrics[q]);
  bvh_.build(bounds);

  const Bounds3f b = bvh_.bounds();
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
      if (!(total > 0)) throw Error("an emitting mesh has zero area");
      light.triangles = Distribution1D(areas);
      light.area = float(total);
    } else {
      light.area = area(quadrics[light.object - meshes.size()]);
    }
  }
  std::vector<float> power(lights.size());
  for (size_t i = 0; i < lights.size(); ++i) power[i] = light_power(*this, lights[i]);
  light_selection = lights.empty() ? Distribution1D() : Distribution1D(power);
}

void Scene::triangle_vertices(uint32_t prim, Vec3f* p0, Vec3f* p1, Vec3f* p2) const {
  const Vec3f* v = &tri_vertices_[3 * size_t(prim)];
  *p0 = v[0];
  *p1 = v[1];
  *p2 = v[2];
}

bool Scene::intersect(Ray& ray, Hit* hit) const {
  const uint32_t ntri = triangle_count();
  const WatertightRay wr(ray);
  return bvh_.intersect(ray, [&](uint32_t prim, Ray& r) {
    if (prim < ntri) {
      Vec3f p0, p1, p2;
      triangle_vertices(prim, &p0, &p1, &p2);
      TriangleHit th;
      if (!intersect_triangle(wr, r.t_max, p0, p1, p2, &th)) return false;
      r.t_max = th.t;
      *hit = {th.t, prim, th.b1, th.b2};
      return true;
    }
    float t;
    Vec2f uv;
    if (!torte::intersect(quadrics[prim - ntri], r, &t, &uv)) return false;
    r.t_max = t;
    *hit = {t, prim, uv.x, uv.y};
    return true;
  });
}

bool Scene::occluded(const Ray& ray) const {
  const uint32_t ntri = triangle_count();
  const WatertightRay wr(ray);
  return bvh_.occluded(ray, [&](uint32_t prim, const Ray& r) {
    if (prim < ntri) {
      Vec3f p0, p1, p2;
      triangle_vertices(prim, &p0, &p1, &p2);
      return intersect_triangle(wr, r.t_max, p0, p1, p2, nullptr);
    }
    float t;
    Vec2f uv;
    return torte::intersect(quadrics[prim - ntri], r, &t, &uv);
  });
}

SurfaceHit Scene::surface(const Ray& ray, const Hit& hit) const {
  SurfaceHit s;
  s.object = object_of(hit.prim);
  if (hit.prim < triangle_count()) {
    const TriangleMesh& mesh = meshes[tri_mesh_[hit.prim]];
    const uint32_t* idx = &mesh.indices[3 * size_t(hit.prim - mesh_first_[tri_mesh_[hit.prim]])];
    const Vec3f p0 = mesh.position(idx[0]), p1 = mesh.position(idx[1]), p2 = mesh.position(idx[2]);
    const float b0 = 1 - hit.b1 - hit.b2;
    // Interpolating the vertices is more accurate than o + t d far from the origin.
    s.p = p0 * b0 + p1 * hit.b1 + p2 * hit.b2;
    s.ng = normalize(cross(p1 - p0, p2 - p0));
    s.ns = s.ng;
    if (mesh.has_normals()) {
      const Vec3f n = mesh.normal(idx[0]) * b0 + mesh.normal(idx[1]) * hit.b1 + mesh.normal(idx[2]) * hit.b2;
      if (length_squared(n) > 0) {
        s.ns = normalize(n);
        // Vertex normals state which side is the front: the geometric normal follows them (as in pbrt).
        s.ng = face_forward(s.ng, s.ns);
      }
    }
    if (mesh.has_uvs()) {
      s.uv = Vec2f(mesh.u[idx[0]] * b0 + mesh.u[idx[1]] * hit.b1 + mesh.u[idx[2]] * hit.b2,
                   mesh.v[idx[0]] * b0 + mesh.v[idx[1]] * hit.b1 + mesh.v[idx[2]] * hit.b2);
    } else {
      s.uv = Vec2f(hit.b1 + hit.b2, hit.b2);  // (0,0), (1,0), (1,1) at the vertices
    }
    return s;
  }
  const SurfacePoint sp = surface_at(quadrics[hit.prim - triangle_count()], Vec2f(hit.b1, hit.b2));
  s.p = sp.p;
  s.ng = s.ns = sp.n;
  s.uv = sp.uv;
  (void)ray;
  return s;
}

}  // namespace torte
