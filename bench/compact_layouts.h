// The compact triangle layouts (accel/compact_bvh.h) of a benchmark scene, for embree-compare --compact: the
// default tree's nodes quantised, its leaves as indices into shared vertices, and both; traced through the same
// kernels (simd/traverse.h) as the default layout, next to it, in the same run.
#pragma once
#include <cstddef>
#include <cstdint>

#include "accel/compact_bvh.h"
#include "accel/hit.h"
#include "accel/packed_leaves.h"
#include "workloads.h"

namespace torte::bench {

enum class Layout { kDefault, kQuantNodes, kIndexedLeaves, kCompact, kPackedLeaves, kCompactPacked };
constexpr Layout kCompactLayouts[] = {Layout::kQuantNodes, Layout::kIndexedLeaves, Layout::kCompact,
                                      Layout::kPackedLeaves, Layout::kCompactPacked};
constexpr Layout kAllLayouts[] = {Layout::kDefault,      Layout::kQuantNodes,   Layout::kIndexedLeaves,
                                  Layout::kCompact,      Layout::kPackedLeaves, Layout::kCompactPacked};
/// "default", "quant-nodes", "indexed-leaves", "compact" (quant + indexed), "packed-leaves", "compact-packed".
const char* layout_name(Layout l);

/// The compact parts of `a`'s tree over `mesh` (one mesh: the leaves own their triples and the vertices in order
/// of first use, as a placed or several-mesh scene's do).
struct CompactAccel {
  CompactBvh quant;
  IndexedLeaves indexed;
  WideBvh<8> wide_packed;  // the default tree with its leaf references rewritten to the packed blocks
  CompactBvh quant_packed;
  PackedLeaves packed;
};
CompactAccel build_compact(const TorteAccel<8>& a, const TriangleMesh& mesh);

/// Bytes per triangle of layout `l`: nodes + leaves (+ prim_indices, as TorteAccel::bytes counts them).
double layout_bytes_per_triangle(Layout l, const TorteAccel<8>& a, const CompactAccel& c, size_t triangles);

/// Rays [0, n) of `rays` through layout `l`: closest hits into `hits` or occlusion into `occluded` (the other
/// null), one ray at a time or in packets of `packet` (0: single rays).
void trace_layout(Layout l, const TorteAccel<8>& a, const CompactAccel& c, const RaySoA& rays, size_t n, Hit* hits,
                  uint8_t* occluded, int packet);

}  // namespace torte::bench
