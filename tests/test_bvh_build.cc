// Parallel binned-SAH build and wide collapse (bvh_build.h): structure invariants for N = 4 and 8, degenerate
// inputs, determinism across thread counts, SAH quality, triangle leaves, and the scalar wide traversal
// (wide_bvh_reference.h) against brute force. Mesh-scale tests (dragon memory budget, build speed) are in
// test_bvh_build_mesh.cc.
#include <catch2/catch.hpp>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "accel/bvh_build.h"
#include "accel/wide_bvh_reference.h"
#include "core/error.h"
#include "core/rng.h"
#include "geometry/mesh.h"
#include "geometry/triangle.h"
#include "test_random.h"

using namespace torte;
using torte::test::random_vec;
using torte::test::random_direction;

namespace {

// Three vertices per triangle. With `clusters` > 0 the centres gather around that many random points, a
// distribution where the SAH clearly beats median splits.
std::vector<Vec3f> random_triangles(int n, uint64_t seed, int clusters = 0) {
  Pcg32 rng(seed);
  std::vector<Vec3f> centres;
  for (int i = 0; i < clusters; ++i) centres.push_back(random_vec(rng) * 40 - Vec3f(20, 20, 20));
  std::vector<Vec3f> v;
  for (int i = 0; i < n; ++i) {
    Vec3f c = random_vec(rng) * 20 - Vec3f(10, 10, 10);
    if (clusters > 0) c = centres[rng.next_u32() % clusters] + (random_vec(rng) - Vec3f(0.5f, 0.5f, 0.5f)) * 2;
    const float s = clusters > 0 ? 0.2f : 0.3f + 1.5f * rng.next_float();
    for (int k = 0; k < 3; ++k) v.push_back(c + random_direction(rng) * s);
  }
  return v;
}

std::vector<Bounds3f> bounds_of(const std::vector<Vec3f>& v) {
  std::vector<Bounds3f> b(v.size() / 3);
  for (size_t i = 0; i < b.size(); ++i)
    for (int k = 0; k < 3; ++k) b[i].extend(v[3 * i + k]);
  return b;
}

std::vector<uint32_t> iota(size_t n) {
  std::vector<uint32_t> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = uint32_t(i);
  return v;
}

bool same_box(const Bounds3f& a, const Bounds3f& b) { return a.lo == b.lo && a.hi == b.hi; }

// Checks every invariant of wide_bvh.h and of the collapse; `expected` lists the primitives that must appear
// (each exactly once). Returns the deepest leaf level.
template <int N>
int check_wide(const WideBvh<N>& bvh, const std::vector<Bounds3f>& prims, const std::vector<uint32_t>& expected,
               int max_leaf) {
  const auto& idx = bvh.prim_indices;
  REQUIRE(idx.size() == expected.size());
  std::vector<int> seen(prims.size(), 0);
  for (uint32_t p : idx) {
    REQUIRE(p < prims.size());
    ++seen[p];
  }
  for (uint32_t p : expected) CHECK(seen[p] == 1);
  if (expected.empty()) {
    CHECK(bvh.nodes.empty());
    return 0;
  }
  REQUIRE(!bvh.nodes.empty());
  uint32_t next_node = 0, next_prim = 0;
  int max_depth = 0;
  // Depth-first in slot order: nodes must come up in index order (pre-order layout) and leaves must cover
  // prim_indices left to right. Returns the union of the subtree's primitive bounds.
  auto visit = [&](auto&& self, uint32_t index, int depth) -> Bounds3f {
    REQUIRE(index == next_node++);
    REQUIRE(index < bvh.nodes.size());
    const WideNode<N>& n = bvh.nodes[index];
    Bounds3f all;
    int used = 0;
    for (int i = 0; i < N; ++i) {
      const Bounds3f box = wide_child_bounds(n, i);
      if (n.child[i] == kEmptyChild) {
        // Empty slots only after the occupied ones, as an inverted box every ray misses.
        CHECK(box.lo == Vec3f(kInfinity, kInfinity, kInfinity));
        CHECK(box.hi == Vec3f(-kInfinity, -kInfinity, -kInfinity));
        CHECK(n.leaf_count[i] == 0);
        continue;
      }
      CHECK(i == used++);
      Bounds3f sub;
      if (n.child[i] & kLeafFlag) {
        const uint32_t first = n.child[i] & ~kLeafFlag, count = n.leaf_count[i];
        max_depth = std::max(max_depth, depth + 1);
        CHECK(count >= 1);
        CHECK(int(count) <= max_leaf);
        REQUIRE(first == next_prim);
        REQUIRE(size_t(first) + count <= idx.size());
        next_prim += count;
        for (uint32_t k = first; k < first + count; ++k) sub.extend(prims[idx[k]]);
      } else {
        CHECK(n.leaf_count[i] == 0);
        sub = self(self, n.child[i], depth + 1);
      }
      // Exactly the union of the subtree's primitives: contains them, and the collapse lost no tightness.
      CHECK(same_box(box, sub));
      all.extend(sub);
    }
    CHECK(used >= (index == 0 ? 1 : 2));
    return all;
  };
  const Bounds3f root = visit(visit, 0, 0);
  CHECK(next_node == bvh.nodes.size());  // every node reached, once
  CHECK(next_prim == idx.size());        // leaves partition prim_indices
  CHECK(same_box(root, bvh.bounds));
  CHECK(max_depth <= kMaxBvhDepth);
  const BvhStats s = bvh_stats(bvh);
  CHECK(s.nodes == bvh.nodes.size());
  CHECK(s.primitives == idx.size());
  CHECK(s.max_depth == max_depth);
  CHECK(s.node_bytes == bvh.nodes.size() * sizeof(WideNode<N>));
  CHECK(s.avg_children <= N);
  return max_depth;
}

Bounds3f box(Vec3f lo, Vec3f hi) {
  Bounds3f b;
  b.extend(lo);
  b.extend(hi);
  return b;
}

template <int N>
bool same_tree(const WideBvh<N>& a, const WideBvh<N>& b) {
  // Nodes are value-initialised before being filled, so padding is zero and a byte compare is exact.
  return a.nodes.size() == b.nodes.size() && a.prim_indices == b.prim_indices && same_box(a.bounds, b.bounds) &&
         std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(WideNode<N>)) == 0;
}

}  // namespace

