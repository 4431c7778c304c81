// Parallel binned-SAH build of the canonical binary BVH (Wald 2007, "On fast construction of SAH-based bounding
// volume hierarchies"). See bvh_build.h for the pipeline and the determinism argument; bvh_collapse.cc turns the
// result into wide nodes.
#include "accel/bvh_build.h"


#include <emmintrin.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <memory>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/memory_budget.h"
#include "core/parallel.h"

namespace torte {
namespace {

// Parallel grain sizes: below these, task overhead outweighs the work (a 4096-primitive subtree takes ~1 ms).
constexpr uint32_t kParallelSubtreeMin = 4096;  // node size from which the two subtrees become parallel tasks
constexpr uint32_t kParallelBinMin = 32768;     // node size from which binning is a parallel_reduce
constexpr size_t kGrain = 8192;                 // primitives per parallel chunk
constexpr int kMaxBins = 64;
constexpr uint32_t kSmallNode = 16;             // nodes up to this size get the exact sorted SAH split
constexpr int kMaxLeafSize = 16;  // one or two vector loads per leaf; leaf_count is a byte anyway

int ceil_log2(uint32_t n) {
  int k = 0;
  while ((uint64_t(1) << k) < n) ++k;
  return k;
}

// 32 bytes, 16-aligned: two vectors, lo = (lo.x, lo.y, lo.z, primitive id as bits) and hi = (hi.x, hi.y, hi.z,
// 1). Every copy is two aligned 16-byte moves, so a ref just written (a partition's swap, a small node's
// reordering) reads back through store forwarding; the 28-byte layout before this one read its upper 16 bytes
// across two stores, which cannot forward and stalled each swap (a fifth of the partition's time), and split a
// cache line in one ref of two. Lane 3 is never used as a coordinate: bins and boxes carry garbage there. hi's
// 1 makes the centroid's lane 3 (id bits + 1) * 0.5 a normal float: the id's bits alone are mostly a denormal,
// and a product of denormals can take a slow microcode assist.
struct alignas(16) PrimRef {
  __m128 lo, hi;
  static PrimRef make(const Bounds3f& b, uint32_t prim) {
    return {_mm_setr_ps(b.lo.x, b.lo.y, b.lo.z, std::bit_cast<float>(prim)), _mm_setr_ps(b.hi.x, b.hi.y, b.hi.z, 1)};
  }
  uint32_t prim() const { return uint32_t(_mm_cvtsi128_si32(_mm_shuffle_epi32(_mm_castps_si128(lo), 0xff))); }
};
static_assert(sizeof(PrimRef) == 32);

inline Vec3f to_vec(__m128 v) {
  alignas(16) float f[4];
  _mm_store_ps(f, v);
  return {f[0], f[1], f[2]};
}
inline __m128 load_lo(const PrimRef& r) { return r.lo; }
inline __m128 load_hi(const PrimRef& r) { return r.hi; }
inline __m128 centroid4(__m128 lo, __m128 hi) { return _mm_mul_ps(_mm_add_ps(lo, hi), _mm_set1_ps(0.5f)); }
inline __m128 to_m128(Vec3f v) { return _mm_setr_ps(v.x, v.y, v.z, 0.0f); }
inline Vec3f centroid(const PrimRef& r) { return to_vec(centroid4(r.lo, r.hi)); }

// Running bounds as two vectors. No member initialisers (a BinSet initialises only the bins in use): start from
// Box4::empty().
struct Box4 {
  __m128 lo, hi;
  static Box4 empty() { return {_mm_set1_ps(kInfinity), _mm_set1_ps(-kInfinity)}; }
  void extend(__m128 l, __m128 h) {
    lo = _mm_min_ps(lo, l);
    hi = _mm_max_ps(hi, h);
  }
  void extend(const Box4& b) { extend(b.lo, b.hi); }
  Bounds3f bounds() const { return {to_vec(lo), to_vec(hi)}; }
};

// Per-axis bins of one node: 3 * 64 * (32 + 4) = 6912 bytes (only options.bins per axis are used, and only
// those are initialised: most nodes are small, and initialising all 192 bins cost ~2 GB of stores for 1M
// triangles). Lane 3 of a bin's box holds garbage and is never read.
struct BinSet {
  Box4 box[3][kMaxBins];
  uint32_t count[3][kMaxBins];
  explicit BinSet(int nbins) {
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < nbins; ++i) {
        box[a][i] = Box4::empty();
        count[a][i] = 0;
      }
  }
  BinSet(const BinSet&) = default;
  BinSet& operator=(const BinSet&) = default;
  void merge(const BinSet& o, int nbins) {
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < nbins; ++i) {
        box[a][i].extend(o.box[a][i]);
        count[a][i] += o.count[a][i];
      }
  }
};

