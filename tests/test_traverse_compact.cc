// The compact layouts (accel/compact_bvh.h: quantised nodes; accel/packed_leaves.h: packed leaves) through the SIMD kernels on every
// Highway target compiled in and supported here: the same hits as the default layout and the scalar reference,
// quantised boxes that always hold the exact ones, and no hit lost on rays grazing the boxes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "accel/compact_bvh.h"
#include "traverse_test_support.h"

using namespace torte;
using namespace torte::test::traverse;
using torte::test::random_direction;
using torte::test::random_vec;

namespace {

// A tree over a soup in every layout: the default one (Tree<8>), its quantised nodes, and its packed leaves under
// a copy of the default nodes and under quantised nodes (their leaf references rewritten).
struct Layouts {
  Tree<8> wide;
  CompactBvh quant;
  WideBvh<8> wide_packed;
  CompactBvh quant_packed;
  PackedLeaves packed;
};

Layouts build_layouts(const Soup& soup, BvhBuildOptions options = {}) {
  Layouts l;
  l.wide = build<8>(soup, options);
  l.quant = quantize(WideBvh<8>(l.wide.bvh));  // copies: quantize consumes its tree
  l.wide_packed = l.wide.bvh;
  l.packed = make_packed_leaves(l.wide_packed, soup);
  l.quant_packed = quantize(WideBvh<8>(l.wide_packed));
  return l;
}

enum class Combo { kQuantTriangles, kQuantPacked, kWidePacked };
constexpr Combo kCombos[] = {Combo::kQuantTriangles, Combo::kQuantPacked, Combo::kWidePacked};
const char* combo_name(Combo c) {
  switch (c) {
    case Combo::kQuantTriangles: return "quantised nodes + triangle leaves";
    case Combo::kQuantPacked: return "quantised nodes + packed leaves";
    case Combo::kWidePacked: return "default nodes + packed leaves";
  }
  return "?";
}

template <class Tree, class Leaves>
void trace_with(const Tree& t, const Leaves& l, const Rays& r, Mode m, size_t n, Hit* hits, uint8_t* occ) {
  if (m == Mode::kSingle) {
    intersect_closest(t, l, r.soa(), n, hits);
    intersect_any(t, l, r.soa(), n, occ);
  } else {
    const int p = m == Mode::kPacket8 ? 8 : 16;
    intersect_closest_packets(t, l, r.soa(), n, hits, p);
    intersect_any_packets(t, l, r.soa(), n, occ, p);
  }
}

void trace(const Layouts& l, Combo c, const Rays& r, Mode m, size_t n, std::vector<Hit>& hits,
           std::vector<uint8_t>& occ) {
  hits.assign(n, Hit{});
  occ.assign(n, 7);
  if (c == Combo::kQuantTriangles) trace_with(l.quant, l.wide.leaves, r, m, n, hits.data(), occ.data());
  if (c == Combo::kQuantPacked) trace_with(l.quant_packed, l.packed, r, m, n, hits.data(), occ.data());
  if (c == Combo::kWidePacked) trace_with(l.wide_packed, l.packed, r, m, n, hits.data(), occ.data());
}

// Every combination in every mode against `e` (the scalar reference or brute force, in the soup's numbering).
// Packed leaves under default nodes test the same vertices in the same order: their hits must equal
// the default layout's bit for bit. Quantised nodes visit leaves in another order: hits at equal t may differ.
void check_layouts(const Layouts& l, const Soup& soup, const Rays& r, const Expected& e, size_t count) {
  for (Combo c : kCombos)
    for (Mode m : kModes) {
      INFO(combo_name(c) << ", " << mode_name(m) << ", " << count << " rays");
      std::vector<Hit> got, base;
      std::vector<uint8_t> occ;
      trace(l, c, r, m, count, got, occ);
      base = trace(l.wide, r, m, count);
      size_t bad = 0, bad_any = 0, unlike_default = 0;
      std::string first_bad;
      for (size_t i = 0; i < count; ++i) {
        const Hit g = to_soup(l.wide, got[i]);
        if (!same_hit(e.hits[i], g, soup, r.ray(i)) && bad++ == 0) first_bad = describe(r.ray(i), e.hits[i], g);
        bad_any += occ[i] != e.occluded[i];
        if (c == Combo::kWidePacked)
          unlike_default += got[i].prim != base[i].prim || got[i].t != base[i].t || got[i].b1 != base[i].b1;
      }
      INFO(first_bad);
      CHECK(bad == 0);
      CHECK(bad_any == 0);
      CHECK(unlike_default == 0);
    }
}

}  // namespace

