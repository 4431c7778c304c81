// The compact layouts (accel/compact_bvh.h: quantised nodes, indexed leaves) through the SIMD kernels on every
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

// A tree over a soup in every layout: the default one (Tree<8>), its quantised nodes and its indexed leaves.
struct Layouts {
  Tree<8> wide;
  CompactBvh quant;
  IndexedLeaves indexed;
};

Layouts build_layouts(const Soup& soup, BvhBuildOptions options = {}) {
  Layouts l;
  l.wide = build<8>(soup, options);
  WideBvh<8> copy;
  copy.nodes.assign(l.wide.bvh.nodes.begin(), l.wide.bvh.nodes.end());
  copy.prim_indices.assign(l.wide.bvh.prim_indices.begin(), l.wide.bvh.prim_indices.end());
  copy.bounds = l.wide.bvh.bounds;
  l.quant = quantize(std::move(copy));
  l.indexed = make_indexed_leaves(l.wide.bvh.prim_indices, soup);
  return l;
}

enum class Combo { kQuantTriangles, kQuantIndexed, kWideIndexed };
constexpr Combo kCombos[] = {Combo::kQuantTriangles, Combo::kQuantIndexed, Combo::kWideIndexed};
const char* combo_name(Combo c) {
  return c == Combo::kQuantTriangles ? "quantised nodes + triangle leaves"
         : c == Combo::kQuantIndexed ? "quantised nodes + indexed leaves"
                                     : "default nodes + indexed leaves";
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
  if (c == Combo::kQuantIndexed) trace_with(l.quant, l.indexed, r, m, n, hits.data(), occ.data());
  if (c == Combo::kWideIndexed) trace_with(l.wide.bvh, l.indexed, r, m, n, hits.data(), occ.data());
}

// Every combination in every mode against `e` (the scalar reference or brute force, in the soup's numbering).
// Indexed leaves under default nodes test the same vertices in the same order: their hits must equal the
// default layout's bit for bit. Quantised nodes visit leaves in another order: hits at equal t may differ.
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
        if (c == Combo::kWideIndexed)
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
