// The work counts of the traversal_cost AOV (TraversalCost, accel/hit.h): the counting kernel against the plain
// kernel (the same hits, bit for bit) and against the scalar reference (the same nodes and triangles), on every
// Highway target; the packed and compact layouts against the default one; and the scene's levels (quadrics,
// instances, voxel grids) through Scene::intersect.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "geometry/subdivide.h"
#include "scene/scene.h"
#include "test_random.h"
#include "traverse_test_support.h"
#include "voxel/voxel_accel.h"
#include "voxel/voxel_tree.h"

using namespace torte;
using namespace torte::test;
using namespace torte::test::traverse;

namespace {

bool same_bits(const Hit& a, const Hit& b) {
  return a.prim == b.prim && std::memcmp(&a.t, &b.t, 4) == 0 && std::memcmp(&a.b1, &b.b1, 4) == 0 &&
         std::memcmp(&a.b2, &b.b2, 4) == 0;
}

// Rays from around the soup towards points inside it, some axis-aligned (the kernel's exact slab test), and last
// one that points away from everything.
Rays random_rays(int n, uint64_t seed) {
  Pcg32 rng(seed);
  Rays r;
  for (int i = 0; i < n; ++i) {
    const Vec3f o = random_vec(rng) * 40 - Vec3f(20, 20, 20);
    Vec3f d = normalize(random_vec(rng) * 16 - Vec3f(8, 8, 8) - o);
    if (i % 16 == 0) d = Vec3f(0, 0, o.z < 0 ? 1.0f : -1.0f);
    r.add(o, d);
  }
  r.add({0, 40, 0}, {0, 1, 0});
  return r;
}

// A closed bumpy sphere of 12 * 4^5 triangles: a subdivided cube pushed out to radius 1 + 0.15 sin sin sin.
TriangleMesh bumpy_sphere() {
  TriangleMesh m = subdivide(make_cube(), 5);
  for (size_t i = 0; i < m.vertex_count(); ++i) {
    const Vec3f p = normalize(m.position(uint32_t(i)) - Vec3f(0.5f, 0.5f, 0.5f));
    const Vec3f v = p * (1 + 0.15f * std::sin(7 * p.x) * std::sin(5 * p.y) * std::sin(6 * p.z));
    m.x[i] = v.x, m.y[i] = v.y, m.z[i] = v.z;
  }
  return m;
}

std::unique_ptr<Scene> scene_of(const TriangleMesh& mesh, BvhLayout layout) {
  auto scene = std::make_unique<Scene>();
  scene->meshes.push_back(mesh);
  scene->objects.resize(1);
  scene->accel_options.layout = layout;
  scene->finalize();
  return scene;
}

}  // namespace

TEST_CASE("traversal cost: the counting kernel's hits are the plain kernel's, its counts the scalar reference's",
          "[traverse][aov]") {
  Soup s = icosphere(4, {0, 0, 0}, 5);
  const Soup extra = random_soup(3000, 7);
  s.insert(s.end(), extra.begin(), extra.end());
  const Tree<8> t = build<8>(s);
  const Rays r = random_rays(4000, 11);
  const size_t n = r.size();
  std::vector<TraversalCost> want(n);
  for (size_t i = 0; i < n; ++i) wide_closest_hit_reference(t.bvh, t.leaves, r.ray(i), &want[i]);
  // The ray pointing away from everything visits the root and tests nothing.
  CHECK(want[n - 1].nodes == 1);
  CHECK(want[n - 1].prims == 0);
  for_each_target([&](const std::string&, bool) {
    const std::vector<Hit> plain = trace(t, r, Mode::kSingle, n);
    std::vector<Hit> counted(n);
    std::vector<TraversalCost> cost(n);
    intersect_closest_counted(t.bvh, t.leaves, r.soa(), n, counted.data(), cost.data());
    size_t differ = 0, hits = 0;
    uint64_t nodes = 0, want_nodes = 0, prims = 0, want_prims = 0;
    for (size_t i = 0; i < n; ++i) {
      INFO(describe(r.ray(i), plain[i], counted[i]));
      REQUIRE(same_bits(plain[i], counted[i]));
      hits += plain[i].prim != kNoHit;
      // The kernel's slab test widens boxes by a margin of a few ulps (traverse-inl.h), so a ray grazing a box
      // may enter it where the reference does not: rare.
      differ += cost[i].nodes != want[i].nodes || cost[i].prims != want[i].prims;
      nodes += cost[i].nodes, want_nodes += want[i].nodes, prims += cost[i].prims, want_prims += want[i].prims;
    }
    INFO("rays " << n << ", hits " << hits << ", counts differing from the reference " << differ << "; nodes "
                 << nodes << " (reference " << want_nodes << "), triangles " << prims << " (" << want_prims << ")");
    CHECK(hits > n / 4);
    CHECK(differ <= n / 200);
    CHECK(nodes >= want_nodes);
    CHECK(double(nodes) <= 1.002 * double(want_nodes));
    CHECK(prims >= want_prims);
    CHECK(double(prims) <= 1.002 * double(want_prims));
    CHECK(cost[n - 1].nodes == 1);
    CHECK(cost[n - 1].prims == 0);
  });
}

