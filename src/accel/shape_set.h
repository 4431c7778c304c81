// Triangle meshes and analytic shapes in one space, with their acceleration structures: the part of a geometry
// set (accel/geometry_set.h) without voxel grids, and the whole geometry of a voxel cell shape
// (voxel/voxel_accel.h). Meshes and quadrics are owned by the caller and must outlive the set.
//
// Memory (the dragon, one mesh with vertex normals): wide nodes 6.8 B/tri, leaf triangles 36.1 (with the leaf-start
// bitmap), mesh indices 12 and normals 6 once the scene releases the mesh positions (the leaves hold them):
// 61.0 B/tri, checked by test_geometry_set.cc. Sets of several meshes, or of placed meshes (a scene's, which
// share the script's arrays: TriangleMesh::make_placed), add 4 B/tri (each triangle's place in the meshes
// concatenated) and keep only their world normals.
// The packed layout (picked by accel_options.h) keeps the wide nodes with packed leaves (each leaf's distinct
// vertices and 8-bit indices, accel/packed_leaves.h): 18.9 B/tri for the leaves, 43.7 in all. The compact layout
// (accel/compact_bvh.h) quantises the nodes too and holds the dragon in 40.3 B/tri: nodes 3.4, leaves 18.9,
// indices 12, normals 6 (test_compact_layout.cc); placed or several meshes add the 4 B/tri map.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "accel/accel_options.h"
#include "accel/bvh2.h"
#include "accel/bvh_build.h"
#include "accel/compact_bvh.h"
#include "accel/hit.h"
#include "accel/packed_leaves.h"
#include "accel/wide_bvh.h"
#include "core/progress_counter.h"
#include "geometry/mesh.h"
#include "geometry/quadric.h"
#include "geometry/surface_hit.h"

namespace torte {

/// Sets of at most this many triangles build their BVH with per-triangle leaf costs (BvhBuildOptions::
/// leaf_block_size 1), larger ones with the default block of 8: 22 B/tri more node memory is under 1.5 MB here.
inline constexpr size_t kFineLeavesMaxTriangles = size_t(1) << 16;

class ShapeSet {
 public:
  /// Builds the BVHs over `meshes` then `quadrics` (local objects 0.. in that order). Reorders each mesh's
  /// triangles into the BVH's leaf order, so triangle numbers in hits are leaf positions and a one-mesh set keeps
  /// no index map; afterwards surface() reads positions from the leaves. `progress` gets 3 units per triangle.
  /// `layout`: kDefault, kPacked or kCompact (accel/accel_options.h; kAuto is resolved by the caller).
  void build(std::vector<TriangleMesh>& meshes, const std::vector<Quadric>& quadrics,
             ProgressCounter* progress = nullptr, BvhLayout layout = BvhLayout::kDefault);
  /// The triangles' layout: kDefault, kPacked or kCompact.
  BvhLayout layout() const { return layout_; }

  // Triangles in the BVH (all but those with empty bounds, which nothing can hit).
  uint32_t triangle_count() const { return triangle_count_; }
  uint32_t quadric_count() const { return quadrics_ ? uint32_t(quadrics_->size()) : 0; }
  uint32_t mesh_count() const { return meshes_ ? uint32_t(meshes_->size()) : 0; }
  uint32_t primitive_count() const { return triangle_count() + quadric_count(); }
  /// Local object (mesh index, then mesh_count() + quadric index) of a primitive: triangles, then quadrics.
  uint32_t local_object_of(uint32_t prim) const {
    if (prim < triangle_count()) return triangle_ref(prim).mesh;
    return mesh_count() + (prim - triangle_count());
  }
  Bounds3f bounds() const { return bounds_; }
  bool empty() const { return primitive_count() == 0; }

