// Packet traversal of the packed voxel kd-tree (see voxel_packet.h for the semantics), after Wald et al. 2001:
// the packet walks the implicit tree as one; per inner node every lane computes, exactly as the single-ray
// trace_tree (voxel/voxel_traverse.h) does, its split distance and whether it goes to the near child, the far
// child or both, with its own entry/exit interval and entry axis. All lanes of a packet share their direction
// sign on each axis, so the lanes that go to both children agree on which one comes first (the child on the
// direction's negative side): the packet descends into that child with the lanes that want it, and pushes the
// other with its lanes and their intervals. Every lane thus visits its nodes in its single-ray order. In a leaf
// that is not empty, each active lane runs the single-ray leaf code (voxel_detail::solid_voxel / walk_cells);
// a lane that hits (or stops) is dead and masked out of everything popped afterwards.
//
// State per node (tn, tf, entry axis, active mask) is kept per lane in float arrays, one vector per lane group
// (CappedTag<float, P>; targets narrower than P loop over groups). The stack holds whole states; a node's
// children are written to stack[k] (the second child) and stack[k + 1] (the first), which saves copies: an
// unwanted second child is marked dead (an empty leaf) and skipped when popped. The tree depth is at most 38
// levels (2^26 chunk cells, voxel_tree.cc), so the stack never holds more than 40 states.

// No contraction into FMA: the single-ray code inlined here (entry_cell, face_uv: o + d * t) must round as it does
// in the single-ray functions compiled without FMA. Before every include.
#include "core/no_fp_contract.h"  // before every other include

#include "voxel_packet.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "voxel_packet.cc"  // found through the simd/ include directory of torte_core
#include <hwy/foreach_target.h>               // IWYU pragma: keep
#include <hwy/highway.h>

#ifndef TORTE_SIMD_VOXEL_PACKET_COMMON_
#define TORTE_SIMD_VOXEL_PACKET_COMMON_
namespace torte::voxel_packet_detail {

// A single-ray cell handler over the callbacks.
struct CallbackCells {
  const VoxelCellCallbacks& cb;
  bool intersect(int16_t id, const Ray& r, Hit* h) const { return cb.intersect && cb.intersect(cb.ctx, id, r, h); }
  bool occluded(int16_t id, const Ray& r) const { return cb.occluded && cb.occluded(cb.ctx, id, r); }
};

constexpr int kStackStates = 48;

}  // namespace torte::voxel_packet_detail
#endif

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
using voxel_packet_detail::CallbackCells;
using voxel_packet_detail::kStackStates;
namespace vd = voxel_detail;

template <size_t P>
struct VoxelPacket {
  alignas(64) float o[3][P], d[3][P], inv[3][P];  // local rays (make_local), zeros in lanes not traced here
  alignas(64) float t_max[P];
  alignas(64) float alive[P];  // mask: lanes still looking for a hit
  int origin[3];
  bool positive[3];  // the packet's direction sign per axis (lanes with d = 0 on the axis never go both ways)

  vd::LocalRay ray(size_t i) const {
    vd::LocalRay r;
    for (int a = 0; a < 3; ++a) {
      r.o[a] = o[a][i];
      r.d[a] = d[a][i];
      r.inv[a] = inv[a][i];
      r.origin[a] = origin[a];
    }
    r.t_max = t_max[i];
    return r;
  }
};

template <size_t P>
struct alignas(64) VoxelState {
  float tn[P], tf[P], entry[P], active[P];  // entry axis as a float (-1: the origin's own cell); active: mask
  VoxelNode node;
  int32_t lo[3], lg[3];
};

