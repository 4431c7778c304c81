// Shared by the traversal tests (test_traverse*.cc): triangle soups and trees, ray batches, the brute-force and
// scalar-reference expectations, and a loop over every Highway target compiled in and supported here.
#pragma once
#include <catch2/catch.hpp>
#include <hwy/highway.h>  // HWY_TARGETS
#include <hwy/targets.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "accel/bvh_build.h"
#include "accel/wide_bvh_reference.h"
#include "core/rng.h"
#include "geometry/mesh.h"
#include "geometry/subdivide.h"
#include "geometry/triangle.h"
#include "traverse.h"
#include "test_random.h"

namespace torte::test::traverse {

inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Triangles as vertex triples (p0, p1, p2 per triangle), the caller's numbering.
using Soup = std::vector<Vec3f>;

inline Soup random_soup(int n, uint64_t seed) {
  Pcg32 rng(seed);
  Soup s;
  for (int i = 0; i < n; ++i) {
    const Vec3f c = random_vec(rng) * 20 - Vec3f(10, 10, 10);
    const float size = 0.2f + 1.2f * rng.next_float();
    for (int k = 0; k < 3; ++k) s.push_back(c + random_direction(rng) * size);
  }
  return s;
}

inline Soup soup_of(const TriangleMesh& m) {
  Soup s;
  for (uint32_t i : m.indices) s.push_back(m.position(i));
  return s;
}

// Icosahedron subdivided `levels` times, vertices on the unit sphere scaled by `radius` around `center`: closed,
// with shared vertices, not axis-aligned.
inline Soup icosphere(int levels, Vec3f center, float radius) {
  const float p = (1 + std::sqrt(5.0f)) / 2;
  TriangleMesh m;
  for (Vec3f v : {Vec3f(-1, p, 0), Vec3f(1, p, 0), Vec3f(-1, -p, 0), Vec3f(1, -p, 0), Vec3f(0, -1, p),
                  Vec3f(0, 1, p), Vec3f(0, -1, -p), Vec3f(0, 1, -p), Vec3f(p, 0, -1), Vec3f(p, 0, 1),
                  Vec3f(-p, 0, -1), Vec3f(-p, 0, 1)})
    m.add_vertex(v);
  const uint32_t f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                             {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (const auto& t : f) m.add_triangle(t[0], t[1], t[2]);
  m = subdivide(m, levels);
  for (size_t i = 0; i < m.vertex_count(); ++i) {
    const Vec3f v = center + normalize(m.position(uint32_t(i))) * radius;
    m.x[i] = v.x, m.y[i] = v.y, m.z[i] = v.z;
  }
  return soup_of(m);
}

template <int N>
struct Tree {
  WideBvh<N> bvh;
  TriangleLeaves leaves;
};

template <int N>
Tree<N> build(const Soup& s, BvhBuildOptions options = {}) {
  std::vector<Bounds3f> b(s.size() / 3);
  for (size_t i = 0; i < b.size(); ++i)
    for (int k = 0; k < 3; ++k) b[i].extend(s[3 * i + k]);
  Tree<N> t;
  options.parallel = false;
  t.bvh = build_wide_bvh<N>(b, options);
  t.leaves = make_triangle_leaves(t.bvh, s, false);
  return t;
}

struct Rays {
  std::vector<float> ox, oy, oz, dx, dy, dz, t_max;
  void add(Vec3f o, Vec3f d, float t = kInfinity) {
    ox.push_back(o.x), oy.push_back(o.y), oz.push_back(o.z);
    dx.push_back(d.x), dy.push_back(d.y), dz.push_back(d.z);
    t_max.push_back(t);
  }
  size_t size() const { return ox.size(); }
  Ray ray(size_t i) const { return {{ox[i], oy[i], oz[i]}, {dx[i], dy[i], dz[i]}, t_max[i]}; }
  RaySoA soa(size_t first = 0) const {
    return {ox.data() + first, oy.data() + first, oz.data() + first, dx.data() + first,
            dy.data() + first, dz.data() + first, t_max.data() + first};
  }
};

// Brute force over every triangle with the scalar watertight test; prim in the soup's numbering.
inline Hit brute_closest(const Soup& s, const Ray& ray) {
  const WatertightRay wr(ray);
  Hit h;
  float t_max = ray.t_max;
  for (size_t i = 0; i < s.size() / 3; ++i) {
    TriangleHit th;
    if (!intersect_triangle(wr, t_max, s[3 * i], s[3 * i + 1], s[3 * i + 2], &th)) continue;
    t_max = th.t;
    h = {th.t, uint32_t(i), th.b1, th.b2};
  }
  return h;
}

// Reports `got` in the soup's numbering (prim through prim_indices).
template <int N>
Hit to_soup(const Tree<N>& t, Hit got) {
  if (got.prim != kNoHit) got.prim = t.bvh.prim_indices.at(got.prim);
  return got;
}

// Same hit: both miss; or both on the same triangle with identical t and barycentrics (the kernels do the scalar
// test's arithmetic operation for operation, so not even the last bit may differ); or, for a ray through a shared
// edge or vertex, on another triangle that the scalar test hits at the same t (within 1e-5 relative).
inline bool same_hit(const Hit& want, const Hit& got, const Soup& s, const Ray& ray) {
  if (want.prim == kNoHit || got.prim == kNoHit) return want.prim == got.prim && got.t == kInfinity;
  if (got.prim == want.prim) return got.t == want.t && got.b1 == want.b1 && got.b2 == want.b2;
  if (!(std::fabs(got.t - want.t) <= 1e-5f * want.t)) return false;
  TriangleHit th;
  Ray r = ray;
  r.t_max = kInfinity;
  const size_t i = 3 * size_t(got.prim);
  return got.prim < s.size() / 3 && intersect_triangle(r, s[i], s[i + 1], s[i + 2], &th) &&
         std::fabs(th.t - want.t) <= 1e-5f * want.t;
}

inline std::string describe(const Ray& r, const Hit& want, const Hit& got) {
  char buf[320];
  std::snprintf(buf, sizeof buf, "ray o (%a %a %a) d (%a %a %a) t_max %g: want prim %u t %.9g, got prim %u t %.9g",
                r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z, r.t_max, want.prim, want.t, got.prim, got.t);
  return buf;
}

// Calls f() once per Highway target compiled in and supported here, best (the default dispatch) first, with
// dispatch forced to that target; restores normal dispatch afterwards, also when a REQUIRE throws.
template <class F>
void for_each_target(F&& f) {
  struct Restore {
    ~Restore() { hwy::SetSupportedTargetsForTest(0); }
  } restore;
  const int64_t targets = HWY_TARGETS & hwy::SupportedTargets();
  REQUIRE(targets != 0);
  bool first = true;
  for (int64_t rest = targets; rest != 0; rest &= rest - 1) {
    const int64_t target = rest & -rest;  // lower bits are better targets
    hwy::SetSupportedTargetsForTest(target);
    const std::string name = hwy::TargetName(target);
    INFO("target " << name);
    REQUIRE(std::string(traversal_target_name()) == name);
    f(name, first);
    first = false;
  }
}

enum class Mode { kSingle, kPacket8, kPacket16 };
inline constexpr Mode kModes[] = {Mode::kSingle, Mode::kPacket8, Mode::kPacket16};
inline const char* mode_name(Mode m) { return m == Mode::kSingle ? "single" : m == Mode::kPacket8 ? "packet8" : "packet16"; }

template <int N>
std::vector<Hit> trace(const Tree<N>& t, const Rays& r, Mode m, size_t count) {
  std::vector<Hit> h(count);
  if (m == Mode::kSingle) intersect_closest(t.bvh, t.leaves, r.soa(), count, h.data());
  else intersect_closest_packets(t.bvh, t.leaves, r.soa(), count, h.data(), m == Mode::kPacket8 ? 8 : 16);
  return h;
}

template <int N>
std::vector<uint8_t> occluded(const Tree<N>& t, const Rays& r, Mode m, size_t count) {
  std::vector<uint8_t> o(count, 7);
  if (m == Mode::kSingle) intersect_any(t.bvh, t.leaves, r.soa(), count, o.data());
  else intersect_any_packets(t.bvh, t.leaves, r.soa(), count, o.data(), m == Mode::kPacket8 ? 8 : 16);
  return o;
}

// Expected results in the soup's numbering: brute force (small meshes) or the scalar wide-BVH reference.
struct Expected {
  std::vector<Hit> hits;
  std::vector<uint8_t> occluded;
};

inline Expected expect_brute(const Soup& s, const Rays& r) {
  Expected e;
  for (size_t i = 0; i < r.size(); ++i) {
    e.hits.push_back(brute_closest(s, r.ray(i)));
    e.occluded.push_back(e.hits.back().prim != kNoHit);
  }
  return e;
}

// any_from_closest: "occluded" is "has a closest hit" (the same thing by definition), which halves the cost.
template <int N>
Expected expect_reference(const Tree<N>& t, const Rays& r, bool any_from_closest = false) {
  Expected e;
  for (size_t i = 0; i < r.size(); ++i) {
    e.hits.push_back(to_soup(t, wide_closest_hit_reference(t.bvh, t.leaves, r.ray(i))));
    const bool occluded = any_from_closest ? e.hits.back().prim != kNoHit
                                           : wide_any_hit_reference(t.bvh, t.leaves, r.ray(i));
    e.occluded.push_back(occluded ? 1 : 0);
  }
  return e;
}

// Traces the first `count` rays one by one and the first `packet_count` in packets, closest and any hit, and
// requires the expected results; packets must also give exactly the single-ray results.
template <int N>
void check_all_modes(const Tree<N>& t, const Soup& s, const Rays& r, const Expected& e, size_t count,
                     size_t packet_count) {
  std::vector<Hit> single;
  for (Mode m : kModes) {
    const size_t n = m == Mode::kSingle ? count : packet_count;
    INFO("N = " << N << ", " << mode_name(m) << ", " << n << " rays");
    const std::vector<Hit> got = trace(t, r, m, n);
    const std::vector<uint8_t> occ = occluded(t, r, m, n);
    size_t bad = 0, bad_any = 0, unlike_single = 0;
    std::string first_bad;
    for (size_t i = 0; i < n; ++i) {
      if (!same_hit(e.hits[i], to_soup(t, got[i]), s, r.ray(i)) && bad++ == 0)
        first_bad = describe(r.ray(i), e.hits[i], to_soup(t, got[i]));
      bad_any += occ[i] != e.occluded[i];
      if (m != Mode::kSingle && i < single.size())
        unlike_single += !same_hit(to_soup(t, single[i]), to_soup(t, got[i]), s, r.ray(i));
    }
    if (m == Mode::kSingle) single = got;
    INFO(first_bad);
    CHECK(bad == 0);
    CHECK(bad_any == 0);
    CHECK(unlike_single == 0);
  }
}

// Every ray of `rays` traced through trees of width 4 and 8 over `soup`, in every mode on every target, against
// brute force; more than `min_hits_divisor`-th of the rays must hit (the comparison must be about hits).
inline void check_against_brute(const Soup& soup, const Rays& rays, size_t min_hits_divisor,
                                const BvhBuildOptions& options = {}) {
  const Expected e = expect_brute(soup, rays);
  size_t hits = 0;
  for (const Hit& h : e.hits) hits += h.prim != kNoHit;
  REQUIRE(hits > rays.size() / min_hits_divisor);
  const Tree<4> t4 = build<4>(soup, options);
  const Tree<8> t8 = build<8>(soup, options);
  for_each_target([&](const std::string&, bool) {
    check_all_modes(t4, soup, rays, e, rays.size(), rays.size());
    check_all_modes(t8, soup, rays, e, rays.size(), rays.size());
  });
}

}  // namespace torte::test::traverse
