// The compact triangle layouts (accel/compact_bvh.h) of a benchmark scene, for embree-compare --compact: the
// default tree's nodes quantised, its leaves packed with their own vertices (accel/packed_leaves.h), and both;
// traced through the same kernels (simd/traverse.h) as the default layout, next to it, in the same run.
#pragma once
#include <cstddef>
#include <cstdint>

#include "accel/compact_bvh.h"
#include "accel/hit.h"
#include "accel/packed_leaves.h"
#include "workloads.h"

namespace torte::bench {

enum class Layout { kDefault, kQuantNodes, kPackedLeaves, kCompact };
constexpr Layout kCompactLayouts[] = {Layout::kQuantNodes, Layout::kPackedLeaves, Layout::kCompact};
constexpr Layout kAllLayouts[] = {Layout::kDefault, Layout::kQuantNodes, Layout::kPackedLeaves, Layout::kCompact};
/// "default", "quant-nodes", "packed-leaves", "compact" (both).
const char* layout_name(Layout l);

/// The compact parts of `a`'s tree over `mesh`: its nodes quantised (with the default leaves), its packed leaves
/// under a copy of its nodes and under quantised nodes (both with their leaf references rewritten).
struct CompactAccel {
  CompactBvh quant;
  WideBvh<8> wide_packed;
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
