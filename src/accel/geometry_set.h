// One level of geometry: triangle meshes, analytic shapes (a ShapeSet, accel/shape_set.h) and voxel grids in a
// common space. The scene's own (top-level) shapes form one set; every instanced group is another, shared by all
// its instances (accel/aggregate.h). Meshes, quadrics and grids are owned by the caller and must outlive the set.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "accel/hit.h"
#include "accel/shape_set.h"
#include "core/progress_counter.h"
#include "geometry/mesh.h"
#include "geometry/quadric.h"
#include "geometry/surface_hit.h"
#include "voxel/voxel_accel.h"

namespace torte {

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
  // `layout`: the triangles' (ShapeSet::build).
  void build(std::vector<TriangleMesh>& meshes, const std::vector<Quadric>& quadrics,
             const std::vector<VoxelGridAccel>& grids, uint32_t object_base, ProgressCounter* progress = nullptr,
             BvhLayout layout = BvhLayout::kDefault);

  // Triangles in the BVH (all but those with empty bounds, which nothing can hit).
  uint32_t triangle_count() const { return shapes_.triangle_count(); }
  uint32_t grid_count() const { return grids_ ? uint32_t(grids_->size()) : 0; }
  // Triangles, quadrics and one per voxel grid.
  uint32_t primitive_count() const { return shapes_.primitive_count() + grid_count(); }
  // Scene object of a primitive (Hit::prim: triangles first, then quadrics, then voxel hits).
  uint32_t object_of(uint32_t prim) const {
    if (is_voxel_prim(prim)) return object_base_ + shapes_.mesh_count() + shapes_.quadric_count() + voxel_prim_grid(prim);
    return object_base_ + shapes_.local_object_of(prim);
  }
  Bounds3f bounds() const { return bounds_; }
  bool empty() const { return primitive_count() == 0; }

  // Closest hits (written from scratch; Hit::instance is kNoHit) and occlusion, for `count` rays through
  // `kernel`; voxel grids take packets of 16 for either packet kernel (at 16 rays or more).
  void intersect(const RaySoA& rays, size_t count, Hit* hits, TraceKernel kernel) const;
  void occluded(const RaySoA& rays, size_t count, uint8_t* occluded, TraceKernel kernel) const;
  // One ray: updates *hit when something closer than min(ray.t_max, hit->t) is hit. `cost` (optional): adds the
  // work the search did (TraversalCost).
  bool intersect_one(const Ray& ray, Hit* hit, TraversalCost* cost = nullptr) const;
  bool occluded_one(const Ray& ray) const;
  // The ray (in this set's space, as traced) is needed for voxel hits only.
  SurfaceHit surface(const Hit& hit, const Ray* ray = nullptr) const;
  size_t accel_bytes() const;
  ShapeSet::TriangleMemory triangle_memory() const { return shapes_.triangle_memory(); }
  const WideBvh<kDefaultBvhWidth>& triangle_bvh() const { return shapes_.triangle_bvh(); }
  const CompactBvh& compact_bvh() const { return shapes_.compact_bvh(); }
  BvhLayout layout() const { return shapes_.layout(); }
  /// The set's voxel grids (none when it has none).
  const VoxelGridAccel* grid(uint32_t g) const { return &(*grids_)[g]; }

 private:
  void intersect_grids(const RaySoA& rays, size_t count, Hit* hits, TraceKernel kernel) const;
  ShapeSet shapes_;
  const std::vector<VoxelGridAccel>* grids_ = nullptr;
  uint32_t object_base_ = 0;
  Bounds3f bounds_;
};

}  // namespace torte
