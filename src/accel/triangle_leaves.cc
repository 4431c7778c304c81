// make_triangle_leaves: the wide BVH's triangles copied into leaf order (accel/wide_bvh.h, TriangleLeaves), and
// TriangleLeaves::leaf_of, which finds a triangle's leaf from the leaf-start bitmap.

#include <bit>
#include <string>

#include "accel/bvh_build.h"
#include "core/error.h"
#include "core/parallel.h"
#include "geometry/mesh.h"

namespace torte {

void TriangleLeaves::leaf_of(uint32_t i, uint32_t* first, uint32_t* count) const {
  // Leaves hold at most 255 triangles, so both scans stop within five words.
  size_t w = i / 64;
  const uint64_t upto = ~uint64_t(0) >> (63 - i % 64);  // bits 0..i % 64
  uint64_t bits = leaf_starts[w] & upto;
  while (bits == 0) bits = leaf_starts[--w];  // bit 0 (triangle 0 starts the first leaf) ends the scan
  *first = uint32_t(w * 64 + 63 - size_t(std::countl_zero(bits)));
  w = i / 64;
  bits = leaf_starts[w] & ~upto;
  while (bits == 0 && ++w < leaf_starts.size()) bits = leaf_starts[w];
  const size_t end = w < leaf_starts.size() ? w * 64 + size_t(std::countr_zero(bits)) : size();
  *count = uint32_t(end - *first);
}

namespace {

template <int N, class Vertices>
TriangleLeaves fill_leaves(const WideBvh<N>& bvh, bool parallel, Vertices&& vertices) {
  TriangleLeaves leaves;
  const std::span<const uint32_t> prim_indices = bvh.prim_indices;
  const size_t n = prim_indices.size();
  if (n == 0) return leaves;
  // Zero-filled, which also writes the padding.
  leaves.data = make_huge_page_vector<float>(9 * n + TriangleLeaves::kLeafPadding);
  float* const data = leaves.data.data();
  // Every leaf is a slot of exactly one node: fill node by node.
  auto fill = [&](size_t b, size_t e) {
    for (size_t ni = b; ni < e; ++ni) {
      const WideNode<N>& node = bvh.nodes[ni];
      for (int c = 0; c < N; ++c) {
        if (!is_leaf_child(node.child[c])) continue;
        const uint32_t first = node.child[c] & ~kLeafFlag, count = node.leaf_count[c];
        if (size_t(first) + count > n) throw Error("Triangle leaves: a leaf lies outside prim_indices.");
        float* const out = data + 9 * size_t(first);
        for (uint32_t j = 0; j < count; ++j) {
          Vec3f p[3];
          vertices(prim_indices[first + j], p);
          for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) out[size_t(3 * k + a) * count + j] = p[k][a];
        }
      }
    }
  };
  const size_t nodes = bvh.nodes.size();
  if (parallel && n > 16384) {
    parallel_for_blocks(size_t(0), nodes, 1024, [&](IndexRange<size_t> r) { fill(r.begin(), r.end()); });
  } else {
    fill(0, nodes);
  }
  // Serial: neighbouring leaves share bitmap words (a pass over the nodes, not the triangles).
  leaves.leaf_starts.assign((n + 63) / 64, 0);
  for (const WideNode<N>& node : bvh.nodes)
    for (int c = 0; c < N; ++c)
      if (is_leaf_child(node.child[c])) {
        const uint32_t first = node.child[c] & ~kLeafFlag;
        leaves.leaf_starts[first / 64] |= uint64_t(1) << (first % 64);
      }
  return leaves;
}

void check_prims(std::span<const uint32_t> prim_indices, size_t triangles) {
  for (uint32_t p : prim_indices)
    if (p >= triangles)
      throw Error("Triangle leaves: primitive " + std::to_string(p) + " is out of range (" +
                  std::to_string(triangles) + " triangles).");
}

}  // namespace

template <int N>
TriangleLeaves make_triangle_leaves(const WideBvh<N>& bvh, std::span<const Vec3f> vertices, bool parallel) {
  if (vertices.size() % 3 != 0)
    throw Error("Triangle leaves: " + std::to_string(vertices.size()) + " vertices is not three per triangle.");
  check_prims(bvh.prim_indices, vertices.size() / 3);
  return fill_leaves(bvh, parallel, [&](uint32_t t, Vec3f* p) {
    for (int j = 0; j < 3; ++j) p[j] = vertices[3 * size_t(t) + j];
  });
}

template <int N>
TriangleLeaves make_triangle_leaves(const WideBvh<N>& bvh, const TriangleMesh& mesh, bool parallel) {
  check_prims(bvh.prim_indices, mesh.triangle_count());
  return fill_leaves(bvh, parallel, [&](uint32_t t, Vec3f* p) {
    const uint32_t* idx = mesh.triangle(t);
    for (int j = 0; j < 3; ++j) p[j] = mesh.position(idx[j]);
  });
}

template <int N>
TriangleLeaves make_triangle_leaves(const WideBvh<N>& bvh, std::span<const TriangleMesh> meshes,
                                    std::span<const uint32_t> mesh_first, bool parallel) {
  if (mesh_first.size() != meshes.size())
    throw Error("Triangle leaves: " + std::to_string(mesh_first.size()) + " first triangles for " +
                std::to_string(meshes.size()) + " meshes.");
  const size_t total = meshes.empty() ? 0 : mesh_first.back() + meshes.back().triangle_count();
  check_prims(bvh.prim_indices, total);
  return fill_leaves(bvh, parallel, [&](uint32_t t, Vec3f* p) {
    const uint32_t m = mesh_holding(mesh_first, t);
    const TriangleMesh& mesh = meshes[m];
    const size_t local = t - mesh_first[m];
    const uint32_t* idx = mesh.triangle(local);
    for (int j = 0; j < 3; ++j) p[j] = mesh.position(idx[j]);
  });
}

template TriangleLeaves make_triangle_leaves<4>(const WideBvh<4>&, std::span<const Vec3f>, bool);
template TriangleLeaves make_triangle_leaves<8>(const WideBvh<8>&, std::span<const Vec3f>, bool);
template TriangleLeaves make_triangle_leaves<4>(const WideBvh<4>&, const TriangleMesh&, bool);
template TriangleLeaves make_triangle_leaves<8>(const WideBvh<8>&, const TriangleMesh&, bool);
template TriangleLeaves make_triangle_leaves<4>(const WideBvh<4>&, std::span<const TriangleMesh>,
                                                std::span<const uint32_t>, bool);
template TriangleLeaves make_triangle_leaves<8>(const WideBvh<8>&, std::span<const TriangleMesh>,
                                                std::span<const uint32_t>, bool);

}  // namespace torte
