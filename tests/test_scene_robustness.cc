// Scene construction and rendering never crash, hang or silently give a wrong image (issue 22): nesting limits
// of materials, textures and groups, lights placed by instances, filters wider than the image, non-finite and
// out-of-range values, warnings for legitimately black scenes, and Ctrl-C while a scene is built.

#include <catch2/catch.hpp>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <thread>

#include "accel/bvh_build.h"
#include "core/interrupt.h"
#include "core/parallel.h"
#include "geometry/subdivide.h"
#include "render/render.h"
#include "core/progress_counter.h"
#include "scene/builder.h"
#include "scene_helpers.h"

using namespace torte;
using namespace torte::test;

namespace {

// A unit sphere under a uniform white sky, seen by the furnace camera; `m` is its material.
SceneBuilder furnace_scene(std::shared_ptr<const MaterialDesc> m) {
  SceneBuilder b;
  ShapeDesc s = sphere_shape(1, Transform(), nullptr);
  s.material = std::move(m);
  b.add_shape(s);
  b.add_light(uniform_sky(Rgb(1)));
  return b;
}

RenderSettings small_render(int size, int spp) {
  RenderSettings rs;
  rs.width = rs.height = size;
  rs.spp = spp;
  rs.max_depth = 3;
  return rs;
}

// Mean of |a - b| over the mean of b, per 8x8 tiles of the two images, as the largest tile's value.
double worst_tile_difference(const Image& a, const Image& b) {
  double worst = 0;
  for (int y = 0; y + 8 <= a.height; y += 8)
    for (int x = 0; x + 8 <= a.width; x += 8) {
      const float ma = tile_mean(a, x, y, x + 8, y + 8).average(), mb = tile_mean(b, x, y, x + 8, y + 8).average();
      worst = std::max(worst, std::fabs(double(ma) - mb) / std::max(1e-3, double(mb)));
    }
  return worst;
}

FloatInput constant_input(float v) { return {v, nullptr}; }

}  // namespace

// ---- materials --------------------------------------------------------------------------------------------

TEST_CASE("mix and bump materials nest at most kMaxMaterialNesting levels", "[robustness][material]") {
  std::shared_ptr<const MaterialDesc> m = matte(0.5f);
  for (int i = 0; i < kMaxMaterialNesting; ++i)
    m = i % 2 ? make_mix(m, matte(0.1f), constant_input(0)) : make_bump(m, constant_input(0), 1);
  CHECK(m->nesting == kMaxMaterialNesting);
  CHECK_THROWS_WITH(make_bump(m, constant_input(0), 1), Catch::Contains("nests 65 levels") && Catch::Contains("limit is 64"));
  CHECK_THROWS_WITH(make_mix(matte(0.2f), m, constant_input(0.5f)), Catch::Contains("nests 65 levels"));
  // 100,000 levels: refused at the 65th, so neither the chain nor its destructor recurse deeply.
  std::shared_ptr<const MaterialDesc> deep = matte(0.5f);
  int made = 0;
  try {
    for (; made < 100000; ++made) deep = make_mix(deep, deep, constant_input(0));
  } catch (const Error&) {
  }
  CHECK(made == kMaxMaterialNesting);
}

TEST_CASE("the deepest allowed mix/bump chain resolves and renders like its leaf", "[robustness][material][render]") {
  // amount 0 always picks `a`, a zero height leaves the normal: the chain is the leaf material in disguise.
  std::shared_ptr<const MaterialDesc> chain = matte(0.6f);
  for (int i = 0; i < kMaxMaterialNesting; ++i)
    chain = i % 2 ? make_mix(chain, matte(0.05f), constant_input(0)) : make_bump(chain, constant_input(0), 1);
  const RenderSettings rs = small_render(32, 32);
  const Image deep = render_view(*furnace_scene(chain).flatten(), furnace_camera(), rs).image;
  const Image leaf = render_view(*furnace_scene(matte(0.6f)).flatten(), furnace_camera(), rs).image;
  CHECK(worst_tile_difference(deep, leaf) < 0.05);
  CHECK(image_mean(deep) == Approx(image_mean(leaf)).epsilon(0.02));
}

