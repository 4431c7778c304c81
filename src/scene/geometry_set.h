// One level of geometry: triangle meshes, analytic shapes and voxel grids in a common space, with their
// acceleration structures. The scene's own (top-level) shapes form one set; every instanced group is another, shared by all
// its instances (see scene/scene.h). Meshes and quadrics are owned by the caller and must outlive the set.
//
// Memory (the dragon, one mesh with vertex normals): wide nodes 6.8 B/tri, leaf triangles 36.1 (with the leaf-start
// bitmap), mesh indices 12 and normals 6 once the scene releases the mesh positions (the leaves hold them):
// 61.0 B/tri, checked by test_geometry_set.cc. Sets of several meshes add 4 B/tri (each triangle's place in
// the meshes concatenated).
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "accel/bvh2.h"
#include "accel/bvh_build.h"
#include "accel/hit.h"
#include "accel/wide_bvh.h"
#include "core/progress_counter.h"
#include "geometry/mesh.h"
#include "geometry/quadric.h"
#include "voxel/voxel_accel.h"

namespace torte {

// Everything shading needs about a hit point.
struct SurfaceHit {
  Vec3f p;
  Vec3f ng;  // unit geometric normal, front side as defined by the shape (winding / outward)
  Vec3f ns;  // unit shading normal (interpolated vertex normals), on the same side as ng
  Vec2f uv;
  Vec3f dpdu, dpdv;  // surface tangents along the uv parameterization (textures, bump mapping)
  uint32_t object;
  // Material override: an index into Scene::material_overrides (voxel faces and cell shapes), -1 = the object's.
  int32_t material = -1;
};

class GeometrySet {
 public:
  static constexpr uint64_t kProgressPerTriangle = 3;
  // Builds the BVHs. Object i of this set is meshes[i] for i < meshes.size(), then the quadrics, numbered from
  // object_base in the scene's object table. Reorders each mesh's triangles into the BVH's leaf order (their
  // order means nothing else to the renderer), so triangle numbers in hits are leaf positions and a one-mesh set
  // keeps no index map. After the build, the meshes' positions are needed only by whoever else reads them
  // (area lights): surface() takes them from the leaves.
  void build(std::vector<TriangleMesh>& meshes, const std::vector<Quadric>& quadrics, uint32_t object_base);
  // With voxel grids: their objects follow the quadrics'. Voxel hits have prim >= kVoxelPrimBit (see
  // voxel/voxel_accel.h for the encoding).
  // `progress` (optional) gets kProgressPerTriangle units per input triangle as the build goes (the caller sets
  // its total): one as the triangle bounds are computed, one from the binary BVH build, one from the steps after.
  void build(std::vector<TriangleMesh>& meshes, const std::vector<Quadric>& quadrics,
             const std::vector<VoxelGridAccel>& grids, uint32_t object_base, ProgressCounter* progress = nullptr);

  // Triangles in the BVH (all but those with empty bounds, which nothing can hit).
  uint32_t triangle_count() const { return triangle_count_; }
  uint32_t grid_count() const { return grids_ ? uint32_t(grids_->size()) : 0; }
  // Triangles, quadrics and one per voxel grid.
  uint32_t primitive_count() const { return triangle_count() + uint32_t(quadrics_->size()) + grid_count(); }
  // Scene object of a primitive (Hit::prim: triangles first, then quadrics, then voxel hits).
  uint32_t object_of(uint32_t prim) const {
    if (is_voxel_prim(prim))
      return object_base_ + uint32_t(meshes_->size() + quadrics_->size()) + voxel_prim_grid(prim);
    if (prim < triangle_count()) return object_base_ + triangle_ref(prim).mesh;
    return object_base_ + uint32_t(meshes_->size()) + (prim - triangle_count());
  }
  Bounds3f bounds() const { return bounds_; }
  bool empty() const { return primitive_count() == 0; }

  // Closest hits (Hit::instance is left as it was) and occlusion, for `count` rays; `coherent` rays go through
  // the packet kernels.
  void intersect(const RaySoA& rays, size_t count, Hit* hits, bool coherent) const;
  void occluded(const RaySoA& rays, size_t count, uint8_t* occluded, bool coherent) const;
  // One ray: updates *hit when something closer than min(ray.t_max, hit->t) is hit.
  bool intersect_one(const Ray& ray, Hit* hit) const;
  bool occluded_one(const Ray& ray) const;
  // The ray (in this set's space, as traced) is needed for voxel hits only.
  SurfaceHit surface(const Hit& hit, const Ray* ray = nullptr) const;
  size_t accel_bytes() const;

 private:
  void intersect_quadrics(const RaySoA& rays, size_t count, Hit* hits) const;
  void intersect_grids(const RaySoA& rays, size_t count, Hit* hits, bool coherent) const;
  void store_in_leaf_order(std::vector<TriangleMesh>& meshes, const std::vector<uint32_t>& mesh_first,
                           std::span<std::byte> scratch);
  const std::vector<TriangleMesh>* meshes_ = nullptr;
  const std::vector<Quadric>* quadrics_ = nullptr;
  const std::vector<VoxelGridAccel>* grids_ = nullptr;
  uint32_t object_base_ = 0;
  uint32_t triangle_count_ = 0;
  // Sets of several meshes only (null for one mesh): triangle (leaf position) -> its place in the meshes
  // concatenated, mesh_first_[m] + its index in mesh m (4 B/tri; the mesh is found by a binary search over
  // mesh_first_, which costs less per hit than 4 more bytes per triangle cost the scene).
  // Not a std::vector: nothing reads it before the build writes every entry, and zero-filling 28 M entries first
  // costs a second of page faults on a VM.
  std::unique_ptr<uint32_t[]> tri_ref_;
  std::vector<uint32_t> mesh_first_;  // first triangle of each mesh in the concatenation (several meshes only)
  struct TriangleRef {
    uint32_t mesh, local;
  };
  TriangleRef triangle_ref(uint32_t prim) const {
    if (!tri_ref_) return {0, prim};
    const uint32_t g = tri_ref_[prim], m = mesh_holding(mesh_first_, g);
    return {m, g - mesh_first_[m]};
  }
  // All triangles of all meshes in one wide BVH (SIMD kernels, simd/traverse.h); the few analytic shapes in a
  // scalar BVH2 of their own, traced after it with t_max clipped to the triangle hit.
  WideBvh<kDefaultBvhWidth> tri_bvh_;
  TriangleLeaves tri_leaves_;
  Bvh2 quadric_bvh_;
  Bounds3f bounds_;
};

}  // namespace torte
