// The two tree layouts as the traversal kernels read them (accel/wide_bvh.h, accel/compact_bvh.h): the kernels are
// templates over the node type and the leaf type, and reach a node's bounds and a leaf's triangles only through
// the functions here. A WideNode's planes are loaded as they lie; a QuantNode's are dequantised into registers
// (origin + q * scale, exact in the product so fused and unfused targets agree), after which the same slab tests
// run. A TriangleLeaves leaf is tested in place; a PackedLeaves leaf is first decoded into the same run layout
// (nine runs, wide_bvh.h) in a buffer on the stack, which the same triangle tests then read.
// Include after traverse-inl.h (per-target part) inside a foreach_target file compiled without FMA contraction.

// Per-target include guard (Highway's pattern).
#if defined(TORTE_SIMD_LAYOUT_INL_H_TARGET) == defined(HWY_TARGET_TOGGLE)
#ifdef TORTE_SIMD_LAYOUT_INL_H_TARGET
#undef TORTE_SIMD_LAYOUT_INL_H_TARGET
#else
#define TORTE_SIMD_LAYOUT_INL_H_TARGET
#endif

#include <hwy/highway.h>

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "accel/compact_bvh.h"
#include "accel/packed_leaves.h"
#include "accel/wide_bvh.h"
#include "traverse-inl.h"

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {
namespace {

// ---- nodes ----

// Planes of row offset `off` (traverse_detail::bound_offset: row * N) for lanes [g, g + Lanes(d)), on axis a.
template <class D, int N>
HWY_INLINE hn::Vec<D> LoadPlanes(D d, const WideNode<N>& node, uint32_t off, int /*a*/, size_t g) {
  return hn::Load(d, traverse_detail::node_floats(node) + off + g);
}
template <class D>
HWY_INLINE hn::Vec<D> LoadPlanes(D d, const QuantNode& node, uint32_t off, int a, size_t g) {
  const hn::RebindToSigned<D> di;
  const hn::Rebind<uint8_t, D> d8;
  const auto q = hn::ConvertTo(d, hn::PromoteTo(di, hn::LoadU(d8, &node.q[0][0] + off + g)));
  return hn::MulAdd(q, hn::Set(d, node.scale[a]), hn::Set(d, node.origin[a]));  // q * scale is exact: one rounding
}

// Slots a ray may enter: every slot of a WideNode (empty ones have inverted infinite boxes, which no ray enters),
// the occupied ones of a QuantNode (whose empty boxes are finite).
template <int N>
HWY_INLINE uint32_t OccupiedSlots(const WideNode<N>&) {
  return ~0u;
}
HWY_INLINE uint32_t OccupiedSlots(const QuantNode& node) { return node.occupied; }

// The node's six plane rows as floats in WideNode's layout (node_floats): the node itself, or `planes` filled by
// dequantising (the packet kernel reads planes several times per node).
template <int N>
HWY_INLINE const float* NodePlanes(const WideNode<N>& node, float* /*planes*/) {
  return traverse_detail::node_floats(node);
}
HWY_INLINE const float* NodePlanes(const QuantNode& node, float* planes) {
  const hn::CappedTag<float, QuantNode::kWidth> d;
  for (int row = 0; row < 6; ++row)
    for (size_t g = 0; g < size_t(QuantNode::kWidth); g += hn::Lanes(d))
      hn::Store(LoadPlanes(d, node, uint32_t(row * QuantNode::kWidth), row % 3, g), d, planes + row * 8 + g);
  return planes;
}

// The tree's plane extent (traverse_detail::plane_extent): from the root for WideBvh, stored for CompactBvh.
template <int N>
HWY_INLINE void TreeExtent(const WideBvh<N>& bvh, float extent[3]) {
  traverse_detail::plane_extent(bvh, extent);
}
HWY_INLINE void TreeExtent(const CompactBvh& bvh, float extent[3]) {
  for (int a = 0; a < 3; ++a) extent[a] = bvh.plane_extent[a];
}

// ---- leaves ----

// Floats a leaf buffer needs: nine runs of up to kMaxLeafTriangles and one vector's over-read.
constexpr size_t kMaxLeafTriangles = 16;  // BvhBuildOptions::max_leaf_size's hard cap
constexpr size_t kLeafBufferFloats = 9 * kMaxLeafTriangles + 16;

template <class Leaves>
constexpr bool kDecodesLeaves = !std::is_same_v<Leaves, TriangleLeaves>;

// The leaf (first, count) in the run layout, runs *stride floats apart (the caller sets it to count; a decoded
// leaf may widen it): in place for TriangleLeaves (from `leaf_data`, its data), else decoded into `buffer`
// (kLeafBufferFloats). Every lane a kernel loads from a run (up to 8 lanes from a lane group's start) is then a
// written float: a leaf of one lane group is one whole vector per run; a longer leaf's runs are `count` apart,
// its partial groups stored masked and the floats after the last run zeroed.
HWY_INLINE const float* LeafBlock(const TriangleLeaves&, const float* leaf_data, uint32_t first, uint32_t,
                                  float*, uint32_t* /*stride: count*/) {
  return leaf_data + 9 * size_t(first);
}

// Decoding a packed leaf block: per index run one byte load widened to int32 lanes, and per coordinate one table
// lookup (TableLookupLanes: a permute across the lanes) into the block's coordinate runs loaded as vectors; two
// tables and a blend when the leaf's vertices outnumber the lanes, hardware gathers when they outnumber two
// vectors (leaves of many triangles sharing few vertices). Lanes past the leaf take its vertex 0.
// A leaf of one vector's triangles takes runs of a whole vector each (stride L): every run is one store, which
// the kernels' loads then read whole, where runs of `count` overlapping stores stall the loads spanning two
// (store forwarding fails on them). Returns the stride.
template <class D>
HWY_INLINE uint32_t DecodeLeaf(D d, const PackedLeaves& t, uint32_t offset, uint32_t count, float* buffer) {
  constexpr size_t L = hn::MaxLanes(D());
  const uint8_t* const b = t.bytes(offset);
  const uint32_t nv = b[1];
  const uint8_t* const idx = b + 2;
  const float* const xyz = t.data.data() + offset + PackedLeaves::block_words(count, 0);
  if constexpr (L == 1) {  // HWY_SCALAR: plain copies
    for (uint32_t j = 0; j < count; ++j)
      for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a) buffer[size_t(3 * k + a) * count + j] = xyz[a * nv + idx[k * count + j]];
    buffer[9 * size_t(count)] = 0;
    return count;
  } else {
    const hn::RebindToSigned<D> di;
    const hn::Rebind<uint8_t, D> d8;
    const bool one_group = count <= L, two = nv > L, gather = nv > 2 * L;
    const uint32_t stride = one_group ? uint32_t(L) : count;
    hn::Vec<D> lo[3], hi[3];
    if (!gather)
      for (int a = 0; a < 3; ++a) {
        lo[a] = hn::LoadU(d, xyz + a * nv);
        hi[a] = two ? hn::LoadU(d, xyz + a * nv + L) : lo[a];
      }
    for (uint32_t g = 0; g < count; g += uint32_t(L)) {
      const auto live = hn::FirstN(di, count - g);
      for (int k = 0; k < 3; ++k) {
        const auto iv = hn::IfThenElseZero(live, hn::PromoteTo(di, hn::LoadU(d8, idx + k * count + g)));
        hn::Vec<D> run[3];
        if (HWY_UNLIKELY(gather)) {
          for (int a = 0; a < 3; ++a) run[a] = hn::GatherIndex(d, xyz + a * nv, iv);
        } else {
          const auto in_hi = hn::RebindMask(d, hn::Gt(iv, hn::Set(di, int32_t(L - 1))));
          const auto ind = hn::IndicesFromVec(d, hn::And(iv, hn::Set(di, int32_t(L - 1))));
          for (int a = 0; a < 3; ++a) {
            run[a] = hn::TableLookupLanes(lo[a], ind);
            if (two) run[a] = hn::IfThenElse(in_hi, hn::TableLookupLanes(hi[a], ind), run[a]);
          }
        }
        for (int a = 0; a < 3; ++a) {
          float* const out = buffer + size_t(3 * k + a) * stride + g;
          if (one_group || g + L <= count) hn::StoreU(run[a], d, out);
          else hn::BlendedStore(run[a], hn::RebindMask(d, live), d, out);
        }
      }
    }
    if (!one_group) hn::StoreU(hn::Zero(d), d, buffer + 9 * size_t(count));
    return stride;
  }
}
HWY_INLINE const float* LeafBlock(const PackedLeaves& t, const float*, uint32_t offset, uint32_t count,
                                  float* buffer, uint32_t* stride) {
  *stride = DecodeLeaf(hn::CappedTag<float, 8>(), t, offset, count, buffer);  // 8 lanes: the kernels' groups
  return buffer;
}

// A packed leaf of at most one vector's triangles whose vertices fit two vectors, decoded straight into registers
// for one ray (no store and reload): v[k][j] = vertex k's coordinate on axis axis[j] minus origin[j] (lane =
// triangle; lanes past the leaf: vertex 0), the values the run layout's loads would give. False for other leaves.
template <class D>
HWY_INLINE bool PackedLeafInRegisters(D d, const PackedLeaves& t, uint32_t offset, uint32_t count,
                                      const int (&axis)[3], const float (&origin)[3], hn::Vec<D> (&v)[3][3]) {
  constexpr size_t L = hn::MaxLanes(D());
  const uint8_t* const b = t.bytes(offset);
  const uint32_t nv = b[1];
  if (count > L || nv > 2 * L) return false;
  const float* const xyz = t.data.data() + offset + PackedLeaves::block_words(count, 0);
  const hn::RebindToSigned<D> di;
  const hn::Rebind<uint8_t, D> d8;
  const bool two = nv > L;
  hn::Vec<D> lo[3], hi[3];
  for (int j = 0; j < 3; ++j) {
    lo[j] = hn::LoadU(d, xyz + axis[j] * nv);
    hi[j] = two ? hn::LoadU(d, xyz + axis[j] * nv + L) : lo[j];
  }
  const auto live = hn::FirstN(di, count);
  for (int k = 0; k < 3; ++k) {
    const auto iv = hn::IfThenElseZero(live, hn::PromoteTo(di, hn::LoadU(d8, b + 2 + k * count)));
    const auto in_hi = hn::RebindMask(d, hn::Gt(iv, hn::Set(di, int32_t(L - 1))));
    const auto ind = hn::IndicesFromVec(d, hn::And(iv, hn::Set(di, int32_t(L - 1))));
    for (int j = 0; j < 3; ++j) {
      auto c = hn::TableLookupLanes(lo[j], ind);
      if (two) c = hn::IfThenElse(in_hi, hn::TableLookupLanes(hi[j], ind), c);
      v[k][j] = hn::Sub(c, hn::Set(d, origin[j]));
    }
  }
  return true;
}

// The leaf-order index of the first triangle of the leaf a child reference (less kLeafFlag) names: the reference
// itself, or a packed block's first word.
HWY_INLINE uint32_t LeafFirst(const TriangleLeaves&, uint32_t leaf) { return leaf; }
HWY_INLINE uint32_t LeafFirst(const PackedLeaves& t, uint32_t leaf) { return t.first(leaf); }

// Vertex k of leaf triangle j (< count) of a leaf in the run layout, runs `stride` floats apart.
HWY_INLINE Vec3f BlockVertex(const float* block, uint32_t stride, uint32_t j, int k) {
  const size_t at = size_t(3 * k) * stride + j;
  return {block[at], block[at + stride], block[at + 2 * size_t(stride)]};
}

// Starts loading the leaf (first, count): its run block, or its packed block.
HWY_INLINE void PrefetchLeaf(const TriangleLeaves&, const float* leaf_data, uint32_t first, uint32_t count) {
  const char* p = reinterpret_cast<const char*>(leaf_data + 9 * size_t(first));
  const uintptr_t end = reinterpret_cast<uintptr_t>(p) + 36 * size_t(count);
  for (uintptr_t a = reinterpret_cast<uintptr_t>(p) & ~uintptr_t(63); a < end; a += 64)
    __builtin_prefetch(reinterpret_cast<const void*>(a));
}
// A packed block's size is in its header: the lines of a typical one (about 19 bytes per triangle).
HWY_INLINE void PrefetchLeaf(const PackedLeaves& t, const float*, uint32_t offset, uint32_t count) {
  const char* p = reinterpret_cast<const char*>(t.data.data() + offset);
  const uintptr_t end = reinterpret_cast<uintptr_t>(p) + 8 + 19 * size_t(count);
  for (uintptr_t a = reinterpret_cast<uintptr_t>(p) & ~uintptr_t(63); a < end; a += 64)
    __builtin_prefetch(reinterpret_cast<const void*>(a));
}

// Start of the leaf data the single-ray kernel keeps at hand (SingleRay::leaf_data).
HWY_INLINE const float* LeafData(const TriangleLeaves& t) { return t.data.data(); }
HWY_INLINE const float* LeafData(const PackedLeaves&) { return nullptr; }

}  // namespace
}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // TORTE_SIMD_LAYOUT_INL_H_TARGET
