#include "geometry/subdivide.h"


#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <string>
#include <tuple>
#include <vector>

#include "core/error.h"
#include "core/huge_pages.h"
#include "core/interrupt.h"
#include "core/memory_budget.h"
#include "core/parallel.h"

namespace torte {

namespace {

constexpr size_t kGrain = 1 << 14;
constexpr uint64_t kMaxTriangles = kMaxSubdividedTriangles;

template <class Fn>
void parallel(size_t n, Fn fn) {
  parallel_for_blocks(size_t(0), n, kGrain, [&](IndexRange<size_t> r) {
    throw_if_interrupted("subdividing a mesh");  // a safe point per block: TBB rethrows in the caller
    for (size_t i = r.begin(); i != r.end(); ++i) fn(i);
  });
}

uint64_t mix64(uint64_t x) {  // splitmix64's finalizer: every input bit affects every output bit
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Uniform in [-1, 1) from the top 24 bits.
float signed_unit(uint64_t h) { return float(h >> 40) * 0x1p-23f - 1.0f; }

Vec3f face_normal(const TriangleMesh& m, size_t tri) {  // length = 2 x area
  const uint32_t* i = &m.indices[3 * tri];
  const Vec3f p0 = m.position(i[0]);
  return cross(m.position(i[1]) - p0, m.position(i[2]) - p0);
}

// Hash of a position's bits: equal positions (e.g. the two sides of a uv seam) get equal random numbers.
uint64_t position_hash(Vec3f p) {
  return mix64(std::bit_cast<uint32_t>(p.x) ^ mix64(uint64_t(std::bit_cast<uint32_t>(p.y)) << 32 |
                                                      std::bit_cast<uint32_t>(p.z)));
}

// Unit normal per vertex for displacement: area-weighted face normals summed over every vertex at the same
// position, so vertices split at uv seams or normal creases move together and the surface does not tear.
std::vector<Vec3f> welded_normals(const TriangleMesh& m) {
  const size_t V = m.vertex_count();
  std::vector<uint32_t> order(V);
  std::iota(order.begin(), order.end(), 0u);
  auto key = [&](uint32_t i) { return std::tuple(m.x[i], m.y[i], m.z[i], i); };
  parallel_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
  std::vector<uint32_t> canon(V);  // the lowest index at the same position
  for (size_t k = 0; k < V; ++k)
    canon[order[k]] = k > 0 && m.position(order[k]) == m.position(order[k - 1]) ? canon[order[k - 1]] : order[k];
  std::vector<Vec3f> sum(V);
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const Vec3f n = face_normal(m, t);
    for (int k = 0; k < 3; ++k) sum[canon[m.indices[3 * t + k]]] += n;
  }
  std::vector<Vec3f> dn(V);
  parallel(V, [&](size_t i) {
    const Vec3f n = sum[canon[i]];
    dn[i] = length_squared(n) > 0 ? normalize(n) : Vec3f();
  });
  return dn;
}

// One level. Edges are found without a hash map: half-edges are bucketed by their lower vertex (a counting
// sort), each small bucket is sorted by the upper vertex, and equal neighbours are one edge. Every pass is a
// parallel loop over half-edges or vertices; the atomic scatter leaves buckets in a racy order, but sorting
// each bucket by (upper vertex, half-edge id) makes the edge numbering deterministic.
// `dn` (displacement only) holds the displacement normal per vertex and is extended to the new vertices.
TriangleMesh subdivide_once(const TriangleMesh& m, float displacement, uint64_t seed, int level,
                            std::vector<Vec3f>* dn) {
  const size_t V = m.vertex_count(), T = m.triangle_count(), H = 3 * T;
  if (4 * uint64_t(T) > kMaxTriangles)
    throw Error("subdivide: the result would have " + std::to_string(4 * uint64_t(T)) +
                " triangles, more than 2^31");
  const uint32_t* idx = m.indices.data();
  auto ends = [idx](size_t h, uint32_t* lo, uint32_t* hi) {
    const uint32_t a = idx[h], b = idx[h % 3 == 2 ? h - 2 : h + 1];
    *lo = std::min(a, b);
    *hi = std::max(a, b);
  };

  // Bucket start per lower vertex.
  std::vector<uint32_t> start(V + 1, 0);
  parallel(H, [&](size_t h) {
    uint32_t lo, hi;
    ends(h, &lo, &hi);
    std::atomic_ref<uint32_t>(start[lo + 1]).fetch_add(1, std::memory_order_relaxed);
  });
  std::inclusive_scan(start.begin(), start.end(), start.begin());
  std::vector<uint64_t> entries(H);  // (upper vertex << 32) | half-edge id
  {
    std::vector<uint32_t> cursor(start.begin(), start.end() - 1);
    parallel(H, [&](size_t h) {
      uint32_t lo, hi;
      ends(h, &lo, &hi);
      const uint32_t pos = std::atomic_ref<uint32_t>(cursor[lo]).fetch_add(1, std::memory_order_relaxed);
      entries[pos] = uint64_t(hi) << 32 | h;
    });
  }
  // Sort each bucket and count its distinct edges; then number edges bucket by bucket.
  std::vector<uint32_t> edge_base(V + 1, 0);
  parallel(V, [&](size_t v) {
    uint64_t* b = entries.data() + start[v];
    uint64_t* e = entries.data() + start[v + 1];
    std::sort(b, e);
    uint32_t distinct = 0;
    for (uint64_t* p = b; p != e; ++p) distinct += p == b || (*p >> 32) != (p[-1] >> 32);
    edge_base[v + 1] = distinct;
  });
  std::inclusive_scan(edge_base.begin(), edge_base.end(), edge_base.begin());
  const size_t E = edge_base[V];
  if (V + E > UINT32_MAX) throw Error("subdivide: the result would have more than 2^32 vertices");

  TriangleMesh out;
  const size_t NV = V + E;
  const bool normals = m.has_normals(), uvs = m.has_uvs();
  auto grow = [&](std::vector<float>& dst, const std::vector<float>& src) {
    dst.resize(NV);
    std::memcpy(dst.data(), src.data(), V * sizeof(float));
  };
  grow(out.x, m.x), grow(out.y, m.y), grow(out.z, m.z);
  if (normals) grow(out.nx, m.nx), grow(out.ny, m.ny), grow(out.nz, m.nz);
  if (uvs) grow(out.u, m.u), grow(out.v, m.v);

  if (dn) dn->resize(NV);
  // Midpoint vertices, and the edge of each half-edge for building the triangles.
  std::vector<uint32_t> edge_of(H);
  const uint64_t level_seed = mix64(seed ^ mix64(uint64_t(level) + 0x5EED));
  parallel(V, [&](size_t lo) {
    const uint64_t* b = entries.data() + start[lo];
    const uint64_t* e = entries.data() + start[lo + 1];
    uint32_t edge = edge_base[lo];
    for (const uint64_t* p = b; p != e; ++edge) {
      const uint32_t hi = uint32_t(*p >> 32);
      const uint32_t a = uint32_t(lo);
      for (; p != e && uint32_t(*p >> 32) == hi; ++p) edge_of[uint32_t(*p)] = edge;
      const size_t nv = V + edge;
      const Vec3f pa = m.position(a), pb = m.position(hi);
      Vec3f p_mid = (pa + pb) * 0.5f;
      if (normals) {
        const Vec3f na = m.normal(a), sum = na + m.normal(hi);
        const Vec3f n = length_squared(sum) > 0 ? normalize(sum) : na;
        out.nx[nv] = n.x, out.ny[nv] = n.y, out.nz[nv] = n.z;
      }
      if (dn) {
        // Everything here is symmetric in the end points, so copies of an edge at a seam land together.
        const Vec3f sum = (*dn)[a] + (*dn)[hi];
        const Vec3f n = length_squared(sum) > 0 ? normalize(sum) : Vec3f();
        (*dn)[nv] = n;
        const float r = signed_unit(mix64(level_seed ^ (position_hash(pa) + position_hash(pb))));
        p_mid += n * (displacement * length(pb - pa) * r);
      }
      out.x[nv] = p_mid.x, out.y[nv] = p_mid.y, out.z[nv] = p_mid.z;
      if (uvs) {
        out.u[nv] = 0.5f * (m.u[a] + m.u[hi]);
        out.v[nv] = 0.5f * (m.v[a] + m.v[hi]);
      }
    }
  });
  free_storage(entries);
  free_storage(start);

  // (a, b, c) with midpoints ab, bc, ca -> three corner triangles and the middle one, same winding.
  out.indices.resize(12 * T);
  uint32_t* o = out.indices.data();
  parallel(T, [&](size_t t) {
    const uint32_t a = idx[3 * t], b = idx[3 * t + 1], c = idx[3 * t + 2];
    const uint32_t ab = uint32_t(V + edge_of[3 * t]), bc = uint32_t(V + edge_of[3 * t + 1]),
                   ca = uint32_t(V + edge_of[3 * t + 2]);
    const uint32_t tris[12] = {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca};
    std::memcpy(o + 12 * t, tris, sizeof tris);
  });
  return out;
}

}  // namespace

void compute_vertex_normals(TriangleMesh& m) {
  const size_t V = m.vertex_count();
  // Accumulated serially, in triangle order, so the sums (and normals) are identical on every run.
  std::vector<Vec3f> sum(V);
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const Vec3f n = face_normal(m, t);
    for (int k = 0; k < 3; ++k) sum[m.indices[3 * t + k]] += n;
  }
  m.nx.resize(V), m.ny.resize(V), m.nz.resize(V);
  parallel(V, [&](size_t i) {
    const float len = length(sum[i]);
    const Vec3f n = len > 0 ? sum[i] / len : Vec3f();
    m.nx[i] = n.x, m.ny[i] = n.y, m.nz[i] = n.z;
  });
}