template <bool kAny, size_t P>
HWY_NOINLINE void TracePacket(const VoxelTree& tree, const Ray* rays, size_t n, const CallbackCells& cells,
                              VoxelHit* hits, uint8_t* found) {
  const hn::CappedTag<float, P> d;
  const size_t L = hn::Lanes(d);
  VoxelPacket<P> p;
  VoxelState<P> stack[kStackStates];
  VoxelState<P>& root = stack[0];
  const int* org = tree.origin();
  const int* lg0 = tree.log2_size();
  for (int a = 0; a < 3; ++a) {
    p.origin[a] = org[a];
    root.lo[a] = 0;
    root.lg[a] = lg0[a];
  }
  root.node = tree.root();
  uint32_t traced = 0;  // lanes traced as a packet
  int sign_set = 0;     // axes whose packet sign is fixed
  for (size_t i = 0; i < P; ++i) {
    for (int a = 0; a < 3; ++a) p.o[a][i] = p.d[a][i] = p.inv[a][i] = 0;
    p.t_max[i] = 0;
    root.tn[i] = root.tf[i] = root.entry[i] = 0;
    if (i >= n) continue;
    if constexpr (!kAny) hits[i] = VoxelHit{};
    found[i] = 0;
    const Ray& ray = rays[i];
    bool packet = true;
    for (int a = 0; a < 3 && packet; ++a) {
      const float da = ray.d[a];
      packet = std::isfinite(ray.o[a]) && std::isfinite(da) && (da == 0 || std::isfinite(1.0f / da));
      if (!packet || da == 0) continue;
      if (!((sign_set >> a) & 1)) {
        sign_set |= 1 << a;
        p.positive[a] = da > 0;
      } else if ((da > 0) != p.positive[a]) {
        packet = false;
      }
    }
    if (!packet) {  // alone, with the single-ray function
      VoxelHit h;
      found[i] = vd::trace_tree<kAny>(tree, ray, cells, &h) ? 1 : 0;
      if constexpr (!kAny) hits[i] = h;
      continue;
    }
    vd::LocalRay r;
    float t0, t1;
    int entry;
    if (!vd::make_local(tree, ray, &r, &t0, &t1, &entry)) continue;
    for (int a = 0; a < 3; ++a) {
      p.o[a][i] = r.o[a];
      p.d[a][i] = r.d[a];
      p.inv[a][i] = r.inv[a];
    }
    p.t_max[i] = r.t_max;
    root.tn[i] = t0;
    root.tf[i] = t1;
    root.entry[i] = float(entry);
    traced |= 1u << i;
  }
  if (traced == 0) return;
  for (int a = 0; a < 3; ++a)
    if (!((sign_set >> a) & 1)) p.positive[a] = true;
  {
    uint32_t bits = 0;
    for (size_t i = 0; i < P; ++i) {
      bits = ((traced >> i) & 1) ? ~0u : 0u;
      __builtin_memcpy(&root.active[i], &bits, 4);
      p.alive[i] = root.active[i];
    }
  }
  const VoxelNode* nodes = tree.nodes().data();
  const auto zero = hn::Zero(d), minus_one = hn::Set(d, -1.0f);
  constexpr uint32_t kEmpty = VoxelNode::leaf(0).bits;
  int k = 0;
  for (;;) {
    VoxelState<P>& s = stack[k];
    const VoxelNode node = s.node;
    if (!node.is_leaf()) {
      const int a = node.axis();
      const VoxelNode* kids = nodes + 2 * size_t(node.pair());
      const int lga = s.lg[a] - 1;
      const int split = s.lo[a] + (1 << lga);
      const bool pos = p.positive[a];
      VoxelState<P>& f = stack[k + 1];
      const VoxelNode first = kids[pos ? 0 : 1], second = kids[pos ? 1 : 0];
      for (int b = 0; b < 3; ++b) {
        f.lo[b] = s.lo[b];
        f.lg[b] = s.lg[b];
      }
      f.lg[a] = s.lg[a] = lga;
      f.lo[a] = pos ? s.lo[a] : split;
      s.lo[a] = pos ? split : s.lo[a];
      f.node = first;
      s.node = second;
      const auto fsplit = hn::Set(d, float(split)), axis = hn::Set(d, float(a));
      bool any_first = false, any_second = false;
      for (size_t g = 0; g < P; g += L) {
        const auto act = hn::MaskFromVec(hn::Load(d, s.active + g));
        const auto oa = hn::Load(d, p.o[a] + g), da = hn::Load(d, p.d[a] + g), inva = hn::Load(d, p.inv[a] + g);
        const auto tn = hn::Load(d, s.tn + g), tf = hn::Load(d, s.tf + g), entry = hn::Load(d, s.entry + g);
        // As trace_tree: the near child holds the origin (on the plane: the side the ray goes to).
        const auto below = hn::Or(hn::Lt(oa, fsplit), hn::And(hn::Eq(oa, fsplit), hn::Lt(da, zero)));
        const auto ts = hn::IfThenElse(hn::Eq(da, zero), minus_one, hn::Mul(hn::Sub(fsplit, oa), inva));
        const auto near_only = hn::Or(hn::Gt(ts, tf), hn::Le(ts, zero));
        const auto far_only = hn::AndNot(near_only, hn::Lt(ts, tn));
        const auto both = hn::Not(hn::Or(near_only, far_only));
        // Is the lane's near child the packet's first child?
        const auto near_first = pos ? below : hn::Not(below);
        const auto one_side = hn::Or(hn::And(near_only, near_first), hn::AndNot(near_first, far_only));
        const auto other_side = hn::Or(hn::AndNot(near_first, near_only), hn::And(far_only, near_first));
        const auto want_first = hn::And(act, hn::Or(one_side, both));
        const auto want_second = hn::And(act, hn::Or(other_side, both));
        any_first |= !hn::AllFalse(d, want_first);
        any_second |= !hn::AllFalse(d, want_second);
        hn::Store(tn, d, f.tn + g);
        hn::Store(hn::IfThenElse(both, ts, tf), d, f.tf + g);
        hn::Store(entry, d, f.entry + g);
        hn::Store(hn::VecFromMask(d, want_first), d, f.active + g);
        hn::Store(hn::IfThenElse(both, ts, tn), d, s.tn + g);
        hn::Store(hn::IfThenElse(both, axis, entry), d, s.entry + g);
        hn::Store(hn::VecFromMask(d, want_second), d, s.active + g);
      }
      const bool go_first = any_first && first.bits != kEmpty;
      const bool keep_second = any_second && second.bits != kEmpty;
      if (go_first) {
        if (!keep_second) s.node = VoxelNode{kEmpty};
        ++k;
        continue;
      }
      if (keep_second) continue;  // the second child only, already in stack[k]
    } else if (const int16_t id = node.id(); id != 0) {
      const int blo[3] = {s.lo[0], s.lo[1], s.lo[2]};
      const int bhi[3] = {blo[0] + (1 << s.lg[0]), blo[1] + (1 << s.lg[1]), blo[2] + (1 << s.lg[2])};
      for (size_t i = 0; i < P; ++i) {
        if (s.active[i] == 0.0f) continue;  // masks are 0 or NaN (all ones): NaN != 0
        const vd::LocalRay r = p.ray(i);
        const float tn = s.tn[i], tf = s.tf[i];
        const int entry = int(s.entry[i]);
        VoxelHit h;
        vd::Step st;
        if (id > 0) {
          int v[3];
          vd::entry_cell(r, blo, bhi, tn, entry, v);
          st = vd::solid_voxel(r, v, id, tn, entry, &h);
        } else {
          st = vd::walk_cells(r, blo, bhi, tn, tf, entry, [&](const int* v, float, float te, int) {
            return vd::cell_voxel<kAny>(r, v, id, te, cells, &h);
          });
        }
        if (st == vd::kContinue) continue;
        p.alive[i] = 0.0f;
        if (st == vd::kHit) {
          found[i] = 1;
          if constexpr (!kAny) hits[i] = h;
        }
      }
    }
    // Pop: the next state with live lanes.
    for (--k; k >= 0; --k) {
      VoxelState<P>& t = stack[k];
      if (t.node.bits == kEmpty) continue;
      bool any = false;
      for (size_t g = 0; g < P; g += L) {
        const auto act = hn::And(hn::MaskFromVec(hn::Load(d, t.active + g)), hn::MaskFromVec(hn::Load(d, p.alive + g)));
        any |= !hn::AllFalse(d, act);
        hn::Store(hn::VecFromMask(d, act), d, t.active + g);
      }
      if (any) break;
    }
    if (k < 0) return;
  }
}

