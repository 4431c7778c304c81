// A voxel grid placed in a GeometrySet (accel/geometry_set.h): the shared kd-tree, the grid-to-set transform,
// the material of each (id, face) and the unit-cell geometry of each negative id. Traced after the set's
// triangles and quadrics with t_max clipped to their hit.
//
// Hit encoding (accel/hit.h) of a voxel hit in its set: prim has bit 31 set (kVoxelPrimBit), then
//   bit  30      0 = a cube face, 1 = a cell shape
//   bits 19..29  the grid's index in its set (up to 2048 grids per set)
//   bits 16..18  the face (0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z; 0 for cell shapes)
//   bits 0..15   the voxel id (int16)
// and (b1, b2) = the cube face's uv (the cell shape's own b1, b2 for cell shapes). The voxel itself is not stored:
// surface() recovers it from the ray (cubes: the face plane and the uv; cell shapes: by tracing the grid again
// up to the hit distance, which finds the same hit since traversal is deterministic).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "accel/hit.h"
#include "accel/shape_set.h"
#include "core/transform.h"
#include "geometry/mesh.h"
#include "geometry/quadric.h"
#include "geometry/surface_hit.h"
#include "voxel/voxel_traverse.h"

namespace torte {

constexpr uint32_t kVoxelPrimBit = 1u << 31;
constexpr uint32_t kVoxelCellBit = 1u << 30;
constexpr uint32_t kMaxVoxelGridsPerSet = 1u << 11;

inline bool is_voxel_prim(uint32_t prim) { return prim != kNoHit && (prim & kVoxelPrimBit); }
inline uint32_t voxel_prim(uint32_t grid, bool cell, int face, int16_t id) {
  return kVoxelPrimBit | (cell ? kVoxelCellBit : 0) | grid << 19 | uint32_t(face & 7) << 16 | uint16_t(id);
}
inline uint32_t voxel_prim_grid(uint32_t prim) { return (prim >> 19) & (kMaxVoxelGridsPerSet - 1); }
inline int voxel_prim_face(uint32_t prim) { return int(prim >> 16) & 7; }
inline int16_t voxel_prim_id(uint32_t prim) { return int16_t(uint16_t(prim & 0xffff)); }
inline bool voxel_prim_is_cell(uint32_t prim) { return (prim & kVoxelCellBit) != 0; }

// The geometry of one negative id in unit-cell space, with the material override of each of its objects. A
// ShapeSet, not a GeometrySet: cells hold no grids, so voxel code depends on the shape level only (no cycle).
struct VoxelCellGeometry {
  std::vector<TriangleMesh> meshes;
  std::vector<Quadric> quadrics;
  ShapeSet set;
  std::vector<int32_t> object_material;  // per object of `set`: index into Scene::material_overrides
  void build() { set.build(meshes, quadrics); }  // once meshes and quadrics are final
};

struct VoxelGridAccel {
  std::shared_ptr<const VoxelTree> tree;
  Transform to_set;  // grid cell space -> the set's space
  // Material override per (id, face): face_material[(id - id_lo) * 6 + face], an index into
  // Scene::material_overrides, -1 = the grid object's own material.
  int32_t id_lo = 0;
  std::vector<int32_t> face_material;
  // Cell geometry of id -k at cells[k] (null: empty cell).
  std::vector<std::shared_ptr<const VoxelCellGeometry>> cells;

  Bounds3f bounds() const { return to_set.apply(tree->bounds()); }
  int32_t material_of(int16_t id, int face) const {
    const int64_t k = (int64_t(id) - id_lo) * 6 + face;
    return k >= 0 && k < int64_t(face_material.size()) ? face_material[size_t(k)] : -1;
  }
  const VoxelCellGeometry* cell(int16_t id) const {
    const size_t k = size_t(-int32_t(id));
    return id < 0 && k < cells.size() ? cells[k].get() : nullptr;
  }
  // set-space ray; `hit` is updated when the grid is hit closer than min(ray.t_max, hit->t). `index` = the
  // grid's index in its set. `cost` (optional): adds the kd-tree nodes descended and the voxels and cells tested
  // (with the cell shapes' own nodes and primitives).
  bool intersect(const Ray& ray, uint32_t index, Hit* hit, TraversalCost* cost = nullptr) const;
  bool occluded(const Ray& ray) const;
  // The same for coherent set-space rays (camera rays in tiles, shadow rays towards one point), traced in packets
  // of 16 (simd/voxel_packet.h): 2.5x faster than single rays for camera rays, slower for incoherent ones.
  // occluded_coherent skips rays already blocked and sets blocked[i] for the others the grid blocks.
  void intersect_coherent(const RaySoA& set_rays, size_t count, uint32_t index, Hit* hits) const;
  void occluded_coherent(const RaySoA& set_rays, size_t count, uint8_t* blocked) const;
  // The surface of a hit of this grid, in the set's space; `ray` is the set-space ray that was traced.
  SurfaceHit surface(const Hit& hit, const Ray& ray) const;
  size_t bytes() const { return tree->nodes().size() * sizeof(VoxelNode); }
};

}  // namespace torte