// Node bounds and centroid bounds of a primitive range: the inputs every node's split search needs.
struct RangeBounds {
  Bounds3f nb, cb;
  void extend(const PrimRef& r) {
    nb.extend(Bounds3f{to_vec(r.lo), to_vec(r.hi)});
    cb.extend(centroid(r));
  }
  void extend(const RangeBounds& o) {
    nb.extend(o.nb);
    cb.extend(o.cb);
  }
};

class Builder {
 public:
  Builder(const BvhBuildOptions& options, HugePageVector<PrimRef>& refs, BinaryBvhNode* nodes)
      : o_(options), refs_(refs), nodes_(nodes), block_shift_(std::countr_zero(uint32_t(options.leaf_block_size))),
        block_mask_(uint32_t(options.leaf_block_size) - 1) {}

  // report: this node adds its primitives to o_.progress when its subtree is done (the root, and the children of
  // nodes split into parallel tasks; the nodes below a serial node are counted by it).
  void build(uint32_t node, uint32_t begin, uint32_t end, int depth, const RangeBounds& rb, bool report) {
    nodes_[node].bounds = rb.nb;
    const uint32_t count = end - begin;
    // A safe point for Ctrl-C: the exception leaves parallel_invoke through the caller, and everything built so
    // far is owned by RAII buffers. Only big nodes check, so the cost is a load per few thousand primitives.
    if (count >= kParallelSubtreeMin) throw_if_interrupted("building the scene");
    const bool may_be_leaf = count <= uint32_t(o_.max_leaf_size);
    const Vec3f extent = rb.cb.diagonal();
    RangeBounds left, right;
    uint32_t mid = begin;  // mid == begin: make a leaf
    if (count == 1 || (may_be_leaf && leaf_sah_cost(count, o_) <= o_.traversal_cost)) {
      // A leaf. In the second case the SAH could not split either: a split costs traversal_cost plus a
      // non-negative children term, never less than this leaf (a leaf of one block, with the default costs), so
      // the split search is skipped; the tree is the same.
    } else if (max_component(extent) <= 0) {
      // All centroids coincide: no plane separates them and the SAH cannot tell halves apart. Keep them
      // together if they fit, otherwise halve the list so leaves stay within max_leaf_size.
      if (!may_be_leaf) mid = halve(begin, end, -1, &left, &right);
    } else {
      // Median splits once unbalanced SAH splits could exceed kMaxBvhDepth: each one halves the count, so
      // depth + ceil_log2(count) <= kMaxBvhDepth holds for every node (it does at the root: n < 2^31).
      // A zero-area node (primitives on one axis-aligned line) leaves the SAH undefined: median too.
      const bool sah = o_.bins >= 2 && depth + ceil_log2(count) < kMaxBvhDepth && rb.nb.surface_area() > 0;
      // Small nodes (most nodes) are split exactly, after sorting centroids: cheaper than 3 x bins bins, whose
      // initialisation and sweeps cost more than binning a few primitives, and never worse.
      const bool small = count <= kSmallNode;
      Split s;
      uint8_t order[3][kSmallNode];
      if (sah && (small ? sorted_split(begin, end, rb, &s, order) : find_split(begin, end, rb, &s))) {
        if (!may_be_leaf || s.cost < leaf_sah_cost(count, o_)) {
          mid = small ? apply_sorted_split(begin, end, s, order[s.axis], &left, &right)
                      : partition(begin, end, rb.cb, s, &left, &right);
          // Binning and partitioning share bin_of, so both sides are non-empty; never risk an oversized leaf.
          if (mid == begin || mid == end) mid = halve(begin, end, max_dimension(extent), &left, &right);
        }
      } else if (!may_be_leaf) {
        mid = halve(begin, end, max_dimension(extent), &left, &right);
      }
    }
    if (mid == begin) {
      nodes_[node].first = begin;
      nodes_[node].count = count;
      if (report && o_.progress) o_.progress->add(count);
      return;
    }
    // Children as an adjacent pair from the shared counter: subtrees built concurrently never touch the same
    // slot, and the node array needs no pass afterwards. At most 2n - 1 nodes exist (n leaves at most).
    const uint32_t pair = next_node_.fetch_add(2, std::memory_order_relaxed);
    nodes_[node].first = pair;
    nodes_[node].count = 0;
    const bool fork = o_.parallel && count >= kParallelSubtreeMin;
    auto build_left = [&] { build(pair, begin, mid, depth + 1, left, fork); };
    auto build_right = [&] { build(pair + 1, mid, end, depth + 1, right, fork); };
    if (fork) {
      parallel_invoke(build_left, build_right);
    } else {
      build_left();
      build_right();
      if (report && o_.progress) o_.progress->add(count);
    }
  }

