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

#include "traverse_kernels-inl.h"

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {
TORTE_PACKET_KERNELS(8)
}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace torte {
static_assert(kMaxBvhDepth <= traverse_detail::kMaxWideDepth, "traversal stacks are sized for the builder's depth");
TORTE_PACKET_ENTRIES(8)
}  // namespace torte
#endif  // HWY_ONCE
