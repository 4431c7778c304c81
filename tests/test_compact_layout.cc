// The packed and compact triangle layouts in a scene (accel/accel_options.h, accel/compact_bvh.h): their bytes
// per triangle against the default layout's (the memory tests of issue 25), hits and surfaces equal to the default
// layout's, the same image, and the automatic choice by memory budget.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <memory>
#include <string>

#include "core/memory_budget.h"
#include "core/rng.h"
#include "geometry/mesh_io.h"
#include "geometry/mesh_normals.h"
#include "geometry/subdivide.h"
#include "render/render.h"
#include "scene/builder.h"
#include "scene/scene.h"
#include "scene_helpers.h"
#include "test_random.h"

using namespace torte;
using namespace torte::test;

namespace {

const std::string kDragon = std::string(TORTE_SHARED_DATA) + "/meshes/dragon/dragon_100k_binary_le.ply";

std::unique_ptr<Scene> scene_of(TriangleMesh mesh, BvhLayout layout) {
  auto scene = std::make_unique<Scene>();
  scene->meshes.push_back(std::move(mesh));
  scene->objects.resize(1);
  scene->accel_options.layout = layout;
  scene->finalize();
  return scene;
}

// Random rays at the scene's bounds: the same hits (t bit for bit) and surfaces in both layouts.
void check_same_hits(const Scene& a, const Scene& b, int rays, int min_hits) {
  Pcg32 rng(9);
  const Bounds3f box = a.bounds();
  int hits = 0, other_prim = 0;
  for (int i = 0; i < rays; ++i) {
    const Vec3f target = box.lo + mul(box.hi - box.lo, random_vec(rng));
    const Vec3f o = box.center() + random_direction(rng) * length(box.diagonal());
    Ray ra{o, normalize(target - o)}, rb = ra;
    Hit ha, hb;
    const bool fa = a.intersect(ra, &ha), fb = b.intersect(rb, &hb);
    REQUIRE(fa == fb);
    if (!fa) continue;
    ++hits;
    REQUIRE(ha.t == hb.t);
    if (ha.prim != hb.prim) {  // a ray through a shared edge: either triangle (traverse.h)
      ++other_prim;
      continue;
    }
    const SurfaceHit sa = a.surface(ra, ha), sb = b.surface(rb, hb);
    CHECK(sa.p == sb.p);
    CHECK(sa.ns == sb.ns);
    CHECK(sa.ng == sb.ng);
  }
  CHECK(hits >= min_hits);
  CHECK(other_prim <= hits / 1000);
}

}  // namespace

