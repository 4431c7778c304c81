// Instancing: groups placed by transforms (and nested groups) must trace and shade exactly like the same shapes
// placed directly with the composed transforms — hits, distances, points and normals (including under
// non-uniform scales and mirroring) — and share memory: a thousand dragons cost little more than one.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <memory>

#include "core/rng.h"
#include "geometry/mesh_io.h"
#include "render/render.h"
#include "scene/builder.h"
#include "scene_helpers.h"

using namespace torte;
using namespace torte::test;

namespace {

// A few shapes of every kind, in group space: a sphere, a disk, a cube mesh and a smooth-normal torus-ish mesh
// (a subdivided octahedron with vertex normals, so shading normals are exercised too).
std::vector<ShapeDesc> group_shapes() {
  std::vector<ShapeDesc> shapes;
  ShapeDesc sphere;
  sphere.kind = ShapeDesc::Kind::Quadric;
  sphere.quadric.kind = QuadricKind::Sphere;
  sphere.quadric.radius = 0.5f;
  sphere.transform = translate({0.6f, 0.1f, 0});
  sphere.material = matte(0.7f);
  shapes.push_back(sphere);
  ShapeDesc disk = sphere;
  disk.quadric.kind = QuadricKind::Disk;
  disk.transform = translate({-0.7f, 0, 0.3f}) * rotate(40, {1, 0, 0});
  shapes.push_back(disk);
  ShapeDesc cube;
  cube.kind = ShapeDesc::Kind::Mesh;
  cube.mesh = std::make_shared<TriangleMesh>(make_cube());
  cube.transform = translate({0, -0.4f, 0.5f}) * scale({0.3f, 0.2f, 0.4f});
  cube.material = matte(0.4f);
  shapes.push_back(cube);
  TriangleMesh oct;
  for (Vec3f p : {Vec3f(1, 0, 0), Vec3f(-1, 0, 0), Vec3f(0, 1, 0), Vec3f(0, -1, 0), Vec3f(0, 0, 1), Vec3f(0, 0, -1)}) {
    oct.add_vertex(p);
    oct.nx.push_back(p.x), oct.ny.push_back(p.y), oct.nz.push_back(p.z);
  }
  const uint32_t faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (const auto& f : faces) oct.add_triangle(f[0], f[1], f[2]);
  ShapeDesc smooth = cube;
  smooth.mesh = std::make_shared<TriangleMesh>(oct);
  smooth.transform = translate({0, 0.6f, -0.3f}) * scale({0.35f, 0.3f, 0.35f});
  shapes.push_back(smooth);
  return shapes;
}

// Placements of the group: rotations, non-uniform scales and a mirror.
std::vector<Transform> placements() {
  return {translate({-2, 0, 0}), translate({0, 0.2f, 1}) * rotate(35, {0, 1, 0}) * scale({1.5f, 0.6f, 1}),
          translate({2, -0.3f, 0}) * scale({-1, 1, 1}) * rotate(-20, {0, 0, 1}),
          translate({0.3f, 1.8f, -0.5f}) * rotate(70, {1, 1, 0}) * scale({0.5f, 0.8f, 1.3f})};
}

void expect_same_hits(const Scene& a, const Scene& b, int rays) {
  Pcg32 rng(7);
  int hits = 0;
  for (int i = 0; i < rays; ++i) {
    const Vec3f o(rng.next_float() * 8 - 4, rng.next_float() * 6 - 3, -6);
    const Vec3f target(rng.next_float() * 6 - 3, rng.next_float() * 4 - 2, rng.next_float() * 2 - 1);
    const Vec3f d = normalize(target - o);
    Ray ra{o, d, kInfinity}, rb{o, d, kInfinity};
    Hit ha, hb;
    const bool hit_a = a.intersect(ra, &ha), hit_b = b.intersect(rb, &hb);
    REQUIRE(hit_a == hit_b);
    if (!hit_a) continue;
    ++hits;
    INFO("ray " << i);
    REQUIRE(ha.t == Approx(hb.t).epsilon(1e-4));
    const SurfaceHit sa = a.surface(ra, ha), sb = b.surface(rb, hb);
    CHECK(length(sa.p - sb.p) < 1e-4f * (1 + length(sb.p)));
    CHECK(dot(sa.ng, sb.ng) > 0.9999f);
    CHECK(dot(sa.ns, sb.ns) > 0.9999f);
    const MaterialRef ma = a.objects[sa.object].material, mb = b.objects[sb.object].material;
    REQUIRE(ma.type == mb.type);
    CHECK(a.materials.lambert[ma.index].albedo.value == b.materials.lambert[mb.index].albedo.value);
    CHECK(a.occluded(Ray{o, d, ha.t * 1.001f}) == true);
    CHECK(a.occluded(Ray{o, d, ha.t * 0.999f}) == b.occluded(Ray{o, d, hb.t * 0.999f}));
  }
  CHECK(hits > rays / 10);
}

}  // namespace