TEMPLATE_TEST_CASE_SIG("bvh_build: wide tree invariants on random triangles", "[bvh_build]", ((int N), N), 4, 8) {
  const std::vector<Bounds3f> prims = bounds_of(random_triangles(20000, 1));
  for (int max_leaf : {1, 4, 8, 16}) {
    INFO("max_leaf_size " << max_leaf);
    const BvhBuildOptions o{.max_leaf_size = max_leaf, .leaf_block_size = std::min(4, max_leaf)};
    const WideBvh<N> bvh = build_wide_bvh<N>(prims, o);
    const int depth = check_wide(bvh, prims, iota(prims.size()), max_leaf);
    CHECK(depth < 30);
    CHECK(bvh_stats(bvh).avg_children > 0.7 * N);  // measured 0.73-0.87 N
    // The binary tree: 32-byte nodes, pairs, and the wide tree is exactly its collapse.
    const BinaryBvh binary = build_binary_bvh(prims, o);
    CHECK(binary.memory_bytes() == binary.nodes.size() * 32 + prims.size() * 4);
    CHECK(binary.nodes.size() % 2 == 1);
    CHECK(same_tree(collapse<N>(binary, o), bvh));
    CHECK(sah_cost(bvh, o) < sah_cost(binary, o));  // wide nodes: fewer node visits for the same leaves
    // The greedy largest-area collapse is one of the collapses the dynamic programme considers, so the
    // optimal one costs no more (up to rounding), and it fills nodes better.
    BvhBuildOptions g = o;
    g.collapse = CollapseMode::LargestArea;
    const WideBvh<N> greedy = collapse<N>(binary, g);
    check_wide(greedy, prims, iota(prims.size()), max_leaf);
    INFO("SAH optimal " << sah_cost(bvh, o) << ", greedy " << sah_cost(greedy, o) << "; nodes " << bvh.nodes.size()
                        << ", " << greedy.nodes.size());
    CHECK(sah_cost(bvh, o) <= 1.0001f * sah_cost(greedy, o));
    CHECK(bvh.nodes.size() < greedy.nodes.size());
  }
}