TEST_CASE("traversal cost: the packed layout counts as the default one, the compact one at least as much",
          "[compact][aov]") {
  const TriangleMesh mesh = bumpy_sphere();
  const auto def = scene_of(mesh, BvhLayout::kDefault), packed = scene_of(mesh, BvhLayout::kPacked),
             compact = scene_of(mesh, BvhLayout::kCompact);
  Pcg32 rng(3);
  uint64_t nodes[2] = {}, prims[2] = {};
  int hits = 0;
  for (int i = 0; i < 5000; ++i) {
    const Vec3f o = random_direction(rng) * 4, target = (random_vec(rng) * 2 - Vec3f(1, 1, 1)) * 0.8f;
    const Ray ray{o, normalize(target - o)};
    Ray rd = ray, rp = ray, rc = ray, ru = ray;
    Hit hd, hp, hc, hu;
    TraversalCost cd, cp, cc;
    const bool fd = def->intersect(rd, &hd, &cd);
    REQUIRE(def->intersect(ru, &hu) == fd);
    REQUIRE(same_bits(hd, hu));
    REQUIRE(packed->intersect(rp, &hp, &cp) == fd);
    REQUIRE(compact->intersect(rc, &hc, &cc) == fd);
    hits += fd;
    if (fd) {
      REQUIRE(hp.t == hd.t);
      REQUIRE(hc.t == hd.t);
    }
    // The same wide nodes and leaves, so the same decisions.
    REQUIRE(cp.nodes == cd.nodes);
    REQUIRE(cp.prims == cd.prims);
    CHECK(cd.nodes >= 1);
    nodes[0] += cd.nodes, prims[0] += cd.prims, nodes[1] += cc.nodes, prims[1] += cc.prims;
  }
  INFO("default nodes " << nodes[0] << " triangles " << prims[0] << "; compact " << nodes[1] << ", " << prims[1]);
  CHECK(hits > 1000);
  // Quantised boxes hold their children's boxes and a little more: never fewer visits in all.
  CHECK(nodes[1] >= nodes[0]);
  CHECK(prims[1] >= prims[0]);
  CHECK(double(nodes[1]) < 1.5 * double(nodes[0]));
}

TEST_CASE("traversal cost: quadrics, instances and voxel grids count their levels", "[aov]") {
  // One quadric: its BVH2 is a lone leaf, so a ray into its box tests it once and visits no node.
  Scene sphere;
  Quadric q;
  q.to_world = translate({0, 0, 5});
  sphere.quadrics.push_back(q);
  sphere.objects.resize(1);
  sphere.finalize();
  {
    Ray hit_ray{{0, 0, 0}, {0, 0, 1}}, miss_ray{{0, 0, 0}, {0, 1, 0}};
    Hit h;
    TraversalCost c, m;
    REQUIRE(sphere.intersect(hit_ray, &h, &c));
    CHECK(h.t == Approx(4));
    CHECK(c.nodes == 0);
    CHECK(c.prims == 1);
    CHECK_FALSE(sphere.intersect(miss_ray, &h, &m));
    CHECK(m.nodes == 0);
    CHECK(m.prims == 0);
  }

  // Instances: a row of k copies of a one-triangle group along the ray, each nearer copy hiding the ones behind.
  // The counts grow with the instance BVH's depth, and each copy entered adds its own tree (a node and a
  // triangle); the copies behind the first hit are not entered.
  const auto row = [](int k, TraversalCost* cost, float* t) {
    Scene s;
    auto proto = std::make_unique<Prototype>();
    proto->meshes.push_back(make_polygon({{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}));
    s.prototypes.push_back(std::move(proto));
    for (int i = 0; i < k; ++i) s.instances.push_back({translate({0, 0, 2.0f + 3.0f * float(i)}), 0});
    s.objects.resize(1);
    s.finalize();
    Ray ray{{0, 0, 0}, {0, 0, 1}};
    Hit h;
    REQUIRE(s.intersect(ray, &h, cost));
    CHECK(h.instance == 0);
    *t = h.t;
    // Any ray: the counting search finds the batched instance level's hit.
    Pcg32 rng(5);
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vec3f o = random_vec(rng) * 6 - Vec3f(3, 3, 3);
      const Vec3f target{0.5f * rng.next_float(), 0, 2.0f + 3.0f * float(i % k)};
      Ray a{o, normalize(target - o)}, b = a;
      Hit ha, hb;
      TraversalCost c;
      const bool fa = s.intersect(a, &ha), fb = s.intersect(b, &hb, &c);
      REQUIRE(fa == fb);
      hits += fa;
      if (fa) {
        REQUIRE(same_bits(ha, hb));
        REQUIRE(ha.instance == hb.instance);
      }
    }
    CHECK(hits > 100);
  };
  TraversalCost one, eight;
  float t1, t8;
  row(1, &one, &t1);
  row(8, &eight, &t8);
  CHECK(t1 == Approx(2));
  CHECK(t8 == Approx(2));
  CHECK(one.prims == 2);   // the instance (the instance BVH2 is a lone leaf) and its triangle
  CHECK(one.nodes == 1);   // the group's wide BVH root
  CHECK(eight.prims > 1);  // the instance leaves reached and the entered copy's triangle
  CHECK(eight.nodes > one.nodes);

  // A voxel grid of three solid voxels: a ray into one descends the kd-tree and tests that voxel only; a ray
  // between them tests none.
  VoxelGrid grid;
  for (int k : {0, 10, 31}) grid.set(k, k, k, 1);
  Scene vox;
  VoxelGridAccel g;
  g.tree = std::make_shared<const VoxelTree>(VoxelTree::build(grid));
  vox.grids.push_back(std::move(g));
  vox.objects.resize(1);
  vox.finalize();
  {
    Ray hit_ray{{10.5f, 10.5f, -5}, {0, 0, 1}}, miss_ray{{20.5f, 3.5f, -5}, {0, 0, 1}};
    Hit h;
    TraversalCost c, m;
    REQUIRE(vox.intersect(hit_ray, &h, &c));
    CHECK(h.t == Approx(15));
    CHECK(c.nodes >= 3);
    CHECK(c.prims == 1);
    CHECK_FALSE(vox.intersect(miss_ray, &h, &m));
    CHECK(m.nodes >= 1);
    CHECK(m.prims == 0);
  }
}
