// The packet traversal kernel and its batch drivers, templates over the tree and leaf layouts (layout-inl.h),
// included by traverse_packet*.cc (the default layout) and traverse_compact_*.cc inside their foreach_target, after
// the other -inl headers, compiled without FMA contraction (see traverse.cc).
// Packet traversal: P = 8 or 16 consecutive rays per packet, lanes = rays
// (CappedTag<float, P>; narrower targets loop over lane groups). See traverse.h for the semantics; the packet
// itself (per-lane state, set-up, lane queries) is in packet-inl.h, its node and leaf tests in packet_tests-inl.h.
// Nodes: each child box is tested against all rays of the packet that reached the node; a child is skipped when
// none of them hits it, and hit children are visited in order of the smallest entry distance among their rays.
// Each stack entry carries the lanes that hit its box, so lane groups without such rays are skipped below it.
// Leaves: one triangle at a time against all lanes, with the watertight test of traverse-inl.h.
// In a same-octant packet the node's children are first tested against the packet's interval of origins / inverse
// directions (one vector test for all N children, Reshetov et al. 2005); the interval's far bound is the largest
// t_max of the packet, which closest hit lowers as its lanes find hits. Closest hit then takes the interval's
// verdict for interior children (they inherit the node's lanes and are ordered by the interval's entry bound) and
// tests only leaf children lane by lane, unless the packet's rays have parted (per-lane mode, see PacketStats);
// any hit tests the survivors lane by lane (it needs live-lane counts for the single-ray fallback). Closest-hit
// leaves of such packets test the interval against each triangle's bounds first (8 triangles per vector) and
// skip the triangles it misses: three quarters of them for camera packets. The any-hit leaf test skips the
// division when no lane is inside the triangle; closest hit, where that is a coin toss after the culling, runs
// branch-free.
// Any hit, and closest hit in per-lane mode: once an entry holds few live rays (kSingleThreshold,
// kClosestSingleThreshold) its subtree is traced one ray at a time with the single-ray kernel (Benthin et al.
// 2012). Any hit visits children in any order (no entry distances computed).
// Rays that are done (invalid input, padding past `count`, occluded in an any-hit query) get t_max = -inf, which
// fails every slab and triangle test, so they never disturb the others; an any-hit packet stops when all its
// rays are occluded.

// Per-target include guard (Highway's pattern).
#if defined(TORTE_SIMD_PACKET_TRACE_INL_H_TARGET) == defined(HWY_TARGET_TOGGLE)
#ifdef TORTE_SIMD_PACKET_TRACE_INL_H_TARGET
#undef TORTE_SIMD_PACKET_TRACE_INL_H_TARGET
#else
#define TORTE_SIMD_PACKET_TRACE_INL_H_TARGET
#endif