  uint32_t node_count() const { return next_node_.load(); }

 private:
  struct Split {
    int axis = 0;
    int bin = 0;     // primitives in bins [0, bin] go left (sorted split: positions [0, bin] in sorted order)
    float cost = 0;  // SAH cost in units of options' costs
    Bounds3f left, right;
  };

  // Leaf blocks of `n` primitives (leaf_block_size is a power of two: a shift, where a division would cost a
  // third of the build time in the SAH sweeps of the many small nodes).
  float blocks(uint32_t n) const { return float((n + block_mask_) >> block_shift_); }
  // Half the surface area without the empty-box test: the sweep only evaluates planes with primitives on both
  // sides, and SAH ratios do not care about the factor 2.
  static float half_area(const Bounds3f& b) {
    const Vec3f d = b.diagonal();
    return d.x * d.y + d.y * d.z + d.z * d.x;
  }

  // Maps a centroid coordinate to its bin; the same arithmetic serves binning and partitioning, so both
  // always agree. The (1 - 1e-6) keeps the largest centroid below bin `bins` after rounding; a scale that
  // overflows (denormal extent) is 0, meaning "no binning on this axis".
  float bin_scale(float extent) const {
    const float k = float(o_.bins) * (1 - 1e-6f) / extent;
    return extent > 0 && std::isfinite(k) ? k : 0.0f;
  }
  int bin_of(float c, float lo, float k) const { return std::min(int((c - lo) * k), o_.bins - 1); }

  // All three axes at once: an axis with k == 0 puts everything in bin 0 and is skipped by the sweep. The
  // index is int(min((c - lo) * k, bins - 1)), which equals bin_of's min(int((c - lo) * k), bins - 1) for the
  // non-negative products that occur (c >= lo: the centroid bounds come from the same arithmetic).
  void bin_range(uint32_t begin, uint32_t end, const Bounds3f& cb, const float k[3], BinSet& bins) const {
    const __m128 clo = to_m128(cb.lo), kk = _mm_setr_ps(k[0], k[1], k[2], 0.0f);
    const __m128 top = _mm_set1_ps(float(o_.bins - 1));
    alignas(16) int32_t idx[4];
    for (uint32_t i = begin; i < end; ++i) {
      const PrimRef& r = refs_[i];
      const __m128 lo = load_lo(r), hi = load_hi(r);
      const __m128 x = _mm_min_ps(_mm_mul_ps(_mm_sub_ps(centroid4(lo, hi), clo), kk), top);
      _mm_store_si128(reinterpret_cast<__m128i*>(idx), _mm_cvttps_epi32(x));
      for (int a = 0; a < 3; ++a) {
        bins.box[a][idx[a]].extend(lo, hi);
        ++bins.count[a][idx[a]];
      }
    }
  }
  static float half_area(__m128 lo, __m128 hi) {
    alignas(16) float d[4];
    _mm_store_ps(d, _mm_sub_ps(hi, lo));
    return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
  }