TEMPLATE_TEST_CASE_SIG("bvh_build: closest hit and any hit equal brute force", "[bvh_build]", ((int N), N), 4, 8) {
  const std::vector<Vec3f> verts = random_triangles(3000, 2);
  const std::vector<Bounds3f> prims = bounds_of(verts);
  const size_t n = prims.size();
  for (int max_leaf : {1, 8, 16}) {
    INFO("max_leaf_size " << max_leaf);
    const WideBvh<N> bvh = build_wide_bvh<N>(prims, {.max_leaf_size = max_leaf});
    const TriangleLeaves leaves = make_triangle_leaves(bvh, verts);
    REQUIRE(leaves.size() == n);
    Pcg32 rng(3);
    int hits = 0;
    for (int i = 0; i < 1000; ++i) {
      Ray ray{random_vec(rng) * 30 - Vec3f(15, 15, 15), random_direction(rng) * (0.5f + rng.next_float())};
      if (i % 3 == 0) ray.t_max = 20 * rng.next_float();  // bounded rays: shadow-ray segments
      TriangleHit best{kInfinity, 0, 0};
      uint32_t best_prim = kNoHit;
      Ray rb = ray;
      for (uint32_t p = 0; p < n; ++p) {
        TriangleHit th;
        if (intersect_triangle(rb, verts[3 * p], verts[3 * p + 1], verts[3 * p + 2], &th)) {
          rb.t_max = th.t;
          best = th;
          best_prim = p;
        }
      }
      const Hit h = wide_closest_hit_reference(bvh, leaves, ray);
      REQUIRE((h.prim == kNoHit) == (best_prim == kNoHit));
      CHECK(wide_any_hit_reference(bvh, leaves, ray) == (best_prim != kNoHit));
      if (h.prim == kNoHit) continue;
      ++hits;
      // Hit::prim is the leaf-order index; prim_indices maps it back to the caller's triangle.
      REQUIRE(h.prim < n);
      CHECK(h.t == best.t);
      if (bvh.prim_indices[h.prim] != best_prim) continue;  // an exact tie in t (shared edge): either is right
      CHECK(h.b1 == best.b1);
      CHECK(h.b2 == best.b2);
    }
    CHECK(hits > 200);  // the comparison covered many hits and many misses
    CHECK(hits < 950);
  }
}

