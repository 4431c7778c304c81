// The compact layout's builders: quantize (WideBvh<8> -> CompactBvh) and make_indexed_leaves (accel/compact_bvh.h).

#include "accel/compact_bvh.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "geometry/mesh.h"

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

namespace {
// The vertex copy: 3 floats per vertex and the padding (zero).
void allocate_vertices(IndexedLeaves& leaves, size_t vertices) {
  leaves.vertices = vertices;
  leaves.owned_xyz = make_huge_page_vector<float>(3 * vertices + IndexedLeaves::kPadding);
  leaves.xyz = leaves.owned_xyz.data();
}
}  // namespace

IndexedLeaves make_indexed_leaves(size_t triangles, const TriangleMesh& mesh) {
  if (mesh.placed() || mesh.triangle_count() < triangles)
    throw Error("internal: indexed leaves borrow the leaf-order triples of an owned mesh");
  IndexedLeaves leaves;
  leaves.triangles = triangles;
  leaves.idx = mesh.indices.data();
  allocate_vertices(leaves, mesh.vertex_count());
  float* const out = leaves.owned_xyz.data();
  parallel_for_blocks(size_t(0), leaves.vertices, 65536, [&](IndexRange<size_t> r) {
    for (size_t v = r.begin(); v < r.end(); ++v)
      out[3 * v] = mesh.x[v], out[3 * v + 1] = mesh.y[v], out[3 * v + 2] = mesh.z[v];
  });
  return leaves;
}

IndexedLeaves make_indexed_leaves(std::span<const uint32_t> prim_indices, std::span<const TriangleMesh> meshes,
                                  std::span<const uint32_t> mesh_first) {
  if (mesh_first.size() != meshes.size())
    throw Error("Indexed leaves: " + std::to_string(mesh_first.size()) + " first triangles for " +
                std::to_string(meshes.size()) + " meshes.");
  IndexedLeaves leaves;
  const size_t n = prim_indices.size();
  leaves.triangles = n;
  // Global vertex numbering: mesh after mesh. remap: global vertex -> its number here, by first use.
  std::vector<size_t> vertex_first(meshes.size() + 1, 0);
  for (size_t m = 0; m < meshes.size(); ++m) vertex_first[m + 1] = vertex_first[m] + meshes[m].vertex_count();
  if (vertex_first.back() >= kEmptyChild) throw Error("more than 2^32 - 1 vertices in one scene or group");
  std::vector<uint32_t> remap(vertex_first.back(), kEmptyChild), used;  // used: new number -> global vertex
  const auto global_vertex = [&](uint32_t g, int k) {
    const uint32_t m = mesh_holding(mesh_first, g);
    return uint32_t(vertex_first[m] + meshes[m].triangle(g - mesh_first[m])[k]);
  };
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      const uint32_t gv = global_vertex(prim_indices[i], k);
      if (remap[gv] == kEmptyChild) remap[gv] = uint32_t(used.size()), used.push_back(gv);
    }
  allocate_vertices(leaves, used.size());
  leaves.owned_idx = make_huge_page_vector<uint32_t>(3 * n);
  uint32_t* const idx = leaves.owned_idx.data();
  parallel_for_blocks(size_t(0), n, 65536, [&](IndexRange<size_t> r) {
    for (size_t i = r.begin(); i < r.end(); ++i)
      for (int k = 0; k < 3; ++k) idx[3 * i + size_t(k)] = remap[global_vertex(prim_indices[i], k)];
  });
  float* const out = leaves.owned_xyz.data();
  parallel_for_blocks(size_t(0), used.size(), 65536, [&](IndexRange<size_t> r) {
    for (size_t v = r.begin(); v < r.end(); ++v) {
      const size_t gv = used[v];
      const auto after = std::upper_bound(vertex_first.begin(), vertex_first.end(), gv);
      const size_t m = size_t(after - vertex_first.begin()) - 1;
      const Vec3f p = meshes[m].position(uint32_t(gv - vertex_first[m]));
      out[3 * v] = p.x, out[3 * v + 1] = p.y, out[3 * v + 2] = p.z;
    }
  });
  leaves.idx = leaves.owned_idx.data();
  return leaves;
}

IndexedLeaves make_indexed_leaves(std::span<const uint32_t> prim_indices, std::span<const Vec3f> vertices) {
  IndexedLeaves leaves;
  const size_t n = prim_indices.size();
  leaves.triangles = n;
  allocate_vertices(leaves, 3 * n);
  leaves.owned_idx = make_huge_page_vector<uint32_t>(3 * n);
  for (size_t i = 0; i < n; ++i) {
    if (3 * size_t(prim_indices[i]) + 2 >= vertices.size())
      throw Error("Indexed leaves: primitive " + std::to_string(prim_indices[i]) + " is out of range.");
    for (int k = 0; k < 3; ++k) {
      const Vec3f v = vertices[3 * size_t(prim_indices[i]) + size_t(k)];
      leaves.owned_idx[3 * i + size_t(k)] = uint32_t(3 * i + size_t(k));
      for (int a = 0; a < 3; ++a) leaves.owned_xyz[3 * (3 * i + size_t(k)) + size_t(a)] = v[a];
    }
  }
  leaves.idx = leaves.owned_idx.data();
  return leaves;
}

}  // namespace torte
