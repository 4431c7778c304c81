// The compact triangle layout, for meshes that would not fit in memory otherwise (accel/shape_set.h picks it by a
// memory budget, accel/accel_options.h):
// - QuantNode: a wide node whose children's bounds are 8-bit offsets on a per-node grid (origin + per-axis
//   power-of-two scale), as in Ylitie, Karras & Laine 2017 ("Efficient incoherent ray traversal on GPUs through
//   compressed wide BVHs"): 128 bytes for 8 children where WideNode<8> takes 256. Rounded conservatively (lo
//   down, hi up, checked with the kernels' own arithmetic), so a dequantised box holds its child's box.
// - IndexedLeaves: leaf triangles as three vertex indices (12 B/tri) into shared vertices, where TriangleLeaves
//   copies 36 B/tri of positions; a set of one owned mesh borrows the mesh's own index triples (already in leaf
//   order, shape_set.cc), so its leaves cost only the vertex copy (12 B/vertex, about 6 B/tri).
// The kernels (simd/traverse.h) take any pairing of {WideBvh<8>, CompactBvh} with {TriangleLeaves, IndexedLeaves}.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "accel/wide_bvh.h"
#include "core/bounds.h"
#include "core/huge_pages.h"
#include "core/vec.h"

namespace torte {

struct TriangleMesh;

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

// Leaf triangles as vertex indices: leaf-order triangle i has vertices idx[3 i + k] (k = 0, 1, 2), vertex v at
// xyz[3 v, 3 v + 3). The vertices are always a copy owned here (x, y, z per vertex, then kPadding floats, so a
// kernel may load 4 floats at any vertex); the triples are owned here too (owned_idx) or are a mesh's (see
// make_indexed_leaves), which must then outlive these.
//   Owned triples: 12 B/tri + 12 B/vertex; borrowing a mesh's triples: 12 B/vertex.
struct IndexedLeaves {
  static constexpr size_t kPadding = 4;
  IndexedLeaves() = default;
  IndexedLeaves(IndexedLeaves&&) = default;  // the buffers move with their pointers
  IndexedLeaves& operator=(IndexedLeaves&&) = default;
  IndexedLeaves(const IndexedLeaves&) = delete;
  const uint32_t* idx = nullptr;
  const float* xyz = nullptr;
  size_t triangles = 0, vertices = 0;
  HugePageVector<uint32_t> owned_idx;
  HugePageVector<float> owned_xyz;
  size_t size() const { return triangles; }
  size_t memory_bytes() const { return owned_idx.size() * sizeof(uint32_t) + owned_xyz.size() * sizeof(float); }
  Vec3f vertex(uint32_t i, int k) const {
    const float* p = xyz + 3 * size_t(idx[3 * size_t(i) + size_t(k)]);
    return {p[0], p[1], p[2]};
  }
  void triangle(uint32_t i, Vec3f p[3]) const {
    for (int k = 0; k < 3; ++k) p[k] = vertex(i, k);
  }
};

/// Indexed leaves of the tree whose leaf-order triangle i is input triangle prim_indices[i] (mesh m's triangle t
/// being input triangle mesh_first[m] + t): triples of their own into a copy of the vertices the tree's triangles
/// use, numbered in order of first use in leaf order (placed meshes' vertices in world space), so a leaf's
/// vertices lie close together. Throws torte::Error beyond 2^32 - 1 vertices.
IndexedLeaves make_indexed_leaves(std::span<const uint32_t> prim_indices, std::span<const TriangleMesh> meshes,
                                  std::span<const uint32_t> mesh_first);
/// Indexed leaves over the first `triangles` triples of `mesh` (one owned mesh whose triples are in leaf order):
/// they point at the mesh's triples, which must stay, and copy its positions, which it may then release.
IndexedLeaves make_indexed_leaves(size_t triangles, const TriangleMesh& mesh);
/// Same for a triangle soup (three vertices per triangle in `vertices`, the caller's numbering), each triangle
/// with three vertices of its own (tests).
IndexedLeaves make_indexed_leaves(std::span<const uint32_t> prim_indices, std::span<const Vec3f> vertices);

}  // namespace torte