TEMPLATE_TEST_CASE_SIG("bvh_build: zero, one and invalid primitives", "[bvh_build]", ((int N), N), 4, 8) {
  const WideBvh<N> none = build_wide_bvh<N>({});
  CHECK(none.nodes.empty());
  CHECK(none.prim_indices.empty());
  CHECK(none.bounds.empty());
  CHECK(sah_cost(none) == 0);
  CHECK(bvh_stats(none).nodes == 0);
  CHECK(make_triangle_leaves(none, std::vector<Vec3f>{}).size() == 0);
  Ray ray{{0.5f, 0.5f, -5}, {0, 0, 1}};
  CHECK_FALSE(wide_intersect(none, ray, [](uint32_t, Ray&) { return true; }));
  CHECK_FALSE(wide_occluded(none, ray, [](uint32_t, const Ray&) { return true; }));
  // Empty and NaN bounds are left out, as in bvh2.cc: they can never be hit.
  Bounds3f nan_box = box({0, 0, 0}, {1, 1, 1});
  nan_box.hi.y = std::numeric_limits<float>::quiet_NaN();
  CHECK(build_wide_bvh<N>(std::vector<Bounds3f>{Bounds3f{}, nan_box}).nodes.empty());

  // One primitive: a root with a single leaf child.
  const std::vector<Bounds3f> one{box({0, 0, 0}, {1, 1, 1})};
  const WideBvh<N> single = build_wide_bvh<N>(one);
  REQUIRE(single.nodes.size() == 1);
  CHECK(single.nodes[0].child[0] == (kLeafFlag | 0));
  CHECK(single.nodes[0].leaf_count[0] == 1);
  check_wide(single, one, {0}, 1);
  int calls = 0;
  CHECK(wide_intersect(single, ray, [&](uint32_t p, Ray& r) { ++calls; r.t_max = 4; return p == 0; }));
  CHECK(calls == 1);
  CHECK(ray.t_max == 4);

  // Invalid boxes among real ones: never in a leaf.
  std::vector<Bounds3f> prims = bounds_of(random_triangles(500, 8));
  std::vector<uint32_t> kept;
  for (uint32_t i = 0; i < prims.size(); ++i) {
    if (i % 7 == 3) prims[i] = i % 2 ? Bounds3f{} : nan_box;
    else kept.push_back(i);
  }
  check_wide(build_wide_bvh<N>(prims, {.max_leaf_size = 4}), prims, kept, 4);
}

TEMPLATE_TEST_CASE_SIG("bvh_build: coincident centroids, depth bound, many tiny boxes", "[bvh_build]", ((int N), N),
                       4, 8) {
  // 1000 copies of one box: no plane separates them; halving keeps leaves within the limit.
  const std::vector<Bounds3f> same(1000, box({0, 0, 0}, {1, 2, 3}));
  check_wide(build_wide_bvh<N>(same, {.max_leaf_size = 3}), same, iota(same.size()), 3);
  // Nested boxes sharing a centre: a ray from the centre must be offered all of them.
  std::vector<Bounds3f> nested;
  for (int i = 1; i <= 777; ++i) nested.push_back(box(Vec3f(-1, -1, -1) * float(i), Vec3f(1, 1, 1) * float(i)));
  const WideBvh<N> nest = build_wide_bvh<N>(nested, {.max_leaf_size = 5});
  check_wide(nest, nested, iota(nested.size()), 5);
  int calls = 0;
  Ray ray{{0, 0, 0}, {1, 0, 0}};
  wide_intersect(nest, ray, [&](uint32_t, Ray&) { ++calls; return false; });
  CHECK(calls == 777);

  // Geometrically growing positions with 2 bins: each SAH split peels off a few boxes (77 levels if
  // unchecked); median splits must take over in time to keep leaves at depth <= kMaxBvhDepth.
  std::vector<Bounds3f> chain;
  for (int i = 0; i < 300; ++i) {
    const float x = std::pow(1.2f, float(i));
    chain.push_back(box({x, 0, 0}, {x * 1.01f, 1, 1}));
  }
  const BvhBuildOptions deep{.max_leaf_size = 1, .bins = 2, .leaf_block_size = 1};
  const WideBvh<N> c = build_wide_bvh<N>(chain, deep);
  check_wide(c, chain, iota(chain.size()), 1);
  int binary_depth = 0;
  {
    // The binary tree went deep (so this input exercises the bound) yet within it.
    const BinaryBvh b = build_binary_bvh(chain, deep);
    std::vector<std::pair<uint32_t, int>> stack{{0, 0}};
    while (!stack.empty()) {
      const auto [i, d] = stack.back();
      stack.pop_back();
      binary_depth = std::max(binary_depth, d);
      if (b.nodes[i].count == 0) stack.insert(stack.end(), {{b.nodes[i].first, d + 1}, {b.nodes[i].first + 1, d + 1}});
    }
  }
  CHECK(binary_depth > 50);
  CHECK(binary_depth <= kMaxBvhDepth);
  for (int i = 0; i < 300; i += 7) {  // each box is found by a ray through it
    const float x = (chain[i].lo.x + chain[i].hi.x) / 2;
    Ray r{{x, 0.5f, -1}, {0, 0, 1}};
    bool found = false;
    wide_intersect(c, r, [&](uint32_t p, Ray&) { found |= c.prim_indices[p] == uint32_t(i); return false; });
    CHECK(found);
  }

  // Many tiny boxes, every other one a single point (zero area: valid, but SAH weights vanish).
  Pcg32 rng(12);
  std::vector<Bounds3f> points(200000);
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3f p = random_vec(rng) * 1000;
    points[i] = box(p, i % 2 ? p : p + random_vec(rng) * 1e-3f);
  }
  const int depth = check_wide(build_wide_bvh<N>(points), points, iota(points.size()), 8);
  CHECK(depth < 25);
}

