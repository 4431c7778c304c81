// Voxel grids: node packing, the build (homogeneous regions collapse, bytes per voxel, serial = parallel) and the
// kd-tree traversal against the brute-force 3D-DDA on random rays over random and structured grids.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "core/rng.h"
#include "voxel/voxel_traverse.h"
#include "voxel_test_cells.h"

namespace {
float uniform(torte::Pcg32& rng) { return rng.next_float(); }
}  // namespace

using namespace torte;
using torte::test::random_grid;
using torte::test::SlabCells;
using torte::test::terrain_grid;

namespace {



Ray random_ray(Pcg32& rng, const VoxelTree& tree, bool inside) {
  const Bounds3f b = tree.bounds();
  const Vec3f ext = b.diagonal();
  Ray r;
  for (int a = 0; a < 3; ++a) {
    const float u = uniform(rng);
    r.o[a] = inside ? b.lo[a] + u * ext[a] : b.lo[a] - 0.3f * ext[a] + 1.6f * u * ext[a];
  }
  // Some origins exactly on cell boundaries (rays leaving a face): both traversals must pick the same cell.
  if (uniform(rng) < 0.25f) {
    const int a = std::min(2, int(uniform(rng) * 3));
    r.o[a] = std::floor(r.o[a]);
  }
  const float z = 1 - 2 * uniform(rng), phi = 6.2831853f * uniform(rng), s = std::sqrt(std::max(0.0f, 1 - z * z));
  r.d = Vec3f(s * std::cos(phi), s * std::sin(phi), z) * (0.5f + uniform(rng));
  r.t_max = uniform(rng) < 0.2f ? ext.x * uniform(rng) : kInfinity;
  return r;
}

struct Compare {
  int rays = 0, hits = 0, inside = 0, cells = 0, mismatches = 0;
};

void compare(const VoxelGrid& grid, const VoxelTree& tree, int count, uint64_t seed, Compare* c) {
  Pcg32 rng(seed);
  for (int i = 0; i < count; ++i) {
    const Ray r = random_ray(rng, tree, i % 2 == 0);
    VoxelHit a, b;
    const bool ha = voxel_intersect(tree, r, &a, SlabCells{});
    const bool hb = voxel_intersect_dda(tree, grid, r, &b, SlabCells{});
    const bool oa = voxel_occluded(tree, r, SlabCells{});
    const bool ob = voxel_occluded_dda(tree, grid, r, SlabCells{});
    ++c->rays;
    bool same = ha == hb && oa == ob && oa == ha;
    if (ha && hb) {
      ++c->hits;
      c->inside += a.inside;
      c->cells += a.face < 0;
      same = same && a.t == b.t && a.id == b.id && a.face == b.face && a.inside == b.inside &&
             a.voxel[0] == b.voxel[0] && a.voxel[1] == b.voxel[1] && a.voxel[2] == b.voxel[2] && a.u == b.u &&
             a.v == b.v;
      // The reported voxel holds the reported id.
      same = same && grid.get(a.voxel[0], a.voxel[1], a.voxel[2]) == a.id;
    }
    if (!same) {
      if (c->mismatches < 5)
        UNSCOPED_INFO("ray " << i << ": o " << r.o.x << " " << r.o.y << " " << r.o.z << " d " << r.d.x << " "
                             << r.d.y << " " << r.d.z << " kd " << ha << " t " << a.t << " v " << a.voxel[0] << ","
                             << a.voxel[1] << "," << a.voxel[2] << " f " << int(a.face) << " | dda " << hb << " t "
                             << b.t << " v " << b.voxel[0] << "," << b.voxel[1] << "," << b.voxel[2] << " f "
                             << int(b.face));
      ++c->mismatches;
    }
  }
}

}  // namespace