template <bool kAny, size_t P>
void TraceAll(const VoxelTree& tree, const Ray* rays, size_t count, const VoxelCellCallbacks& cb, VoxelHit* hits,
              uint8_t* found) {
  const CallbackCells cells{cb};
  for (size_t b = 0; b < count; b += P)
    TracePacket<kAny, P>(tree, rays + b, std::min(P, count - b), cells, kAny ? nullptr : hits + b, found + b);
}

}  // namespace

void VoxelClosest8(const VoxelTree& t, const Ray* r, size_t n, VoxelHit* h, uint8_t* f, const VoxelCellCallbacks& c) {
  TraceAll<false, 8>(t, r, n, c, h, f);
}
void VoxelClosest16(const VoxelTree& t, const Ray* r, size_t n, VoxelHit* h, uint8_t* f, const VoxelCellCallbacks& c) {
  TraceAll<false, 16>(t, r, n, c, h, f);
}
void VoxelAny8(const VoxelTree& t, const Ray* r, size_t n, uint8_t* o, const VoxelCellCallbacks& c) {
  TraceAll<true, 8>(t, r, n, c, nullptr, o);
}
void VoxelAny16(const VoxelTree& t, const Ray* r, size_t n, uint8_t* o, const VoxelCellCallbacks& c) {
  TraceAll<true, 16>(t, r, n, c, nullptr, o);
}
int64_t VoxelPacketTarget() { return HWY_TARGET; }

}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace torte {

HWY_EXPORT(VoxelClosest8);
HWY_EXPORT(VoxelClosest16);
HWY_EXPORT(VoxelAny8);
HWY_EXPORT(VoxelAny16);
HWY_EXPORT(VoxelPacketTarget);

static void check_packet_size(int packet_size) {
  if (packet_size != 8 && packet_size != 16)
    throw Error("voxel packets: packet size must be 8 or 16, not " + std::to_string(packet_size));
}

void voxel_intersect_packets(const VoxelTree& tree, const Ray* rays, size_t count, VoxelHit* hits, uint8_t* found,
                             int packet_size, const VoxelCellCallbacks& cells) {
  check_packet_size(packet_size);
  if (packet_size == 8)
    HWY_DYNAMIC_DISPATCH(VoxelClosest8)(tree, rays, count, hits, found, cells);
  else
    HWY_DYNAMIC_DISPATCH(VoxelClosest16)(tree, rays, count, hits, found, cells);
}

void voxel_occluded_packets(const VoxelTree& tree, const Ray* rays, size_t count, uint8_t* occluded,
                            int packet_size, const VoxelCellCallbacks& cells) {
  check_packet_size(packet_size);
  if (packet_size == 8)
    HWY_DYNAMIC_DISPATCH(VoxelAny8)(tree, rays, count, occluded, cells);
  else
    HWY_DYNAMIC_DISPATCH(VoxelAny16)(tree, rays, count, occluded, cells);
}

const char* voxel_packet_target_name() { return hwy::TargetName(HWY_DYNAMIC_DISPATCH(VoxelPacketTarget)()); }

}  // namespace torte
#endif  // HWY_ONCE
