// GeometrySet: triangles stored in leaf order (meshes reordered, positions read from the leaves), what a hit's
// surface looks like afterwards, and the memory budget of a finished scene (issue "SIMD core": 64 B/triangle).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/rng.h"
#include "geometry/mesh.h"
#include "geometry/mesh_io.h"
#include "geometry/triangle.h"
#include "accel/bvh_build.h"
#include "accel/geometry_set.h"
#include "scene/scene.h"

using namespace torte;

namespace {

const std::string kDragon = std::string(TORTE_SHARED_DATA) + "/meshes/dragon/dragon_100k_binary_le.ply";

// A bumpy grid of (n x n) quads in the xy-plane at height z, with per-vertex normals and uvs that differ from
// vertex to vertex, so a shading lookup through the wrong triangle shows.
TriangleMesh grid_mesh(int n, float z, float seed) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = float(i) / float(n), y = float(j) / float(n);
      m.add_vertex({x, y, z + 0.05f * std::sin(7 * x + seed) * std::cos(5 * y)});
      m.nx.push_back(0.1f * std::sin(3 * x + seed));
      m.ny.push_back(0.1f * std::cos(4 * y));
      m.nz.push_back(1);
      m.u.push_back(x * x + seed);
      m.v.push_back(y);
    }
  const auto at = [n](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.add_triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.add_triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return m;
}

// The closest hit among all triangles of `meshes` by brute force: mesh, triangle and the hit record.
struct BruteHit {
  int mesh = -1;
  size_t tri = 0;
  TriangleHit hit;
};
BruteHit brute_force(const std::vector<TriangleMesh>& meshes, Ray ray) {
  BruteHit best;
  for (size_t m = 0; m < meshes.size(); ++m)
    for (size_t t = 0; t < meshes[m].triangle_count(); ++t) {
      const uint32_t* idx = &meshes[m].indices[3 * t];
      TriangleHit th;
      if (!intersect_triangle(ray, meshes[m].position(idx[0]), meshes[m].position(idx[1]),
                              meshes[m].position(idx[2]), &th))
        continue;
      ray.t_max = th.t;
      best = {int(m), t, th};
    }
  return best;
}

// Shading normal and uv of a brute-force hit, interpolated from the original mesh.
void reference_shading(const TriangleMesh& mesh, size_t tri, const TriangleHit& h, Vec3f* ns, Vec2f* uv) {
  const uint32_t* idx = &mesh.indices[3 * tri];
  const float b0 = 1 - h.b1 - h.b2;
  *ns = normalize(mesh.normal(idx[0]) * b0 + mesh.normal(idx[1]) * h.b1 + mesh.normal(idx[2]) * h.b2);
  *uv = Vec2f(mesh.u[idx[0]], mesh.v[idx[0]]) * b0 + Vec2f(mesh.u[idx[1]], mesh.v[idx[1]]) * h.b1 +
        Vec2f(mesh.u[idx[2]], mesh.v[idx[2]]) * h.b2;
}

}  // namespace

