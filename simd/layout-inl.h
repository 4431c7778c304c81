// The two tree layouts as the traversal kernels read them (accel/wide_bvh.h, accel/compact_bvh.h): the kernels are
// templates over the node type and the leaf type, and reach a node's bounds and a leaf's triangles only through
// the functions here. A WideNode's planes are loaded as they lie; a QuantNode's are dequantised into registers
// (origin + q * scale, exact in the product so fused and unfused targets agree), after which the same slab tests
// run. A TriangleLeaves leaf is tested in place; an IndexedLeaves leaf is first gathered into the same run layout
// (nine runs of `count` floats, wide_bvh.h) in a buffer on the stack, which the same triangle tests then read.
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
constexpr bool kGathersLeaves = !std::is_same_v<Leaves, TriangleLeaves>;

// The leaf (first, count) in the run layout: in place for TriangleLeaves (from `leaf_data`, its data), else
// gathered into `buffer` (kLeafBufferFloats). Every lane a kernel loads from a run (up to 8 lanes from any
// position inside it) is written: runs are gathered in order, a group's lanes past the run spilling into the
// next run before that is written, and masked-out lanes read triangle `first`'s vertices.
HWY_INLINE const float* LeafBlock(const TriangleLeaves&, const float* leaf_data, uint32_t first, uint32_t,
                                  float*) {
  return leaf_data + 9 * size_t(first);
}
HWY_INLINE const float* LeafBlock(const IndexedLeaves& t, const float*, uint32_t first, uint32_t count,
                                  float* buffer) {
  const hn::CappedTag<float, 8> d;
  const hn::RebindToSigned<decltype(d)> di;
  const size_t L = hn::Lanes(d);
  const int32_t* const idx = reinterpret_cast<const int32_t*>(t.idx) + 3 * size_t(first);
  const auto stride = hn::Set(di, int32_t(t.stride));
  const auto offsets = [&](size_t g, int k) {
    const auto lane = hn::Iota(di, int32_t(g));
    return hn::IfThenElseZero(hn::Lt(lane, hn::Set(di, int32_t(count))),
                              hn::Add(hn::Mul(lane, hn::Set(di, 3)), hn::Set(di, k)));
  };
  if (count <= L) {  // one group (every leaf at the default max_leaf_size on 8-lane targets)
    for (int k = 0; k < 3; ++k) {
      const auto v = hn::Mul(hn::GatherIndex(di, idx, offsets(0, k)), stride);
      for (int a = 0; a < 3; ++a) hn::StoreU(hn::GatherIndex(d, t.pos[a], v), d, buffer + size_t(3 * k + a) * count);
    }
    return buffer;
  }
  for (int r = 0; r < 9; ++r)
    for (size_t g = 0; g < count; g += L) {
      const auto v = hn::Mul(hn::GatherIndex(di, idx, offsets(g, r / 3)), stride);
      hn::StoreU(hn::GatherIndex(d, t.pos[r % 3], v), d, buffer + size_t(r) * count + g);
    }
  return buffer;
}

// Vertex k of leaf triangle j (< count) of a leaf in the run layout.
HWY_INLINE Vec3f BlockVertex(const float* block, uint32_t count, uint32_t j, int k) {
  const size_t at = size_t(3 * k) * count + j;
  return {block[at], block[at + count], block[at + 2 * size_t(count)]};
}

// Starts loading the leaf (first, count): its run block, or its index triples (the vertices follow from those).
HWY_INLINE void PrefetchLeaf(const TriangleLeaves&, const float* leaf_data, uint32_t first, uint32_t count) {
  const char* p = reinterpret_cast<const char*>(leaf_data + 9 * size_t(first));
  const uintptr_t end = reinterpret_cast<uintptr_t>(p) + 36 * size_t(count);
  for (uintptr_t a = reinterpret_cast<uintptr_t>(p) & ~uintptr_t(63); a < end; a += 64)
    __builtin_prefetch(reinterpret_cast<const void*>(a));
}
HWY_INLINE void PrefetchLeaf(const IndexedLeaves& t, const float*, uint32_t first, uint32_t count) {
  const char* p = reinterpret_cast<const char*>(t.idx + 3 * size_t(first));
  const uintptr_t end = reinterpret_cast<uintptr_t>(p) + 12 * size_t(count);
  for (uintptr_t a = reinterpret_cast<uintptr_t>(p) & ~uintptr_t(63); a < end; a += 64)
    __builtin_prefetch(reinterpret_cast<const void*>(a));
}

// Start of the leaf data the single-ray kernel keeps at hand (SingleRay::leaf_data).
HWY_INLINE const float* LeafData(const TriangleLeaves& t) { return t.data.data(); }
HWY_INLINE const float* LeafData(const IndexedLeaves&) { return nullptr; }

}  // namespace
}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // TORTE_SIMD_LAYOUT_INL_H_TARGET