TEST_CASE("instances trace and shade like the same shapes placed directly", "[instancing]") {
  auto group = std::make_shared<SceneBuilder>();
  for (const ShapeDesc& s : group_shapes()) group->add_shape(s);
  SceneBuilder instanced, flat;
  for (const Transform& t : placements()) {
    instanced.add_instance({group, t});
    for (ShapeDesc s : group_shapes()) {
      s.transform = t * s.transform;
      flat.add_shape(s);
    }
  }
  const auto a = instanced.flatten(), b = flat.flatten();
  CHECK(a->instances.size() == placements().size());
  CHECK(a->prototypes.size() == 1);
  expect_same_hits(*a, *b, 20000);
}

TEST_CASE("nested frames compose their transforms, normals included", "[instancing]") {
  // inner: the shapes; middle: the inner group twice; the scene: the middle group at every placement.
  auto inner = std::make_shared<SceneBuilder>();
  for (const ShapeDesc& s : group_shapes()) inner->add_shape(s);
  auto middle = std::make_shared<SceneBuilder>();
  const Transform m1 = scale({0.5f, 0.5f, 0.5f}), m2 = translate({0.2f, 0.4f, 0.1f}) * scale({0.4f, 0.9f, 0.3f});
  middle->add_instance({inner, m1});
  middle->add_instance({inner, m2});
  SceneBuilder nested, flat;
  for (const Transform& t : placements()) {
    nested.add_instance({middle, t});
    for (const Transform& m : {m1, m2})
      for (ShapeDesc s : group_shapes()) {
        s.transform = t * m * s.transform;
        flat.add_shape(s);
      }
  }
  const auto a = nested.flatten(), b = flat.flatten();
  CHECK(a->instances.size() == 2 * placements().size());
  CHECK(a->prototypes.size() == 1);  // the middle group has no shapes of its own
  expect_same_hits(*a, *b, 20000);
}

TEST_CASE("an instanced scene renders like the flattened one (tile means)", "[instancing][render]") {
  auto group = std::make_shared<SceneBuilder>();
  for (const ShapeDesc& s : group_shapes()) group->add_shape(s);
  SceneBuilder instanced, flat;
  for (SceneBuilder* b : {&instanced, &flat}) {
    b->add_light(uniform_sky(Rgb(1)));
  }
  CameraDesc cam;
  cam.camera_to_world = look_at({0, 0.5f, -6}, {0, 0.2f, 0}, {0, 1, 0});
  cam.fov_degrees = 50;
  for (const Transform& t : placements()) {
    instanced.add_instance({group, t});
    for (ShapeDesc s : group_shapes()) {
      s.transform = t * s.transform;
      flat.add_shape(s);
    }
  }
  RenderSettings rs;
  rs.width = rs.height = 48;
  rs.spp = 16;
  rs.max_depth = 4;
  // Same sampler seed and identical geometry: the images agree up to floating-point differences of the hits.
  const Image ia = render_view(*instanced.flatten(), cam, rs).image, ib = render_view(*flat.flatten(), cam, rs).image;
  double diff = 0, total = 0;
  for (int y = 0; y < rs.height; ++y)
    for (int x = 0; x < rs.width; ++x) {
      diff += std::fabs(ia.at(x, y).average() - ib.at(x, y).average());
      total += ib.at(x, y).average();
    }
  CHECK(diff / total < 0.01);
}

TEST_CASE("instancing errors: emitters and lights inside groups, groups containing themselves", "[instancing]") {
  auto group = std::make_shared<SceneBuilder>();
  ShapeDesc lamp = group_shapes()[0];
  lamp.emission = Rgb(1);
  group->add_shape(lamp);
  SceneBuilder scene;
  scene.add_instance({group, Transform()});
  CHECK_THROWS_WITH(scene.flatten(), Catch::Contains("emitting shape"));

  auto loop = std::make_shared<SceneBuilder>();
  loop->add_shape(group_shapes()[0]);
  // A cycle (the Lua binding refuses the direct case).
  loop->add_instance({loop, translate({1, 0, 0})});
  SceneBuilder s2;
  s2.add_instance({loop, Transform()});
  CHECK_THROWS_WITH(s2.flatten(), Catch::Contains("nest more than 32 levels"));
  *loop = SceneBuilder();  // breaks the cycle, which would otherwise leak (LeakSanitizer)
}

TEST_CASE("a thousand instances of the dragon cost less than 10 percent more memory than one", "[instancing][memory]") {
  const std::string path = std::string(TORTE_SHARED_DATA) + "/meshes/dragon/dragon_100k_binary_le.ply";
  if (!std::filesystem::exists(path)) {
    WARN("skipped: " << path << " not found (../shared/data absent)");
    return;
  }
  auto dragon = std::make_shared<SceneBuilder>();
  ShapeDesc s;
  s.kind = ShapeDesc::Kind::Mesh;
  s.mesh = std::make_shared<TriangleMesh>(load_mesh(path));
  dragon->add_shape(s);
  auto bytes = [&](int count) {
    SceneBuilder b;
    for (int i = 0; i < count; ++i)
      b.add_instance({dragon, translate({float(i % 40), 0, float(i / 40)}) * rotate(float(i), {0, 1, 0})});
    const auto scene = b.flatten();
    return double(scene->accel_bytes() + scene->geometry_bytes());
  };
  const double one = bytes(1), thousand = bytes(1000);
  INFO("one dragon: " << one / 1e6 << " MB, 1000 instances: " << thousand / 1e6 << " MB");
  CHECK(thousand < 1.1 * one);
}