  /// Closest hits of `count` rays through `kernel`, written from scratch (a miss is Hit{}; Hit::instance stays
  /// kNoHit). Quadrics are tested one ray at a time whatever the kernel. `costs` (optional, kSingle only): adds
  /// each ray's work to costs[i] (the counting kernels, TraversalCost).
  void intersect(const RaySoA& rays, size_t count, Hit* hits, TraceKernel kernel,
                 TraversalCost* costs = nullptr) const;
  /// blocked[i] = 1 when something blocks ray i in (0, t_max), else 0.
  void occluded(const RaySoA& rays, size_t count, uint8_t* blocked, TraceKernel kernel) const;
  /// One ray: updates *hit (keeping its instance) when something closer than min(ray.t_max, hit->t) is hit.
  /// `cost` (optional): adds the work the search did (the counting kernels, TraversalCost).
  bool intersect_one(const Ray& ray, Hit* hit, TraversalCost* cost = nullptr) const;
  bool occluded_one(const Ray& ray) const;
  /// The surface at a triangle or quadric hit of this set; SurfaceHit::object is the local object plus
  /// `object_base`.
  SurfaceHit surface(const Hit& hit, uint32_t object_base = 0) const;
  size_t accel_bytes() const;
  /// The triangle BVH's parts in bytes, for the render summary and memory tests.
  struct TriangleMemory {
    size_t nodes = 0, leaves = 0, index_map = 0;  // wide nodes; leaf vertices + leaf starts; tri_ref_ + mesh_first_
  };
  /// The triangle BVH itself (statistics: depth, leaves, SAH cost): the default and packed layouts' (empty in
  /// the compact one), and the compact layout's (empty in the others).
  const WideBvh<kDefaultBvhWidth>& triangle_bvh() const { return tri_bvh_; }
  const CompactBvh& compact_bvh() const { return ctri_bvh_; }
  TriangleMemory triangle_memory() const {
    return {tri_bvh_.nodes.size() * sizeof(tri_bvh_.nodes[0]) + ctri_bvh_.nodes.size() * sizeof(QuantNode),
            tri_leaves_.memory_bytes() + ptri_leaves_.memory_bytes(),
            (tri_ref_.size() + mesh_first_.size()) * sizeof(uint32_t)};
  }

 private:
  void intersect_quadrics(const RaySoA& rays, size_t count, Hit* hits, TraversalCost* costs) const;
  void store_in_leaf_order(std::vector<TriangleMesh>& meshes, const std::vector<uint32_t>& mesh_first);
  const std::vector<TriangleMesh>* meshes_ = nullptr;
  const std::vector<Quadric>* quadrics_ = nullptr;
  uint32_t triangle_count_ = 0;
  // Sets of several meshes or with a placed mesh only (empty for one owned mesh): triangle (leaf position) -> its
  // mesh and its index there, 4 B/tri, often the tree's own prim_indices moved here. Packed as mesh << bits |
  // index when both fit in 32 bits (ref_local_bits_ > 0): a hit then finds its mesh with a shift, where a search
  // over mesh_first_ cost 60 to 80 instructions a hit. Otherwise the index in the meshes concatenated,
  // mesh_first_[m] + the index in mesh m, and the mesh is searched for.
  HugePageVector<uint32_t> tri_ref_;
  std::vector<uint32_t> mesh_first_;  // first triangle of each mesh in the concatenation (several meshes only)
  uint8_t ref_local_bits_ = 0;
  void pack_triangle_refs(const std::vector<TriangleMesh>& meshes);
  struct TriangleRef {
    uint32_t mesh, local;
  };
  TriangleRef triangle_ref(uint32_t prim) const {
    if (tri_ref_.empty()) return {0, prim};
    if (ref_local_bits_ != 0) {
      const uint32_t r = tri_ref_[prim];
      return {r >> ref_local_bits_, r & ((1u << ref_local_bits_) - 1)};
    }
    const uint32_t g = tri_ref_[prim], m = mesh_holding(mesh_first_, g);
    return {m, g - mesh_first_[m]};
  }
  // All triangles of all meshes in one wide BVH (SIMD kernels, simd/traverse.h); the few analytic shapes in a
  // scalar BVH2 of their own, traced after it with t_max clipped to the triangle hit. The default layout fills
  // tri_bvh_ and tri_leaves_, the packed one tri_bvh_ and ptri_leaves_, the compact one ctri_bvh_ and ptri_leaves_.
  BvhLayout layout_ = BvhLayout::kDefault;
  /// Calls f(nodes, leaves) with the layout's pair (one kernel instantiation each, simd/traverse.h).
  template <class F>
  void with_layout(const F& f) const {
    switch (layout_) {
      case BvhLayout::kCompact: return f(ctri_bvh_, ptri_leaves_);
      case BvhLayout::kPacked: return f(tri_bvh_, ptri_leaves_);
      default: return f(tri_bvh_, tri_leaves_);
    }
  }
  WideBvh<kDefaultBvhWidth> tri_bvh_;
  TriangleLeaves tri_leaves_;
  CompactBvh ctri_bvh_;
  PackedLeaves ptri_leaves_;
  Bvh2 quadric_bvh_;
  Bounds3f bounds_;
};

}  // namespace torte