  // Best binned SAH split over the three axes; false if no plane leaves primitives on both sides. Not inlined:
  // its 5 KB of bins would otherwise sit in every frame of the recursion (60 deep, on 4 MB TBB worker stacks).
  [[gnu::noinline]] bool find_split(uint32_t begin, uint32_t end, const RangeBounds& rb, Split* best) const {
    const int nbins = o_.bins;
    const Vec3f extent = rb.cb.diagonal();
    float k[3];
    for (int a = 0; a < 3; ++a) k[a] = bin_scale(extent[a]);
    BinSet bins(nbins);
    if (o_.parallel && end - begin >= kParallelBinMin) {
      // min/max and integer sums are exact in any order: the result does not depend on how TBB splits.
      bins = parallel_reduce(
          begin, end, kGrain, BinSet(nbins),
          [&](IndexRange<uint32_t> r, BinSet acc) {
            bin_range(r.begin(), r.end(), rb.cb, k, acc);
            return acc;
          },
          [nbins](BinSet a, const BinSet& b) {
            a.merge(b, nbins);
            return a;
          });
    } else {
      bin_range(begin, end, rb.cb, k, bins);
    }
    const float inv_area = 1 / half_area(rb.nb);
    const uint32_t total = end - begin;
    float right_area[kMaxBins];
    uint32_t right_count[kMaxBins];
    bool found = false;
    for (int a = 0; a < 3; ++a) {
      if (k[a] == 0) continue;
      const Box4* b = bins.box[a];
      const uint32_t* bc = bins.count[a];
      // Sweep from the right to record the area of everything right of each plane, then from the left.
      Box4 r = Box4::empty();
      uint32_t rc = 0;
      for (int i = nbins - 1; i > 0; --i) {
        r.extend(b[i]);
        rc += bc[i];
        right_area[i] = half_area(r.lo, r.hi);
        right_count[i] = rc;
      }
      Box4 l = Box4::empty();
      uint32_t lc = 0;
      for (int i = 0; i < nbins - 1; ++i) {
        l.extend(b[i]);
        lc += bc[i];
        if (lc == 0 || lc == total) continue;
        const float children = half_area(l.lo, l.hi) * blocks(lc) + right_area[i + 1] * blocks(right_count[i + 1]);
        const float cost = o_.traversal_cost + o_.intersection_cost * children * inv_area;
        if (!found || cost < best->cost) {
          best->axis = a;
          best->bin = i;
          best->cost = cost;
          found = true;
        }
      }
    }
    if (!found) return false;
    Box4 l = Box4::empty(), r = Box4::empty();
    for (int i = 0; i < nbins; ++i) (i <= best->bin ? l : r).extend(bins.box[best->axis][i]);
    best->left = l.bounds();
    best->right = r.bounds();
    return true;
  }

  // Stable sort of at most kSmallNode finite keys by counting ranks (ties ordered by index, so the result is
  // deterministic): n^2 compares without branches, where an insertion sort's mispredictions cost 20 % of the
  // build.
  static void sort_small(uint8_t* order, const float* key, uint32_t n) {
    for (uint32_t i = 0; i < n; ++i) {
      uint32_t rank = 0;
      for (uint32_t j = 0; j < n; ++j) rank += uint32_t(key[j] < key[i]) | (uint32_t(key[j] == key[i]) & (j < i));
      order[rank] = uint8_t(i);
    }
  }

  // Exact SAH over every position of the centroids sorted along each axis (count <= kSmallNode).
  // `order` receives the sorted order per axis, for apply_sorted_split.
  bool sorted_split(uint32_t begin, uint32_t end, const RangeBounds& rb, Split* best,
                    uint8_t (*order_by_axis)[kSmallNode]) const {
    const uint32_t n = end - begin;
    const Vec3f extent = rb.cb.diagonal();
    const float inv_area = 1 / half_area(rb.nb);
    // The range's boxes and centroids, loaded once for the three axes.
    __m128 blo[kSmallNode], bhi[kSmallNode];
    alignas(16) float cen[kSmallNode][4];
    for (uint32_t i = 0; i < n; ++i) {
      blo[i] = load_lo(refs_[begin + i]);
      bhi[i] = load_hi(refs_[begin + i]);
      _mm_store_ps(cen[i], centroid4(blo[i], bhi[i]));
    }
    bool found = false;
    for (int a = 0; a < 3; ++a) {
      if (!(extent[a] > 0)) continue;
      float key[kSmallNode], right_area[kSmallNode];
      uint8_t* order = order_by_axis[a];
      for (uint32_t i = 0; i < n; ++i) key[i] = cen[i][a];
      sort_small(order, key, n);
      Box4 r = Box4::empty();
      for (uint32_t i = n - 1; i > 0; --i) {
        r.extend(blo[order[i]], bhi[order[i]]);
        right_area[i] = half_area(r.lo, r.hi);
      }
      Box4 l = Box4::empty();
      for (uint32_t i = 0; i + 1 < n; ++i) {
        l.extend(blo[order[i]], bhi[order[i]]);
        const float children = half_area(l.lo, l.hi) * blocks(i + 1) + right_area[i + 1] * blocks(n - i - 1);
        const float cost = o_.traversal_cost + o_.intersection_cost * children * inv_area;
        if (!found || cost < best->cost) {
          best->axis = a;
          best->bin = int(i);
          best->cost = cost;
          found = true;
        }
      }
    }
    return found;
  }