TEST_CASE("quantised child boxes hold the exact boxes, near and far from the origin, tiny and flat",
          "[traverse][compact]") {
  Pcg32 rng(3);
  for (const float offset : {0.0f, 3e4f, -1e6f})
    for (const float size : {1e-6f, 0.05f, 40.0f}) {
      Soup soup;
      for (int i = 0; i < 2000; ++i) {
        const Vec3f c = Vec3f(offset, -offset, 0.5f * offset) + random_vec(rng) * (size * 60);
        for (int k = 0; k < 3; ++k) {
          Vec3f v = c + random_direction(rng) * size;
          if (i % 7 == 0) v.y = c.y;  // flat in y: boxes of zero extent on one axis
          soup.push_back(v);
        }
      }
      const Layouts l = build_layouts(soup);
      REQUIRE(l.quant.nodes.size() == l.wide.bvh.nodes.size());
      size_t boxes = 0, loose = 0;
      for (size_t n = 0; n < l.quant.nodes.size(); ++n) {
        const WideNode<8>& w = l.wide.bvh.nodes[n];
        const QuantNode& q = l.quant.nodes[n];
        const float* lo[3] = {w.lo_x, w.lo_y, w.lo_z};
        const float* hi[3] = {w.hi_x, w.hi_y, w.hi_z};
        for (int c = 0; c < 8; ++c) {
          REQUIRE(q.child[c] == w.child[c]);
          REQUIRE(q.leaf_count[c] == w.leaf_count[c]);
          REQUIRE(((q.occupied >> c) & 1) == (w.child[c] != kEmptyChild));
          if (w.child[c] == kEmptyChild) continue;
          ++boxes;
          for (int a = 0; a < 3; ++a) {
            const float qlo = dequantize(q, a, q.q[a][c]), qhi = dequantize(q, a, q.q[3 + a][c]);
            REQUIRE(qlo <= lo[a][c]);
            REQUIRE(qhi >= hi[a][c]);
            CHECK(std::max(std::fabs(qlo), std::fabs(qhi)) <= l.quant.plane_extent[a]);
            const float ulp = std::max(std::fabs(qlo), std::fabs(qhi)) * 0x1p-23f;
            loose += (qhi - qlo) > (hi[a][c] - lo[a][c]) + 3 * q.scale[a] + 4 * ulp;
          }
        }
      }
      INFO("offset " << offset << ", size " << size << ": " << loose << " of " << boxes << " boxes too loose");
      // No box is wider than its exact extent plus about a grid step at each end (and the float rounding there).
      CHECK(loose == 0);
    }
}

TEST_CASE("compact layouts give the scalar reference's hits on random rays, every target", "[traverse][compact]") {
  const Soup soup = random_soup(8000, 29);
  const Layouts l = build_layouts(soup);
  Pcg32 rng(31);
  Rays rays;
  for (size_t i = 0; i < 60000; ++i) {
    const Vec3f o = random_vec(rng) * 30 - Vec3f(15, 15, 15);
    rays.add(o, random_direction(rng) * (0.5f + rng.next_float()), i % 4 == 0 ? 20 * rng.next_float() : kInfinity);
  }
  const Expected e = expect_reference(l.wide, rays);
  size_t hits = 0;
  for (const Hit& h : e.hits) hits += h.prim != kNoHit;
  REQUIRE(hits > rays.size() / 4);
  for_each_target([&](const std::string&, bool best) { check_layouts(l, soup, rays, e, best ? rays.size() : 15000); });
}

TEST_CASE("compact layouts trace coherent camera and shadow rays like the default layout", "[traverse][compact]") {
  TriangleMesh floor = make_polygon({{-6, -1.2f, -6}, {6, -1.2f, -6}, {6, -1.2f, 6}, {-6, -1.2f, 6}});
  Soup soup = soup_of(subdivide(floor, 3));
  const Soup sphere = icosphere(4, {0.2f, 0.1f, 0.3f}, 1.0f);
  soup.insert(soup.end(), sphere.begin(), sphere.end());
  const Layouts l = build_layouts(soup);
  Rays cam;
  const Vec3f eye(0.3f, 1.5f, -5);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 96; ++x)
      cam.add(eye, normalize(Vec3f((x - 47.5f) / 60, (31.5f - y) / 60 - 0.3f, 1)), y % 3 == 2 ? 5.5f : kInfinity);
  const Expected e = expect_reference(l.wide, cam);
  Rays shadow;
  const Vec3f light(2, 4, -2);
  for (size_t i = 0; i < cam.size(); ++i) {
    if (e.hits[i].prim == kNoHit) continue;
    const Vec3f p = cam.ray(i).at(e.hits[i].t);
    shadow.add(p + (light - p) * 1e-4f, light - p, 1 - 1e-4f);
  }
  const Expected es = expect_reference(l.wide, shadow);
  for_each_target([&](const std::string&, bool) {
    check_layouts(l, soup, cam, e, cam.size());
    check_layouts(l, soup, shadow, es, shadow.size());
  });
}

