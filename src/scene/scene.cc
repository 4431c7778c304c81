#include "scene/scene.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "core/error.h"
#include "geometry/triangle.h"
#include "traverse.h"

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
  // Triangles: world-space vertices per global triangle, bounds, the wide BVH and its leaf-order vertex copy.
  std::vector<Vec3f> vertices(size_t(triangle_count()) * 3);
  std::vector<Bounds3f> tri_bounds(triangle_count());
  // Parallel over meshes and, nested, over each mesh's triangles: one big mesh would otherwise run serially.
  tbb::parallel_for(uint32_t(0), uint32_t(meshes.size()), [&](uint32_t m) {
    const TriangleMesh& mesh = meshes[m];
    tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.triangle_count(), 8192),
                      [&](const tbb::blocked_range<size_t>& r) {
                        for (size_t t = r.begin(); t < r.end(); ++t) {
                          const size_t g = mesh_first_[m] + t;
                          for (int k = 0; k < 3; ++k) vertices[3 * g + k] = mesh.position(mesh.indices[3 * t + k]);
                          tri_bounds[g] = mesh.triangle_bounds(t);
                        }
                      });
  });
  tri_bvh_ = build_wide_bvh<kDefaultBvhWidth>(tri_bounds);
  tri_leaves_ = make_triangle_leaves(tri_bvh_.prim_indices, vertices);
  std::vector<Bounds3f> quadric_bounds(quadrics.size());
  for (size_t q = 0; q < quadrics.size(); ++q) quadric_bounds[q] = world_bounds(quadrics[q]);
  quadric_bvh_.build(quadric_bounds);
  bounds_ = merge(tri_bvh_.bounds, quadric_bvh_.bounds());

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

namespace {

// A one-ray RaySoA view of a Ray.
struct SingleRay {
  float v[7];
  explicit SingleRay(const Ray& r) : v{r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z, r.t_max} {}
  RaySoA soa() const { return {&v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6]}; }
};

}  // namespace

bool Scene::intersect(Ray& ray, Hit* hit) const {
  const SingleRay one(ray);
  Hit h;
  intersect(one.soa(), 1, &h, false);
  if (h.prim == kNoHit) return false;
  *hit = h;
  ray.t_max = h.t;
  return true;
}

bool Scene::occluded(const Ray& ray) const {
  const SingleRay one(ray);
  uint8_t blocked = 0;
  occluded(one.soa(), 1, &blocked, false);
  return blocked != 0;
}

void Scene::intersect(const RaySoA& rays, size_t count, Hit* hits, bool coherent) const {
  if (triangle_count() > 0) {
    if (coherent) {
      intersect_closest_packets(tri_bvh_, tri_leaves_, rays, count, hits, 8);
    } else {
      intersect_closest(tri_bvh_, tri_leaves_, rays, count, hits);
    }
    // The kernels report leaf order; the rest of the renderer numbers triangles globally.
    for (size_t i = 0; i < count; ++i)
      if (hits[i].prim != kNoHit) hits[i].prim = tri_bvh_.prim_indices[hits[i].prim];
  } else {
    std::fill(hits, hits + count, Hit{});
  }
  if (!quadrics.empty()) intersect_quadrics(rays, count, hits);
}

void Scene::intersect_quadrics(const RaySoA& rays, size_t count, Hit* hits) const {
  const uint32_t ntri = triangle_count();
  for (size_t i = 0; i < count; ++i) {
    Ray r{{rays.ox[i], rays.oy[i], rays.oz[i]}, {rays.dx[i], rays.dy[i], rays.dz[i]}, std::min(rays.t_max[i], hits[i].t)};
    if (!(r.t_max > 0)) continue;
    quadric_bvh_.intersect(r, [&](uint32_t q, Ray& ray) {
      float t;
      Vec2f uv;
      if (!torte::intersect(quadrics[q], ray, &t, &uv)) return false;
      ray.t_max = t;
      hits[i] = {t, ntri + q, uv.x, uv.y};
      return true;
    });
  }
}

void Scene::occluded(const RaySoA& rays, size_t count, uint8_t* blocked, bool coherent) const {
  if (triangle_count() > 0) {
    if (coherent) {
      intersect_any_packets(tri_bvh_, tri_leaves_, rays, count, blocked, 8);
    } else {
      intersect_any(tri_bvh_, tri_leaves_, rays, count, blocked);
    }
  } else {
    std::fill(blocked, blocked + count, uint8_t(0));
  }
  if (quadrics.empty()) return;
  for (size_t i = 0; i < count; ++i) {
    if (blocked[i]) continue;
    const Ray r{{rays.ox[i], rays.oy[i], rays.oz[i]}, {rays.dx[i], rays.dy[i], rays.dz[i]}, rays.t_max[i]};
    blocked[i] = quadric_bvh_.occluded(r, [&](uint32_t q, const Ray& ray) {
      float t;
      Vec2f uv;
      return torte::intersect(quadrics[q], ray, &t, &uv);
    });
  }
}

size_t Scene::accel_bytes() const {
  return tri_bvh_.memory_bytes() + tri_leaves_.memory_bytes() + quadric_bvh_.nodes().size() * sizeof(Bvh2Node) +
         quadric_bvh_.prim_indices().size() * sizeof(uint32_t);
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