TEST_CASE("material flattening refuses hand-built chains past the limit instead of recursing", "[robustness][material]") {
  // MaterialDesc built without make_mix (its nesting field left 0): the flattener bounds its own recursion.
  std::shared_ptr<MaterialDesc> m = matte(0.5f);
  for (int i = 0; i < 2000; ++i) {
    auto mix = std::make_shared<MaterialDesc>();
    mix->type = MaterialType::Mix;
    mix->a = m;
    mix->b = m;
    m = mix;
  }
  SceneBuilder b = furnace_scene(m);
  CHECK_THROWS_WITH(b.flatten(), Catch::Contains("levels of mix/bump materials"));
}

TEST_CASE("material tables with cycles or deep nesting are refused before rendering", "[robustness][material]") {
  MaterialTables t;
  t.lambert.push_back({});
  t.mix.push_back({FloatParam{0, -1}, MaterialRef{MaterialType::Mix, 0}, MaterialRef{MaterialType::Lambert, 0}});
  CHECK_THROWS_WITH(validate_material_tables(t), Catch::Contains("cycle"));
  t.mix.clear();
  // A bump chain one level too deep, stored root first (the slowest order for the relaxation).
  const int n = kMaxMaterialNesting + 1;
  for (int i = 0; i < n; ++i)
    t.bump.push_back({FloatParam{}, 1, i + 1 < n ? MaterialRef{MaterialType::Bump, uint32_t(i + 1)}
                                                 : MaterialRef{MaterialType::Lambert, 0}});
  CHECK_THROWS(validate_material_tables(t));
  t.bump.clear();
  for (int i = 0; i < kMaxMaterialNesting; ++i)  // the deepest allowed chain passes
    t.bump.push_back({FloatParam{}, 1, i + 1 < kMaxMaterialNesting ? MaterialRef{MaterialType::Bump, uint32_t(i + 1)}
                                                                   : MaterialRef{MaterialType::Lambert, 0}});
  CHECK_NOTHROW(validate_material_tables(t));
  t.bump[0].inner = MaterialRef{MaterialType::Conductor, 0};  // no conductor row
  CHECK_THROWS_WITH(validate_material_tables(t), Catch::Contains("missing material"));
}

// ---- textures ---------------------------------------------------------------------------------------------

TEST_CASE("texture expressions nest at most kMaxTextureDepth levels", "[robustness][texture]") {
  // checker{constants} .. uv is 3 levels; each add one more.
  TexturePtr t = texture::close(texture::checker(texture::constant(0.2f), texture::constant(0.2f), 2));
  REQUIRE(t->depth == 3);
  for (uint32_t d = 4; d <= kMaxTextureDepth; ++d) t = texture::add(t, texture::constant(0.0003f));
  CHECK(t->depth == kMaxTextureDepth);
  CHECK_THROWS_WITH(texture::add(t, texture::constant(1.0f)),
                    Catch::Contains("nests 1025 levels deep") && Catch::Contains("limit is 1024"));
  CHECK_THROWS_WITH(texture::scale(t, 2), Catch::Contains("nests 1025"));

  // The deepest allowed expression flattens and evaluates (recursively) on TBB's worker threads.
  TextureTableBuilder builder;
  const FloatParam p = builder.add(FloatInput{0, t});
  const TextureTable table = builder.finish();
  const float expected = 0.2f + 0.0003f * float(kMaxTextureDepth - 3);
  std::atomic<int> wrong{0};
  torte::parallel_for(0, 64, [&](int i) {
    TextureContext ctx{};
    ctx.uv = Vec2f(0.01f * float(i), 0.3f);
    if (std::fabs(table.eval(p, ctx) - expected) > 1e-3f) ++wrong;
  });
  CHECK(wrong == 0);
}

