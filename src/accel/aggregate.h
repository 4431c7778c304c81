// The one room for tracing: both levels of the scene's geometry. The bottom level is geometry sets (meshes,
// quadrics and voxel grids, accel/geometry_set.h): the scene's own shapes in world space and one set per
// instanced prototype in its own space. The top level places prototypes by instances, with a BVH2 over their
// world bounds. Rays come in SoA queues (RaySoA) and hits go out in queue order.
//
// The instance level traces in batches (accel/instance_level.cc): in rounds, every ray walks the instance BVH2
// front to back to its next leaf, the leaves' instances are binned by prototype and each bin goes through the
// SIMD kernels at once, as one RaySoA of rays in their instances' spaces; hits clip the walks of the next round.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "accel/bvh2.h"
#include "accel/geometry_set.h"
#include "accel/hit.h"
#include "core/progress_counter.h"
#include "core/transform.h"
#include "geometry/surface_hit.h"

namespace torte {

// A group of shapes placed by instances (torte.group / scene:frame): its own geometry set, in group space.
struct Prototype {
  std::vector<TriangleMesh> meshes;
  std::vector<Quadric> quadrics;
  std::vector<VoxelGridAccel> grids;
  GeometrySet geometry;
};

// One placement of a prototype. Nested frames are flattened into one instance per path through the nesting,
// with the composed transform, so tracing needs two levels only (as Embree does).
struct Instance {
  Transform to_world;
  uint32_t prototype;
};

class Aggregate {
 public:
  /// Builds every level: the root set over (meshes, quadrics, grids) with objects from 0, each prototype's set
  /// with objects numbered on after them, and the instance BVH. The arrays are the caller's and must outlive the
  /// aggregate (the sets point into them; meshes are reordered, see accel/shape_set.h). Throws torte::Error for
  /// instances of missing prototypes or placed beyond the coordinate range. `options` pick the triangles' layout
  /// for every set at once (resolve_layout over all the scene's triangles).
  void build(std::vector<TriangleMesh>& meshes, const std::vector<Quadric>& quadrics,
             const std::vector<VoxelGridAccel>& grids, std::vector<std::unique_ptr<Prototype>>& prototypes,
             const std::vector<Instance>& instances, ProgressCounter* progress = nullptr,
             const AccelOptions& options = {});
  /// The triangles' layout the build chose (kDefault, kPacked or kCompact).
  BvhLayout layout() const { return layout_; }

  /// The scene's own (non-instanced) geometry.
  const GeometrySet& root() const { return root_; }
  Bounds3f bounds() const { return bounds_; }

  /// Closest hits of rays [0, count) in queue order (Hit::instance = kNoHit for the root's shapes, else the
  /// instance's index). `kernel` applies to the root's geometry; packet kernels need neighbouring rays in
  /// aligned groups of their width. Instanced prototypes always trace single rays (binned rays are not coherent).
  void intersect(const RaySoA& rays, size_t count, Hit* hits, TraceKernel kernel) const;
  /// One ray's closest hit (*hit from scratch, as intersect's), adding to *cost the nodes visited and primitives
  /// tested at every level (the root's sets, the instance BVH2, each entered prototype's set): the
  /// traversal_cost AOV. Single-ray kernels, instances one at a time, front to back.
  bool intersect_counted(const Ray& ray, Hit* hit, TraversalCost* cost) const;
  /// blocked[i] = 1 when anything blocks ray i in (0, t_max), else 0.
  void occluded(const RaySoA& rays, size_t count, uint8_t* blocked, TraceKernel kernel) const;
  /// The hit's surface in world space (instances map points, normals and tangents to the world); `ray` is the
  /// world ray that was traced (voxel hits need it).
  SurfaceHit surface(const Ray& ray, const Hit& hit) const;
  /// Bytes of acceleration data of all levels, prototypes counted once.
  size_t accel_bytes() const;

 private:
  void intersect_instances(const RaySoA& rays, size_t count, Hit* hits) const;
  void occluded_instances(const RaySoA& rays, size_t count, uint8_t* blocked) const;
  GeometrySet root_;
  const std::vector<std::unique_ptr<Prototype>>* prototypes_ = nullptr;
  const std::vector<Instance>* instances_ = nullptr;
  std::vector<Bounds3f> instance_bounds_;  // world bounds, for the entry distance of each candidate
  Bvh2 instance_bvh_;
  uint32_t instance_depth_ = 1;  // stack entries a walk of instance_bvh_ needs: its depth in nodes
  BvhLayout layout_ = BvhLayout::kDefault;
  Bounds3f bounds_;
};

}  // namespace torte
