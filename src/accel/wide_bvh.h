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
#include "core/huge_pages.h"
#include "core/ray.h"

namespace torte {

// Child reference: an interior child is a node index; a leaf is kLeafFlag | first primitive (a position in
// leaf order), with the primitive count in WideNode::leaf_count; an unused slot is kEmptyChild.
constexpr uint32_t kLeafFlag = 0x80000000u;
constexpr uint32_t kEmptyChild = 0xffffffffu;
// kEmptyChild has kLeafFlag set too: a leaf is a reference with the flag that is not empty.
constexpr bool is_leaf_child(uint32_t ref) { return ref != kEmptyChild && (ref & kLeafFlag) != 0; }

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
  static constexpr int kWidth = N;
  using Node = WideNode<N>;
  HugePageVector<WideNode<N>> nodes;   // root at index 0 (or empty when there are no primitives); huge pages
  HugePageVector<uint32_t> prim_indices;  // leaf order -> caller's primitive index
  Bounds3f bounds;
  size_t memory_bytes() const { return nodes.size() * sizeof(WideNode<N>) + prim_indices.size() * sizeof(uint32_t); }
};

// Triangle vertices in leaf order, grouped per leaf: 36 bytes per triangle. The leaf (first, count) of a node
// owns floats [9 * first, 9 * (first + count)) of `data`, as nine runs of `count` floats, run r = 3 * vertex +
// axis (v0x, v0y, v0z, v1x, ..., v2z), so a leaf is one contiguous block (a leaf of 4 triangles: 144 bytes, two or
// three cache lines, where nine separate arrays cost nine or more). Built from the tree by make_triangle_leaves,
// whose leaves it follows. `data` ends with kLeafPadding zeros so a kernel may load a full vector (up to 16
// lanes) from any position inside any run.
//
// These are the only copy of the positions a renderer needs (accel/shape_set.h shades from them):
// `leaf_starts` (one bit per triangle, 0.125 B/tri) marks the first triangle of every leaf, so triangle(i)
// finds its leaf's run layout from the leaf-order index alone.
struct TriangleLeaves {
  static constexpr size_t kLeafPadding = 16;
  HugePageVector<float> data;  // on huge pages (core/huge_pages.h), as the nodes
  std::vector<uint64_t> leaf_starts;  // bit i (word i / 64, bit i % 64): leaf-order triangle i starts a leaf
  size_t size() const { return data.empty() ? 0 : (data.size() - kLeafPadding) / 9; }
  size_t memory_bytes() const { return data.size() * sizeof(float) + leaf_starts.size() * sizeof(uint64_t); }
  // Start of run r of the leaf (first, count).
  const float* run(uint32_t first, uint32_t count, int r) const {
    return data.data() + 9 * size_t(first) + size_t(r) * count;
  }
  // Vertex k (0..2) of leaf-order triangle i of the leaf (first, count).
  Vec3f vertex(uint32_t first, uint32_t count, uint32_t i, int k) const {
    const size_t at = 9 * size_t(first) + size_t(3 * k) * count + (i - first);
    return {data[at], data[at + count], data[at + 2 * size_t(count)]};
  }
  // The leaf (first, count) holding leaf-order triangle i < size(), from leaf_starts.
  void leaf_of(uint32_t i, uint32_t* first, uint32_t* count) const;
  // The three vertices of leaf-order triangle i < size().
  void triangle(uint32_t i, Vec3f p[3]) const {
    uint32_t first, count;
    leaf_of(i, &first, &count);
    for (int k = 0; k < 3; ++k) p[k] = vertex(first, count, i, k);
  }
};

}  // namespace torte
