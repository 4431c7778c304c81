// Pieces shared by the traversal kernels' dispatch files (traverse_packet*.cc, traverse_compact_*.cc): the
// packet-size check of their entry points and, for the compact layouts, one macro pair per (node, leaf) pairing.
// Each pairing has a translation unit of its own: instantiated for every Highway target, one pairing takes
// minutes to compile (most under the sanitizers), and separate files compile in parallel.
#pragma once
#include <string>

#include "core/error.h"

namespace torte::traverse_detail {

/// Packets hold 8 or 16 rays; anything else from a caller is a clear error, not a wrong kernel.
inline void check_packet_size(int packet_size) {
  if (packet_size != 8 && packet_size != 16)
    throw Error("Ray packets hold 8 or 16 rays, not " + std::to_string(packet_size) + ".");
}

}  // namespace torte::traverse_detail

// The per-target kernels of one compact pairing (inside torte::HWY_NAMESPACE, after packet_trace-inl.h).
// Exported per target (HWY_EXPORT needs plain function names): Q = quantised nodes, W = default nodes,
// T = triangle leaves, P = packed leaves; packet_size is 8 or 16 (checked by the entry points).
#define TORTE_COMPACT_KERNELS(Name, Tree, Leaves)                                                              \
  void ClosestSingle##Name(const Tree& b, const Leaves& t, const RaySoA& r, size_t n, Hit* h) {               \
    ClosestSingle(b, t, r, n, h);                                                                              \
  }                                                                                                            \
  void ClosestSingleCounted##Name(const Tree& b, const Leaves& t, const RaySoA& r, size_t n, Hit* h,         \
                                  TraversalCost* c) {                                                          \
    ClosestSingleCounted(b, t, r, n, h, c);                                                                    \
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

// The per-target packet kernels of the default layout at width W (inside torte::HWY_NAMESPACE), and their
// dispatch entry points (inside namespace torte, under HWY_ONCE); packet_size is 8 or 16.
#define TORTE_PACKET_KERNELS(W)                                                                                \
  void ClosestPackets##W(const WideBvh<W>& b, const TriangleLeaves& t, const RaySoA& r, size_t n, Hit* h,    \
                         int ps) {                                                                             \
    ps == 16 ? ClosestPackets<16>(b, t, r, n, h) : ClosestPackets<8>(b, t, r, n, h);                          \
  }                                                                                                            \
  void AnyPackets##W(const WideBvh<W>& b, const TriangleLeaves& t, const RaySoA& r, size_t n, uint8_t* o,     \
                     int ps) {                                                                                 \
    ps == 16 ? AnyPackets<16>(b, t, r, n, o) : AnyPackets<8>(b, t, r, n, o);                                  \
  }
#define TORTE_PACKET_ENTRIES(W)                                                                                \
  HWY_EXPORT(ClosestPackets##W);                                                                               \
  HWY_EXPORT(AnyPackets##W);                                                                                   \
  void intersect_closest_packets(const WideBvh<W>& bvh, const TriangleLeaves& tris, const RaySoA& rays,      \
                                 size_t count, Hit* hits, int packet_size) {                                   \
    traverse_detail::check_packet_size(packet_size);                                                           \
    HWY_DYNAMIC_DISPATCH(ClosestPackets##W)(bvh, tris, rays, count, hits, packet_size);                        \
  }                                                                                                            \
  void intersect_any_packets(const WideBvh<W>& bvh, const TriangleLeaves& tris, const RaySoA& rays,          \
                             size_t count, uint8_t* occluded, int packet_size) {                               \
    traverse_detail::check_packet_size(packet_size);                                                           \
    HWY_DYNAMIC_DISPATCH(AnyPackets##W)(bvh, tris, rays, count, occluded, packet_size);                        \
  }

// The dispatch entry points of traverse.h for one compact pairing (inside namespace torte, under HWY_ONCE).
#define TORTE_COMPACT_ENTRIES(Name, Tree, Leaves)                                                              \
  HWY_EXPORT(ClosestSingle##Name);                                                                             \
  HWY_EXPORT(ClosestSingleCounted##Name);                                                                      \
  HWY_EXPORT(AnySingle##Name);                                                                                 \
  HWY_EXPORT(ClosestPackets##Name);                                                                            \
  HWY_EXPORT(AnyPackets##Name);                                                                                \
  void intersect_closest(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count, Hit* hits) {  \
    HWY_DYNAMIC_DISPATCH(ClosestSingle##Name)(bvh, tris, rays, count, hits);                                   \
  }                                                                                                            \
  void intersect_closest_counted(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count,       \
                                 Hit* hits, TraversalCost* costs) {                                            \
    HWY_DYNAMIC_DISPATCH(ClosestSingleCounted##Name)(bvh, tris, rays, count, hits, costs);                     \
  }                                                                                                            \
  void intersect_any(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count, uint8_t* occ) {   \
    HWY_DYNAMIC_DISPATCH(AnySingle##Name)(bvh, tris, rays, count, occ);                                        \
  }                                                                                                            \
  void intersect_closest_packets(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count,       \
                                 Hit* hits, int packet_size) {                                                 \
    traverse_detail::check_packet_size(packet_size);                                                           \
    HWY_DYNAMIC_DISPATCH(ClosestPackets##Name)(bvh, tris, rays, count, hits, packet_size);                     \
  }                                                                                                            \
  void intersect_any_packets(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count,           \
                             uint8_t* occ, int packet_size) {                                                  \
    traverse_detail::check_packet_size(packet_size);                                                           \
    HWY_DYNAMIC_DISPATCH(AnyPackets##Name)(bvh, tris, rays, count, occ, packet_size);                          \
  }
