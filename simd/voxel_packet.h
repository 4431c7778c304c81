// Packet traversal of a voxel grid's packed kd-tree (voxel/voxel_tree.h): P = 8 or 16 rays per packet traced
// together through the implicit tree (lanes = rays), a Highway kernel (voxel_packet.cc) dispatched at run time.
//
// Results are those of the single-ray functions of voxel/voxel_traverse.h, to the bit: per ray, found / not
// found, and for hits VoxelHit's t, voxel, id, face, inside, u, v (and `cell` from the handler for negative ids),
// including rays starting inside solid voxels, rays on cell boundaries and axis-parallel rays. The kernel runs the
// single-ray code's comparisons lane by lane (same near/far decision from the origin's side of the split plane,
// same split distances (split - o) / d computed as (split - o) * (1 / d), same entry/exit intervals and entry
// axis per lane) and, in leaves, the single-ray code itself for each ray that reached the leaf.
// Within a packet, rays whose direction sign on some axis differs from the packet's (the first valid ray's),
// and rays with a non-finite component in origin, direction or 1 / direction, are traced alone with the
// single-ray function (so NaN rays never disturb the others and get the single-ray result).
//
// Cell shapes (negative ids) go to `cells`, a plain function-pointer adaptor of the single-ray Cells handlers
// (voxel_cell_callbacks(handler)); the default sees no geometry in cells, as NoVoxelCells.
#pragma once
#include <cstddef>
#include <cstdint>

#include "voxel/voxel_traverse.h"

namespace torte {

struct VoxelCellCallbacks {
  const void* ctx = nullptr;
  bool (*intersect)(const void* ctx, int16_t id, const Ray& ray, Hit* hit) = nullptr;
  bool (*occluded)(const void* ctx, int16_t id, const Ray& ray) = nullptr;
};

// Adapts a single-ray cell handler (voxel/voxel_traverse.h); `cells` must outlive the callbacks.
template <class Cells>
VoxelCellCallbacks voxel_cell_callbacks(const Cells& cells) {
  VoxelCellCallbacks cb;
  cb.ctx = &cells;
  cb.intersect = [](const void* c, int16_t id, const Ray& r, Hit* h) {
    return static_cast<const Cells*>(c)->intersect(id, r, h);
  };
  cb.occluded = [](const void* c, int16_t id, const Ray& r) { return static_cast<const Cells*>(c)->occluded(id, r); };
  return cb;
}

// Closest hits of rays[0, count) in packets of `packet_size` (8 or 16, else torte::Error) consecutive rays.
// found[i] = what voxel_intersect returns; hits[i] = its hit, or VoxelHit{} when not found.
void voxel_intersect_packets(const VoxelTree& tree, const Ray* rays, size_t count, VoxelHit* hits, uint8_t* found,
                             int packet_size = 8, const VoxelCellCallbacks& cells = {});
// occluded[i] = voxel_occluded(tree, rays[i]).
void voxel_occluded_packets(const VoxelTree& tree, const Ray* rays, size_t count, uint8_t* occluded,
                            int packet_size = 8, const VoxelCellCallbacks& cells = {});

// Name of the Highway target the voxel packet kernel dispatches to on this CPU.
const char* voxel_packet_target_name();

}  // namespace torte