TEST_CASE("voxel node packing round-trips leaf ids and inner axis and child pair", "[voxel]") {
  STATIC_REQUIRE(sizeof(VoxelNode) == 4);
  for (int id = -32768; id <= 32767; ++id) {
    const VoxelNode n = VoxelNode::leaf(int16_t(id));
    REQUIRE(n.is_leaf());
    REQUIRE(n.id() == id);
    REQUIRE((n.bits & 0x7fff0000u) == 0);
  }
  Pcg32 rng(3);
  for (int i = 0; i < 100000; ++i) {
    const int axis = int(uniform(rng) * 3);
    const uint32_t pair = uint32_t(uniform(rng) * float(VoxelNode::kPairMask)) & VoxelNode::kPairMask;
    const VoxelNode n = VoxelNode::inner(axis, pair);
    REQUIRE(!n.is_leaf());
    REQUIRE(n.axis() == axis);
    REQUIRE(n.pair() == pair);
  }
  CHECK(VoxelNode::inner(1, VoxelNode::kPairMask).pair() == VoxelNode::kPairMask);
  CHECK(VoxelNode::leaf(-1).bits == 0x8000ffffu);
  CHECK(VoxelNode::inner(2, 7).bits == (2u << 29 | 7u));
}

TEST_CASE("voxel homogeneous regions collapse: a full 64^3 block is one leaf", "[voxel]") {
  VoxelGrid g;
  std::vector<int16_t> ids(kVoxelChunkVoxels, 9);
  for (int cz = 0; cz < 4; ++cz)
    for (int cy = 0; cy < 4; ++cy)
      for (int cx = 0; cx < 4; ++cx) g.set_chunk(cx, cy, cz, ids.data());
  VoxelTree t = VoxelTree::build(g);
  CHECK(t.root().is_leaf());
  CHECK(t.root().id() == 9);
  CHECK(t.stats().nodes == 1);
  CHECK(t.stats().voxels == 64 * 64 * 64);
  CHECK(t.log2_size()[0] == 6);
  // One differing voxel costs one path of the tree: 2 nodes per level, 18 levels.
  g.set(5, 6, 7, 3);
  t = VoxelTree::build(g);
  CHECK(t.stats().nodes == 1 + 2 * 18);
  CHECK(t.lookup(5, 6, 7) == 3);
  CHECK(t.lookup(5, 6, 8) == 9);
  // A block in empty space: the empty region is few leaves too.
  VoxelGrid h;
  for (int z = 0; z < 16; ++z)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) h.set(x + 32, y, z + 64, 4);
  h.set(0, 100, 0, 1);  // stretch the box
  h.set(0, 100, 0, 0);
  t = VoxelTree::build(h);
  CHECK(t.stats().nodes < 40);
}

TEST_CASE("voxel tree lookup equals the grid, parallel build equals serial, worst case under 8 bytes per cell",
          "[voxel]") {
  const VoxelGrid g = random_grid(11, 70, 0.4f, true);
  const VoxelTree serial = VoxelTree::build(g, false);
  const VoxelTree par = VoxelTree::build(g, true);
  REQUIRE(serial.nodes().size() == par.nodes().size());
  CHECK(std::equal(serial.nodes().begin(), serial.nodes().end(), par.nodes().begin()));
  for (int z = -40; z < 40; ++z)
    for (int y = -2; y < 72; ++y)
      for (int x = -30; x < 50; ++x) REQUIRE(serial.lookup(x, y, z) == g.get(x, y, z));
  // Worst case: every voxel differs from its neighbours (ids 1, 2, ... in a 3D checkerboard-free pattern).
  VoxelGrid worst;
  for (int z = 0; z < 64; ++z)
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) worst.set(x, y, z, int16_t(1 + (x + 3 * y + 5 * z) % 17));
  const VoxelTree w = VoxelTree::build(worst);
  const double bpv = w.stats().bytes_per_voxel();
  std::fprintf(stderr, "voxel worst case: %llu voxels, %llu nodes, %.3f bytes/voxel\n",
               static_cast<unsigned long long>(w.stats().voxels), static_cast<unsigned long long>(w.stats().nodes), bpv);
  CHECK(w.stats().voxels == 64 * 64 * 64);
  CHECK(bpv <= 8.0);
  CHECK(bpv > 7.9);
  const VoxelTree t = VoxelTree::build(terrain_grid(128));
  std::fprintf(stderr, "voxel terrain 128^2: %llu voxels, %llu nodes, %.3f bytes/voxel\n",
               static_cast<unsigned long long>(t.stats().voxels), static_cast<unsigned long long>(t.stats().nodes),
               t.stats().bytes_per_voxel());
  CHECK(t.stats().bytes_per_voxel() < 2.0);
}

