// Single-ray traversal of WideBvh<N> + TriangleLeaves (see traverse.h for the semantics): the dispatch entry
// points. The kernel itself is in traverse_single-inl.h, shared with the packet kernels' single-ray fallback and
// with traverse_compact.cc.

// No contraction into FMA anywhere in this file: the edge functions must round like the scalar test's (see
// geometry/triangle.cc); the exact slab test then also rounds exactly like SlabRay (the FMA slab test fuses
// explicitly). Before every include, so that all inlined Highway functions carry the same option.
#include "core/no_fp_contract.h"  // before every other include

#include "traverse.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "geometry/triangle.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "traverse.cc"  // found through the simd/ include directory of torte_core
#include <hwy/foreach_target.h>           // IWYU pragma: keep
#include <hwy/highway.h>

#include "traverse-inl.h"
#include "traverse_single-inl.h"

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {

// Block set-up against one-ray set-up, ray by ray (see traverse.h).
size_t CountRaySetupMismatches(const RaySoA& rays, size_t count, const float* extent) {
  size_t mismatches = 0;
  RayBlock vec, one;
  for (size_t first = 0; first < count; first += kRayBlock) {
    const size_t n = std::min(kRayBlock, count - first);
    SetupRays<8>(rays, first, n, extent, vec);
    one.valid = one.fma_slabs = 0;
    for (size_t j = 0; j < n; ++j) SetupRay<8>(ray_at(rays, first + j), extent, one, j);
    for (size_t j = 0; j < n; ++j) {
      const bool valid = (vec.valid >> j) & 1;
      const bool fma = (vec.fma_slabs >> j) & 1;
      bool same = valid == (((one.valid >> j) & 1) != 0) && fma == (((one.fma_slabs >> j) & 1) != 0);
      const auto same_bits = [&](const auto& a, const auto& b) { return std::memcmp(&a, &b, sizeof(a)) == 0; };
      for (int a = 0; valid && same && a < 3; ++a) {
        same = same_bits(vec.o[a][j], one.o[a][j]) && same_bits(vec.inv_d[a][j], one.inv_d[a][j]) &&
               same_bits(vec.inv_d_far[a][j], one.inv_d_far[a][j]) && vec.near_off[a][j] == one.near_off[a][j] &&
               vec.far_off[a][j] == one.far_off[a][j] && vec.k[a][j] == one.k[a][j] &&
               same_bits(vec.ok[a][j], one.ok[a][j]) && same_bits(vec.s[a][j], one.s[a][j]);
      }
      for (int a = 0; valid && fma && same && a < 3; ++a)
        same = same_bits(vec.org_near[a][j], one.org_near[a][j]) && same_bits(vec.org_far[a][j], one.org_far[a][j]);
      if (valid && same) same = same_bits(vec.t_max[j], one.t_max[j]);
      mismatches += same ? 0 : 1;
    }
  }
  return mismatches;
}

// Exported per target (HWY_EXPORT needs plain function names).
void ClosestSingle4(const WideBvh<4>& b, const TriangleLeaves& t, const RaySoA& r, size_t n, Hit* h) {
  ClosestSingle(b, t, r, n, h);
}
void ClosestSingle8(const WideBvh<8>& b, const TriangleLeaves& t, const RaySoA& r, size_t n, Hit* h) {
  ClosestSingle(b, t, r, n, h);
}
void ClosestSingleCounted8(const WideBvh<8>& b, const TriangleLeaves& t, const RaySoA& r, size_t n, Hit* h,
                           TraversalCost* c) {
  ClosestSingleCounted(b, t, r, n, h, c);
}
void AnySingle4(const WideBvh<4>& b, const TriangleLeaves& t, const RaySoA& r, size_t n, uint8_t* o) {
  AnySingle(b, t, r, n, o);
}
void AnySingle8(const WideBvh<8>& b, const TriangleLeaves& t, const RaySoA& r, size_t n, uint8_t* o) {
  AnySingle(b, t, r, n, o);
}
int64_t TraversalTarget() { return HWY_TARGET; }

}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace torte {

HWY_EXPORT(ClosestSingle4);
HWY_EXPORT(ClosestSingle8);
HWY_EXPORT(ClosestSingleCounted8);
HWY_EXPORT(AnySingle4);
HWY_EXPORT(AnySingle8);
HWY_EXPORT(TraversalTarget);
HWY_EXPORT(CountRaySetupMismatches);

void intersect_closest(const WideBvh<4>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                       Hit* hits) {
  HWY_DYNAMIC_DISPATCH(ClosestSingle4)(bvh, tris, rays, count, hits);
}
void intersect_closest(const WideBvh<8>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                       Hit* hits) {
  HWY_DYNAMIC_DISPATCH(ClosestSingle8)(bvh, tris, rays, count, hits);
}
void intersect_closest_counted(const WideBvh<8>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                               Hit* hits, TraversalCost* costs) {
  HWY_DYNAMIC_DISPATCH(ClosestSingleCounted8)(bvh, tris, rays, count, hits, costs);
}
void intersect_any(const WideBvh<4>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                   uint8_t* occluded) {
  HWY_DYNAMIC_DISPATCH(AnySingle4)(bvh, tris, rays, count, occluded);
}
void intersect_any(const WideBvh<8>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                   uint8_t* occluded) {
  HWY_DYNAMIC_DISPATCH(AnySingle8)(bvh, tris, rays, count, occluded);
}
const char* traversal_target_name() { return hwy::TargetName(HWY_DYNAMIC_DISPATCH(TraversalTarget)()); }

size_t traverse_detail::count_ray_setup_mismatches(const RaySoA& rays, size_t count, const float extent[3]) {
  return HWY_DYNAMIC_DISPATCH(CountRaySetupMismatches)(rays, count, extent);
}

}  // namespace torte
#endif  // HWY_ONCE