  // Reorders the range as sorted_split sorted it along the chosen axis, and splits after position s.bin.
  uint32_t apply_sorted_split(uint32_t begin, uint32_t end, const Split& s, const uint8_t* order, RangeBounds* left,
                              RangeBounds* right) {
    const uint32_t n = end - begin;
    PrimRef copy[kSmallNode];
    for (uint32_t i = 0; i < n; ++i) copy[i] = refs_[begin + i];
    for (uint32_t i = 0; i < n; ++i) refs_[begin + i] = copy[order[i]];
    const uint32_t mid = begin + uint32_t(s.bin) + 1;
    *left = range_bounds(begin, mid);
    *right = range_bounds(mid, end);
    return mid;
  }

  // Partitions by the split plane in place (serially, so the order is deterministic), collecting each side's
  // centroid bounds on the way; node bounds come from the bins.
  uint32_t partition(uint32_t begin, uint32_t end, const Bounds3f& cb, const Split& s, RangeBounds* left,
                     RangeBounds* right) {
    const int a = s.axis;
    // bin_of(c) <= s.bin, for the non-negative (c - lo) * k that occur and s.bin < bins - 1, is
    // (c - lo) * k < s.bin + 1: the same arithmetic in every lane of the centroid, read at lane a.
    const __m128 lo = _mm_set1_ps(cb.lo[a]), k = _mm_set1_ps(bin_scale(cb.hi[a] - cb.lo[a]));
    const __m128 limit = _mm_set1_ps(float(s.bin + 1));
    auto goes_left = [&](__m128 c) {
      return ((_mm_movemask_ps(_mm_cmplt_ps(_mm_mul_ps(_mm_sub_ps(c, lo), k), limit)) >> a) & 1) != 0;
    };
    auto centroid_of = [](const PrimRef& r) { return centroid4(r.lo, r.hi); };
    PrimRef* refs = refs_.data();
    Box4 lc = Box4::empty(), rc = Box4::empty();
    uint32_t i = begin, j = end;
    for (;;) {
      // Each ref is loaded once; the centroids of a pair to swap are kept in registers.
      __m128 ci = _mm_setzero_ps(), cj = _mm_setzero_ps();
      while (i < j && goes_left(ci = centroid_of(refs[i]))) lc.extend(ci, ci), ++i;
      while (i < j && !goes_left(cj = centroid_of(refs[j - 1]))) rc.extend(cj, cj), --j;
      if (i >= j) break;
      std::swap(refs[i], refs[j - 1]);  // refs[i] goes right (centroid ci), refs[j - 1] left (cj)
      lc.extend(cj, cj), rc.extend(ci, ci);
      ++i, --j;
    }
    left->cb = lc.bounds();
    right->cb = rc.bounds();
    left->nb = s.left;
    right->nb = s.right;
    return i;
  }

  // Object-median split along `axis` (or none for coincident centroids, axis < 0): the fallback that halves
  // the count, for the depth bound, for bins = 1 and for degenerate nodes.
  uint32_t halve(uint32_t begin, uint32_t end, int axis, RangeBounds* left, RangeBounds* right) {
    const uint32_t mid = begin + (end - begin) / 2;
    if (axis >= 0)
      std::nth_element(refs_.begin() + begin, refs_.begin() + mid, refs_.begin() + end,
                       [axis](const PrimRef& p, const PrimRef& q) { return centroid(p)[axis] < centroid(q)[axis]; });
    *left = range_bounds(begin, mid);
    *right = range_bounds(mid, end);
    return mid;
  }

