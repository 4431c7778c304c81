// Parallel binned-SAH BVH builder (Wald 2007) and its collapse into the wide layout of wide_bvh.h.
//
// Pipeline: build_binary_bvh writes one canonical binary tree straight into a flat node array (children are
// allocated as adjacent pairs by an atomic counter, so parallel subtree tasks never share a write and no pointer
// tree or linearisation pass exists); collapse<N> groups binary nodes into N-wide nodes (bvh_collapse.cc);
// make_triangle_leaves copies triangle vertices into leaf order. build_wide_bvh<N> runs the first two steps.
//
// Determinism: the tree's structure and its primitive order depend only on the input and the options, never on
// the thread count or on scheduling (binning reduces with min/max and integer sums, which are exact in any
// order; partitions and small-node sorts run serially inside their task). Only the binary node *indices* depend
// on scheduling; the collapse computes each node's choice from its children's alone and emits the tree in child
// order, so the wide tree is identical bit for bit whatever the thread count (tested).
//
// Primitives with empty (or NaN) bounds can never be hit: they are left out of the tree and of prim_indices,
// as in bvh2.cc. Infinite bounds throw torte::Error.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "accel/wide_bvh.h"
#include "core/bounds.h"
#include "core/progress_counter.h"
#include "core/vec.h"

