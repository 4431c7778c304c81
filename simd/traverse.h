// SIMD traversal of a wide triangle BVH (WideBvh<N> + TriangleLeaves, accel/wide_bvh.h): closest hit and any hit,
// one ray at a time or in packets of consecutive rays. Plain C++ API over arrays; the kernels are Highway code
// (traverse.cc, traverse_packet.cc) dispatched at run time to the best target the CPU supports.
//
// Semantics shared by every entry point (they match the scalar reference: Bvh2 or wide_bvh_reference.h driving
// geometry/triangle.h's intersect_triangle):
// - A ray hits a triangle at t with 0 < t < t_max (strict on both ends), tested with the watertight test of
//   Woop, Benthin & Wald 2013 making the same decisions as the scalar intersect_triangle, so rays through shared
//   edges or vertices of a closed mesh never slip through.
// - Hit::prim is a position in LEAF ORDER (an index into the TriangleLeaves arrays), not the caller's triangle
//   index: map it through bvh.prim_indices[hit.prim] when needed. b1, b2 are the barycentrics of vertices 1 and 2.
//   A miss is Hit{} (t = inf, prim = kNoHit). When two triangles are hit at exactly the same t (a ray through a
//   shared edge) either may be reported.
// - Invalid rays (a NaN or infinite origin or direction component, a zero direction, or t_max that is NaN or
//   <= 0) are misses / not occluded. In a packet they never affect the other rays.
// - A ray starting exactly on a surface: the triangle it starts on is hit only if its computed t rounds to a
//   positive value (t = 0 exactly, e.g. an origin on a vertex, is a miss; a point interpolated inside the
//   triangle may give t ~ 1e-7 and self-hit). Offset origins with offset_origin (core/ray.h) as with the scalar
//   test.
// - Trees must have at most 64 levels of wide nodes (a binary build bounded at 64 levels collapses to that).
//   Leaves may hold any number of triangles (leaf_count <= 255); the root is node 0 and is always a node.
// - Rays are read from RaySoA (all seven arrays must hold `count` entries); results are written per ray.
#pragma once
#include <cstddef>
#include <cstdint>

#include "accel/compact_bvh.h"
#include "accel/hit.h"
#include "accel/packed_leaves.h"
#include "accel/wide_bvh.h"

namespace torte {

// One ray at a time (lanes = children in nodes, lanes = triangles in leaves).
void intersect_closest(const WideBvh<4>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                       Hit* hits);
void intersect_closest(const WideBvh<8>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                       Hit* hits);
/// As intersect_closest, counting: adds to costs[i] the nodes ray i visited and the triangles it tested (a separate
/// kernel instantiation, as fast as the plain one but for its two additions per node and leaf).
void intersect_closest_counted(const WideBvh<8>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                               Hit* hits, TraversalCost* costs);
// occluded[i] = 1 if anything blocks ray i in (0, t_max), else 0.
void intersect_any(const WideBvh<4>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                   uint8_t* occluded);
void intersect_any(const WideBvh<8>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                   uint8_t* occluded);

// Packets of `packet_size` (8 or 16, else torte::Error) consecutive rays traced together (lanes = rays): best for
// coherent rays (camera rays of a tile, shadow rays towards one light). `count` need not be a multiple of the
// packet size. Results are the same as the single-ray functions' (up to the choice between equal-t hits).
void intersect_closest_packets(const WideBvh<4>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                               Hit* hits, int packet_size = 8);
void intersect_closest_packets(const WideBvh<8>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                               Hit* hits, int packet_size = 8);
void intersect_any_packets(const WideBvh<4>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                           uint8_t* occluded, int packet_size = 8);
void intersect_any_packets(const WideBvh<8>& bvh, const TriangleLeaves& tris, const RaySoA& rays, size_t count,
                           uint8_t* occluded, int packet_size = 8);

// The compact layouts (accel/compact_bvh.h, accel/packed_leaves.h): quantised nodes (CompactBvh) with either leaf
// type, or the default nodes with packed leaves (a tree whose leaf references make_packed_leaves rewrote). The same kernels and semantics (hits in the same leaf order); packet_size as above.
#define TORTE_COMPACT_TRAVERSAL(Tree, Leaves)                                                                      \
  void intersect_closest(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count, Hit* hits);        \
  void intersect_closest_counted(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count, Hit* hits, \
                                 TraversalCost* costs);                                                            \
  void intersect_any(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count, uint8_t* occluded);    \
  void intersect_closest_packets(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count, Hit* hits, \
                                 int packet_size = 8);                                                             \
  void intersect_any_packets(const Tree& bvh, const Leaves& tris, const RaySoA& rays, size_t count,                \
                             uint8_t* occluded, int packet_size = 8);
TORTE_COMPACT_TRAVERSAL(CompactBvh, TriangleLeaves)
TORTE_COMPACT_TRAVERSAL(CompactBvh, PackedLeaves)
TORTE_COMPACT_TRAVERSAL(WideBvh<8>, PackedLeaves)
#undef TORTE_COMPACT_TRAVERSAL

// Name of the Highway target the traversal kernels dispatch to on this CPU (e.g. "AVX3", "AVX2", "SCALAR").
const char* traversal_target_name();

namespace traverse_detail {
// For tests: how many of rays [0, count) get different per-ray constants (validity, or any bit of a valid ray's
// origin, inverse direction, FMA slab choice and constants, plane offsets, watertight axes, shear) from the
// single-ray kernel's block set-up (vector ops across 16 rays, simd/single_ray-inl.h) than from the one-ray scalar
// set-up, for a tree whose plane_extent is `extent`. 0 when consistent.
size_t count_ray_setup_mismatches(const RaySoA& rays, size_t count, const float extent[3]);
}  // namespace traverse_detail

}  // namespace torte