TEST_CASE("geometry_set: meshes in leaf order shade like the originals", "[geometry_set]") {
  // Three stacked grids and an empty mesh (one set of several meshes) and, separately, one grid alone (no index
  // maps).
  for (const bool several : {true, false}) {
    std::vector<TriangleMesh> original;
    original.push_back(grid_mesh(20, 0.0f, 0.0f));
    if (several) {
      original.push_back(grid_mesh(7, 0.5f, 1.0f));
      original.push_back(TriangleMesh{});  // an empty mesh keeps its object number
      original.push_back(grid_mesh(13, -0.5f, 2.0f));
    }
    std::vector<TriangleMesh> meshes = original;
    const std::vector<Quadric> no_quadrics;
    GeometrySet set;
    set.build(meshes, no_quadrics, 10);
    size_t total = 0;
    for (size_t m = 0; m < meshes.size(); ++m) {
      CHECK(meshes[m].indices.size() == original[m].indices.size());
      total += original[m].triangle_count();
    }
    REQUIRE(set.triangle_count() == total);
    // Every mesh holds the same triangles, in another order.
    for (size_t m = 0; m < meshes.size(); ++m) {
      auto sorted = [](const TriangleMesh& mesh) {
        std::vector<std::array<uint32_t, 3>> t(mesh.triangle_count());
        for (size_t i = 0; i < t.size(); ++i)
          t[i] = {mesh.indices[3 * i], mesh.indices[3 * i + 1], mesh.indices[3 * i + 2]};
        std::sort(t.begin(), t.end());
        return t;
      };
      CHECK(sorted(meshes[m]) == sorted(original[m]));
      if (!original[m].indices.empty()) CHECK(meshes[m].indices != original[m].indices);
    }
    // The positions are not needed any more: the set shades from its leaves.
    for (TriangleMesh& m : meshes) m.x = m.y = m.z = {};

    Pcg32 rng(several ? 3 : 4);
    int hits = 0;
    for (int i = 0; i < 4000; ++i) {
      const float side = rng.next_float() < 0.5f ? 2.0f : -2.0f;
      const Vec3f o(rng.next_float() * 1.2f - 0.1f, rng.next_float() * 1.2f - 0.1f, side);
      const Vec3f target(rng.next_float(), rng.next_float(), rng.next_float() - 0.5f);
      const Ray ray{o, normalize(target - o)};
      const BruteHit expect = brute_force(original, ray);
      Hit h;
      const bool got = set.intersect_one(ray, &h);
      REQUIRE(got == (expect.mesh >= 0));
      if (!got) continue;
      ++hits;
      INFO("ray " << i);
      CHECK(h.t == expect.hit.t);
      CHECK(set.object_of(h.prim) == 10 + uint32_t(expect.mesh));
      const SurfaceHit s = set.surface(h);
      CHECK(s.object == 10 + uint32_t(expect.mesh));
      const Vec3f p = ray.o + ray.d * h.t;
      CHECK(length(s.p - p) < 1e-4f);
      Vec3f ns;
      Vec2f uv;
      reference_shading(original[size_t(expect.mesh)], expect.tri, expect.hit, &ns, &uv);
      CHECK(length(s.ns - ns) < 1e-5f);
      CHECK(std::fabs(s.uv.x - uv.x) < 1e-5f);
      CHECK(std::fabs(s.uv.y - uv.y) < 1e-5f);
    }
    CHECK(hits > 1500);
  }
}

TEST_CASE("geometry_set: every triangle of a large several-mesh set finds its own vertex attributes", "[geometry_set]") {
  // 145,000 triangles: the reorder runs in parallel blocks of 64 k leaf positions.
  std::vector<TriangleMesh> meshes{grid_mesh(200, 0.0f, 0.0f), grid_mesh(150, 0.5f, 1.0f), grid_mesh(100, -0.5f, 2.0f)};
  const std::vector<Quadric> no_quadrics;
  GeometrySet set;
  set.build(meshes, no_quadrics, 0);
  REQUIRE(set.triangle_count() == 145000);
  // A grid vertex's uv is (x^2 + seed, y) and its normal's x is 0.1 sin(3x + seed), so the attributes read through
  // the reordered indices must belong to the position read from the leaves: vertex k of every triangle.
  int bad = 0;
  for (uint32_t i = 0; i < set.triangle_count(); ++i)
    for (int k = 0; k < 3; ++k) {
      const Hit h{1.0f, i, k == 1 ? 1.0f : 0.0f, k == 2 ? 1.0f : 0.0f};
      const SurfaceHit sh = set.surface(h);
      const float seed = float(sh.object);
      const Vec3f n = normalize(Vec3f(0.1f * std::sin(3 * sh.p.x + seed), 0.1f * std::cos(4 * sh.p.y), 1));
      if (std::fabs(sh.uv.x - (sh.p.x * sh.p.x + seed)) > 1e-5f || std::fabs(sh.uv.y - sh.p.y) > 1e-6f ||
          length(sh.ns - n) > 1e-5f)
        ++bad;
    }
  CHECK(bad == 0);
}

TEST_CASE("geometry_set: a scene's build progress adds up to its total, triangles left out included", "[geometry_set]") {
  Scene scene;
  scene.meshes = {grid_mesh(60, 0.0f, 0.0f), grid_mesh(40, 0.5f, 1.0f)};
  const uint32_t bad = uint32_t(scene.meshes[1].vertex_count());
  scene.meshes[1].add_vertex({std::numeric_limits<float>::quiet_NaN(), 0, 0});
  scene.meshes[1].add_triangle(bad, bad, bad);  // NaN bounds: the tree leaves it out
  scene.objects.resize(scene.meshes.size());
  ProgressCounter progress;
  scene.finalize(&progress);
  const uint64_t triangles = 2 * 60 * 60 + 2 * 40 * 40 + 1;
  CHECK(GeometrySet::kProgressPerTriangle == 3);  // bounds, the binary BVH build, the rest
  CHECK(progress.total.load() == 3 * triangles);
  CHECK(progress.done.load() == 3 * triangles);
}

