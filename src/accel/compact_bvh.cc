// The compact layout's node builder: quantize (WideBvh<8> -> CompactBvh, accel/compact_bvh.h).

#include "accel/compact_bvh.h"

#include <algorithm>
#include <cmath>
#include "core/parallel.h"

namespace torte {

namespace {

// The grid of one axis: origin `lo` and the smallest power-of-two scale whose 255 steps reach `hi`, checked with
// the dequantisation's own float arithmetic (lo + 255 * scale, one rounding).
float grid_scale(float lo, float hi) {
  const float range = hi - lo;
  int e = -126;
  if (range > 0) {
    std::frexp(range / 255.0f, &e);  // range / 255 < 2^e
    e = std::max(e - 1, -126);
  }
  float scale = std::ldexp(1.0f, e);
  while (lo + 255.0f * scale < hi) scale *= 2;  // the rounding of the division or of the sum fell short
  return scale;
}

// Child bounds [clo, chi] on the grid (origin, scale): q_lo rounded down, q_hi up, each checked against the
// dequantised value so the box never shrinks.
void quantize_interval(float origin, float scale, float clo, float chi, uint8_t* q_lo, uint8_t* q_hi) {
  float lo = std::floor((clo - origin) / scale), hi = std::ceil((chi - origin) / scale);
  lo = std::clamp(lo, 0.0f, 255.0f), hi = std::clamp(hi, 0.0f, 255.0f);
  while (lo > 0 && origin + lo * scale > clo) lo -= 1;
  while (hi < 255 && origin + hi * scale < chi) hi += 1;
  *q_lo = uint8_t(lo), *q_hi = uint8_t(hi);
}

}  // namespace

CompactBvh quantize(WideBvh<8>&& wide) {
  CompactBvh out;
  out.bounds = wide.bounds;
  out.prim_indices = std::move(wide.prim_indices);
  const size_t n = wide.nodes.size();
  out.nodes = make_huge_page_vector<QuantNode>(n);
  const auto convert = [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const WideNode<8>& w = wide.nodes[i];
      QuantNode& q = out.nodes[i];
      const float* lo[3] = {w.lo_x, w.lo_y, w.lo_z};
      const float* hi[3] = {w.hi_x, w.hi_y, w.hi_z};
      q.occupied = 0;
      for (int c = 0; c < 8; ++c) {
        q.child[c] = w.child[c];
        q.leaf_count[c] = w.leaf_count[c];
        if (w.child[c] != kEmptyChild) q.occupied |= uint8_t(1u << c);
      }
      for (int a = 0; a < 3; ++a) {
        float node_lo = kInfinity, node_hi = -kInfinity;
        for (int c = 0; c < 8; ++c)
          if ((q.occupied >> c) & 1) node_lo = std::min(node_lo, lo[a][c]), node_hi = std::max(node_hi, hi[a][c]);
        if (q.occupied == 0) node_lo = node_hi = 0;
        q.origin[a] = node_lo;
        q.scale[a] = grid_scale(node_lo, node_hi);
        for (int c = 0; c < 8; ++c) {
          if ((q.occupied >> c) & 1) {
            quantize_interval(q.origin[a], q.scale[a], lo[a][c], hi[a][c], &q.q[a][c], &q.q[3 + a][c]);
          } else {
            q.q[a][c] = 255, q.q[3 + a][c] = 0;  // inverted; `occupied` keeps rays out anyway
          }
        }
      }
    }
  };
  parallel_for_blocks(size_t(0), n, 4096, [&](IndexRange<size_t> r) { convert(r.begin(), r.end()); });
  free_storage(wide.nodes);
  for (const QuantNode& q : out.nodes)
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 8; ++c)
        if ((q.occupied >> c) & 1)
          out.plane_extent[a] = std::max({out.plane_extent[a], std::fabs(dequantize(q, a, q.q[a][c])),
                                          std::fabs(dequantize(q, a, q.q[3 + a][c]))});
  return out;
}

}  // namespace torte
