// The packed kd-tree of a voxel grid: an implicit tree over a box whose sides are powers of two (the grid's
// chunk bounds, padded up per axis), each node splitting its box in the middle of its longest axis (ties: x, then
// y, then z). Split planes are not stored: traversal recomputes them from the box. A box holding one id only
// (empty, one block type, ...) is a single leaf, however large.
//
// Node word (4 bytes, VoxelNode):
//   bit  31      1 = leaf, 0 = inner
//   leaf:  bits 0..15   the voxel id (int16, two's complement: full 16-bit ids); bits 16..30 are zero
//   inner: bits 29..30  split axis (0 = x, 1 = y, 2 = z; redundant with the box, stored to save the argmax)
//          bits 0..28   k: the children are nodes[2k] (below the split) and nodes[2k + 1] (above)
// nodes[0] is the root and nodes[1] unused, so children pairs are 8-byte aligned and k >= 1. A tree holds at most
// 2^30 nodes (4 GB). Worst case (no two neighbouring voxels alike): one leaf per voxel plus one inner node per
// leaf minus one, i.e. < 8 bytes per voxel of the box.
#pragma once
#include <cstdint>
#include <vector>

#include "core/bounds.h"
#include "voxel/voxel_grid.h"

namespace torte {

struct VoxelNode {
  uint32_t bits = 0;

  static constexpr uint32_t kLeafBit = 1u << 31;
  static constexpr int kAxisShift = 29;
  static constexpr uint32_t kPairMask = (1u << 29) - 1;

  static constexpr VoxelNode leaf(int16_t id) { return {kLeafBit | uint16_t(id)}; }
  static constexpr VoxelNode inner(int axis, uint32_t pair) { return {uint32_t(axis) << kAxisShift | pair}; }
  constexpr bool is_leaf() const { return (bits & kLeafBit) != 0; }
  constexpr int16_t id() const { return int16_t(uint16_t(bits & 0xffff)); }
  constexpr int axis() const { return int(bits >> kAxisShift) & 3; }
  constexpr uint32_t pair() const { return bits & kPairMask; }
  constexpr bool operator==(const VoxelNode&) const = default;
};
static_assert(sizeof(VoxelNode) == 4);
static_assert(VoxelNode::leaf(-1).id() == -1 && VoxelNode::leaf(-32768).id() == -32768 &&
              VoxelNode::leaf(32767).id() == 32767 && VoxelNode::leaf(-1).is_leaf());
static_assert(VoxelNode::inner(2, VoxelNode::kPairMask).axis() == 2 &&
              VoxelNode::inner(2, VoxelNode::kPairMask).pair() == VoxelNode::kPairMask &&
              !VoxelNode::inner(2, 5).is_leaf());

// Axis a box of log2 sizes lg splits along: the longest, ties to the lowest axis. -1 for a single voxel.
inline int voxel_split_axis(const int lg[3]) {
  if (lg[0] == 0 && lg[1] == 0 && lg[2] == 0) return -1;
  int a = 0;
  if (lg[1] > lg[a]) a = 1;
  if (lg[2] > lg[a]) a = 2;
  return a;
}

struct VoxelBuildStats {
  uint64_t voxels = 0;  // non-empty voxels
  uint64_t cells = 0;   // voxels of the (padded) root box
  uint64_t nodes = 0, leaves = 0;
  size_t bytes = 0;  // node array
  double seconds = 0;
  double bytes_per_voxel() const { return voxels ? double(bytes) / double(voxels) : 0; }
};

class VoxelTree {
 public:
  // Builds the tree of a grid; `parallel` runs big subtrees as TBB tasks.
  static VoxelTree build(const VoxelGrid& grid, bool parallel = true);

  const std::vector<VoxelNode>& nodes() const { return nodes_; }
  VoxelNode root() const { return nodes_[0]; }
  // Root box in voxel coordinates: [origin, origin + 2^log2_size) per axis.
  const int* origin() const { return origin_; }
  const int* log2_size() const { return lg_; }
  Bounds3f bounds() const;
  // The id of voxel (x, y, z) by descending the tree (0 outside the box).
  int16_t lookup(int x, int y, int z) const;
  // Calls f(lo, size, id) for every leaf whose id is not 0: the leaf's box is [lo, lo + size) per axis in voxel
  // coordinates (int lo[3], int size[3]). Empty subtrees cost one node each.
  template <class F>
  void for_each_leaf(F&& f) const {
    int lo[3] = {origin_[0], origin_[1], origin_[2]}, lg[3] = {lg_[0], lg_[1], lg_[2]};
    visit_leaves(0, lo, lg, f);
  }
  const VoxelBuildStats& stats() const { return stats_; }

 private:
  template <class F>
  void visit_leaves(size_t node, const int lo[3], const int lg[3], F& f) const {
    const VoxelNode n = nodes_[node];
    if (n.is_leaf()) {
      if (n.id() != 0) {
        const int size[3] = {1 << lg[0], 1 << lg[1], 1 << lg[2]};
        f(lo, size, n.id());
      }
      return;
    }
    const int a = n.axis();
    int clg[3] = {lg[0], lg[1], lg[2]};
    --clg[a];
    int hi_lo[3] = {lo[0], lo[1], lo[2]};
    hi_lo[a] += 1 << clg[a];
    visit_leaves(2 * size_t(n.pair()), lo, clg, f);
    visit_leaves(2 * size_t(n.pair()) + 1, hi_lo, clg, f);
  }
  std::vector<VoxelNode> nodes_{VoxelNode::leaf(0), VoxelNode{}};
  int origin_[3] = {0, 0, 0};
  int lg_[3] = {kVoxelChunkBits, kVoxelChunkBits, kVoxelChunkBits};
  VoxelBuildStats stats_;
};

}  // namespace torte
