// Packed leaves: the compact layout's leaf triangles (accel/compact_bvh.h), each leaf one contiguous block that
// carries its own de-duplicated vertices and 8-bit indices into them, so a kernel reads a leaf with no dependent
// load (leaves of indices into shared vertices wait on the index line, then on the vertex lines it names). About
// 19 B per triangle where TriangleLeaves copy 36.
//
// A block, in 4-byte words from PackedLeaves::data + offset (leaf child reference kLeafFlag | offset, which
// make_packed_leaves writes into the tree in place of the first triangle):
//   word 0:        first, the leaf-order index of the leaf's first triangle (hits report first + j)
//   words 1..:     bytes count, nv, then three runs of `count` 8-bit indices (vertex 0, 1, 2 of each triangle),
//                  zero-padded to a word
//   then:          x[nv], y[nv], z[nv] (floats): the leaf's distinct vertices in order of first use
// A leaf holds at most kMaxLeafTriangles (16, the builder's cap) triangles, so nv <= 48 and 8 bits always index.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

#include "accel/wide_bvh.h"
#include "core/huge_pages.h"
#include "core/vec.h"

namespace torte {

struct TriangleMesh;

struct PackedLeaves {
  static constexpr uint32_t kMaxLeafTriangles = 16;
  static constexpr uint32_t kMaxLeafVertices = 3 * kMaxLeafTriangles;
  // Floats after the last block: a decoder may load 32 floats from a block's last run (two 16-lane tables) and
  // 16 index bytes from its last index run.
  static constexpr size_t kPadding = 32;
  // Triangles per entry of block_at (0.25 B/tri): triangle(i) walks at most this many triangles' blocks.
  static constexpr uint32_t kStride = 16;
  HugePageVector<float> data;          // the blocks in leaf order, then kPadding zeros
  HugePageVector<uint32_t> block_at;   // [i / kStride]: offset of the block holding triangle kStride * (i / kStride)
  size_t triangles = 0;
  size_t size() const { return triangles; }
  size_t memory_bytes() const { return data.size() * sizeof(float) + block_at.size() * sizeof(uint32_t); }

  /// Words of a block of `count` triangles and `vertices` distinct vertices.
  static constexpr size_t block_words(uint32_t count, uint32_t vertices) {
    return 1 + (2 + 3 * size_t(count) + 3) / 4 + 3 * size_t(vertices);
  }
  /// The block at `offset`: its first triangle, triangle count, vertex count and index runs.
  uint32_t first(uint32_t offset) const {
    uint32_t f;
    std::memcpy(&f, data.data() + offset, 4);
    return f;
  }
  const uint8_t* bytes(uint32_t offset) const { return reinterpret_cast<const uint8_t*>(data.data() + offset + 1); }
  /// The three vertices of leaf-order triangle i < size() (hit reconstruction: a few blocks' headers are read).
  void triangle(uint32_t i, Vec3f p[3]) const;
};

/// Packed leaves of `bvh`, whose leaf-order triangle i is input triangle prim_indices[i] (mesh m's triangle t being
/// input triangle mesh_first[m] + t; placed meshes in world space). Rewrites every leaf child reference of `bvh`
/// to its block (so `bvh`, or a CompactBvh quantised from it, must be traced with these leaves only). Throws
/// torte::Error for a leaf of more than kMaxLeafTriangles or beyond 2^31 words of blocks.
PackedLeaves make_packed_leaves(WideBvh<8>& bvh, std::span<const TriangleMesh> meshes,
                                std::span<const uint32_t> mesh_first);
/// Same for a triangle soup (three vertices per input triangle in `vertices`; tests). Vertices are shared within a
/// leaf when their bits are equal.
PackedLeaves make_packed_leaves(WideBvh<8>& bvh, std::span<const Vec3f> vertices);

}  // namespace torte
