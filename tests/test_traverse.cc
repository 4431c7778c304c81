// SIMD wide-BVH traversal (simd/traverse.h) on every Highway target compiled in and supported by this CPU,
// against the scalar reference (accel/wide_bvh_reference.h, or brute force over all triangles): closest and any
// hit on random rays, packets against single rays, watertightness on closed meshes, axis-parallel rays and zero
// direction components, rays starting on a surface, and invalid rays inside packets.
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
#include "core/error.h"
#include "core/rng.h"
#include "geometry/mesh.h"
#include "geometry/subdivide.h"
#include "geometry/triangle.h"
#include "traverse.h"
#include "test_random.h"

using namespace torte;
using torte::test::random_vec;
using torte::test::random_direction;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Triangles as vertex triples (p0, p1, p2 per triangle), the caller's numbering.
using Soup = std::vector<Vec3f>;

Soup random_soup(int n, uint64_t seed) {
  Pcg32 rng(seed);
  Soup s;
  for (int i = 0; i < n; ++i) {
    const Vec3f c = random_vec(rng) * 20 - Vec3f(10, 10, 10);
    const float size = 0.2f + 1.2f * rng.next_float();
    for (int k = 0; k < 3; ++k) s.push_back(c + random_direction(rng) * size);
  }
  return s;
}

Soup soup_of(const TriangleMesh& m) {
  Soup s;
  for (uint32_t i : m.indices) s.push_back(m.position(i));
  return s;
}

