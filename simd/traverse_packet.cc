// Packet traversal of WideBvh<8> + TriangleLeaves (see traverse.h for the semantics): the dispatch entry points.
// The kernel (the algorithm and its measurements) is in packet_trace-inl.h, shared with the compact layouts'
// files; width 4 has its own file (traverse_packet_wide4.cc) so the two compile in parallel (kernel_entries.h).

// No FMA contraction (see traverse.cc): the watertight test must round exactly like the scalar one.
#include "core/no_fp_contract.h"  // before every other include

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "accel/bvh_build.h"
#include "kernel_entries.h"
#include "geometry/triangle.h"
#include "traverse.h"

#include <hwy/cache_control.h>  // Stream, FlushStream

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "traverse_packet.cc"  // found through the simd/ include directory of torte_core
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "traverse-inl.h"
#include "packet-inl.h"
#include "traverse_single-inl.h"
#include "packet_tests-inl.h"
#include "packet_trace-inl.h"

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {

// Exported per target; packet_size is 8 or 16 (checked by the callers below).
void ClosestPackets8(const WideBvh<8>& b, const TriangleLeaves& t, const RaySoA& r, size_t n, Hit* h, int ps) {
  ps == 16 ? ClosestPackets<16>(b, t, r, n, h) : ClosestPackets<8>(b, t, r, n, h);
}
void AnyPackets8(const WideBvh<8>& b, const TriangleLeaves& t, const RaySoA& r, size_t n, uint8_t* o, int ps) {
  ps == 16 ? AnyPackets<16>(b, t, r, n, o) : AnyPackets<8>(b, t, r, n, o);
}

}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace torte {

static_assert(kMaxBvhDepth <= traverse_detail::kMaxWideDepth, "traversal stacks are sized for the builder's depth");

HWY_EXPORT(ClosestPackets8);
HWY_EXPORT(AnyPackets8);

void intersect_closest_packets(const WideBvh<8>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                               Hit* hits, int packet_size) {
  traverse_detail::check_packet_size(packet_size);
  HWY_DYNAMIC_DISPATCH(ClosestPackets8)(bvh, tris, rays, count, hits, packet_size);
}
void intersect_any_packets(const WideBvh<8>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                           uint8_t* occluded, int packet_size) {
  traverse_detail::check_packet_size(packet_size);
  HWY_DYNAMIC_DISPATCH(AnyPackets8)(bvh, tris, rays, count, occluded, packet_size);
}

}  // namespace torte
#endif  // HWY_ONCE
