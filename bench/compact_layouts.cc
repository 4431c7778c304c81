#include "compact_layouts.h"

#include <span>
#include <utility>

#include "geometry/mesh.h"
#include "traverse.h"

namespace torte::bench {

const char* layout_name(Layout l) {
  switch (l) {
    case Layout::kDefault: return "default";
    case Layout::kQuantNodes: return "quant-nodes";
    case Layout::kIndexedLeaves: return "indexed-leaves";
    case Layout::kCompact: return "compact";
  }
  return "?";
}

CompactAccel build_compact(const TorteAccel<8>& a, const TriangleMesh& mesh) {
  CompactAccel c;
  WideBvh<8> copy;
  copy.nodes.assign(a.bvh.nodes.begin(), a.bvh.nodes.end());
  copy.prim_indices.assign(a.bvh.prim_indices.begin(), a.bvh.prim_indices.end());
  copy.bounds = a.bvh.bounds;
  c.quant = quantize(std::move(copy));
  const uint32_t first = 0;
  c.indexed = make_indexed_leaves(a.bvh.prim_indices, std::span<const TriangleMesh>(&mesh, 1),
                                  std::span<const uint32_t>(&first, 1));
  return c;
}

double layout_bytes_per_triangle(Layout l, const TorteAccel<8>& a, const CompactAccel& c, size_t triangles) {
  const bool quant = l == Layout::kQuantNodes || l == Layout::kCompact;
  const bool indexed = l == Layout::kIndexedLeaves || l == Layout::kCompact;
  const size_t nodes = quant ? c.quant.nodes.size() * sizeof(QuantNode) : a.bvh.nodes.size() * sizeof(WideNode<8>);
  const size_t leaves = indexed ? c.indexed.memory_bytes() : a.leaves.memory_bytes();
  return double(nodes + leaves + a.bvh.prim_indices.size() * sizeof(uint32_t)) / double(triangles);
}

namespace {
template <class Tree, class Leaves>
void trace_with(const Tree& t, const Leaves& l, const RaySoA& rays, size_t n, Hit* hits, uint8_t* occluded,
                int packet) {
  if (hits) {
    if (packet) intersect_closest_packets(t, l, rays, n, hits, packet);
    else intersect_closest(t, l, rays, n, hits);
  } else {
    if (packet) intersect_any_packets(t, l, rays, n, occluded, packet);
    else intersect_any(t, l, rays, n, occluded);
  }
}
}  // namespace

void trace_layout(Layout l, const TorteAccel<8>& a, const CompactAccel& c, const RaySoA& rays, size_t n, Hit* hits,
                  uint8_t* occluded, int packet) {
  switch (l) {
    case Layout::kDefault: return trace_with(a.bvh, a.leaves, rays, n, hits, occluded, packet);
    case Layout::kQuantNodes: return trace_with(c.quant, a.leaves, rays, n, hits, occluded, packet);
    case Layout::kIndexedLeaves: return trace_with(a.bvh, c.indexed, rays, n, hits, occluded, packet);
    case Layout::kCompact: return trace_with(c.quant, c.indexed, rays, n, hits, occluded, packet);
  }
}

}  // namespace torte::bench