// Icosahedron subdivided `levels` times, vertices on the unit sphere scaled by `radius` around `center`: closed,
// with shared vertices, not axis-aligned.
Soup icosphere(int levels, Vec3f center, float radius) {
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
Tree<N> build(const Soup& s) {
  std::vector<Bounds3f> b(s.size() / 3);
  for (size_t i = 0; i < b.size(); ++i)
    for (int k = 0; k < 3; ++k) b[i].extend(s[3 * i + k]);
  Tree<N> t;
  BvhBuildOptions options;
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
Hit brute_closest(const Soup& s, const Ray& ray) {
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
bool same_hit(const Hit& want, const Hit& got, const Soup& s, const Ray& ray) {
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

std::string describe(const Ray& r, const Hit& want, const Hit& got) {
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
const Mode kModes[] = {Mode::kSingle, Mode::kPacket8, Mode::kPacket16};
const char* mode_name(Mode m) { return m == Mode::kSingle ? "single" : m == Mode::kPacket8 ? "packet8" : "packet16"; }

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

Expected expect_brute(const Soup& s, const Rays& r) {
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

}  // namespace

TEST_CASE("SIMD closest and any hit equal the scalar reference on random rays", "[traverse]") {
  const Soup soup = random_soup(10000, 7);
  const Tree<4> t4 = build<4>(soup);
  const Tree<8> t8 = build<8>(soup);
  // Origins inside and around the soup, random directions; a quarter with a finite t_max. 1M rays for the
  // dispatched target unless that is HWY_SCALAR (the scalar-only build), which is slow.
  const int64_t targets = HWY_TARGETS & hwy::SupportedTargets();
  const bool scalar_only = (targets & -targets) == HWY_SCALAR;
  const size_t kRays = scalar_only ? 1 << 18 : 1 << 20, kOtherTargets = 100000, kPackets = 20000;
  Pcg32 rng(11);
  Rays rays;
  for (size_t i = 0; i < kRays; ++i) {
    const Vec3f o = random_vec(rng) * 30 - Vec3f(15, 15, 15);
    const Vec3f d = random_direction(rng) * (0.5f + rng.next_float());
    rays.add(o, d, i % 4 == 0 ? 20 * rng.next_float() : kInfinity);
  }
  const Expected e = expect_reference(t8, rays, true);
  size_t hits = 0;
  for (const Hit& h : e.hits) hits += h.prim != kNoHit;
  REQUIRE(hits > kRays / 4);  // the comparison must be about hits, not mostly misses
  REQUIRE(hits < kRays - kRays / 8);
  for_each_target([&](const std::string&, bool best) {
    // 1M rays per node width on the dispatched target, 100k on the others; packets of random rays are the
    // slow (incoherent, mixed octants and axis permutations) case, so fewer.
    check_all_modes(t4, soup, rays, e, best ? kRays : kOtherTargets, kPackets);
    check_all_modes(t8, soup, rays, e, best ? kRays : kOtherTargets, kPackets);
  });
}

TEST_CASE("ray packets equal single rays on coherent camera rays", "[traverse]") {
  // A bumpy closed sphere in front of a floor: camera rays from a pinhole, one tile of 64 x 48 plus 5 more (the
  // count is no multiple of 16); every third row gets a finite t_max. Shadow rays towards a point light from the
  // hit points cover the any-hit side.
  TriangleMesh floor = make_polygon({{-6, -1.2f, -6}, {6, -1.2f, -6}, {6, -1.2f, 6}, {-6, -1.2f, 6}});
  Soup soup = soup_of(subdivide(floor, 3));
  const Soup sphere = icosphere(3, {0.2f, 0.1f, 0.3f}, 1.0f);
  soup.insert(soup.end(), sphere.begin(), sphere.end());
  const Tree<4> t4 = build<4>(soup);
  const Tree<8> t8 = build<8>(soup);
  Rays cam;
  const Vec3f eye(0.3f, 1.5f, -5);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x)
      cam.add(eye, normalize(Vec3f((x - 31.5f) / 40, (23.5f - y) / 40 - 0.3f, 1)), y % 3 == 2 ? 5.5f : kInfinity);
  for (int i = 0; i < 5; ++i) cam.add(eye, {0.01f * i, -0.3f, 1});
  const Expected e = expect_reference(t8, cam);
  Rays shadow;
  const Vec3f light(2, 4, -2);
  for (size_t i = 0; i < cam.size(); ++i) {
    if (e.hits[i].prim == kNoHit) continue;
    const Vec3f p = cam.ray(i).at(e.hits[i].t);
    shadow.add(p + (light - p) * 1e-4f, light - p, 1 - 1e-4f);  // t in (0, 1): the segment to the light
  }
  const Expected es = expect_reference(t8, shadow);
  size_t blocked = 0;
  for (uint8_t o : es.occluded) blocked += o;
  REQUIRE(blocked > shadow.size() / 20);
  REQUIRE(blocked < shadow.size() - shadow.size() / 20);
  for_each_target([&](const std::string&, bool) {
    check_all_modes(t4, soup, cam, e, cam.size(), cam.size());
    check_all_modes(t8, soup, cam, e, cam.size(), cam.size());
    check_all_modes(t4, soup, shadow, es, shadow.size(), shadow.size());
    check_all_modes(t8, soup, shadow, es, shadow.size(), shadow.size());
  });
}

TEST_CASE("rays from inside a closed mesh never escape, even through vertices and edges", "[traverse]") {
  Pcg32 rng(5);
  // Sphere: rays from inside aimed exactly at every vertex, at edge points (including midpoints), and random.
  const Soup sphere = icosphere(3, {0.1f, -0.2f, 0.05f}, 2.0f);
  // Cube subdivided twice (vertices on a 0.5 grid): axis-parallel rays from grid points hit its vertices and
  // edges exactly, and their origins lie on the nodes' slab planes (0 * inf = NaN in the slab test).
  const Soup cube = soup_of(subdivide(make_cube(), 2));
  for (const Soup* s : {&sphere, &cube}) {
    Rays rays;
    const bool is_cube = s == &cube;
    const std::vector<Vec3f> origins = is_cube ? std::vector<Vec3f>{{0, 0, 0}, {0.5f, 0.5f, 0}, {0.25f, -0.5f, 0.5f}}
                                               : std::vector<Vec3f>{{0.1f, -0.2f, 0.05f}, {0.9f, 0.3f, -0.4f}};
    for (Vec3f o : origins)
      for (size_t i = 0; i < s->size(); i += 3) {
        const Vec3f a = (*s)[i], b = (*s)[i + 1];
        rays.add(o, a - o);                           // at a vertex
        rays.add(o, (a + b) * 0.5f - o);              // at an edge midpoint
        const float u = rng.next_float();
        rays.add(o, a + (b - a) * u - o);             // at an edge point
        rays.add(o, random_direction(rng));
      }
    if (is_cube) {
      const float grid[] = {-0.75f, -0.5f, -0.25f, 0, 0.25f, 0.5f, 0.75f};
      const Vec3f axes[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {-0.0f, 0, 1}};
      for (float x : grid)
        for (float y : grid)
          for (float z : grid)
            for (Vec3f d : axes) rays.add({x, y, z}, d);
      for (float x : grid)  // diagonals through the cube's edges and corners
        for (Vec3f d : {Vec3f(1, 1, 0), Vec3f(0, -1, 1), Vec3f(1, 1, 1), Vec3f(-1, 1, -1)}) rays.add({x, 0, 0}, d);
    }
    INFO((is_cube ? "cube, " : "sphere, ") << rays.size() << " rays");
    const Expected e = expect_brute(*s, rays);
    for (size_t i = 0; i < rays.size(); ++i)
      if (e.hits[i].prim == kNoHit) FAIL("the scalar reference itself lets a ray escape: " << i);
    const Tree<4> t4 = build<4>(*s);
    const Tree<8> t8 = build<8>(*s);
    for_each_target([&](const std::string&, bool) {
      check_all_modes(t4, *s, rays, e, rays.size(), rays.size());
      check_all_modes(t8, *s, rays, e, rays.size(), rays.size());
    });
  }
}

namespace {

// Unit cubes on an integer grid in a 3D checkerboard pattern (x + y + z even): node bounds lie on the integer and
// half-integer planes that the axis-parallel test rays start on and run along.
Soup checkerboard_cubes() {
  Soup soup;
  for (int x = -2; x <= 2; ++x)
    for (int y = -2; y <= 2; ++y)
      for (int z = -1; z <= 1; ++z) {
        if ((x + y + z) % 2 != 0) continue;
        TriangleMesh c = make_cube();
        for (size_t i = 0; i < c.vertex_count(); ++i)
          c.x[i] = x + 0.5f * c.x[i], c.y[i] = y + 0.5f * c.y[i], c.z[i] = z + 0.5f * c.z[i];
        const Soup cs = soup_of(c);
        soup.insert(soup.end(), cs.begin(), cs.end());
      }
  return soup;
}

}  // namespace

TEST_CASE("axis-parallel rays and zero direction components on box-aligned geometry", "[traverse]") {
  // Small cubes on an integer grid: node bounds lie on planes where the rays' origins are, and the rays run
  // along those planes, so slabs see 0 * inf = NaN and +-inf reciprocals. Expected: brute force.
  const Soup soup = checkerboard_cubes();
  Rays rays;
  const float coords[] = {-3, -2.5f, -2, -1.5f, -1, -0.5f, 0, 0.5f, 1, 1.5f, 2.5f};
  const Vec3f dirs[] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},  {0, -1, 0},  {0, 0, 1},     {0, 0, -1},
                        {1, 1, 0},  {0, 1, -1}, {-1, 0, 1}, {-0.0f, 1, 0}, {0, -0.0f, -1}, {1e-30f, 0, 1}};
  for (float a : coords)
    for (float b : coords)
      for (Vec3f d : dirs) {
        rays.add({a, b, -2.75f}, d);
        rays.add({a, -2.75f, b}, d, 3.0f);
        rays.add({-3.5f, a, b}, d);
      }
  const Expected e = expect_brute(soup, rays);
  size_t hits = 0;
  for (const Hit& h : e.hits) hits += h.prim != kNoHit;
  REQUIRE(hits > rays.size() / 10);
  const Tree<4> t4 = build<4>(soup);
  const Tree<8> t8 = build<8>(soup);
  for_each_target([&](const std::string&, bool) {
    check_all_modes(t4, soup, rays, e, rays.size(), rays.size());
    check_all_modes(t8, soup, rays, e, rays.size(), rays.size());
  });
}

TEST_CASE("packets sharing a direction with zero components, spread origins (interval culling)", "[traverse]") {
  // As above, but consecutive rays share one direction (whole packets in one octant, some with +-0 or tiny
  // components, i.e. infinite or huge reciprocals) while their origins spread over the grid: the any-hit packet
  // kernel culls children by the packet's interval of origins and reciprocals there. Expected: brute force.
  const Soup soup = checkerboard_cubes();
  Rays rays;
  const float coords[] = {-3, -2.5f, -2, -1.5f, -1, -0.5f, 0, 0.5f, 1, 1.5f, 2.5f};
  const Vec3f dirs[] = {{0, 0, 1},     {1, 0.5f, 1},  {-0.0f, 0.25f, 1}, {0.3f, -0.0f, 1}, {1e-30f, 0, 1},
                        {0.2f, 0.1f, 1}, {-0.2f, 0.3f, 1}};
  for (Vec3f d : dirs)
    for (float a : coords)
      for (float b : coords) rays.add({a, b, -2.75f}, d, b > 1 ? 2.0f : kInfinity);
  const Expected e = expect_brute(soup, rays);
  size_t hits = 0, misses = 0;
  for (const Hit& h : e.hits) (h.prim != kNoHit ? hits : misses) += 1;
  REQUIRE(hits > rays.size() / 10);
  REQUIRE(misses > rays.size() / 10);
  const Tree<4> t4 = build<4>(soup);
  const Tree<8> t8 = build<8>(soup);
  for_each_target([&](const std::string&, bool) {
    check_all_modes(t4, soup, rays, e, rays.size(), rays.size());
    check_all_modes(t8, soup, rays, e, rays.size(), rays.size());
  });
}

TEST_CASE("closest-hit packets culled by a shrinking interval still reach the far layers", "[traverse]") {
  // Four layers of unit squares at z = 0, 1, 2, 3 with holes in different cells of each layer; packets share one
  // direction (one octant) so closest-hit packets use interval culling, whose far bound follows the packet's
  // largest t_max as lanes find hits. Rays falling through the holes of the near layers must still find the
  // far ones, and rays hitting a near layer must not report a farther one. Expected: brute force.
  Soup soup;
  for (int k = 0; k < 4; ++k)
    for (int x = -4; x < 4; ++x)
      for (int y = -4; y < 4; ++y) {
        // Holes: even x in layer 0, even y in layer 1, x % 4 in {0, 1} in layer 2, y % 4 in {2, 3} in layer 3;
        // about 1/2, 1/4, 1/8 of the rays reach layers 1, 2, 3.
        const bool hole = k == 0 ? (x & 1) == 0 : k == 1 ? (y & 1) == 0 : k == 2 ? (x & 2) == 0 : (y & 2) != 0;
        if (hole) continue;
        const float z = float(k), x0 = float(x), y0 = float(y);
        const Soup q = soup_of(make_polygon({{x0, y0, z}, {x0 + 1, y0, z}, {x0 + 1, y0 + 1, z}, {x0, y0 + 1, z}}));
        soup.insert(soup.end(), q.begin(), q.end());
      }
  Rays rays;
  const Vec3f dirs[] = {{0, 0, 1}, {0.05f, 0.03f, 1}, {-0.04f, 0.02f, 1}, {0.03f, -0.06f, 1}};
  for (Vec3f d : dirs)
    for (int i = 0; i < 29; ++i)
      for (int j = 0; j < 29; ++j) {
        const float a = -3.9f + 0.27f * i, b = -3.9f + 0.27f * j;
        rays.add({a, b, -1.0f}, d, (i + j) % 5 == 0 ? 2.5f : kInfinity);
      }
  const Expected e = expect_brute(soup, rays);
  size_t far_hits = 0;
  for (const Hit& h : e.hits) far_hits += h.prim != kNoHit && h.t > 2.5f;
  REQUIRE(far_hits > rays.size() / 20);
  const Tree<4> t4 = build<4>(soup);
  const Tree<8> t8 = build<8>(soup);
  for_each_target([&](const std::string&, bool) {
    check_all_modes(t4, soup, rays, e, rays.size(), rays.size());
    check_all_modes(t8, soup, rays, e, rays.size(), rays.size());
  });
}

TEST_CASE("directions whose largest components tie choose the scalar test's axes", "[traverse]") {
  // |dx| = |dy| > |dz| and the like: the watertight test's axis choice (max_dimension, strict >) decides these
  // ties, and another choice shears differently and changes t in its last bits, which same_hit detects. The
  // sphere is not axis-aligned, so the arithmetic is not exact in either frame.
  const Soup sphere = icosphere(2, {0.1f, -0.2f, 0.05f}, 1.5f);
  Pcg32 rng(9);
  Rays rays;
  for (int i = 0; i < 400; ++i) {
    const float a = 0.2f + rng.next_float(), b = a * rng.next_float();  // b < a
    const float sa = rng.next_u32() & 1 ? -a : a, sb = rng.next_u32() & 1 ? -b : b;
    const float sa2 = rng.next_u32() & 1 ? -a : a;
    const Vec3f dirs[] = {{sa, sa2, sb}, {sb, sa, sa2}, {sa, sb, sa2}, {sa, sa2, sa}};
    const Vec3f o = Vec3f(rng.next_float(), rng.next_float(), rng.next_float()) * 6 - Vec3f(3, 3, 3);
    for (const Vec3f& d : dirs) rays.add(o - d * 2, d);
  }
  const Expected e = expect_brute(sphere, rays);
  size_t hits = 0;
  for (const Hit& h : e.hits) hits += h.prim != kNoHit;
  REQUIRE(hits > rays.size() / 10);
  const Tree<4> t4 = build<4>(sphere);
  const Tree<8> t8 = build<8>(sphere);
  for_each_target([&](const std::string&, bool) {
    check_all_modes(t4, sphere, rays, e, rays.size(), rays.size());
    check_all_modes(t8, sphere, rays, e, rays.size(), rays.size());
  });
}

TEST_CASE("the single-ray kernel's block set-up equals the one-ray scalar set-up bit for bit", "[traverse]") {
  // Random directions of every sign, ties between the largest components (max_dimension's strict > decides),
  // signed zeros, axis-parallel and tiny or huge components, and invalid rays, in a count that is not a multiple
  // of the 16-ray block (the last block is padded).
  Pcg32 rng(31);
  Rays rays;
  const float specials[] = {0.0f, -0.0f, 1.0f, -1.0f, 1e-30f, -1e-30f, 1e30f, -3e-8f, 0.5f, -0.5f};
  for (int i = 0; i < 3000; ++i) {
    const Vec3f o = random_vec(rng) * 200.0f - Vec3f(100, 100, 100);
    Vec3f d = random_direction(rng);
    switch (i % 6) {
      case 1: d = {specials[rng.next_u32() % 10], specials[rng.next_u32() % 10], specials[rng.next_u32() % 10]}; break;
      case 2: d.y = rng.next_u32() & 1 ? d.x : -d.x; break;                      // |dx| = |dy|
      case 3: d.z = rng.next_u32() & 1 ? d.x : -d.x, d.y = d.x * 0.5f; break;  // |dx| = |dz|
      case 4: d = Vec3f(d.x, rng.next_u32() & 1 ? d.x : -d.x, rng.next_u32() & 1 ? d.x : -d.x); break;
      default: break;
    }
    rays.add(o, d, i % 50 == 0 ? -1.0f : (i % 70 == 0 ? kNaN : 10.0f + float(i)));
  }
  rays.add({kNaN, 0, 0}, {0, 0, 1});
  rays.add({0, 0, 0}, {kInfinity, 0, 1});
  rays.add({0, 0, 0}, {0, 0, 0});
  REQUIRE(rays.size() % 16 != 0);
  for_each_target([&](const std::string&, bool) {
    CHECK(traverse_detail::count_ray_setup_mismatches(rays.soa(), rays.size()) == 0);
    CHECK(traverse_detail::count_ray_setup_mismatches(rays.soa(5), 11) == 0);  // one short block
  });
}

TEST_CASE("rays starting on a surface behave as the scalar test does", "[traverse]") {
  // Documented behaviour (traverse.h): hits need t > 0 as computed by the scalar test. An origin exactly on a
  // vertex gives t = 0 on the triangles around it (no self-hit); an origin interpolated inside a triangle may
  // self-hit at |t| ~ 1e-7 exactly when the scalar test does; offset_origin removes the self-hits.
  const Vec3f center(0.1f, -0.2f, 0.05f);
  const Soup sphere = icosphere(2, center, 2.0f);
  const Tree<4> t4 = build<4>(sphere);
  const Tree<8> t8 = build<8>(sphere);
  Pcg32 rng(3);
  Rays at_vertex, inside, offset;
  for (size_t i = 0; i < sphere.size(); i += 3) {
    const Vec3f p0 = sphere[i], p1 = sphere[i + 1], p2 = sphere[i + 2];
    const Vec3f out = normalize(p0 - center);
    at_vertex.add(p0, out);    // outward from a vertex of a convex mesh: nothing to hit
    at_vertex.add(p0, -out);   // inward: the far side, at t ~ 4
    float u = rng.next_float(), v = rng.next_float();
    if (u + v > 1) u = 1 - u, v = 1 - v;
    const Vec3f p = p0 * (1 - u - v) + p1 * u + p2 * v;
    const Vec3f n = normalize(cross(p1 - p0, p2 - p0));
    const Vec3f d = random_direction(rng);
    inside.add(p, d);
    offset.add(offset_origin(p, n, d), d);
  }
  const Expected ev = expect_brute(sphere, at_vertex);
  for (size_t i = 0; i < at_vertex.size(); ++i) {
    if (i % 2 == 0) REQUIRE(ev.hits[i].prim == kNoHit);
    else REQUIRE(ev.hits[i].t > 3.0f);
  }
  const Expected ei = expect_brute(sphere, inside), eo = expect_brute(sphere, offset);
  for (size_t i = 0; i < offset.size(); ++i) {
    // Leaving the convex mesh after the offset: a miss; entering it: another triangle, never the start one.
    const Vec3f p0 = sphere[3 * i], n = face_forward(cross(sphere[3 * i + 1] - p0, sphere[3 * i + 2] - p0), p0 - center);
    if (dot(offset.ray(i).d, n) > 0) REQUIRE(eo.hits[i].prim == kNoHit);
    else REQUIRE((eo.hits[i].prim != kNoHit && eo.hits[i].prim != i));
  }
  for_each_target([&](const std::string&, bool) {
    for (const auto& [rays, e] : {std::pair{&at_vertex, &ev}, std::pair{&inside, &ei}, std::pair{&offset, &eo}}) {
      check_all_modes(t4, sphere, *rays, *e, rays->size(), rays->size());
      check_all_modes(t8, sphere, *rays, *e, rays->size(), rays->size());
    }
  });
}

TEST_CASE("invalid rays are misses and do not disturb the other rays of their packet", "[traverse]") {
  const Soup soup = icosphere(2, {0, 0, 0}, 1.0f);
  const Tree<4> t4 = build<4>(soup);
  const Tree<8> t8 = build<8>(soup);
  // 37 coherent rays towards the sphere (all hit); then a copy with invalid rays in some lanes.
  Rays good;
  for (int i = 0; i < 37; ++i) good.add({0.02f * (i % 7) - 0.06f, 0.02f * (i / 7) - 0.05f, -3}, {0.01f, 0.005f, 1});
  Rays bad = good;
  const std::vector<int> broken = {0, 3, 7, 8, 12, 15, 16, 21, 30, 36};
  auto set = [&](int i, Vec3f o, Vec3f d, float t) {
    bad.ox[i] = o.x, bad.oy[i] = o.y, bad.oz[i] = o.z, bad.dx[i] = d.x, bad.dy[i] = d.y, bad.dz[i] = d.z;
    bad.t_max[i] = t;
  };
  const Vec3f o(0, 0, -3), d(0, 0, 1);
  set(0, {kNaN, 0, -3}, d, kInfinity);
  set(3, o, {0, kNaN, 1}, kInfinity);
  set(7, o, {0, 0, 0}, kInfinity);                   // zero direction
  set(8, {0, kInfinity, -3}, d, kInfinity);
  set(12, o, {-kInfinity, 0, 1}, kInfinity);
  set(15, o, d, kNaN);
  set(16, o, d, 0);
  set(21, o, d, -1);
  set(30, {kNaN, kNaN, kNaN}, {kNaN, kNaN, kNaN}, kNaN);
  set(36, o, {-0.0f, 0.0f, -0.0f}, kInfinity);       // negative zeros: still a zero direction
  const Expected e_good = expect_brute(soup, good);
  Expected e = e_good;
  for (int i : broken) e.hits[i] = Hit{}, e.occluded[i] = 0;
  for (int i = 0; i < 37; ++i) REQUIRE(e_good.hits[i].prim != kNoHit);
  for_each_target([&](const std::string&, bool) {
    check_all_modes(t4, soup, bad, e, bad.size(), bad.size());
    check_all_modes(t8, soup, bad, e, bad.size(), bad.size());
    // Packets starting at every offset, so each broken ray takes every lane position at some point.
    for (size_t first = 1; first < 16; ++first) {
      std::vector<Hit> h(bad.size() - first);
      intersect_closest_packets(t8.bvh, t8.leaves, bad.soa(first), h.size(), h.data(), 16);
      for (size_t i = 0; i < h.size(); ++i) REQUIRE(same_hit(e.hits[first + i], to_soup(t8, h[i]), soup, bad.ray(first + i)));
    }
  });
}

TEST_CASE("empty trees and bad packet sizes", "[traverse]") {
  const Tree<8> empty = build<8>({});
  REQUIRE(empty.bvh.nodes.empty());
  Rays r;
  for (int i = 0; i < 20; ++i) r.add({0, 0, 0}, {1, 0, 0});
  for_each_target([&](const std::string&, bool) {
    for (Mode m : kModes) {
      for (const Hit& h : trace(empty, r, m, r.size())) REQUIRE((h.prim == kNoHit && h.t == kInfinity));
      for (uint8_t o : occluded(empty, r, m, r.size())) REQUIRE(o == 0);
    }
  });
  Hit h;
  REQUIRE_THROWS_AS(intersect_closest_packets(empty.bvh, empty.leaves, r.soa(), 1, &h, 4), Error);
  uint8_t o;
  REQUIRE_THROWS_AS(intersect_any_packets(empty.bvh, empty.leaves, r.soa(), 1, &o, 32), Error);
}
