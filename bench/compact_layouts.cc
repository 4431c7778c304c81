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
    case Layout::kPackedLeaves: return "packed-leaves";
    case Layout::kCompact: return "compact";
  }
  return "?";
}

CompactAccel build_compact(const TorteAccel<8>& a, const TriangleMesh& mesh) {
  CompactAccel c;
  c.quant = quantize(WideBvh<8>(a.bvh));  // copies: quantize consumes its tree
  const uint32_t first = 0;
  const std::span<const TriangleMesh> meshes(&mesh, 1);
  const std::span<const uint32_t> mesh_first(&first, 1);
  c.wide_packed = a.bvh;
  c.packed = make_packed_leaves(c.wide_packed, meshes, mesh_first);
  c.quant_packed = quantize(WideBvh<8>(c.wide_packed));
  return c;
}

double layout_bytes_per_triangle(Layout l, const TorteAccel<8>& a, const CompactAccel& c, size_t triangles) {
  const bool quant = l == Layout::kQuantNodes || l == Layout::kCompact;
  const bool packed = l == Layout::kPackedLeaves || l == Layout::kCompact;
  const size_t nodes = quant ? c.quant.nodes.size() * sizeof(QuantNode) : a.bvh.nodes.size() * sizeof(WideNode<8>);
  const size_t leaves = packed ? c.packed.memory_bytes() : a.leaves.memory_bytes();
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
    case Layout::kPackedLeaves: return trace_with(c.wide_packed, c.packed, rays, n, hits, occluded, packet);
    case Layout::kCompact: return trace_with(c.quant_packed, c.packed, rays, n, hits, occluded, packet);
  }
}

}  // namespace torte::bench
