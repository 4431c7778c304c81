// Edge cases of SIMD wide-BVH traversal (simd/traverse.h) on every Highway target compiled in and supported here:
// ties between direction components, the single-ray kernel's block set-up, rays starting on a surface, invalid
// rays inside packets, empty trees and bad packet sizes.
#include <catch2/catch.hpp>

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
  check_against_brute(sphere, rays, 10);
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
  // Trees around and away from the origin, and one flat in z (extent 0 there: the FMA test's margin floor).
  const float extents[3][3] = {{50, 120, 3}, {1e4f, 2e4f, 3e4f}, {10, 10, 0}};
  for_each_target([&](const std::string&, bool) {
    for (const auto& extent : extents) {
      CHECK(traverse_detail::count_ray_setup_mismatches(rays.soa(), rays.size(), extent) == 0);
      CHECK(traverse_detail::count_ray_setup_mismatches(rays.soa(5), 11, extent) == 0);  // one short block
    }
  });
}

TEST_CASE("rays grazing box corners far from the origin find every hit the brute force finds", "[traverse]") {
  // The FMA slab test rounds o * (1 / d), an error relative to |o| rather than to the distance: 2e-3 units at
  // 3e4, far more than these triangles' size. Its margin (traverse_detail::kSlabMargin) must keep it
  // conservative. Small triangles around (2e4, -3e4, 1e4); every ray aims exactly at a vertex, the corner of a
  // leaf box through it, from a few units away.
  const Vec3f center(2e4f, -3e4f, 1e4f);
  Pcg32 rng(41);
  Soup soup;
  for (int i = 0; i < 3000; ++i) {
    const Vec3f c = center + random_vec(rng) * 4.0f;
    for (int k = 0; k < 3; ++k) soup.push_back(c + random_direction(rng) * 0.03f);
  }
  Rays rays;
  for (int i = 0; i < 4000; ++i) {
    const Vec3f target = soup[rng.next_u32() % soup.size()];
    const Vec3f o = target + random_direction(rng) * (1.0f + 6.0f * rng.next_float());
    rays.add(o, target - o);
  }
  check_against_brute(soup, rays, 4);
}

TEST_CASE("leaves of more triangles than a vector holds give the brute force's hits", "[traverse]") {
  // With leaves of up to 16 (SAH leaf blocks of 16), the single-ray kernel tests a leaf in groups of 8 lanes (4
  // on SSE4, 1 on the scalar target); the groups after the first run out of line on 8-lane targets. Overlapping
  // triangles make the closest hit depend on groups after the first.
  const Soup soup = random_soup(3000, 17);
  const BvhBuildOptions big_leaves{.max_leaf_size = 16, .leaf_block_size = 16};
  size_t big = 0, leaves = 0;
  const Tree<8> t = build<8>(soup, big_leaves);
  for (const WideNode<8>& n : t.bvh.nodes)
    for (int i = 0; i < 8; ++i) {
      if (!is_leaf_child(n.child[i])) continue;
      ++leaves;
      big += n.leaf_count[i] > 8;
    }
  INFO(big << " of " << leaves << " leaves hold more than 8 triangles");
  REQUIRE(big > leaves / 2);
  Pcg32 rng(23);
  Rays rays;
  for (int i = 0; i < 3000; ++i) {
    const Vec3f target = soup[rng.next_u32() % soup.size()] + random_direction(rng) * 0.3f;
    const Vec3f o = random_vec(rng) * 30 - Vec3f(15, 15, 15);
    rays.add(o, target - o);
  }
  check_against_brute(soup, rays, 2, big_leaves);
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
