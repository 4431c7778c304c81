#include "accel/geometry_set.h"

#include <algorithm>

#include "core/error.h"

namespace torte {

namespace {
const std::vector<VoxelGridAccel> kNoGrids;
}  // namespace

void GeometrySet::build(std::vector<TriangleMesh>& meshes, const std::vector<Quadric>& quadrics,
                        uint32_t object_base) {
  build(meshes, quadrics, kNoGrids, object_base);
}

void GeometrySet::build(std::vector<TriangleMesh>& meshes, const std::vector<Quadric>& quadrics,
                        const std::vector<VoxelGridAccel>& grids, uint32_t object_base, ProgressCounter* progress,
                        BvhLayout layout) {
  if (grids.size() > kMaxVoxelGridsPerSet) throw Error("more than 2048 voxel grids in one scene or group");
  grids_ = &grids;
  object_base_ = object_base;
  static_assert(kProgressPerTriangle == 3, "ShapeSet::build reports 3 units per triangle");
  shapes_.build(meshes, quadrics, progress, layout);
  bounds_ = shapes_.bounds();
  for (const VoxelGridAccel& g : grids) bounds_.extend(g.bounds());
}

bool GeometrySet::intersect_one(const Ray& ray, Hit* hit, TraversalCost* cost) const {
  if (grid_count() == 0) return shapes_.intersect_one(ray, hit, cost);
  bool found = shapes_.intersect_one(ray, hit, cost);
  for (uint32_t g = 0; g < grid_count(); ++g) found |= (*grids_)[g].intersect(ray, g, hit, cost);
  return found;
}

bool GeometrySet::occluded_one(const Ray& ray) const {
  if (shapes_.occluded_one(ray)) return true;
  for (uint32_t g = 0; g < grid_count(); ++g)
    if ((*grids_)[g].occluded(ray)) return true;
  return false;
}

void GeometrySet::intersect(const RaySoA& rays, size_t count, Hit* hits, TraceKernel kernel) const {
  shapes_.intersect(rays, count, hits, kernel);
  if (grid_count() > 0) intersect_grids(rays, count, hits, kernel);
}

// Voxel grids after the triangles and quadrics, with t_max clipped to their hit: coherent rays in packets
// (simd/voxel_packet.h), others one at a time (voxel/voxel_traverse.h).
void GeometrySet::intersect_grids(const RaySoA& rays, size_t count, Hit* hits, TraceKernel kernel) const {
  if (kernel != TraceKernel::kSingle && count >= 16) {  // packets of 16 (camera rays come in tiles)
    for (uint32_t g = 0; g < grid_count(); ++g) (*grids_)[g].intersect_coherent(rays, count, g, hits);
    return;
  }
  for (size_t i = 0; i < count; ++i) {
    const Ray r = ray_at(rays, i);
    for (uint32_t g = 0; g < grid_count(); ++g) (*grids_)[g].intersect(r, g, &hits[i]);
  }
}

void GeometrySet::occluded(const RaySoA& rays, size_t count, uint8_t* blocked, TraceKernel kernel) const {
  shapes_.occluded(rays, count, blocked, kernel);
  if (grid_count() == 0) return;
  if (kernel != TraceKernel::kSingle && count >= 16) {  // rays already blocked are skipped by the grids
    for (uint32_t g = 0; g < grid_count(); ++g) (*grids_)[g].occluded_coherent(rays, count, blocked);
    return;
  }
  for (size_t i = 0; i < count; ++i) {
    if (blocked[i]) continue;
    const Ray r = ray_at(rays, i);
    for (uint32_t g = 0; g < grid_count() && !blocked[i]; ++g) blocked[i] = (*grids_)[g].occluded(r);
  }
}

size_t GeometrySet::accel_bytes() const {
  size_t grid_bytes = 0;
  for (uint32_t g = 0; g < grid_count(); ++g) grid_bytes += (*grids_)[g].bytes();
  return shapes_.accel_bytes() + grid_bytes;
}

SurfaceHit GeometrySet::surface(const Hit& hit, const Ray* ray) const {
  if (!is_voxel_prim(hit.prim)) return shapes_.surface(hit, object_base_);
  if (!ray) throw Error("internal: the surface of a voxel hit needs its ray");
  SurfaceHit s = (*grids_)[voxel_prim_grid(hit.prim)].surface(hit, *ray);
  s.object = object_of(hit.prim);
  return s;
}

}  // namespace torte