TEST_CASE("a texture doubled by sharing is refused before it costs exponential time", "[robustness][texture]") {
  TexturePtr t = texture::close(texture::checker(texture::constant(0.2f), texture::constant(0.4f), 2));
  int doublings = 0;
  try {
    for (; doublings < 64; ++doublings) t = texture::add(t, t);
  } catch (const Error& e) {
    CHECK_THAT(std::string(e.what()), Catch::Contains("nodes per lookup") && Catch::Contains("65536"));
  }
  CHECK(doublings < 20);
  CHECK(t->visits <= kMaxTextureVisits);
  // A checker visits one of its colours only.
  const TexturePtr c = texture::checker(t, t, 2);
  CHECK(c->visits == t->visits + 1);
}

TEST_CASE("texture mappings refuse transforms whose inverse overflows", "[robustness][texture]") {
  // Invertible in double, but its determinant underflows float and the footprint scale would be infinite.
  CHECK_THROWS_WITH(texture::xyz(scale({1e-25f, 1e-25f, 1e-25f})), Catch::Contains("'transform' must be invertible"));
  CHECK_THROWS_WITH(texture::spherical(scale({1e-16f, 1e-16f, 1e-2f})), Catch::Contains("invertible"));
  CHECK_NOTHROW(texture::planar({1, 0, 0}, {0, 1, 0}, {0, 0}, scale({2, 2, 2})));
}

// ---- groups and instances ---------------------------------------------------------------------------------

TEST_CASE("point, spot and directional lights in instanced groups light the scene like placed copies",
          "[robustness][instancing][render]") {
  // A floor and a back wall, lit by lights that a group holds (the group has no shapes of its own).
  auto lamps = std::make_shared<SceneBuilder>();
  Light point;
  point.kind = LightKind::Point;
  point.position = {0.5f, 1, 0};
  point.radiance = Rgb(2);
  Light spot;
  spot.kind = LightKind::Spot;
  spot.position = {0, 1.5f, 0.5f};
  spot.direction = normalize(Vec3f(0.2f, -1, 0.3f));
  spot.radiance = Rgb(3);
  spot.cos_total = std::cos(0.6f);
  spot.cos_falloff_start = std::cos(0.4f);
  Light sun;
  sun.kind = LightKind::Distant;
  sun.direction = normalize(Vec3f(0.3f, -1, 0.6f));
  sun.radiance = Rgb(0.3f);
  for (const Light& l : {point, spot, sun}) lamps->add_light(l);
  const std::vector<Transform> places = {translate({-1.2f, 0, 0}), translate({1, 0.3f, 0.5f}) * rotate(30, {0, 1, 0}),
                                         translate({0, 0.2f, 1.5f}) * rotate(-25, {1, 0, 0}) * scale({1, 0.8f, 1})};
  SceneBuilder instanced, direct;
  for (SceneBuilder* b : {&instanced, &direct}) {
    ShapeDesc floor;
    floor.kind = ShapeDesc::Kind::Mesh;
    floor.mesh = std::make_shared<TriangleMesh>(make_cube());
    floor.transform = translate({0, -1.1f, 0}) * scale({4, 0.1f, 4});
    floor.material = matte(0.7f);
    b->add_shape(floor);
    ShapeDesc wall = floor;
    wall.transform = translate({0, 0, 3}) * scale({4, 3, 0.1f});
    b->add_shape(wall);
  }
  // A middle group: instances of instances compose their transforms.
  auto middle = std::make_shared<SceneBuilder>();
  middle->add_instance({lamps, places[2]});
  instanced.add_instance({lamps, places[0]});
  instanced.add_instance({lamps, places[1]});
  instanced.add_instance({middle, Transform()});
  for (const Transform& t : places)
    for (const Light& l : {point, spot, sun}) direct.add_light(placed_light(l, t));

  const auto a = instanced.flatten(), b = direct.flatten();
  REQUIRE(a->lights.size() == 9);
  REQUIRE(b->lights.size() == 9);
  RenderSettings rs = small_render(48, 16);
  rs.max_depth = 1;
  rs.sample_all_lights = true;
  const CameraDesc cam = camera_at({0, 1.5f, -5}, {0, 0, 1}, 50);
  const Image ia = render_view(*a, cam, rs).image, ib = render_view(*b, cam, rs).image;
  CHECK(image_mean(ib) > 0.01);
  CHECK(worst_tile_difference(ia, ib) < 0.05);
  CHECK(image_mean(ia) == Approx(image_mean(ib)).epsilon(0.01));
}