TEST_CASE("geometry_set: a triangle the tree leaves out stays in its mesh, after the others", "[geometry_set]") {
  std::vector<TriangleMesh> meshes{grid_mesh(3, 0.0f, 0.0f), grid_mesh(2, 1.0f, 0.0f)};
  // A triangle of NaN vertices has NaN bounds: nothing can hit it, so the BVH leaves it out.
  const uint32_t bad = uint32_t(meshes[1].vertex_count());
  meshes[1].add_vertex({std::numeric_limits<float>::quiet_NaN(), 0, 0});
  meshes[1].add_triangle(bad, bad, bad);
  const std::vector<Quadric> no_quadrics;
  GeometrySet set;
  set.build(meshes, no_quadrics, 0);
  CHECK(set.triangle_count() == 18 + 8);
  REQUIRE(meshes[1].triangle_count() == 9);
  CHECK(meshes[1].indices[3 * 8 + 2] == bad);
}

TEST_CASE("geometry_set: the dragon fits 64 bytes per triangle in a finished scene", "[geometry_set]") {
  if (!std::ifstream(kDragon)) {
    WARN("skipped: " << kDragon << " is absent (shared data not installed)");
    return;
  }
  TriangleMesh mesh = load_mesh(kDragon);
  REQUIRE(mesh.triangle_count() == 100000);
  REQUIRE(mesh.has_normals());
  const TriangleMesh original = mesh;
  Scene scene;
  scene.meshes.push_back(std::move(mesh));
  scene.objects.resize(1);
  scene.finalize();
  // Everything the scene holds for this mesh: nodes, leaf triangles and bitmap, index maps (none for one mesh),
  // and the mesh arrays (indices and normals; positions released because the mesh does not emit).
  const double n = 100000.0;
  const double accel = double(scene.accel_bytes()) / n, geometry = double(scene.geometry_bytes()) / n;
  INFO("acceleration " << accel << " B/tri, mesh " << geometry << " B/tri");
  CHECK(scene.meshes[0].x.empty());
  CHECK(accel + geometry <= 64.0);

  // An emitting mesh keeps its positions (area lights sample them).
  Scene lit;
  lit.meshes.push_back(original);
  lit.objects.resize(1);
  lit.objects[0].area_light = 0;
  Light light;
  light.kind = LightKind::Area;
  light.object = 0;
  light.radiance = Rgb(1);
  lit.lights.push_back(light);
  lit.finalize();
  CHECK(lit.meshes[0].x.size() == original.x.size());
}

// Issue 25: a scene places a script's mesh without copying its positions, uvs or triples (make_placed), and
// traces and shades it exactly as a transformed copy.
TEST_CASE("geometry_set: a placed mesh shares its source and hits like a transformed copy", "[geometry_set][memory]") {
  auto source = std::make_shared<TriangleMesh>(grid_mesh(12, 0.0f, 3.0f));
  const Transform t = translate({0.5f, -0.25f, 2.0f}) * rotate(30.0f, {0, 1, 1}) * scale(Vec3f(1.5f, 0.5f, 2.0f));
  TriangleMesh copy = *source;
  copy.transform(t);
  Scene placed, copied;
  placed.meshes.push_back(make_placed(source, t));
  copied.meshes.push_back(copy);
  for (Scene* s : {&placed, &copied}) {
    s->objects.resize(1);
    s->finalize();
  }
  REQUIRE(placed.meshes[0].placed());
  CHECK(&placed.meshes[0].triple_array() == &source->indices);  // no copy of the triples
  CHECK(placed.meshes[0].x.empty());
  CHECK(placed.meshes[0].own_bytes() == source->nx.size() * 3 * sizeof(float));  // its world normals only
  Pcg32 rng(7);
  int hits = 0;
  for (int i = 0; i < 400; ++i) {
    const Vec3f o{rng.next_float() * 8 - 4, rng.next_float() * 8 - 4, -6};
    const Vec3f target = t.apply_point({rng.next_float(), rng.next_float(), 0});  // the grid spans [0, 1]^2
    Ray a{o, normalize(target - o)}, b = a;
    Hit ha, hb;
    const bool fa = placed.intersect(a, &ha), fb = copied.intersect(b, &hb);
    REQUIRE(fa == fb);
    if (!fa) continue;
    ++hits;
    CHECK(ha.t == hb.t);
    const SurfaceHit sa = placed.surface(a, ha), sb = copied.surface(b, hb);
    CHECK(sa.p == sb.p);
    CHECK(sa.ns == sb.ns);
    CHECK((sa.uv.x == sb.uv.x && sa.uv.y == sb.uv.y));
  }
  CHECK(hits > 200);
}

