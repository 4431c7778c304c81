// The compact triangle layout, for meshes that would not fit in memory otherwise (accel/shape_set.h picks it by a
// memory budget, accel/accel_options.h):
// - QuantNode: a wide node whose children's bounds are 8-bit offsets on a per-node grid (origin + per-axis
//   power-of-two scale), as in Ylitie, Karras & Laine 2017 ("Efficient incoherent ray traversal on GPUs through
//   compressed wide BVHs"): 128 bytes for 8 children where WideNode<8> takes 256. Rounded conservatively (lo
//   down, hi up, checked with the kernels' own arithmetic), so a dequantised box holds its child's box.
// - PackedLeaves (accel/packed_leaves.h): each leaf one block with its own de-duplicated vertices and 8-bit
//   indices, about 19 B/tri where TriangleLeaves copy 36.
// The kernels (simd/traverse.h) take quantised nodes with either leaf type, and packed leaves under either node
// type.
#pragma once
#include <cstddef>
#include <cstdint>

#include "accel/wide_bvh.h"
#include "core/bounds.h"
#include "core/huge_pages.h"

namespace torte {

// One node of 8 children. Child bounds: q[row][i] for rows lo_x, lo_y, lo_z, hi_x, hi_y, hi_z (the rows of
// WideNode, in the same order, so the kernels' plane offsets index both), dequantised as origin[a] + q * scale[a]
// (q * scale is exact: scale is a power of two, q has 8 bits). `occupied` marks the used slots (the first ones):
// an empty slot's box is inverted, but a slab margin could still let a ray through it on a tiny node.
//   12 + 12 + 48 + 32 + 8 + 1 = 113 bytes, padded to 128 (two cache lines).
struct alignas(64) QuantNode {
  static constexpr int kWidth = 8;
  float origin[3];
  float scale[3];
  uint8_t q[6][kWidth];
  uint32_t child[kWidth];       // as WideNode::child (kLeafFlag, kEmptyChild)
  uint8_t leaf_count[kWidth];   // as WideNode::leaf_count
  uint8_t occupied;             // bit i: slot i is used
};
static_assert(sizeof(QuantNode) == 128);
static_assert(offsetof(QuantNode, child) == 72);

/// A wide BVH of QuantNodes: the same tree, leaf order and prim_indices as the WideBvh<8> it was made from.
struct CompactBvh {
  static constexpr int kWidth = QuantNode::kWidth;
  using Node = QuantNode;
  HugePageVector<QuantNode> nodes;  // root at 0, empty for no primitives
  HugePageVector<uint32_t> prim_indices;
  Bounds3f bounds;
  float plane_extent[3] = {0, 0, 0};  // largest |dequantised plane| per axis (the FMA slab test's margin)
  size_t memory_bytes() const { return nodes.size() * sizeof(QuantNode) + prim_indices.size() * sizeof(uint32_t); }
};

/// The bound plane a QuantNode row value q stands for on axis a: exactly the kernels' dequantisation.
inline float dequantize(const QuantNode& n, int a, uint32_t q) { return n.origin[a] + float(q) * n.scale[a]; }

/// `wide` with every node quantised (moves prim_indices out of `wide` and frees its nodes).
CompactBvh quantize(WideBvh<8>&& wide);

}  // namespace torte