TEMPLATE_TEST_CASE_SIG("bvh_build: identical wide tree for 1 and 2 threads and serially", "[bvh_build]",
                       ((int N), N), 4, 8) {
  // Large enough that binning and subtrees run in parallel (>= 32768 and >= 4096 primitives).
  const std::vector<Bounds3f> prims = bounds_of(random_triangles(60000, 5, 40));
  WideBvh<N> one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = build_wide_bvh<N>(prims);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = build_wide_bvh<N>(prims);
  }
  const WideBvh<N> serial = build_wide_bvh<N>(prims, {.parallel = false});
  check_wide(two, prims, iota(prims.size()), BvhBuildOptions{}.max_leaf_size);
  CHECK(same_tree(one, two));
  CHECK(same_tree(one, serial));
  CHECK(same_tree(two, build_wide_bvh<N>(prims)));  // and run to run
}

TEMPLATE_TEST_CASE_SIG("bvh_build: SAH cost, and SAH beats median splits", "[bvh_build]", ((int N), N), 4, 8) {
  // Two unit boxes far apart: one wide node holding two leaves, cost 1 + 2 * 6/600 (block size 1).
  const std::vector<Bounds3f> two{box({0, 0, 0}, {1, 1, 1}), box({9, 9, 9}, {10, 10, 10})};
  const BvhBuildOptions fine{.leaf_block_size = 1};
  const WideBvh<N> split = build_wide_bvh<N>(two, fine);
  REQUIRE(split.nodes.size() == 1);
  CHECK(split.nodes[0].leaf_count[0] == 1);
  CHECK(sah_cost(split, fine) == Approx(1 + 2 * 6.0 / 600));
  // Blocks of 4: a leaf of 2 costs one block, less than any split.
  const WideBvh<N> joined = build_wide_bvh<N>(two);
  REQUIRE(joined.nodes.size() == 1);
  CHECK(joined.nodes[0].leaf_count[0] == 2);
  CHECK(sah_cost(joined) == Approx(1 + 1));

  // Clustered triangles: binned SAH finds the empty space between clusters; median splits (bins = 1) cut
  // through them.
  const std::vector<Bounds3f> prims = bounds_of(random_triangles(8000, 6, 12));
  const WideBvh<N> sah = build_wide_bvh<N>(prims);
  const WideBvh<N> median = build_wide_bvh<N>(prims, {.bins = 1});
  check_wide(median, prims, iota(prims.size()), 8);
  INFO("SAH " << sah_cost(sah) << " vs median " << sah_cost(median));
  CHECK(sah_cost(sah) < 0.7f * sah_cost(median));
  // More bins never hurt much.
  CHECK(sah_cost(build_wide_bvh<N>(prims, {.bins = 32})) < 1.05f * sah_cost(sah));
}