TEST_CASE("a light moves with its instance: placed_light maps positions and directions", "[robustness][instancing]") {
  Light spot;
  spot.kind = LightKind::Spot;
  spot.position = {1, 0, 0};
  spot.direction = {0, 0, 1};
  const Light placed = placed_light(spot, translate({0, 2, 0}) * rotate(90, {0, 1, 0}) * scale({3, 3, 3}));
  CHECK(length(placed.position - Vec3f(0, 2, -3)) < 1e-5f);
  CHECK(length(placed.direction - Vec3f(1, 0, 0)) < 1e-5f);
  Light sky;
  sky.kind = LightKind::Infinite;
  sky.origin = "torte.light.infinite at scene.lua:3";
  CHECK_THROWS_WITH(placed_light(sky, Transform()),
                    Catch::Contains("scene.lua:3") && Catch::Contains("cannot be instanced"));
}

TEST_CASE("lights at infinity and emitters in instanced groups are refused by name", "[robustness][instancing]") {
  auto group = std::make_shared<SceneBuilder>();
  Light env;
  env.kind = LightKind::Infinite;
  env.radiance = Rgb(1);
  env.origin = "torte.light.infinite at lamps.lua:7";
  group->add_light(env);
  SceneBuilder scene;
  scene.add_instance({group, Transform()});
  CHECK_THROWS_WITH(scene.flatten(), Catch::Contains("lamps.lua:7") && Catch::Contains("infinite lights cannot be instanced"));

  auto emitters = std::make_shared<SceneBuilder>();
  ShapeDesc lamp = sphere_shape(1, Transform(), matte(0.5f));
  lamp.emission = Rgb(1);
  lamp.origin = "torte.shape.sphere at lamps.lua:9";
  emitters->add_shape(lamp);
  SceneBuilder s2;
  s2.add_instance({emitters, Transform()});
  CHECK_THROWS_WITH(s2.flatten(), Catch::Contains("lamps.lua:9") && Catch::Contains("emitting shape"));
}

TEST_CASE("nestings that unroll into too many instances are refused before they are made", "[robustness][instancing]") {
  // Each level holds two instances of the one below: 2^30 instances of the sphere, counted in 31 steps.
  auto g = std::make_shared<SceneBuilder>();
  g->add_shape(sphere_shape(0.1f, Transform(), matte(0.5f)));
  for (int level = 0; level < 30; ++level) {
    auto up = std::make_shared<SceneBuilder>();
    up->add_instance({g, translate({0.1f, 0, 0})});
    up->add_instance({g, translate({0, 0.1f, 0})});
    g = up;
  }
  SceneBuilder scene;
  scene.add_instance({g, Transform()});
  const auto t0 = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH(scene.flatten(), Catch::Contains("places 1073741824 instances") && Catch::Contains("268435456"));
  CHECK(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(5));  // counted, not unrolled (a hang guard)
}

TEST_CASE("instances that place their group out of range are refused", "[robustness][instancing]") {
  auto group = std::make_shared<SceneBuilder>();
  group->add_shape(sphere_shape(1, Transform(), matte(0.5f)));
  SceneBuilder scene;
  scene.add_instance({group, translate({3e30f, 0, 0})});
  CHECK_THROWS_WITH(scene.flatten(), Catch::Contains("instance 0") && Catch::Contains("beyond +-1e18"));
}

// ---- filters ----------------------------------------------------------------------------------------------