namespace torte {

struct TriangleMesh;

// Default node width for triangle meshes. With the SAH-optimal collapse, N = 4 and N = 8 cost the same node
// bytes per triangle (9.1 and 9.0 on the dragon at the default options: half the nodes at twice the size), and
// N = 8 has the lower SAH cost (9.5 against 12.8, one traversal cost per node visit either way) and fills one
// AVX2 vector with 8 boxes. The measured table is printed by test_bvh_build_mesh.cc "[.bvh_report]".
constexpr int kDefaultBvhWidth = 8;

// How binary nodes are grouped into N-wide nodes.
enum class CollapseMode {
  // Ylitie, Karras & Laine 2017 ("Efficient incoherent ray traversal on GPUs through compressed wide BVHs",
  // sec. 3.1): dynamic programming over the binary tree picks, for every wide node, which descendants fill its N
  // slots and which subtrees (of at most max_leaf_size primitives) become one leaf, minimising the wide tree's
  // SAH cost. It fills nodes far better than the greedy rule (bottom nodes no longer keep 2-3 children), which
  // is what brings N = 8 nodes under the memory budget.
  SahOptimal,
  // Greedy: open the largest-surface-area interior child until N slots are filled (the classic collapse);
  // leaves stay the binary tree's. Kept for comparison.
  LargestArea,
};

// Memory on the 100k-triangle dragon at the defaults: N = 8 nodes 6.8 B/tri, leaves 36.0 (+ 0.1 leaf-start
// bitmap). prim_indices (4.0) is needed only until a renderer has put its meshes in leaf order, which
// GeometrySet does (accel/geometry_set.h): the finished scene holds 61.0 B/tri with the mesh's indices and normals
// (test_geometry_set.cc checks <= 64, the issue "SIMD core" budget). Per-triangle SAH leaf costs (block 1) make
// leaves of 1.8 triangles on average and 29 B/tri of nodes; block 4 makes leaves of 5.7 and 9.0 B/tri of nodes.
struct BvhBuildOptions {
  // Leaves never hold more (hard cap 16: kernels load one or two vectors per leaf, and leaf_count is a byte).
  int max_leaf_size = 8;
  // Bins per axis over the centroid bounds, 1..64; 1 means object-median splits (no SAH). Nodes of at most 16
  // primitives are split exactly (every position along sorted centroids) whatever this is, when it is >= 2.
  int bins = 16;
  // SAH costs. A leaf costs intersection_cost per started block of leaf_block_size primitives, because the
  // kernels test that many triangles with one vector op: the single-ray kernel tests up to 8 leaf triangles in
  // one 8-lane group, so a leaf of 1..8 costs the same and the SAH stops splitting small nodes that a finer model
  // would cut into tiny leaves (which cost node memory). Against block 4 (2026-11-22, embree-compare, 1 thread,
  // two alternating runs): builds 12-17 % faster and 2.2 B/tri less node memory; traversal within noise (ratio
  // to Embree, diffuse single rays: bunny 1.12 against 1.15-1.20, dragon 1.07-1.10 against 1.08-1.18, the
  // 1M-16M bunnies within 0.01; primary packets within 0.07 either way).
  float traversal_cost = 1.0f;
  float intersection_cost = 1.0f;
  int leaf_block_size = 8;  // 1, 2, 4, 8 or 16
  CollapseMode collapse = CollapseMode::SahOptimal;
  // Executor seam: false runs every step on the calling thread (tests; callers that parallelise above us).
  bool parallel = true;
  // When set, the binary build adds every primitive to progress->done once the subtree holding it is built
  // (in steps of whole serial subtrees); the caller sets progress->total.
  ProgressCounter* progress = nullptr;
};

// 32 bytes, two per cache line. Interior (count == 0): children are nodes first and first + 1. Leaf: primitives
// prim_indices[first, first + count).
struct BinaryBvhNode {
  Bounds3f bounds;
  uint32_t first;
  uint32_t count;
};
static_assert(sizeof(BinaryBvhNode) == 32);

// Root at index 0 (nodes is empty when no primitive has non-empty bounds). prim_indices lists the primitives in
// depth-first leaf order (left child first), so every leaf's range follows its left sibling's.
struct BinaryBvh {
  HugePageVector<BinaryBvhNode> nodes;  // huge pages (core/huge_pages.h): fewer page faults while building
  HugePageVector<uint32_t> prim_indices;
  size_t memory_bytes() const { return nodes.size() * sizeof(BinaryBvhNode) + prim_indices.size() * 4; }
};

// Deepest leaf level of every tree built here (root = 0). Collapsing never deepens a tree, so a traversal
// of WideBvh<N> that pushes at most N - 1 entries per level needs kMaxBvhDepth * (N - 1) + 1 entries:
// kWideStackSize<N> (64 per level) never overflows.
constexpr int kMaxBvhDepth = 60;
template <int N>
constexpr int kWideStackSize = 64 * N;

/// Writes the bounds of primitives [begin, end) to out[0, end - begin). Called once per primitive, on fixed
/// chunks of the range, from several threads at once (when options.parallel).
using PrimBoundsFn = std::function<void(size_t begin, size_t end, Bounds3f* out)>;

// Throws torte::Error for out-of-range options, infinite bounds or more than 2^31 - 1 primitives.
BinaryBvh build_binary_bvh(std::span<const Bounds3f> prim_bounds, const BvhBuildOptions& options = {});
/// Same over `count` primitives whose bounds come from `bounds`, so no array of them is held: a build's peak is
/// its 32-byte references, the binary nodes being written and then the primitive order.
BinaryBvh build_binary_bvh(size_t count, const PrimBoundsFn& bounds, const BvhBuildOptions& options = {});

// Wide nodes in depth-first pre-order (a node precedes its subtree; its children's subtrees follow in slot
// order), root at 0. Occupied slots come first in each node, in the binary tree's left-to-right order, so leaf
// order (and prim_indices) equals the binary tree's; a wide leaf is one binary leaf or, with SahOptimal, a whole
// binary subtree of at most options.max_leaf_size primitives. A tree that is a single leaf becomes a root with
// one leaf child. Uses options' costs, max_leaf_size, collapse and parallel. Throws torte::Error if a leaf
// holds more than 255 primitives.
template <int N>
WideBvh<N> collapse(const BinaryBvh& binary, const BvhBuildOptions& options = {});
// Writes one wide node: slots [0, k) from bounds, child references and leaf counts (used for leaf children
// only), the other slots empty (lo = +inf, hi = -inf, kEmptyChild). Throws torte::Error for a leaf of more than
// 255 primitives. For builders that make wide nodes from trees of their own.
template <int N>
void write_wide_node(WideNode<N>& w, int k, const Bounds3f* bounds, const uint32_t* child, const uint32_t* count);

template <int N>
WideBvh<N> build_wide_bvh(std::span<const Bounds3f> prim_bounds, const BvhBuildOptions& options = {});
template <int N>
WideBvh<N> build_wide_bvh(size_t count, const PrimBoundsFn& bounds, const BvhBuildOptions& options = {});

// SAH cost of a leaf of `count` primitives: intersection_cost per started block of leaf_block_size.
float leaf_sah_cost(uint32_t count, const BvhBuildOptions& options);

// SAH cost of a tree in units of options' costs: each node visit costs traversal_cost, each leaf
// intersection_cost per started leaf_block_size block, weighted by surface area relative to the root (every
// node counts as visited when the root has zero area). Comparable between trees of the same width.
float sah_cost(const BinaryBvh& bvh, const BvhBuildOptions& options = {});
template <int N>
float sah_cost(const WideBvh<N>& bvh, const BvhBuildOptions& options = {});

struct BvhStats {
  size_t nodes = 0;
  size_t leaves = 0;
  size_t primitives = 0;
  double avg_leaf_size = 0;
  double avg_children = 0;  // occupied slots per wide node (N at best)
  int max_depth = 0;        // deepest node level, root = 0 (a leaf child sits one below its node)
  size_t node_bytes = 0;
  size_t index_bytes = 0;   // prim_indices
};
template <int N>
BvhStats bvh_stats(const WideBvh<N>& bvh);

// Triangle vertices in leaf order, laid out per leaf of `bvh` (wide_bvh.h): leaf-order entry i holds the
// triangle bvh.prim_indices[i], read from `vertices`, which has three entries (p0, p1, p2) per triangle of the
// caller's numbering. Padded as wide_bvh.h describes (empty for no triangles). Throws torte::Error for an index
// out of range. `parallel`: the executor seam, as in the options.
template <int N>
TriangleLeaves make_triangle_leaves(const WideBvh<N>& bvh, std::span<const Vec3f> vertices, bool parallel = true);
// Same, with the vertices looked up through the mesh's index triples (the mesh must pass
// TriangleMesh::validate; only prim_indices are range-checked here).
template <int N>
TriangleLeaves make_triangle_leaves(const WideBvh<N>& bvh, const TriangleMesh& mesh, bool parallel = true);
// Same over several meshes numbered one after another: mesh m's triangle t is triangle mesh_first[m] + t
// (mesh_first ascending, one entry per mesh, mesh_first[0] = 0).
template <int N>
TriangleLeaves make_triangle_leaves(const WideBvh<N>& bvh, std::span<const TriangleMesh> meshes,
                                    std::span<const uint32_t> mesh_first, bool parallel = true);

extern template void write_wide_node<4>(WideNode<4>&, int, const Bounds3f*, const uint32_t*, const uint32_t*);
extern template void write_wide_node<8>(WideNode<8>&, int, const Bounds3f*, const uint32_t*, const uint32_t*);
extern template WideBvh<4> collapse<4>(const BinaryBvh&, const BvhBuildOptions&);
extern template WideBvh<8> collapse<8>(const BinaryBvh&, const BvhBuildOptions&);
extern template WideBvh<4> build_wide_bvh<4>(std::span<const Bounds3f>, const BvhBuildOptions&);
extern template WideBvh<8> build_wide_bvh<8>(std::span<const Bounds3f>, const BvhBuildOptions&);
extern template WideBvh<4> build_wide_bvh<4>(size_t, const PrimBoundsFn&, const BvhBuildOptions&);
extern template WideBvh<8> build_wide_bvh<8>(size_t, const PrimBoundsFn&, const BvhBuildOptions&);
extern template float sah_cost<4>(const WideBvh<4>&, const BvhBuildOptions&);
extern template float sah_cost<8>(const WideBvh<8>&, const BvhBuildOptions&);
extern template BvhStats bvh_stats<4>(const WideBvh<4>&);
extern template BvhStats bvh_stats<8>(const WideBvh<8>&);
extern template TriangleLeaves make_triangle_leaves<4>(const WideBvh<4>&, std::span<const Vec3f>, bool);
extern template TriangleLeaves make_triangle_leaves<8>(const WideBvh<8>&, std::span<const Vec3f>, bool);
extern template TriangleLeaves make_triangle_leaves<4>(const WideBvh<4>&, const TriangleMesh&, bool);
extern template TriangleLeaves make_triangle_leaves<8>(const WideBvh<8>&, const TriangleMesh&, bool);
extern template TriangleLeaves make_triangle_leaves<4>(const WideBvh<4>&, std::span<const TriangleMesh>,
                                                       std::span<const uint32_t>, bool);
extern template TriangleLeaves make_triangle_leaves<8>(const WideBvh<8>&, std::span<const TriangleMesh>,
                                                       std::span<const uint32_t>, bool);

}  // namespace torte
