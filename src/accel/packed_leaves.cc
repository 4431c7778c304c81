// make_packed_leaves (accel/packed_leaves.h): every leaf's block, in leaf order, and the tree's leaf references
// rewritten to the blocks; PackedLeaves::triangle for hit reconstruction.

#include "accel/packed_leaves.h"

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "geometry/mesh.h"

namespace torte {

void PackedLeaves::triangle(uint32_t i, Vec3f p[3]) const {
  uint32_t offset = block_at[i / kStride];
  for (;;) {
    const uint8_t* b = bytes(offset);
    const uint32_t f = first(offset), count = b[0], nv = b[1];
    if (i < f + count) {
      const float* x = data.data() + offset + block_words(count, 0);
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = b[2 + size_t(k) * count + (i - f)];
        p[k] = {x[v], x[nv + v], x[2 * size_t(nv) + v]};
      }
      return;
    }
    offset += uint32_t(block_words(count, nv));
  }
}

namespace {

struct Leaf {
  uint32_t first, count;
  uint32_t* ref;  // the tree's child reference
};

// The distinct vertices of a leaf (by bits) in order of first use, and each triangle vertex's number among them.
struct LeafVertices {
  Vec3f v[PackedLeaves::kMaxLeafVertices];
  uint8_t idx[3][PackedLeaves::kMaxLeafTriangles];
  uint32_t nv = 0;
};

using VertexFn = std::function<void(uint32_t input_triangle, Vec3f p[3])>;

void distinct_vertices(const Leaf& leaf, std::span<const uint32_t> prim_indices, const VertexFn& vertices,
                       LeafVertices& out) {
  out.nv = 0;
  for (uint32_t j = 0; j < leaf.count; ++j) {
    Vec3f p[3];
    vertices(prim_indices[leaf.first + j], p);
    for (int k = 0; k < 3; ++k) {
      uint32_t u = 0;
      while (u < out.nv && std::memcmp(&out.v[u], &p[k], sizeof(Vec3f)) != 0) ++u;
      if (u == out.nv) out.v[out.nv++] = p[k];
      out.idx[k][j] = uint8_t(u);
    }
  }
}

PackedLeaves pack(WideBvh<8>& bvh, const VertexFn& vertices) {
  static_assert(sizeof(Vec3f) == 12);
  PackedLeaves out;
  const std::span<const uint32_t> prim_indices = bvh.prim_indices;
  const size_t n = prim_indices.size();
  out.triangles = n;
  std::vector<Leaf> leaves;
  for (WideNode<8>& node : bvh.nodes)
    for (int c = 0; c < 8; ++c)
      if (is_leaf_child(node.child[c])) {
        const Leaf l{node.child[c] & ~kLeafFlag, node.leaf_count[c], &node.child[c]};
        if (l.count > PackedLeaves::kMaxLeafTriangles)
          throw Error("Packed leaves: a leaf of " + std::to_string(l.count) + " triangles (at most " +
                      std::to_string(PackedLeaves::kMaxLeafTriangles) + ").");
        if (size_t(l.first) + l.count > n) throw Error("Packed leaves: a leaf lies outside prim_indices.");
        leaves.push_back(l);
      }
  std::sort(leaves.begin(), leaves.end(), [](const Leaf& a, const Leaf& b) { return a.first < b.first; });
  // Pass 1: each block's size; pass 2 (after a scan): the blocks. Pass 2 finds each leaf's distinct vertices again
  // rather than keeping them from pass 1: kept, they would take more memory than the blocks, on the scenes this
  // layout exists to fit.
  std::vector<size_t> offset(leaves.size() + 1, 0);
  parallel_for_blocks(size_t(0), leaves.size(), 4096, [&](IndexRange<size_t> r) {
    LeafVertices lv;
    for (size_t l = r.begin(); l < r.end(); ++l) {
      distinct_vertices(leaves[l], prim_indices, vertices, lv);
      offset[l + 1] = PackedLeaves::block_words(leaves[l].count, lv.nv);
    }
  });
  for (size_t l = 0; l < leaves.size(); ++l) offset[l + 1] += offset[l];
  if (offset.back() >= size_t(kLeafFlag)) throw Error("Packed leaves: more than 2^31 words of leaf blocks.");
  out.data = make_huge_page_vector<float>(offset.back() + PackedLeaves::kPadding);  // zero-filled
  out.block_at = make_huge_page_vector<uint32_t>((n + PackedLeaves::kStride - 1) / PackedLeaves::kStride);
  parallel_for_blocks(size_t(0), leaves.size(), 4096, [&](IndexRange<size_t> r) {
    LeafVertices lv;
    for (size_t l = r.begin(); l < r.end(); ++l) {
      const Leaf& leaf = leaves[l];
      distinct_vertices(leaf, prim_indices, vertices, lv);
      float* const block = out.data.data() + offset[l];
      std::memcpy(block, &leaf.first, 4);
      uint8_t* const b = reinterpret_cast<uint8_t*>(block + 1);
      b[0] = uint8_t(leaf.count), b[1] = uint8_t(lv.nv);
      for (int k = 0; k < 3; ++k) std::memcpy(b + 2 + size_t(k) * leaf.count, lv.idx[k], leaf.count);
      float* const x = block + PackedLeaves::block_words(leaf.count, 0);
      for (uint32_t u = 0; u < lv.nv; ++u) x[u] = lv.v[u].x, x[lv.nv + u] = lv.v[u].y, x[2 * lv.nv + u] = lv.v[u].z;
      *leaf.ref = kLeafFlag | uint32_t(offset[l]);
      // Every kStride-th triangle of the leaf names this block.
      for (uint32_t t = (leaf.first + PackedLeaves::kStride - 1) / PackedLeaves::kStride * PackedLeaves::kStride;
           t < leaf.first + leaf.count; t += PackedLeaves::kStride)
        out.block_at[t / PackedLeaves::kStride] = uint32_t(offset[l]);
    }
  });
  return out;
}

}  // namespace

PackedLeaves make_packed_leaves(WideBvh<8>& bvh, std::span<const TriangleMesh> meshes,
                                std::span<const uint32_t> mesh_first) {
  if (mesh_first.size() != meshes.size())
    throw Error("Packed leaves: " + std::to_string(mesh_first.size()) + " first triangles for " +
                std::to_string(meshes.size()) + " meshes.");
  return pack(bvh, [&](uint32_t g, Vec3f p[3]) {
    const uint32_t m = mesh_holding(mesh_first, g);
    const uint32_t* idx = meshes[m].triangle(g - mesh_first[m]);
    for (int k = 0; k < 3; ++k) p[k] = meshes[m].position(idx[k]);
  });
}

PackedLeaves make_packed_leaves(WideBvh<8>& bvh, std::span<const Vec3f> vertices) {
  for (uint32_t t : bvh.prim_indices)
    if (3 * size_t(t) + 2 >= vertices.size())
      throw Error("Packed leaves: primitive " + std::to_string(t) + " is out of range.");
  return pack(bvh, [&](uint32_t t, Vec3f p[3]) {
    for (int k = 0; k < 3; ++k) p[k] = vertices[3 * size_t(t) + size_t(k)];
  });
}

}  // namespace torte