TEST_CASE("filter samples off the image are reflected back in", "[robustness][filter]") {
  CHECK(filter_raster_position(3, 4, {0.2f, -0.3f}, 10, 8).x == 3.7f);
  const Vec2f left = filter_raster_position(0, 0, {-2.5f, -0.75f}, 10, 8);
  CHECK(left.x == Approx(2.0f));
  CHECK(left.y == Approx(0.25f));
  const Vec2f right = filter_raster_position(9, 7, {3, 1}, 10, 8);
  CHECK(right.x == Approx(7.5f));
  CHECK(right.y == Approx(7.5f));
  // Any radius lands inside the image.
  for (float r : {1e3f, 1e7f, 3e20f}) {
    const Vec2f p = filter_raster_position(5, 5, {r, -r * 0.7f}, 32, 24);
    CHECK((p.x >= 0 && p.x <= 32 && p.y >= 0 && p.y <= 24));
  }
}

TEST_CASE("a filter wider than the image blurs the frame instead of turning it black", "[robustness][filter][render]") {
  // The furnace sphere fills the middle of the frame; a narrow box gives the reference mean.
  SceneBuilder b = furnace_scene(matte(0.8f));
  const auto scene = b.flatten();
  RenderSettings rs = small_render(24, 64);
  const double reference = image_mean(render_view(*scene, furnace_camera(), rs).image);
  REQUIRE(reference > 0.1);
  for (const Filter& f : {Filter::box(100), Filter::triangle(300), Filter::gaussian(200, 60), Filter::mitchell(500)}) {
    rs.filter = f;
    const Image img = render_view(*scene, furnace_camera(), rs).image;
    // Every pixel now averages the whole frame: the image mean is kept and no corner is black.
    CHECK(image_mean(img) == Approx(reference).epsilon(0.06));
    CHECK(tile_mean(img, 0, 0, 8, 8).average() > 0.5 * reference);
  }
}

// ---- values -----------------------------------------------------------------------------------------------

TEST_CASE("mesh validation names the vertex with a non-finite uv, normal or an out-of-range position",
          "[robustness][mesh]") {
  TriangleMesh m = make_cube();
  m.validate("cube");
  TriangleMesh bad_uv = m;
  bad_uv.v[5] = std::nanf("");
  CHECK_THROWS_WITH(bad_uv.validate("cube.obj"), Catch::Contains("cube.obj: vertex 5 has a non-finite uv"));
  TriangleMesh far = m;
  far.x[7] = 1.8e19f;
  CHECK_THROWS_WITH(far.validate("far.ply"), Catch::Contains("far.ply: vertex 7 lies at (1.8e+19") &&
                                                 Catch::Contains("+-1e+18"));
  TriangleMesh bad_normal = m;
  bad_normal.nx.assign(m.vertex_count(), 0);
  bad_normal.ny.assign(m.vertex_count(), 1);
  bad_normal.nz.assign(m.vertex_count(), 0);
  bad_normal.nz[2] = INFINITY;
  CHECK_THROWS_WITH(bad_normal.validate("n"), Catch::Contains("vertex 2 has a non-finite normal"));
}

TEST_CASE("shapes that their transform takes out of range are named", "[robustness][mesh]") {
  SceneBuilder b;
  ShapeDesc s;
  s.kind = ShapeDesc::Kind::Mesh;
  s.mesh = std::make_shared<TriangleMesh>(make_cube());
  s.transform = scale({1e10f, 1e10f, 1e10f}) * translate({1e9f, 0, 0});
  s.origin = "torte.shape.cube at big.lua:4";
  b.add_shape(s);
  CHECK_THROWS_WITH(b.flatten(), Catch::Contains("big.lua:4: vertex 0 lies at") && Catch::Contains("transform"));
  SceneBuilder q;
  ShapeDesc sphere = sphere_shape(1e12f, scale({1e7f, 1e7f, 1e7f}), matte(0.5f));
  sphere.origin = "torte.shape.sphere at big.lua:9";
  q.add_shape(sphere);
  CHECK_THROWS_WITH(q.flatten(), Catch::Contains("big.lua:9") && Catch::Contains("beyond the range"));
}