TEST_CASE("compact layout: the dragon's bytes per triangle in both layouts", "[compact][memory]") {
  if (!std::ifstream(kDragon)) {
    WARN("skipped: " << kDragon << " is absent (shared data not installed)");
    return;
  }
  const TriangleMesh mesh = load_mesh(kDragon);
  REQUIRE(mesh.triangle_count() == 100000);
  const double n = 100000.0;
  const auto def = scene_of(mesh, BvhLayout::kDefault);
  const auto packed = scene_of(mesh, BvhLayout::kPacked);
  const auto compact = scene_of(mesh, BvhLayout::kCompact);
  REQUIRE(def->accel().layout() == BvhLayout::kDefault);
  REQUIRE(packed->accel().layout() == BvhLayout::kPacked);
  REQUIRE(compact->accel().layout() == BvhLayout::kCompact);
  const ShapeSet::TriangleMemory md = def->accel().root().triangle_memory();
  const ShapeSet::TriangleMemory mp = packed->accel().root().triangle_memory();
  const ShapeSet::TriangleMemory mc = compact->accel().root().triangle_memory();
  INFO("default: nodes " << md.nodes / n << ", leaves " << md.leaves / n << "; packed: nodes " << mp.nodes / n
                         << ", leaves " << mp.leaves / n << "; compact: nodes " << mc.nodes / n << ", leaves "
                         << mc.leaves / n << " B/tri");
  // Default: 8-wide nodes (6.8 measured), leaf vertices 36 + the leaf-start bitmap; all in <= 64 with the mesh's
  // indices and normals. Packed: the same nodes, packed leaves (18.9 measured: a leaf's header and 8-bit indices,
  // 4 + 3 bytes per triangle, and its distinct vertices, 12 bytes each). Compact: nodes of 128 bytes (half),
  // packed leaves.
  CHECK(md.nodes / n <= 8.0);
  CHECK(md.leaves / n <= 36.2);
  CHECK(mp.nodes == md.nodes);
  CHECK(mp.leaves / n <= 19.0);
  CHECK(mc.nodes / n <= 4.0);
  CHECK(mc.leaves == mp.leaves);
  CHECK(mc.index_map == 0);
  CHECK(mp.index_map == 0);
  const double total_default = double(def->accel_bytes() + def->geometry_bytes()) / n;
  const double total_packed = double(packed->accel_bytes() + packed->geometry_bytes()) / n;
  const double total_compact = double(compact->accel_bytes() + compact->geometry_bytes()) / n;
  INFO("finished scene: default " << total_default << ", packed " << total_packed << ", compact " << total_compact
                                  << " B/tri");
  CHECK(total_default <= 64.0);
  CHECK(total_packed <= 44.0);
  CHECK(total_compact <= 40.5);
  CHECK(packed->meshes[0].x.empty());  // its positions: the leaves' copy
  CHECK(compact->meshes[0].x.empty());
  // The budget's estimates (accel_options.h) cover what the layouts take.
  CHECK((md.nodes + md.leaves) / n <= double(kDefaultLayoutBytesPerTriangle));
  CHECK((mp.nodes + mp.leaves) / n <= double(kPackedLayoutBytesPerTriangle));

  // Placed (the script's mesh shared): the same leaves, plus the map (4).
  auto source = std::make_shared<const TriangleMesh>(mesh);
  Scene placed;
  placed.meshes.push_back(make_placed(source, scale({2.0f, 2.0f, 2.0f})));
  placed.objects.resize(1);
  placed.accel_options.layout = BvhLayout::kCompact;
  placed.finalize();
  const ShapeSet::TriangleMemory ml = placed.accel().root().triangle_memory();
  INFO("placed compact: nodes " << ml.nodes / n << ", leaves " << ml.leaves / n << ", map " << ml.index_map / n);
  CHECK(ml.leaves / n <= 19.0);
  CHECK(double(placed.accel_bytes() + placed.meshes[0].own_bytes()) / n <= 32.5);
}

TEST_CASE("compact layout: the dragon's hits and surfaces equal the default layout's", "[compact]") {
  if (!std::ifstream(kDragon)) {
    WARN("skipped: " << kDragon << " is absent (shared data not installed)");
    return;
  }
  const TriangleMesh mesh = load_mesh(kDragon);
  const auto def = scene_of(mesh, BvhLayout::kDefault);
  for (const BvhLayout layout : {BvhLayout::kPacked, BvhLayout::kCompact}) {
    INFO(bvh_layout_name(layout));
    check_same_hits(*def, *scene_of(mesh, layout), 20000, 4000);
    // Placed meshes and several meshes per set: the leaves' own vertex copy (in world space).
    auto source = std::make_shared<const TriangleMesh>(mesh);
    Scene pd, pc;
    for (Scene* s : {&pd, &pc}) {
      s->meshes.push_back(make_placed(source, translate({0.1f, 0, 0}) * scale({2.0f, 2.0f, 2.0f})));
      s->meshes.push_back(make_polygon({{-1, -0.2f, -1}, {1, -0.2f, -1}, {1, -0.2f, 1}, {-1, -0.2f, 1}}));
      s->objects.resize(2);
    }
    pd.accel_options.layout = BvhLayout::kDefault;
    pc.accel_options.layout = layout;
    pd.finalize();
    pc.finalize();
    check_same_hits(pd, pc, 20000, 4000);
  }
}

