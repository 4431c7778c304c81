// The flattened, immutable scene the renderer reads: world-space SoA meshes, transformed analytic shapes, a
// BVH over all primitives, material tables and lights. Built once per render{} by SceneBuilder::flatten.
#pragma once
#include <cstdint>
#include <vector>

#include "accel/bvh2.h"
#include "accel/bvh_build.h"
#include "accel/hit.h"
#include "accel/wide_bvh.h"
#include "camera/camera.h"
#include "core/sampling.h"
#include "geometry/mesh.h"
#include "geometry/quadric.h"
#include "light/light.h"
#include "material/material.h"

namespace torte {

// Hit (accel/hit.h): prim is a global primitive id, [0, triangle_count) triangles, then quadrics.

// Everything shading needs about a hit point.
struct SurfaceHit {
  Vec3f p;
  Vec3f ng;  // unit geometric normal, front side as defined by the shape (winding / outward)
  Vec3f ns;  // unit shading normal (interpolated vertex normals), on the same side as ng
  Vec2f uv;
  uint32_t object;
};

// One placed shape (a mesh or a quadric) with its material and, if it emits, its area light.
struct SceneObject {
  MaterialRef material;
  int32_t area_light = -1;  // index into Scene::lights, -1 if the object does not emit
};

class Scene {
 public:
  // Meshes in world space; object i is meshes[i] for i < meshes.size(), then quadrics.
  std::vector<TriangleMesh> meshes;
  std::vector<Quadric> quadrics;
  std::vector<SceneObject> objects;
  MaterialTables materials;
  std::vector<Light> lights;
  Distribution1D light_selection;  // light selection proportional to power
  CameraDesc camera;
  bool has_camera = false;

  // Builds triangle tables, the BVH and the light distribution; call after filling the arrays above.
  void finalize();

  uint32_t triangle_count() const { return uint32_t(tri_mesh_.size()); }
  uint32_t primitive_count() const { return triangle_count() + uint32_t(quadrics.size()); }
  uint32_t object_of(uint32_t prim) const {
    return prim < triangle_count() ? tri_mesh_[prim] : uint32_t(meshes.size()) + (prim - triangle_count());
  }
  Bounds3f bounds() const { return bounds_; }
  // Bounding sphere of the scene (for infinite lights).
  Vec3f center() const { return center_; }
  float radius() const { return radius_; }

  // One ray (tests, light tools). The renderer traces whole batches with the functions below.
  bool intersect(Ray& ray, Hit* hit) const;
  bool occluded(const Ray& ray) const;
  // Batches: `coherent` rays (neighbours in groups of 8, such as a tile's camera rays) go through the packet
  // kernels, others one ray at a time through the SIMD single-ray kernels.
  void intersect(const RaySoA& rays, size_t count, Hit* hits, bool coherent) const;
  void occluded(const RaySoA& rays, size_t count, uint8_t* occluded, bool coherent) const;
  SurfaceHit surface(const Ray& ray, const Hit& hit) const;
  // Bytes of acceleration data (wide BVH nodes, leaf triangles, index map, quadric BVH).
  size_t accel_bytes() const;

 private:
  // Adds quadric hits to hits already holding the closest triangle hit (or a miss).
  void intersect_quadrics(const RaySoA& rays, size_t count, Hit* hits) const;
  std::vector<uint32_t> tri_mesh_;   // global triangle -> mesh
  std::vector<uint32_t> mesh_first_;  // mesh -> first global triangle
  // All triangles of all meshes in one wide BVH (SIMD kernels, simd/traverse.h); the few analytic shapes in a
  // scalar BVH2 of their own, traced after it with t_max clipped to the triangle hit.
  WideBvh<kDefaultBvhWidth> tri_bvh_;
  TriangleLeaves tri_leaves_;
  Bvh2 quadric_bvh_;
  Bounds3f bounds_;
  Vec3f center_;
  float radius_ = 0;
};

}  // namespace torte
