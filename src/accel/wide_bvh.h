// The wide BVH: node width N (4 or 8) is a compile-time parameter, independent of the SIMD width the traversal
// kernels run at. One canonical binary tree (built by the parallel binned-SAH builder, bvh_build.h) is collapsed
// into this layout. The tree is generic over primitives: it orders primitive indices; a triangle BVH also stores
// its triangles' vertices in leaf order (TriangleLeaves) so the kernels test a leaf with contiguous vector loads.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/bounds.h"
#include "core/ray.h"

namespace torte {

// Child reference: an interior child is a node index; a leaf is kLeafFlag | first primitive (a position in
// leaf order), with the primitive count in WideNode::leaf_count; an unused slot is kEmptyChild.
constexpr uint32_t kLeafFlag = 0x80000000u;
constexpr uint32_t kEmptyChild = 0xffffffffu;

// One node = N children's bounds as structure of arrays (lane i = child i), so one vector op tests one slab of
// all children. Empty slots have lo = +inf and hi = -inf, which every ray misses.
//   N = 4: 6*16 + 16 + 4 = 116 bytes, padded to 128 (two cache lines).
//   N = 8: 6*32 + 32 + 8 = 232 bytes, padded to 256 (four cache lines).
template <int N>
struct alignas(64) WideNode {
  static_assert(N == 4 || N == 8, "node width must be 4 or 8");
  float lo_x[N], lo_y[N], lo_z[N];
  float hi_x[N], hi_y[N], hi_z[N];
  uint32_t child[N];
  uint8_t leaf_count[N];  // primitives in a leaf child, 0 for interior or empty children
};
static_assert(sizeof(WideNode<4>) == 128);
static_assert(sizeof(WideNode<8>) == 256);

template <int N>
struct WideBvh {
  std::vector<WideNode<N>> nodes;      // root at index 0 (or empty when there are no primitives)
  std::vector<uint32_t> prim_indices;  // leaf order -> caller's primitive index
  Bounds3f bounds;
  size_t memory_bytes() const { return nodes.size() * sizeof(WideNode<N>) + prim_indices.size() * sizeof(uint32_t); }
};

// Triangle vertices in leaf order, structure of arrays: 36 bytes per triangle. Each array is padded with
// kLeafPadding zero entries so a kernel may load a full vector from the start of any leaf.
struct TriangleLeaves {
  static constexpr size_t kLeafPadding = 16;
  std::vector<float> v0x, v0y, v0z, v1x, v1y, v1z, v2x, v2y, v2z;
  size_t size() const { return v0x.empty() ? 0 : v0x.size() - kLeafPadding; }
  size_t memory_bytes() const { return 9 * v0x.size() * sizeof(float); }
};

}  // namespace torte