SubdivisionSize subdivision_size(const TriangleMesh& mesh, int levels, bool displaced) {
  SubdivisionSize r;
  const uint64_t per_vertex = 12 + (mesh.has_normals() ? 12 : 0) + (mesh.has_uvs() ? 8 : 0) + (displaced ? 12 : 0);
  uint64_t t = mesh.triangle_count(), v = mesh.vertex_count();
  r.triangles = t, r.vertices = v;
  for (int level = 1; level <= levels; ++level) {
    if (t > kMaxTriangles) {  // 4^levels would overflow long before the memory matters
      r.triangles = UINT64_MAX;
      return r;
    }
    // One level holds its input and output meshes and the edge scratch (8 + 4 bytes per half-edge, 8 per
    // vertex). Each triangle adds at most 3 edges, hence 3 vertices (a closed mesh: 1.5).
    const uint64_t t_out = 4 * t, v_out = v + 3 * t;
    const uint64_t peak = 12 * t + per_vertex * v + 12 * t_out + per_vertex * v_out + 36 * t + 8 * v;
    r.peak_bytes = std::max(r.peak_bytes, peak);
    t = t_out, v = v_out;
  }
  r.triangles = t, r.vertices = v;
  return r;
}

TriangleMesh subdivide(const TriangleMesh& mesh, int levels, float displacement, uint64_t seed) {
  if (levels < 0) throw Error("subdivide: levels must be >= 0, got " + std::to_string(levels));
  if (!std::isfinite(displacement)) throw Error("subdivide: displacement must be finite");
  mesh.validate("subdivide");
  if (levels == 0) return mesh;
  // The whole result is checked before the first level runs.
  const SubdivisionSize size = subdivision_size(mesh, levels, displacement != 0);
  const std::string what = "subdivide: " + std::to_string(levels) + " levels of " +
                           std::to_string(mesh.triangle_count()) + " triangles";
  if (size.triangles > kMaxTriangles) {
    char count[32];
    std::snprintf(count, sizeof count, "%.3g", double(mesh.triangle_count()) * std::pow(4.0, levels));
    throw Error(what + " would give " + count + " triangles, more than the limit of 2^31 (" +
                std::to_string(kMaxTriangles) + ")");
  }
  reserve_memory(size.peak_bytes, what + " (" + std::to_string(size.triangles) + " triangles)");
  std::vector<Vec3f> dn;
  if (displacement != 0) dn = welded_normals(mesh);
  std::vector<Vec3f>* dn_ptr = displacement != 0 ? &dn : nullptr;
  TriangleMesh current = subdivide_once(mesh, displacement, seed, 1, dn_ptr);
  for (int level = 2; level <= levels; ++level) {
    throw_if_interrupted("subdividing a mesh");
    current = subdivide_once(current, displacement, seed, level, dn_ptr);
  }
  if (displacement != 0 && current.has_normals()) compute_vertex_normals(current);
  return current;
}

}  // namespace torte