#include <hwy/cache_control.h>  // Stream, FlushStream
#include <hwy/highway.h>

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "accel/hit.h"
#include "layout-inl.h"
#include "packet-inl.h"
#include "packet_tests-inl.h"
#include "traverse-inl.h"
#include "traverse_single-inl.h"

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {
namespace {

using traverse_detail::kMaxWideDepth;

// Any hit: a packet entry with at most this many live rays is traced one ray at a time (measured on the dragon's
// shadow rays, AVX2, wide8: 6 of 16 and 3 of 8 were best; 0 and "always single" were both ~25% slower).
template <size_t P>
constexpr int kSingleThreshold = P == 16 ? 6 : 3;
// Closest hit in per-lane mode (below): the same hand-over at half the packet (8 of 16 on bunny-16m, AVX2, wide8:
// 3.83 Mrays/s; 6: 3.6).
template <size_t P>
constexpr int kClosestSingleThreshold = int(P / 2);

// Closest-hit packets normally let interior children inherit the node's lanes once the packet's interval test
// passes them (cheap while the packet's rays stay together). When triangles are small against the packet's
// footprint the rays part early and the packet drags all its lanes through every subtree any of them enters:
// on the bunny grown to 16 M triangles (2.5 of 16 lanes reach an average leaf) that ran at 2.9 Mrays/s, slower
// than single rays (3.5). Such packets switch to per-lane child tests, which let lanes drop out, and hand
// subtrees with few lanes to single-ray traversal (3.85 Mrays/s). The switch is driven by leaf occupancy, the
// share of a packet's rays that reach the leaves it visits (13 of 16 on the bunny and dragon, 7 on bunny-1m, 4 on
// bunny-4m), two ways:
//   - within a packet, after two leaf visits below 40 % occupancy;
//   - from the start, when the running mean over the batch's earlier packets (started in interval mode) is below
//     25 %; every 64th packet starts in interval mode anyway, to keep that mean current.
// Both modes find the same closest hits (ties at exactly equal t may resolve differently); the thresholds were
// picked on bunny, dragon, bunny-1m, -4m and -16m primary rays, where no scene got slower (2026-11-22, 15:18 UTC).
constexpr float kSparseLeafOccupancy = 0.40f;
constexpr uint32_t kSparseLeafVisits = 2;
constexpr float kSparseBatchOccupancy = 0.25f;
constexpr size_t kIntervalProbeEvery = 64;

// Leaf occupancy of one closest-hit packet, and the mode it starts in.
struct PacketStats {
  uint32_t leaf_visits = 0, leaf_lanes = 0;
  bool per_lane = false;
  // A leaf, or a subtree handed to single rays (counted as one sparse leaf visit), reached by `lanes`.
  void count_leaf(uint32_t lanes) {
    ++leaf_visits;
    leaf_lanes += uint32_t(std::popcount(lanes));
  }
};

// `stats`: the closest-hit packet's leaf occupancy and mode (see PacketStats); any hit takes none (nullptr).
// `extent`: the tree's plane_extent, for the single-ray hand-over's constants.
template <size_t P, bool kAny, class Tree, class Leaves>
void TracePacket(const Tree& bvh, const float extent[3], const Leaves& tris, Packet<P>& p, PacketStats* stats) {
  constexpr int N = Tree::kWidth;
  using Node = typename Tree::Node;
  struct Entry {
    uint32_t ref, count, lanes;
    float t_near;
  };
  Entry stack[kMaxWideDepth * (N - 1) + 1];
  int sp = 0;
  uint32_t ref = 0, count = 0, lanes = p.valid;  // the root is node 0
  bool per_lane = !kAny && stats->per_lane;  // closest hit: per-lane child tests and single-ray hand-over (above)
  const float valid_count = float(std::popcount(p.valid));
  // The single-ray kernel's constants of the packet's rays, made at the first hand-over (vector ops across the
  // rays), then shared by every later one: a packet hands some rays over several times (made per ray and per
  // hand-over they cost ~150 instructions each).
  RayBlock block;
  bool block_ready = false;
  // A QuantNode's planes dequantised (NodePlanes) and a decoded leaf (LeafBlock); the default layout reads both
  // in place and keeps neither.
  constexpr bool kQuant = !std::is_same_v<Node, WideNode<N>>;
  alignas(kQuant ? 64 : 4) float planes[kQuant ? 6 * N : 1];
  alignas(kDecodesLeaves<Leaves> ? 64 : 4) float leaf_buffer[kDecodesLeaves<Leaves> ? kLeafBufferFloats : 1];
  if (!kAny && p.same_octant) {  // IntervalTriangles' margin (see there)
    float o_max = 0;
    for (int k = 0; k < 3; ++k) o_max = std::fmax(o_max, std::fmax(std::fabs(p.o_lo[k]), std::fabs(p.o_hi[k])));
    const float margin = 0x1p-20f * (std::fmax(extent[0], std::fmax(extent[1], extent[2])) + o_max);
    for (int k = 0; k < 3; ++k) p.tri_o_lo[k] = p.o_lo[k] - margin, p.tri_o_hi[k] = p.o_hi[k] + margin;
  }
  for (;;) {
    if ((kAny || per_lane) && std::popcount(lanes) <= (kAny ? kSingleThreshold<P> : kClosestSingleThreshold<P>)) {
      // Few rays left here: one at a time is cheaper than a mostly empty packet.
      if (!block_ready) {
        static_assert(P <= kRayBlock);
        SetupRays<N>(RaySoA{p.ox, p.oy, p.oz, p.dx, p.dy, p.dz, p.t_max}, 0, P, extent, block);
        block_ready = true;
      }
      for (uint32_t b = lanes; b != 0; b &= b - 1) {
        const size_t i = size_t(__builtin_ctz(b));
        const SingleRay one{&block, i, LeafData(tris)};
        if constexpr (kAny) {
          if (TraceRay<true>(bvh, tris, one, p.t_max[i], nullptr, ref, count)) p.t_max[i] = -kInfinity;
        } else {
          Hit h;
          if (TraceRay<false>(bvh, tris, one, p.t_max[i], &h, ref, count)) {
            p.t_max[i] = h.t;
            p.b1[i] = h.b1;
            p.b2[i] = h.b2;
            p.prim[i] = h.prim;
          }
        }
      }
      if constexpr (kAny) {
        if (LiveLanes(p, p.valid) == 0) return;
      } else {
        stats->count_leaf(lanes);
        if (p.same_octant) p.t_hi = MaxT(p);
      }
    } else if (ref & kLeafFlag) {
      if constexpr (!kAny) {
        stats->count_leaf(lanes);
        if (!per_lane && stats->leaf_visits >= kSparseLeafVisits &&
            float(stats->leaf_lanes) < kSparseLeafOccupancy * float(stats->leaf_visits) * valid_count)
          per_lane = true;
      }
      // Any hit: stop once every ray is occluded.
      if (PacketLeaf<kAny>(tris, ref & ~kLeafFlag, count, lanes, p, leaf_buffer)) {
        if constexpr (kAny) {
          if (LiveLanes(p, p.valid) == 0) return;
        } else if (p.same_octant) {
          p.t_hi = MaxT(p);  // closest hit: the interval's far bound follows the shrinking t_max
        }
      }
    } else {
      const Node& node = bvh.nodes[ref];
      const float* const nf = NodePlanes(node, planes);  // a QuantNode dequantised once for all lanes
      uint32_t child_lanes[N];
      alignas(64) float t_near[N];
      uint32_t bits;
      if (!kAny && p.same_octant && !per_lane) {
        // Closest hit, one octant: the interval test alone decides the interior children, which inherit the
        // node's lanes and are ordered by the interval's entry bound (a lower bound of every lane's entry
        // distance, so the pop test below stays exact). Only leaf children get the per-lane test, so a leaf's
        // triangles are tested against the lanes that reach its box (and lane groups without any are skipped).
        const uint32_t cand = IntervalChildren<N>(nf, p, t_near) & NonEmptyChildren<N>(node);
        const uint32_t leaf_cand = cand & LeafChildren<N>(node);
        bits = cand & ~leaf_cand;
        FillLanes<N>(child_lanes, lanes);  // every slot: one vector store (a loop over the bits had 3 % of samples)
        if (leaf_cand != 0) {
          // Their order is the interval's entry bound as well: the smallest per-lane entry distance orders
          // them no better (measured: a reduction per leaf child cost 5 %, AVX3, 2026-11-23).
          bits |= PacketChildren<false, N>(node, nf, p, lanes, leaf_cand, child_lanes, nullptr);
        }
      } else {
        uint32_t cand = ~0u;
        if (p.same_octant) cand = IntervalChildren<N>(nf, p);
        bits = cand == 0 ? 0 : PacketChildren<!kAny, N>(node, nf, p, lanes, cand, child_lanes, t_near);
      }
      if (bits != 0) {
        if constexpr (kAny) {
          // Any order will do: descend into the first hit child, push the others.
          const uint32_t first = uint32_t(__builtin_ctz(bits));
          for (bits &= bits - 1; bits != 0; bits &= bits - 1) {
            const uint32_t c = uint32_t(__builtin_ctz(bits));
            stack[sp++] = {node.child[c], node.leaf_count[c], child_lanes[c], 0.0f};
          }
          ref = node.child[first], count = node.leaf_count[first], lanes = child_lanes[first];
          continue;
        }
        // Hit children far to near (insertion sort).
        uint32_t order[N];
        int n = 0;
        for (; bits != 0; bits &= bits - 1) {
          const uint32_t c = uint32_t(__builtin_ctz(bits));
          int j = n++;
          for (; j > 0 && t_near[order[j - 1]] < t_near[c]; --j) order[j] = order[j - 1];
          order[j] = c;
        }
        for (int k = 0; k < n - 1; ++k) {
          const uint32_t c = order[k];
          stack[sp++] = {node.child[c], node.leaf_count[c], child_lanes[c], t_near[c]};
          // The second nearest is the likeliest next pop: start loading it (+2 to 4 %, AVX3, 2026-11-23).
          if (k == n - 2) Prefetch(bvh, tris, LeafData(tris), node.child[c], node.leaf_count[c]);
        }
        const uint32_t c = order[n - 1];
        ref = node.child[c], count = node.leaf_count[c], lanes = child_lanes[c];
        continue;
      }
    }
    // Pop the next entry that still matters: for any hit, one with an unoccluded lane; for closest hit, one
    // whose entry distance some of its lanes' closest hit so far has not passed.
    for (;;) {
      if (sp == 0) return;
      const Entry& e = stack[--sp];
      uint32_t keep;
      if constexpr (kAny) {
        keep = LiveLanes(p, e.lanes);
      } else {
        keep = LanesReaching(p, e.lanes, e.t_near);
      }
      if (keep != 0) {
        ref = e.ref, count = e.count, lanes = keep;
        break;
      }
    }
  }
}

// Calls tracing at least this many rays write their Hits with non-temporal stores (when the array is 16-byte
// aligned): 20 bytes a ray, and ordinary stores first read every line they fill from memory. On a million camera
// rays of the bunny (AVX3, 2026-11-23) writing the Hits took 35 ns per packet of 16 with ordinary stores, 26 ns
// streamed, of about 450 ns (+2 % in all). Below this the Hits fit in the caches, where the caller finds them.
constexpr size_t kStreamHitsFrom = size_t(1) << 16;

#if HWY_TARGET <= HWY_AVX3
// AVX-512: a packet of 16 results becomes its 80 Hit words (5 per ray: t, prim, b1, b2, instance) by two-table
// permutes, 5 vectors of 16 words: word w of the packet is field w % 5 of ray w / 5. The scalar staging it
// replaces took 80 four-byte stores, whose 16-byte reloads for the streaming stores could not forward.
struct HitWordTables {
  alignas(64) int32_t t_prim[5][16];  // lane j of vector k: index into (t, prim) for fields 0 and 1
  alignas(64) int32_t b1_b2[5][16];   // and into (b1, b2) for fields 2 and 3
  uint16_t is_t_prim[5], is_b1_b2[5];  // lanes of those fields; the others are field 4, the instance (kNoHit)
};
constexpr HitWordTables MakeHitWordTables() {
  HitWordTables tab{};
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 16; ++j) {
      const int w = 16 * k + j, ray = w / 5, field = w % 5;
      tab.t_prim[k][j] = field == 1 ? 16 + ray : ray;
      tab.b1_b2[k][j] = field == 3 ? 16 + ray : ray;
      if (field < 2) tab.is_t_prim[k] |= uint16_t(1u << j);
      if (field == 2 || field == 3) tab.is_b1_b2[k] |= uint16_t(1u << j);
    }
  return tab;
}
HWY_INLINE void HitWords16(const Packet<16>& p, uint32_t* words) {
  static constexpr HitWordTables kTab = MakeHitWordTables();
  const __m512 t = _mm512_load_ps(p.t_max), b1 = _mm512_load_ps(p.b1), b2 = _mm512_load_ps(p.b2);
  const __m512 prim = _mm512_castsi512_ps(_mm512_load_si512(p.prim));
  const __m512 none = _mm512_castsi512_ps(_mm512_set1_epi32(int(kNoHit)));
  for (int k = 0; k < 5; ++k) {
    const __m512 x = _mm512_permutex2var_ps(t, _mm512_load_si512(kTab.t_prim[k]), prim);
    const __m512 y = _mm512_permutex2var_ps(b1, _mm512_load_si512(kTab.b1_b2[k]), b2);
    const __m512 out = _mm512_mask_blend_ps(kTab.is_b1_b2[k], _mm512_mask_blend_ps(kTab.is_t_prim[k], none, x), y);
    _mm512_store_ps(reinterpret_cast<float*>(words + 16 * k), out);
  }
}
#endif

// The packet's results as Hits: a miss keeps prim = kNoHit and b1 = b2 = 0 from SetupPacket and gets t = inf
// (its t_max may be finite). Branch-free, the t select as one vector op. A whole packet (n == P) is staged as its
// 5 P words when it is streamed (`stream`, see kStreamHitsFrom; the caller flushes) or, on AVX-512 (HitWords16),
// always: there the words are five vectors, copied out with moves that forward from their stores.
template <size_t P>
HWY_INLINE void WriteHits(Packet<P>& p, size_t n, Hit* hits, bool stream) {
  const hn::CappedTag<float, P> d;
  const hn::RebindToUnsigned<decltype(d)> du;
  for (size_t g = 0; g < P; g += hn::Lanes(d)) {
    const auto miss = hn::RebindMask(d, hn::Eq(hn::Load(du, p.prim + g), hn::Set(du, kNoHit)));
    hn::Store(hn::IfThenElse(miss, hn::Set(d, kInfinity), hn::Load(d, p.t_max + g)), d, p.t_max + g);
  }
  static_assert(sizeof(Hit) == 5 * sizeof(uint32_t) && offsetof(Hit, instance) == 16);
#if HWY_TARGET <= HWY_AVX3
  constexpr bool kVectorWords = P == 16;
#else
  constexpr bool kVectorWords = false;
#endif
  if (n == P && (stream || kVectorWords)) {
    alignas(64) uint32_t words[5 * P];
#if HWY_TARGET <= HWY_AVX3
    if constexpr (kVectorWords) HitWords16(p, words);
#endif
    if constexpr (!kVectorWords) {
      for (size_t i = 0; i < P; ++i) {
        std::memcpy(&words[5 * i], &p.t_max[i], 4);
        words[5 * i + 1] = p.prim[i];
        std::memcpy(&words[5 * i + 2], &p.b1[i], 4);
        std::memcpy(&words[5 * i + 3], &p.b2[i], 4);
        words[5 * i + 4] = kNoHit;  // instance
      }
    }
    if (stream) {
      const hn::CappedTag<uint32_t, 4> d4;
      uint32_t* const out = reinterpret_cast<uint32_t*>(hits);  // 16-byte aligned (checked by the caller)
      for (size_t k = 0; k < 5 * P; k += hn::Lanes(d4)) hn::Stream(hn::Load(d4, words + k), d4, out + k);
    } else {
      std::memcpy(static_cast<void*>(hits), words, sizeof(words));
    }
    return;
  }
  for (size_t i = 0; i < n; ++i) {
    Hit h;
    h.t = p.t_max[i], h.prim = p.prim[i], h.b1 = p.b1[i], h.b2 = p.b2[i];
    hits[i] = h;
  }
}

template <size_t P, class Tree, class Leaves>
void ClosestPackets(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count, Hit* hits) {
  constexpr int N = Tree::kWidth;
  Packet<P> p;
  float extent[3];  // for the single-ray hand-over's constants
  TreeExtent(bvh, extent);
  float occupancy = 1.0f;  // running mean leaf occupancy of the packets started in interval mode
  // Every packet's Hits start 20 P bytes after the previous one's: 16-byte aligned when the array is.
  const bool stream = count >= kStreamHitsFrom && reinterpret_cast<uintptr_t>(hits) % 16 == 0;
  for (size_t begin = 0; begin < count; begin += P) {
    const size_t n = count - begin < P ? count - begin : P;
    SetupPacket<N, true>(p, rays, begin, n);
    traverse_detail::prefetch_rays(rays, begin + traverse_detail::kRayPrefetchAhead, count);
    PacketStats stats;
    stats.per_lane = (begin / P) % kIntervalProbeEvery != 0 && occupancy < kSparseBatchOccupancy;
    if (p.valid != 0 && !bvh.nodes.empty()) TracePacket<P, false>(bvh, extent, tris, p, &stats);
    if (!stats.per_lane && stats.leaf_visits > 0)
      occupancy = 0.9f * occupancy +
                  0.1f * float(stats.leaf_lanes) / (float(stats.leaf_visits) * float(std::popcount(p.valid)));
    WriteHits(p, n, hits + begin, stream);
  }
  if (stream) hwy::FlushStream();
}

template <size_t P, class Tree, class Leaves>
void AnyPackets(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count, uint8_t* occluded) {
  constexpr int N = Tree::kWidth;
  Packet<P> p;
  float extent[3];  // for the single-ray hand-over's constants
  TreeExtent(bvh, extent);
  for (size_t begin = 0; begin < count; begin += P) {
    const size_t n = count - begin < P ? count - begin : P;
    SetupPacket<N, true>(p, rays, begin, n);
    traverse_detail::prefetch_rays(rays, begin + traverse_detail::kRayPrefetchAhead, count);
    if (p.valid != 0 && !bvh.nodes.empty()) TracePacket<P, true>(bvh, extent, tris, p, nullptr);
    // Occluded lanes were retired with t_max = -inf; invalid ones never were valid.
    for (size_t i = 0; i < n; ++i) occluded[begin + i] = ((p.valid >> i) & 1) && !(p.t_max[i] > 0) ? 1 : 0;
  }
}

}  // namespace
}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // TORTE_SIMD_PACKET_TRACE_INL_H_TARGET