TEST_CASE("rays grazing quantised boxes, and big leaves, lose no hit the brute force finds", "[traverse][compact]") {
  // Every ray aims exactly at a vertex that is an extreme point of its triangle on some axis: the ray touches
  // the exact child box there, and a quantised box rounded the wrong way would cut it off. Far from the origin,
  // where the FMA slab test's rounding is largest against the triangles' size. Leaves of up to 16 triangles
  // gather in several groups on narrow targets.
  const Vec3f center(2e4f, -3e4f, 1e4f);
  Pcg32 rng(43);
  Soup soup;
  for (int i = 0; i < 3000; ++i) {
    const Vec3f c = center + random_vec(rng) * 4.0f;
    for (int k = 0; k < 3; ++k) soup.push_back(c + random_direction(rng) * 0.03f);
  }
  Rays rays;
  for (int i = 0; i < 4000; ++i) {
    const size_t t = rng.next_u32() % (soup.size() / 3);
    const int axis = int(rng.next_u32() % 3);
    size_t best = 3 * t;
    for (size_t k = 3 * t; k < 3 * t + 3; ++k)
      if (soup[k][axis] > soup[best][axis]) best = k;
    const Vec3f target = soup[best];
    Vec3f dir = random_direction(rng);
    dir[axis] = -std::fabs(dir[axis]) - 0.05f;  // from the far side of the box's hi plane on that axis
    rays.add(target - dir * (1.0f + 6.0f * rng.next_float()), dir);
  }
  const Expected e = expect_brute(soup, rays);
  size_t hits = 0;
  for (const Hit& h : e.hits) hits += h.prim != kNoHit;
  REQUIRE(hits > rays.size() / 8);  // a ray through a vertex hits or misses as the watertight test decides
  const BvhBuildOptions big_leaves{.max_leaf_size = 16, .leaf_block_size = 16};
  for (const BvhBuildOptions& options : {BvhBuildOptions{}, big_leaves}) {
    const Layouts l = build_layouts(soup, options);
    for_each_target([&](const std::string&, bool) { check_layouts(l, soup, rays, e, rays.size()); });
  }
}

namespace {

// Clusters far apart, each of `t` triangles over `u` distinct random points near its centre (triangle j takes
// points 3j, 3j + 1, 3j + 2 modulo u, so every point is used when u <= 3t), which the build keeps in one leaf:
// leaves whose vertex counts sit at the decoder's boundaries (8 and 16 lanes, one or two tables, gathers).
void add_cluster(Soup& soup, Pcg32& rng, Vec3f centre, uint32_t t, uint32_t u) {
  std::vector<Vec3f> points;
  for (uint32_t i = 0; i < u; ++i) points.push_back(centre + random_direction(rng) * (0.2f + 0.8f * rng.next_float()));
  for (uint32_t i = 0; i < 3 * t; ++i) soup.push_back(points[i % u]);
}

// (count, distinct vertices) of every block of `leaves`, walking them in order.
std::vector<std::pair<uint32_t, uint32_t>> block_shapes(const PackedLeaves& leaves) {
  std::vector<std::pair<uint32_t, uint32_t>> shapes;
  for (size_t offset = 0, seen = 0; seen < leaves.size();) {
    const uint8_t* b = leaves.bytes(uint32_t(offset));
    shapes.emplace_back(b[0], b[1]);
    seen += b[0];
    offset += PackedLeaves::block_words(b[0], b[1]);
  }
  return shapes;
}

// Rays at random points of random triangles, from random directions.
Rays rays_at(const Soup& soup, int count, uint64_t seed) {
  Pcg32 rng(seed);
  Rays rays;
  for (int i = 0; i < count; ++i) {
    const size_t t = 3 * (rng.next_u32() % (soup.size() / 3));
    const float a = rng.next_float(), b = rng.next_float() * (1 - a);
    const Vec3f target = soup[t] + (soup[t + 1] - soup[t]) * a + (soup[t + 2] - soup[t]) * b;
    const Vec3f dir = random_direction(rng);
    rays.add(target - dir * (2.0f + 3.0f * rng.next_float()), dir);
  }
  return rays;
}

}  // namespace