TEST_CASE("coordinates up to the range limit build and trace", "[robustness][mesh]") {
  SceneBuilder b;
  ShapeDesc s;
  s.kind = ShapeDesc::Kind::Mesh;
  s.mesh = std::make_shared<TriangleMesh>(make_cube());
  s.transform = scale({0.9e18f, 0.9e18f, 0.9e18f});
  b.add_shape(s);
  b.add_shape(sphere_shape(1, Transform(), matte(0.5f)));
  const auto scene = b.flatten();
  Ray ray{{0, 0, -5}, {0, 0, 1}, kInfinity};
  Hit hit;
  REQUIRE(scene->intersect(ray, &hit));
  CHECK(hit.t == Approx(4.0f));
}

TEST_CASE("a light whose power overflows float is named", "[robustness][light]") {
  SceneBuilder b;
  b.add_shape(sphere_shape(1, Transform(), matte(0.5f)));
  Light l;
  l.kind = LightKind::Point;
  l.radiance = Rgb(3e37f);
  l.origin = "torte.light.point at bright.lua:2";
  b.add_light(l);
  CHECK_THROWS_WITH(b.flatten(), Catch::Contains("bright.lua:2") && Catch::Contains("power is infinite"));
}

TEST_CASE("cameras with a singular or non-finite placement are refused", "[robustness][camera]") {
  CameraDesc c;
  Mat4 m;
  m.m[1][3] = std::nanf("");
  c.camera_to_world = Transform(m);
  CHECK_THROWS_WITH(Camera(c, 8, 8), Catch::Contains("singular or not finite"));
  c.camera_to_world = scale({1e-20f, 1e-20f, 1e-20f});  // invertible in double, degenerate in float
  CHECK_THROWS(Camera(c, 8, 8));
  c.camera_to_world = Transform();
  CHECK_NOTHROW(Camera(c, 8, 8));
}

// ---- black images -----------------------------------------------------------------------------------------

TEST_CASE("scenes that can only be black say why", "[robustness][scene]") {
  CHECK_THAT(black_image_reason(*SceneBuilder().flatten()), Catch::Contains("empty"));
  SceneBuilder unlit;
  unlit.add_shape(sphere_shape(1, Transform(), matte(0.5f)));
  CHECK_THAT(black_image_reason(*unlit.flatten()), Catch::Contains("no lights and no emitting shapes"));
  SceneBuilder dark = furnace_scene(matte(0.5f));
  Light off;
  off.kind = LightKind::Point;
  SceneBuilder off_only;
  off_only.add_shape(sphere_shape(1, Transform(), matte(0.5f)));
  off_only.add_light(off);
  CHECK_THAT(black_image_reason(*off_only.flatten()), Catch::Contains("zero power"));
  SceneBuilder nothing_to_light;
  Light bulb;
  bulb.kind = LightKind::Point;
  bulb.radiance = Rgb(1);
  nothing_to_light.add_light(bulb);
  CHECK_THAT(black_image_reason(*nothing_to_light.flatten()), Catch::Contains("no shapes"));
  CHECK(black_image_reason(*dark.flatten()).empty());
}

// ---- Ctrl-C -----------------------------------------------------------------------------------------------

namespace {
// A flat grid of 2 n^2 triangles.
std::shared_ptr<TriangleMesh> grid_mesh(int n) {
  auto m = std::make_shared<TriangleMesh>();
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) m->add_vertex({float(x) / float(n), float(y) / float(n), 0.01f * float((x * 7 + y * 13) % 5)});
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const uint32_t a = uint32_t(y * (n + 1) + x), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      m->add_triangle(a, b, d);
      m->add_triangle(a, d, c);
    }
  return m;
}

struct ClearInterrupt {
  ~ClearInterrupt() { clear_interrupt(); }
};
}  // namespace