TEST_CASE("bvh_build: triangle leaves in leaf order, one block per leaf, padded", "[bvh_build]") {
  const std::vector<Vec3f> verts = random_triangles(300, 9);
  const WideBvh<8> bvh = build_wide_bvh<8>(bounds_of(verts));
  const TriangleLeaves l = make_triangle_leaves(bvh, verts, false);
  REQUIRE(l.size() == 300);
  CHECK(l.memory_bytes() == (9 * 300 + TriangleLeaves::kLeafPadding) * 4 + 5 * 8);  // + leaf-start bitmap
  REQUIRE(l.data.size() == 9 * 300 + TriangleLeaves::kLeafPadding);
  REQUIRE(l.leaf_starts.size() == 5);
  // Every leaf (first, count) holds its triangles as nine runs of count floats from 9 * first.
  size_t seen = 0;
  for (const WideNode<8>& n : bvh.nodes)
    for (int c = 0; c < 8; ++c) {
      if (n.child[c] == kEmptyChild || !(n.child[c] & kLeafFlag)) continue;
      const uint32_t first = n.child[c] & ~kLeafFlag, count = n.leaf_count[c];
      for (uint32_t i = first; i < first + count; ++i, ++seen) {
        Vec3f p0, p1, p2;
        leaf_triangle(l, first, count, i, &p0, &p1, &p2);
        const uint32_t t = bvh.prim_indices[i];
        CHECK((p0 == verts[3 * t] && p1 == verts[3 * t + 1] && p2 == verts[3 * t + 2]));
        for (int r = 0; r < 9; ++r) CHECK(l.run(first, count, r)[i - first] == verts[3 * t + r / 3][r % 3]);
        // From the leaf-order index alone (the leaf-start bitmap).
        uint32_t f = 0, k = 0;
        l.leaf_of(i, &f, &k);
        CHECK((f == first && k == count));
        Vec3f q[3];
        l.triangle(i, q);
        CHECK((q[0] == p0 && q[1] == p1 && q[2] == p2));
      }
    }
  CHECK(seen == 300);
  for (size_t i = 9 * 300; i < l.data.size(); ++i) CHECK(l.data[i] == 0.0f);
  // The mesh overload reads the same triangles through the index triples.
  TriangleMesh mesh;
  for (size_t i = 0; i < verts.size(); ++i) mesh.add_vertex(verts[verts.size() - 1 - i]);  // reversed storage
  for (uint32_t t = 0; t < 300; ++t) mesh.add_triangle(899 - 3 * t, 898 - 3 * t, 897 - 3 * t);
  const TriangleLeaves m = make_triangle_leaves(bvh, mesh);
  CHECK(m.data == l.data);
  // The several-meshes overload: triangles 0..99 in one mesh, none in a second, 100..299 in a third.
  std::vector<TriangleMesh> parts(3);
  for (uint32_t t = 0; t < 300; ++t) {
    TriangleMesh& part = parts[t < 100 ? 0 : 2];
    const uint32_t v = uint32_t(part.vertex_count());
    for (int k = 0; k < 3; ++k) part.add_vertex(verts[3 * t + k]);
    part.add_triangle(v, v + 1, v + 2);
  }
  const std::vector<uint32_t> part_first = {0, 100, 100};
  CHECK(make_triangle_leaves(bvh, std::span<const TriangleMesh>(parts), part_first).data == l.data);
  CHECK_THROWS_AS(make_triangle_leaves(bvh, std::span<const TriangleMesh>(parts), std::vector<uint32_t>{0, 100}),
                  Error);
  WideBvh<8> bad = bvh;
  bad.prim_indices[0] = 300;
  CHECK_THROWS_WITH(make_triangle_leaves(bad, verts), Catch::Contains("out of range"));
  CHECK_THROWS_WITH(make_triangle_leaves(bad, mesh), Catch::Contains("out of range"));
  CHECK_THROWS_WITH(make_triangle_leaves(bad, std::span<const TriangleMesh>(parts), part_first),
                    Catch::Contains("out of range"));
  CHECK_THROWS_AS(make_triangle_leaves(bvh, std::span<const Vec3f>(verts.data(), 4)), Error);
}