TEST_CASE("geometry_set: the placed dragon costs at most 54 bytes per triangle beyond its shared source",
          "[geometry_set][memory]") {
  if (!std::ifstream(kDragon)) {
    WARN("skipped: " << kDragon << " is absent (shared data not installed)");
    return;
  }
  auto source = std::make_shared<const TriangleMesh>(load_mesh(kDragon));
  REQUIRE(source->triangle_count() == 100000);
  Scene scene;
  scene.meshes.push_back(make_placed(source, scale({2.0f, 2.0f, 2.0f})));
  scene.objects.resize(1);
  scene.finalize();
  const double n = 100000.0;
  const ShapeSet::TriangleMemory m = scene.accel().root().triangle_memory();
  INFO("nodes " << m.nodes / n << ", leaves " << m.leaves / n << ", map " << m.index_map / n << ", own mesh "
                << scene.meshes[0].own_bytes() / n << " B/tri");
  // The parts the summary prints: 8-wide nodes (6.8 measured), leaf vertices (36 + the leaf-start bitmap), the
  // leaf-to-mesh map the shared triples need (4), the mesh's own world normals (6: 50 k vertices).
  CHECK(m.nodes / n <= 8.0);
  CHECK(m.leaves / n <= 36.2);
  CHECK(m.index_map / n <= 4.01);
  CHECK(double(scene.accel_bytes() + scene.meshes[0].own_bytes()) / n <= 54.0);
  // The scene's own share plus the source it reads (the script holds that anyway): under the 64 + 24 B/tri that
  // a copy in the scene cost next to the script's mesh.
  CHECK(double(scene.geometry_bytes() + scene.accel_bytes()) / n <= 80.0);
}

TEST_CASE("geometry_set: small sets split down to tight leaves, large ones keep leaves of up to 8", "[geometry_set]") {
  // Stacked bumpy grids: one block-8 leaf's box spans several layers, so a ray through it would test them all.
  const auto build = [](int n, int layers, GeometrySet& set) {
    std::vector<TriangleMesh> meshes;
    for (int k = 0; k < layers; ++k) meshes.push_back(grid_mesh(n, 0.3f * float(k), float(k)));
    std::vector<Bounds3f> bounds;
    for (const TriangleMesh& m : meshes)
      for (size_t t = 0; t < m.triangle_count(); ++t) bounds.push_back(m.triangle_bounds(t));
    set.build(meshes, {}, 0);
    return bounds;
  };
  BvhBuildOptions fine, coarse;
  fine.leaf_block_size = 1;
  fine.parallel = coarse.parallel = false;
  SECTION("a few hundred triangles: per-triangle leaf costs") {
    GeometrySet set;
    const std::vector<Bounds3f> bounds = build(6, 4, set);  // 288 triangles
    REQUIRE(bounds.size() <= kFineLeavesMaxTriangles);
    const WideBvh<8> block8 = build_wide_bvh<8>(bounds, coarse);
    const float built = sah_cost(set.triangle_bvh(), fine), with_block8 = sah_cost(block8, fine);
    INFO("SAH (per-triangle costs): built " << built << ", block-8 tree " << with_block8);
    CHECK(built < 0.8f * with_block8);
  }
  SECTION("above kFineLeavesMaxTriangles: the default block of 8") {
    GeometrySet set;
    const std::vector<Bounds3f> bounds = build(130, 2, set);  // 67,600 triangles
    REQUIRE(bounds.size() > kFineLeavesMaxTriangles);
    const WideBvh<8> block8 = build_wide_bvh<8>(bounds, coarse);
    CHECK(set.triangle_bvh().nodes.size() == block8.nodes.size());
    CHECK(sah_cost(set.triangle_bvh(), coarse) == Approx(sah_cost(block8, coarse)).epsilon(1e-4));
  }
}