TEST_CASE("an interrupt stops scene building, BVH builds and subdivision at a safe point", "[robustness][interrupt]") {
  ClearInterrupt clear;
  SceneBuilder b;
  ShapeDesc s;
  s.kind = ShapeDesc::Kind::Mesh;
  s.mesh = grid_mesh(64);
  b.add_shape(s);
  request_interrupt();
  CHECK_THROWS_AS(b.flatten(), Interrupted);
  CHECK_THROWS_WITH(b.flatten(), Catch::Contains("interrupted while building the scene"));
  std::vector<Bounds3f> boxes(100000);
  for (size_t i = 0; i < boxes.size(); ++i) {
    const float f = float(i);
    boxes[i] = Bounds3f{Vec3f(f, f, f), Vec3f(f + 1, f + 1, f + 1)};
  }
  CHECK_THROWS_AS(build_binary_bvh(boxes, BvhBuildOptions{}), Interrupted);
  CHECK_THROWS_AS(subdivide(*grid_mesh(16), 2, 0, 0), Interrupted);
  clear_interrupt();
  // Nothing is left half-done: the same builder flattens now.
  const auto scene = b.flatten();
  CHECK(scene->triangle_count() == 2 * 64 * 64);
  CHECK(build_binary_bvh(boxes, BvhBuildOptions{}).prim_indices.size() == boxes.size());
}

TEST_CASE("an interrupt during a long scene build stops it early", "[robustness][interrupt]") {
  ClearInterrupt clear;
  // Four meshes of half a million triangles; Ctrl-C comes once the build reports progress (mid-build).
  SceneBuilder b;
  const auto mesh = grid_mesh(500);
  for (int i = 0; i < 4; ++i) {
    ShapeDesc s;
    s.kind = ShapeDesc::Kind::Mesh;
    s.mesh = mesh;
    s.transform = translate({0, 0, float(i)});
    b.add_shape(s);
  }
  ProgressCounter progress;
  std::atomic<bool> finished{false};
  std::thread press([&] {
    while (progress.done.load() == 0 && !finished) std::this_thread::yield();
    request_interrupt();
  });
  bool interrupted = false;
  try {
    b.flatten(&progress);
  } catch (const Interrupted&) {
    interrupted = true;
  }
  finished = true;
  press.join();
  CHECK(interrupted);
  CHECK(progress.done.load() < progress.total.load());  // stopped before the end
}

TEST_CASE("a chain of 300,000 groups is refused by flatten and released without deep recursion",
          "[robustness][instancing]") {
  auto g = std::make_shared<SceneBuilder>();
  g->add_shape(sphere_shape(1, Transform(), matte(0.5f)));
  for (int i = 0; i < 300000; ++i) {
    auto up = std::make_shared<SceneBuilder>();
    up->add_instance({g, Transform()});
    g = up;
  }
  {
    SceneBuilder scene;
    scene.add_instance({g, Transform()});
    CHECK_THROWS_WITH(scene.flatten(), Catch::Contains("nest more than 32 levels"));
  }
  g.reset();  // one destructor per level overflowed the stack here
  SUCCEED("released");
}

TEST_CASE("noise and checkers stay defined at coordinates far beyond the int range", "[robustness][texture]") {
  // Converting such floats to integers directly is undefined behaviour (the sanitizer build reports it).
  for (float x : {3e9f, -5e12f, 1e18f, 1e30f}) {
    NoiseParams p;
    const float n3 = noise_texture(p, Vec3f(x, 0.5f, -x));
    p.dims = 2;
    p.fractal = NoiseFractal::Fbm;
    const float n2 = noise_texture(p, Vec3f(x, x, 0));
    CHECK((n3 >= 0 && n3 <= 1));
    CHECK((n2 >= 0 && n2 <= 1));
  }
  // Not finite: NaN out, but no undefined conversion on the way.
  CHECK(std::isnan(noise_texture(NoiseParams{}, Vec3f(INFINITY, std::nanf(""), 0))));
  TextureTableBuilder builder;
  const TexturePtr checker3 = texture::checker(texture::constant(0.25f), texture::constant(0.75f), 3, 10);
  const ColorParam c = builder.add(ColorInput{Rgb(), checker3});
  const TextureTable table = builder.finish();
  for (float x : {1e18f, 3e30f, -1e38f}) {
    TextureContext ctx{};
    ctx.p = Vec3f(x, 0.5f, 0.5f);
    const float v = table.eval(c, ctx).r;
    CHECK((v == 0.25f || v == 0.75f));
  }
}