TEST_CASE("voxel kd-tree traversal equals the brute-force 3D-DDA on random rays", "[voxel]") {
  Compare c;
  const VoxelGrid sparse = random_grid(1, 40, 0.05f, true);
  compare(sparse, VoxelTree::build(sparse), 40000, 5, &c);
  const VoxelGrid dense = random_grid(2, 33, 0.5f, true);
  compare(dense, VoxelTree::build(dense), 30000, 6, &c);
  const VoxelGrid terrain = terrain_grid(96);
  compare(terrain, VoxelTree::build(terrain), 40000, 7, &c);
  std::fprintf(stderr, "voxel kd vs dda: %d rays, %d hits (%d starting inside, %d cell shapes), %d mismatches\n",
               c.rays, c.hits, c.inside, c.cells, c.mismatches);
  CHECK(c.rays >= 100000);
  CHECK(c.hits > c.rays / 5);
  CHECK(c.inside > 100);
  CHECK(c.cells > 100);
  CHECK(c.mismatches == 0);
}

TEST_CASE("voxel ray starting inside a solid voxel hits its exit face from inside", "[voxel]") {
  VoxelGrid g;
  for (int x = 0; x < 8; ++x) g.set(x, 0, 0, 1);
  const VoxelTree t = VoxelTree::build(g);
  VoxelHit h;
  REQUIRE(voxel_intersect(t, Ray{{2.5f, 0.5f, 0.5f}, {0, 1, 0}}, &h));
  CHECK(h.inside);
  CHECK(h.t == Approx(0.5f));
  CHECK(h.face == 2);  // +y, the face it leaves through
  CHECK(h.voxel[0] == 2);
  CHECK(h.u == Approx(0.5f));
  CHECK(h.v == Approx(0.5f));
  // Along the row of solid voxels: still the voxel it starts in (inside faces of the voxel, not the region).
  REQUIRE(voxel_intersect(t, Ray{{2.25f, 0.5f, 0.5f}, {1, 0, 0}}, &h));
  CHECK(h.t == Approx(0.75f));
  CHECK(h.face == 0);
  CHECK(h.voxel[0] == 2);
  // Ending inside: no hit.
  CHECK(!voxel_intersect(t, Ray{{2.25f, 0.5f, 0.5f}, {1, 0, 0}, 0.5f}, &h));
  // A ray leaving the top face (origin offset above it) does not hit its voxel; one going back down does.
  CHECK(!voxel_occluded(t, Ray{{2.5f, 1.0001f, 0.5f}, {0.3f, 1, 0.2f}}));
  REQUIRE(voxel_intersect(t, Ray{{2.5f, 1.0001f, 0.5f}, {0, -1, 0}}, &h));
  CHECK(!h.inside);
  CHECK(h.face == 2);
  CHECK(h.t == Approx(0.0001f).margin(1e-6));
  // Entering from outside through -x.
  REQUIRE(voxel_intersect(t, Ray{{-3, 0.25f, 0.75f}, {1, 0, 0}}, &h));
  CHECK(h.face == 1);
  CHECK(h.t == Approx(3));
  CHECK(h.u == Approx(0.75f));  // x faces: u = z, v = y
  CHECK(h.v == Approx(0.25f));
}