TEST_CASE("compact layout: a render equals the default layout's image", "[compact][render]") {
  // A bumpy sphere with vertex normals on a floor, under an area light: every hit is a triangle's.
  SceneBuilder b;
  ShapeDesc ball;
  ball.kind = ShapeDesc::Kind::Mesh;
  TriangleMesh cube = subdivide(make_cube(), 4);
  for (size_t v = 0; v < cube.x.size(); ++v) {
    const Vec3f p = normalize(cube.position(uint32_t(v))) * (0.5f + 0.02f * std::sin(11.0f * cube.x[v]));
    cube.x[v] = p.x, cube.y[v] = p.y, cube.z[v] = p.z;
  }
  compute_smooth_normals(cube);
  ball.mesh = std::make_shared<TriangleMesh>(cube);
  ball.material = matte(0.7f);
  b.add_shape(ball);
  ShapeDesc floor;
  floor.kind = ShapeDesc::Kind::Mesh;
  floor.mesh =
      std::make_shared<TriangleMesh>(make_polygon({{-3, -0.6f, -3}, {3, -0.6f, -3}, {3, -0.6f, 3}, {-3, -0.6f, 3}}));
  floor.material = matte(0.5f);
  b.add_shape(floor);
  ShapeDesc panel = floor;
  panel.mesh = std::make_shared<TriangleMesh>(make_polygon({{-1, 2, -1}, {-1, 2, 1}, {1, 2, 1}, {1, 2, -1}}));
  panel.emission = Rgb(3);
  panel.two_sided = true;
  b.add_shape(panel);
  AccelOptions def{.layout = BvhLayout::kDefault};
  const auto sd = b.flatten(nullptr, &def);
  RenderSettings s;
  s.width = 48;
  s.height = 32;
  s.spp = 8;
  s.max_depth = 4;
  const CameraDesc camera = camera_at({0.3f, 0.8f, -2.5f}, {0, -0.1f, 0}, 45);
  const Image a = render_view(*sd, camera, s).image;
  for (const BvhLayout layout : {BvhLayout::kPacked, BvhLayout::kCompact}) {
    INFO(bvh_layout_name(layout));
    AccelOptions other{.layout = layout};
    const auto sc = b.flatten(nullptr, &other);
    REQUIRE(sc->accel().layout() == layout);
    const Image c = render_view(*sc, camera, s).image;
    size_t same = 0;
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x) {
        const Rgb pa = a.at(x, y), pc = c.at(x, y);
        same += pa.r == pc.r && pa.g == pc.g && pa.b == pc.b;
      }
    // The same hits give the same paths: bitwise, but for rays through shared edges, which may take either
    // triangle (their paths differ from there on).
    INFO(same << " of " << a.width * a.height << " pixels bitwise equal");
    CHECK(same >= size_t(a.width * a.height) * 97 / 100);
    CHECK(max_tile_error(c, a, 16) < 0.02);
  }
}

TEST_CASE("compact layout: chosen by the memory budget", "[compact]") {
  TriangleMesh mesh = subdivide(make_cube(), 3);
  const auto build = [&](AccelOptions o) {
    Scene s;
    s.meshes.push_back(mesh);
    s.objects.resize(1);
    s.accel_options = o;
    s.finalize();
    return s.accel().layout();
  };
  // The process's resident memory alone exceeds 1 KiB; nothing here approaches 1 PiB.
  CHECK(build({.layout = BvhLayout::kAuto, .memory_budget = 1024}) == BvhLayout::kCompact);
  CHECK(build({.layout = BvhLayout::kAuto, .memory_budget = uint64_t(1) << 50}) == BvhLayout::kDefault);
  CHECK(build({.layout = BvhLayout::kDefault, .memory_budget = 1024}) == BvhLayout::kDefault);
  CHECK(build({.layout = BvhLayout::kCompact}) == BvhLayout::kCompact);
  CHECK(build({.layout = BvhLayout::kPacked}) == BvhLayout::kPacked);
  CHECK(build({}) == BvhLayout::kDefault);  // the process's limit: 3/4 of the machine's memory
  CHECK(parse_bvh_layout("compact") == BvhLayout::kCompact);
  CHECK(parse_bvh_layout("packed") == BvhLayout::kPacked);
  CHECK_THROWS_WITH(parse_bvh_layout("tiny"), Catch::Contains("\"auto\", \"default\", \"packed\" or \"compact\""));
  // The fastest layout that fits: 100 M triangles against budgets between the estimates (900 MB apart, far more
  // than the resident memory can move between two calls).
  const uint64_t tris = 100'000'000, resident = resident_memory();
  const auto pick = [&](uint64_t bytes_per_triangle) {
    return resolve_layout({.layout = BvhLayout::kAuto, .memory_budget = resident + tris * bytes_per_triangle}, tris);
  };
  CHECK(pick(kDefaultLayoutBytesPerTriangle + 5) == BvhLayout::kDefault);
  CHECK(pick((kDefaultLayoutBytesPerTriangle + kPackedLayoutBytesPerTriangle) / 2) == BvhLayout::kPacked);
  CHECK(pick(kPackedLayoutBytesPerTriangle - 5) == BvhLayout::kCompact);
}