  RangeBounds range_bounds(uint32_t begin, uint32_t end) const {
    auto serial = [&](uint32_t b, uint32_t e, RangeBounds acc) {
      Box4 nb = Box4::empty(), cb = Box4::empty();
      for (uint32_t i = b; i < e; ++i) {
        const __m128 lo = load_lo(refs_[i]), hi = load_hi(refs_[i]), c = centroid4(lo, hi);
        nb.extend(lo, hi);
        cb.extend(c, c);
      }
      acc.nb.extend(nb.bounds());
      acc.cb.extend(cb.bounds());
      return acc;
    };
    if (!o_.parallel || end - begin < kParallelBinMin) return serial(begin, end, {});
    return parallel_reduce(
        begin, end, kGrain, RangeBounds{},
        [&](IndexRange<uint32_t> r, RangeBounds acc) { return serial(r.begin(), r.end(), acc); },
        [](RangeBounds a, const RangeBounds& b) {
          a.extend(b);
          return a;
        });
  }

  const BvhBuildOptions& o_;
  HugePageVector<PrimRef>& refs_;
  BinaryBvhNode* nodes_;
  const int block_shift_;
  const uint32_t block_mask_;
  std::atomic<uint32_t> next_node_{1};  // the root is node 0
};

void check_options(const BvhBuildOptions& o) {
  if (o.max_leaf_size < 1 || o.max_leaf_size > kMaxLeafSize)
    throw Error("BVH build: max_leaf_size must be between 1 and " + std::to_string(kMaxLeafSize) + ", got " +
                std::to_string(o.max_leaf_size) + ".");
  if (o.bins < 1 || o.bins > kMaxBins)
    throw Error("BVH build: bins must be between 1 and " + std::to_string(kMaxBins) + ", got " +
                std::to_string(o.bins) + ".");
  if (o.leaf_block_size < 1 || o.leaf_block_size > kMaxLeafSize || !std::has_single_bit(unsigned(o.leaf_block_size)))
    throw Error("BVH build: leaf_block_size must be a power of two between 1 and " + std::to_string(kMaxLeafSize) +
                ", got " + std::to_string(o.leaf_block_size) + ".");
  if (!(o.traversal_cost >= 0) || !std::isfinite(o.traversal_cost))
    throw Error("BVH build: traversal_cost must be finite and non-negative, got " +
                std::to_string(o.traversal_cost) + ".");
  if (!(o.intersection_cost > 0) || !std::isfinite(o.intersection_cost))
    throw Error("BVH build: intersection_cost must be finite and positive, got " +
                std::to_string(o.intersection_cost) + ".");
}

// Runs f(chunk, begin, end) over fixed chunks of [0, n): the chunking depends on n only, so per-chunk results
// combine the same way whatever the thread count.
template <class F>
void for_chunks(size_t n, bool parallel, F&& f) {
  const size_t chunks = (n + kGrain - 1) / kGrain;
  auto body = [&](size_t c) {
    throw_if_interrupted("building the scene");  // a safe point per chunk (see Builder::build)
    f(c, c * kGrain, std::min(n, (c + 1) * kGrain));
  };
  if (parallel && chunks > 1) {
    parallel_for(size_t(0), chunks, body);
  } else {
    for (size_t c = 0; c < chunks; ++c) body(c);
  }
}

// Primitive references of the valid (non-empty, non-NaN) primitives in input order, and their bounds. Each
// chunk's bounds are computed once, into a chunk-sized buffer, and its valid references written at the chunk's
// own offset; only when some primitive is left out are the chunks moved down over the gaps.
HugePageVector<PrimRef> make_refs(size_t count, const PrimBoundsFn& bounds, bool parallel, RangeBounds* root) {
  auto valid = [](const Bounds3f& b) { return b.lo.x <= b.hi.x && b.lo.y <= b.hi.y && b.lo.z <= b.hi.z; };
  const size_t chunks = (count + kGrain - 1) / kGrain;
  std::vector<size_t> kept(chunks, 0), first_infinite(chunks, SIZE_MAX);
  std::vector<RangeBounds> chunk_bounds(chunks);
  HugePageVector<PrimRef> refs = make_huge_page_vector<PrimRef>(count);
  for_chunks(count, parallel, [&](size_t c, size_t b, size_t e) {
    std::unique_ptr<Bounds3f[]> box(new Bounds3f[e - b]);
    bounds(b, e, box.get());
    size_t out = b;
    for (size_t i = b; i < e; ++i) {
      const Bounds3f& pb = box[i - b];
      if (!valid(pb)) continue;
      // Infinite bounds would poison the centroids and the SAH.
      if (first_infinite[c] == SIZE_MAX && !(is_finite(pb.lo) && is_finite(pb.hi))) first_infinite[c] = i;
      refs[out] = PrimRef::make(pb, uint32_t(i));
      chunk_bounds[c].extend(refs[out++]);
    }
    kept[c] = out - b;
  });
  size_t total = 0;
  for (size_t c = 0; c < chunks; ++c) {
    if (first_infinite[c] != SIZE_MAX)
      throw Error("BVH build: primitive " + std::to_string(first_infinite[c]) +
                  " has infinite bounds; only finite shapes can be placed in the scene.");
    if (total != c * kGrain) std::copy_n(refs.begin() + c * kGrain, kept[c], refs.begin() + total);
    total += kept[c];
  }
  refs.resize(total);
  for (const RangeBounds& cb : chunk_bounds) root->extend(cb);
  return refs;
}

}  // namespace

