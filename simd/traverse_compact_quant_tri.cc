// Traversal of a compact layout (accel/compact_bvh.h; semantics in traverse.h): quantised nodes with the default triangle leaves. The
// single-ray and packet kernels (traverse_single-inl.h, packet_trace-inl.h) instantiated for this pairing and its
// dispatch entry points; each pairing is a file of its own (kernel_entries.h says why).

// No FMA contraction (see traverse.cc): the watertight test must round exactly like the scalar one.
#include "core/no_fp_contract.h"  // before every other include

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "geometry/triangle.h"
#include "kernel_entries.h"
#include "traverse.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "traverse_compact_quant_tri.cc"  // found through the simd/ include directory of torte_core
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "traverse_kernels-inl.h"

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {
TORTE_COMPACT_KERNELS(QT, CompactBvh, TriangleLeaves)
}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace torte {
TORTE_COMPACT_ENTRIES(QT, CompactBvh, TriangleLeaves)
}  // namespace torte
#endif  // HWY_ONCE
