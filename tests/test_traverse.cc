// SIMD wide-BVH traversal (simd/traverse.h) on every Highway target compiled in and supported by this CPU,
// against the scalar reference (accel/wide_bvh_reference.h, or brute force over all triangles): closest and any
// hit on random rays, packets against single rays, watertightness on closed meshes, axis-parallel rays and zero
// direction components, and packets culled by their interval. Edge cases of the ray set-up and invalid input are
// in test_traverse_edge_cases.cc.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "traverse_test_support.h"

using namespace torte;
using namespace torte::test::traverse;
using torte::test::random_vec;
using torte::test::random_direction;

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

TEST_CASE("same-octant packets aimed at vertices and edges find the brute force's hits (triangle culling)",
          "[traverse]") {
  // Closest-hit packets whose rays share a direction octant skip the leaf triangles their interval misses; a skip
  // too eager shows as a ray through a vertex or an edge that finds no triangle or a farther one. Rays from an
  // inside and an outside origin at every vertex, edge midpoint and a random edge point of a sphere (near the
  // origin, and far from it, where the float spacing of its coordinates is coarse), ordered by octant so that
  // almost every packet of 8 or 16 is one octant.
  Pcg32 rng(11);
  for (const Vec3f center : {Vec3f(0.1f, -0.2f, 0.05f), Vec3f(3000.5f, -1200.25f, 700.125f)}) {
    const Soup sphere = icosphere(3, center, 2.0f);
    Rays rays;
    for (const Vec3f o : {center + Vec3f(0.3f, 0.2f, -0.4f), center + Vec3f(-5, 7, -9)}) {
      std::vector<std::pair<int, Vec3f>> dirs;  // (octant, direction)
      for (size_t i = 0; i < sphere.size(); i += 3) {
        const Vec3f a = sphere[i], b = sphere[i + 1];
        for (const Vec3f p : {a, (a + b) * 0.5f, a + (b - a) * rng.next_float()}) {
          const Vec3f d = p - o;
          dirs.push_back({(d.x < 0) + 2 * (d.y < 0) + 4 * (d.z < 0), d});
        }
      }
      std::stable_sort(dirs.begin(), dirs.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      for (const auto& [octant, d] : dirs) rays.add(o, d);
    }
    INFO("sphere at " << center.x << ", " << rays.size() << " rays");
    check_against_brute(sphere, rays, 2);  // aimed at the mesh: all but silhouette grazers hit
  }
}

TEST_CASE("packets write the single rays' hits on batches large enough to be streamed", "[traverse]") {
  // From 2^16 rays on, closest-hit packets write their Hits with non-temporal stores when the array is 16-byte
  // aligned; a batch of 2^16 + 261 camera rays (every third with a finite t_max, some missing the sphere; the last
  // packet partial, which is written with ordinary stores), written to an aligned array and to one 20 bytes
  // further (not 16-byte aligned: ordinary stores), must give the single-ray kernel's Hits field by field.
  const Soup sphere = icosphere(3, {0, 0, 0}, 1.0f);
  const Tree<8> t8 = build<8>(sphere);
  Rays cam;
  const Vec3f eye(0.2f, 0.1f, -4);
  const int w = 256, h = 257;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      cam.add(eye, normalize(Vec3f((x - 127.5f) / 350, (128.5f - y) / 350, 1)), (x + y) % 3 == 0 ? 3.5f : kInfinity);
  for (int i = 0; i < 5; ++i) cam.add(eye, normalize(Vec3f(0.05f * i, 0.02f, 1)));  // into a partial last packet
  const size_t n = cam.size();
  REQUIRE(n == (size_t(1) << 16) + 261);
  for_each_target([&](const std::string&, bool) {
    std::vector<Hit> single(n);
    intersect_closest(t8.bvh, t8.leaves, cam.soa(), n, single.data());
    size_t hits = 0;
    for (const Hit& hit : single) hits += hit.prim != kNoHit;
    REQUIRE(hits > n / 4);
    REQUIRE(hits < n - n / 4);
    for (int packet : {8, 16}) {
      std::vector<Hit> storage(n + 1);  // operator new: 16-byte aligned; storage.data() + 1 is not
      for (Hit* out : {storage.data(), storage.data() + 1}) {
        INFO("packet " << packet << ", Hits at " << (reinterpret_cast<uintptr_t>(out) % 16) << " mod 16");
        std::fill(storage.begin(), storage.end(), Hit{-1.0f, 7, 2.0f, 3.0f, 5});
        intersect_closest_packets(t8.bvh, t8.leaves, cam.soa(), n, out, packet);
        size_t unlike = 0;
        for (size_t i = 0; i < n; ++i)
          unlike += !(single[i].prim == out[i].prim && single[i].t == out[i].t && single[i].b1 == out[i].b1 &&
                      single[i].b2 == out[i].b2 && out[i].instance == kNoHit);
        CHECK(unlike == 0);
      }
    }
  });
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
  check_against_brute(soup, rays, 10);
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