TEST_CASE("bvh_build: leaf_of finds leaves that span bitmap words", "[bvh_build]") {
  // Leaves of 1, 63, 2, 200 (four words), 1 and 255 triangles: starts at 0, 1, 64, 66, 266, 267; 522 in all.
  const std::vector<uint32_t> sizes{1, 63, 2, 200, 1, 255};
  TriangleLeaves l;
  uint32_t n = 0;
  for (uint32_t s : sizes) n += s;
  l.data.assign(9 * size_t(n) + TriangleLeaves::kLeafPadding, 0.0f);
  l.leaf_starts.assign((n + 63) / 64, 0);
  std::vector<std::pair<uint32_t, uint32_t>> expect;  // (first, count) per triangle
  uint32_t first = 0;
  for (uint32_t s : sizes) {
    l.leaf_starts[first / 64] |= uint64_t(1) << (first % 64);
    for (uint32_t i = 0; i < s; ++i) expect.emplace_back(first, s);
    first += s;
  }
  REQUIRE(l.size() == n);
  for (uint32_t i = 0; i < n; ++i) {
    uint32_t f = 0, c = 0;
    l.leaf_of(i, &f, &c);
    INFO("triangle " << i);
    CHECK(f == expect[i].first);
    CHECK(c == expect[i].second);
  }
}

TEST_CASE("bvh_build: progress counts every primitive in the tree exactly once, in parallel or not", "[bvh_build]") {
  // 60,000 primitives: nodes of 4,096 and more split into parallel tasks, whose children report themselves.
  std::vector<Bounds3f> prims = bounds_of(random_triangles(60000, 9));
  prims[17] = Bounds3f{};  // empty: left out of the tree, so never counted
  for (const bool parallel : {true, false}) {
    ProgressCounter progress;
    const BvhBuildOptions o{.parallel = parallel, .progress = &progress};
    const BinaryBvh bvh = build_binary_bvh(prims, o);
    CHECK(bvh.prim_indices.size() == 59999);
    CHECK(progress.done.load() == 59999);
  }
}

TEST_CASE("bvh_build: invalid options and infinite bounds are reported", "[bvh_build]") {
  CHECK(sizeof(BinaryBvhNode) == 32);
  CHECK(sizeof(WideNode<4>) == 128);
  CHECK(sizeof(WideNode<8>) == 256);
  const std::vector<Bounds3f> one{box({0, 0, 0}, {1, 1, 1})};
  CHECK_THROWS_WITH(build_wide_bvh<8>(one, {.max_leaf_size = 0}), Catch::Contains("max_leaf_size"));
  CHECK_THROWS_WITH(build_wide_bvh<8>(one, {.max_leaf_size = 17}), Catch::Contains("max_leaf_size"));
  CHECK_THROWS_WITH(build_binary_bvh(one, {.bins = 0}), Catch::Contains("bins"));
  CHECK_THROWS_WITH(build_binary_bvh(one, {.bins = 65}), Catch::Contains("bins"));
  CHECK_THROWS_WITH(build_binary_bvh(one, {.leaf_block_size = 0}), Catch::Contains("leaf_block_size"));
  CHECK_THROWS_WITH(build_binary_bvh(one, {.leaf_block_size = 3}), Catch::Contains("power of two"));
  CHECK_THROWS_WITH(build_binary_bvh(one, {.traversal_cost = -1}), Catch::Contains("traversal_cost"));
  CHECK_THROWS_WITH(build_binary_bvh(one, {.intersection_cost = 0}), Catch::Contains("intersection_cost"));
  std::vector<Bounds3f> prims(40000, box({0, 0, 0}, {1, 1, 1}));
  prims[33333].hi.x = kInfinity;
  prims[39999].lo.y = -kInfinity;
  CHECK_THROWS_WITH(build_wide_bvh<4>(prims), Catch::Contains("primitive 33333"));
  // A hand-made binary tree with an oversized leaf cannot be collapsed.
  BinaryBvh big;
  big.nodes.push_back({box({0, 0, 0}, {1, 1, 1}), 0, 300});
  const std::vector<uint32_t> all = iota(300);
  big.prim_indices.assign(all.begin(), all.end());
  CHECK_THROWS_WITH(collapse<4>(big), Catch::Contains("255"));
}