TEST_CASE("packed leaves hold every triangle's vertices, shared within a leaf", "[traverse][compact][memory]") {
  const Soup sphere = icosphere(4, {0.2f, 0.1f, 0.3f}, 1.0f);
  const Layouts l = build_layouts(sphere);
  const size_t n = sphere.size() / 3;
  REQUIRE(l.packed.size() == n);
  for (uint32_t i = 0; i < n; ++i) {
    Vec3f p[3];
    l.packed.triangle(i, p);
    for (int k = 0; k < 3; ++k) REQUIRE(p[k] == sphere[3 * size_t(l.wide.bvh.prim_indices[i]) + size_t(k)]);
  }
  size_t vertices = 0;
  for (const auto& shape : block_shapes(l.packed)) {
    vertices += shape.second;
    CHECK(shape.second <= 3 * shape.first);
  }
  // A closed mesh has about half a vertex per triangle; a leaf of 8 neighbours about 1.2 (their border).
  INFO(double(vertices) / double(n) << " vertices per triangle, " << double(l.packed.memory_bytes()) / double(n)
                                    << " B/tri");
  CHECK(double(vertices) / double(n) < 1.6);
  CHECK(double(l.packed.memory_bytes()) / double(n) <= 24.0);  // TriangleLeaves: 36
}

TEST_CASE("packed leaves: one triangle, full leaves, vertex counts at every decoder boundary, degenerate triangles",
          "[traverse][compact]") {
  Pcg32 rng(61);
  Soup soup;
  // (triangles, distinct vertices): fans of shared vertices, the table boundaries for 4 and 8 lanes, and
  // full leaves whose vertices are all distinct (48: gathers everywhere).
  const std::pair<uint32_t, uint32_t> shapes[] = {{1, 3},  {2, 4},   {6, 8},   {7, 9},   {14, 16}, {15, 17},
                                                  {16, 16}, {16, 17}, {16, 32}, {16, 33}, {16, 48}, {5, 15}};
  // In one row, each cluster between two full ones: a leaf holding two clusters would exceed 16 triangles, so
  // every cluster is a leaf of its own.
  float x = 0;
  const auto separated = [&](uint32_t t, uint32_t u) {
    add_cluster(soup, rng, Vec3f(x, 0, 0), t, u);
    add_cluster(soup, rng, Vec3f(x + 12, 0, 0), 16, 48);
    x += 24;
  };
  for (int rep = 0; rep < 6; ++rep)
    for (const auto& shape : shapes) separated(shape.first, shape.second);
  // Degenerate triangles beside good ones: a point, a segment, a repeated vertex.
  for (int rep = 0; rep < 6; ++rep) {
    separated(6, 9);
    const size_t at = soup.size() - 3 * 16;  // after the 6-triangle cluster
    const Vec3f a = soup[at - 1], b = soup[at - 2];
    soup.insert(soup.begin() + std::ptrdiff_t(at), {a, a, a, a, b, (a + b) * 0.5f, a, a, b});
  }
  const BvhBuildOptions big_leaves{.max_leaf_size = 16, .leaf_block_size = 16};
  const Layouts l = build_layouts(soup, big_leaves);
  // The build keeps each cluster in one leaf: every shape above occurs.
  const auto got = block_shapes(l.packed);
  for (const auto& shape : shapes) {
    INFO("leaf of " << shape.first << " triangles over " << shape.second << " vertices");
    CHECK(std::find(got.begin(), got.end(), shape) != got.end());
  }
  const Rays rays = rays_at(soup, 6000, 67);
  const Expected e = expect_brute(soup, rays);
  size_t hits = 0;
  for (const Hit& h : e.hits) hits += h.prim != kNoHit;
  REQUIRE(hits > rays.size() / 2);
  for_each_target([&](const std::string&, bool) { check_layouts(l, soup, rays, e, rays.size()); });

  // A scene of one triangle: a leaf of one.
  const Soup one(soup.begin(), soup.begin() + 3);
  const Layouts lone = build_layouts(one);
  REQUIRE(block_shapes(lone.packed) == std::vector<std::pair<uint32_t, uint32_t>>{{1, 3}});
  const Rays one_rays = rays_at(one, 200, 71);
  const Expected e1 = expect_brute(one, one_rays);
  for_each_target([&](const std::string&, bool) { check_layouts(lone, one, one_rays, e1, one_rays.size()); });
}

TEST_CASE("packed leaves refuse leaves beyond 16 triangles", "[traverse][compact]") {
  Soup soup;
  Pcg32 rng(73);
  add_cluster(soup, rng, Vec3f(0, 0, 0), 20, 60);
  WideBvh<8> bvh;
  bvh.nodes.resize(1);
  WideNode<8>& root = bvh.nodes[0];
  for (int c = 0; c < 8; ++c) root.child[c] = kEmptyChild, root.leaf_count[c] = 0;
  root.child[0] = kLeafFlag, root.leaf_count[0] = 20;
  for (uint32_t i = 0; i < 20; ++i) bvh.prim_indices.push_back(i);
  CHECK_THROWS_WITH(make_packed_leaves(bvh, soup), Catch::Contains("at most 16"));
}
