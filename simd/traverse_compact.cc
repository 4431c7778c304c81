// Traversal of the compact layouts (accel/compact_bvh.h; see traverse.h for the semantics): the dispatch entry
// points of the single-ray and packet kernels (traverse_single-inl.h, packet_trace-inl.h) instantiated for
// quantised nodes and/or packed leaves. A file of its own so the default layout's kernels compile as before.

// No FMA contraction (see traverse.cc): the watertight test must round exactly like the scalar one.
#include "core/no_fp_contract.h"  // before every other include

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "geometry/triangle.h"
#include "traverse.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "traverse_compact.cc"  // found through the simd/ include directory of torte_core
#include <hwy/foreach_target.h>                   // IWYU pragma: keep
#include <hwy/highway.h>

#include "traverse-inl.h"
#include "packet-inl.h"
#include "traverse_single-inl.h"
#include "packet_tests-inl.h"
#include "packet_trace-inl.h"

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {

// Exported per target (HWY_EXPORT needs plain function names): Q = quantised nodes, W = default nodes,
// T = triangle leaves, P = packed leaves; packet_size is 8 or 16 (checked by the callers below).
#define TORTE_COMPACT_KERNELS(Name, Tree, Leaves)                                                              \
  void ClosestSingle##Name(const Tree& b, const Leaves& t, const RaySoA& r, size_t n, Hit* h) {               \
    ClosestSingle(b, t, r, n, h);                                                                              \
  }                                                                                                            \
  void AnySingle##Name(const Tree& b, const Leaves& t, const RaySoA& r, size_t n, uint8_t* o) {               \
    AnySingle(b, t, r, n, o);                                                                                  \
  }                                                                                                            \
  void ClosestPackets##Name(const Tree& b, const Leaves& t, const RaySoA& r, size_t n, Hit* h, int ps) {      \
    ps == 16 ? ClosestPackets<16>(b, t, r, n, h) : ClosestPackets<8>(b, t, r, n, h);                          \
  }                                                                                                            \
  void AnyPackets##Name(const Tree& b, const Leaves& t, const RaySoA& r, size_t n, uint8_t* o, int ps) {      \
    ps == 16 ? AnyPackets<16>(b, t, r, n, o) : AnyPackets<8>(b, t, r, n, o);                                  \
  }
TORTE_COMPACT_KERNELS(QT, CompactBvh, TriangleLeaves)
TORTE_COMPACT_KERNELS(QP, CompactBvh, PackedLeaves)
TORTE_COMPACT_KERNELS(WP, WideBvh<8>, PackedLeaves)
#undef TORTE_COMPACT_KERNELS

}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace torte {

namespace {
void check_packet_size(int packet_size) {
  if (packet_size != 8 && packet_size != 16)
    throw Error("Ray packets hold 8 or 16 rays, not " + std::to_string(packet_size) + ".");
}
}  // namespace

#define TORTE_COMPACT_ENTRIES(Name, Tree, Leaves)                                                              \
  HWY_EXPORT(ClosestSingle##Name);                                                                             \
  HWY_EXPORT(AnySingle##Name);                                                                                 \
  HWY_EXPORT(ClosestPackets##Name);                                                                            \
  HWY_EXPORT(AnyPackets##Name);                                                                                \
  void intersect_closest(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count, Hit* hits) {  \
    HWY_DYNAMIC_DISPATCH(ClosestSingle##Name)(bvh, tris, rays, count, hits);                                   \
  }                                                                                                            \
  void intersect_any(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count, uint8_t* occ) {   \
    HWY_DYNAMIC_DISPATCH(AnySingle##Name)(bvh, tris, rays, count, occ);                                        \
  }                                                                                                            \
  void intersect_closest_packets(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count,       \
                                 Hit* hits, int packet_size) {                                                 \
    check_packet_size(packet_size);                                                                            \
    HWY_DYNAMIC_DISPATCH(ClosestPackets##Name)(bvh, tris, rays, count, hits, packet_size);                     \
  }                                                                                                            \
  void intersect_any_packets(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count,           \
                             uint8_t* occ, int packet_size) {                                                  \
    check_packet_size(packet_size);                                                                            \
    HWY_DYNAMIC_DISPATCH(AnyPackets##Name)(bvh, tris, rays, count, occ, packet_size);                          \
  }
TORTE_COMPACT_ENTRIES(QT, CompactBvh, TriangleLeaves)
TORTE_COMPACT_ENTRIES(QP, CompactBvh, PackedLeaves)
TORTE_COMPACT_ENTRIES(WP, WideBvh<8>, PackedLeaves)
#undef TORTE_COMPACT_ENTRIES

}  // namespace torte
#endif  // HWY_ONCE