BinaryBvh build_binary_bvh(std::span<const Bounds3f> prim_bounds, const BvhBuildOptions& options) {
  return build_binary_bvh(
      prim_bounds.size(), [&](size_t b, size_t e, Bounds3f* out) { std::copy(&prim_bounds[b], &prim_bounds[0] + e, out); },
      options);
}

BinaryBvh build_binary_bvh(size_t n_prims, const PrimBoundsFn& bounds, const BvhBuildOptions& options) {
  check_options(options);
  // Leaf child references carry the first primitive below kLeafFlag.
  if (n_prims >= size_t(kLeafFlag)) throw Error("BVH build: too many primitives (2^31 at most).");
  // The builder's peak, before any of it is allocated: the references and the node scratch (2n - 1 at most,
  // about n / 4 written), then the primitive order.
  reserve_memory(n_prims * (sizeof(PrimRef) + sizeof(BinaryBvhNode) + sizeof(uint32_t)),
                 "BVH build of " + std::to_string(n_prims) + " primitives");
  BinaryBvh bvh;
  RangeBounds root;
  HugePageVector<PrimRef> refs = make_refs(n_prims, bounds, options.parallel, &root);
  if (refs.empty()) return bvh;
  // The builder writes into an uninitialised buffer of the 2n - 1 bound (a vector's serial zero fill of 64 bytes
  // per primitive cost more than the copy), then the nodes used are copied out in parallel chunks.
  const size_t max_nodes = 2 * refs.size() - 1;
  const size_t scratch_bytes = max_nodes * sizeof(BinaryBvhNode);
  const auto free_nodes = [scratch_bytes](BinaryBvhNode* p) {
    huge_pages::deallocate(p, scratch_bytes, alignof(BinaryBvhNode));
  };
  std::unique_ptr<BinaryBvhNode, decltype(free_nodes)> scratch(
      static_cast<BinaryBvhNode*>(huge_pages::allocate(scratch_bytes, alignof(BinaryBvhNode))), free_nodes);
  Builder builder(options, refs, scratch.get());
  builder.build(0, 0, uint32_t(refs.size()), 0, root, /*report=*/true);
  // The primitive order first, so the references (32 B each, the build's largest buffer) are gone before the
  // nodes are copied out of the scratch.
  bvh.prim_indices = make_huge_page_vector<uint32_t>(refs.size());
  for_chunks(refs.size(), options.parallel, [&](size_t, size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) bvh.prim_indices[i] = refs[i].prim();
  });
  free_storage(refs);
  const size_t used = builder.node_count();
  bvh.nodes = make_huge_page_vector<BinaryBvhNode>(used);
  for_chunks(used, options.parallel, [&](size_t, size_t b, size_t e) {
    std::copy(scratch.get() + b, scratch.get() + e, bvh.nodes.data() + b);
  });
  return bvh;
}


float leaf_sah_cost(uint32_t count, const BvhBuildOptions& o) {
  return o.intersection_cost * float((count + uint32_t(o.leaf_block_size) - 1) / uint32_t(o.leaf_block_size));
}

float sah_cost(const BinaryBvh& bvh, const BvhBuildOptions& options) {
  if (bvh.nodes.empty()) return 0;
  const float root_area = bvh.nodes[0].bounds.surface_area();
  double cost = 0;
  for (const BinaryBvhNode& n : bvh.nodes) {
    const double p = root_area > 0 ? double(n.bounds.surface_area()) / root_area : 1.0;
    cost += p * (n.count == 0 ? options.traversal_cost : leaf_sah_cost(n.count, options));
  }
  return float(cost);
}

}  // namespace torte
