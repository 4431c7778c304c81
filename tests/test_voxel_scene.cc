// Voxel grids in the scene: shaded through the renderer with per-id materials, cell shapes, and transformed and
// instanced grids against the untransformed one.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "core/rng.h"
#include "render/render.h"
#include "scene/builder.h"
#include "scene_helpers.h"
#include "voxel_scene_helpers.h"

using namespace torte;
using torte::test::slab_world;
using torte::test::tile_mean;
using torte::test::voxel_desc;

namespace {

std::shared_ptr<MaterialDesc> matte(Rgb c) {
  auto m = std::make_shared<MaterialDesc>();
  m->color.value = c;
  return m;
}

std::shared_ptr<VoxelShape> wall_shape(std::shared_ptr<MaterialDesc> a, std::shared_ptr<MaterialDesc> b) {
  VoxelGrid g;
  for (int y = 0; y < 4; ++y)
    for (int x = -4; x < 4; ++x) g.set(x, y, 0, int16_t(x < 0 ? 1 : 2));
  auto shape = std::make_shared<VoxelShape>();
  shape->tree = std::make_shared<VoxelTree>(VoxelTree::build(g));
  VoxelCubeDef d1, d2;
  d1.id = 1;
  d2.id = 2;
  for (int f = 0; f < 6; ++f) {
    d1.faces[size_t(f)] = a;
    d2.faces[size_t(f)] = b;
  }
  shape->cubes = {d1, d2};
  return shape;
}

// A small world with cubes of three ids and slab cells (id -1).
std::shared_ptr<VoxelShape> test_world() {
  VoxelGrid g;
  for (int z = 0; z < 20; ++z)
    for (int x = 0; x < 20; ++x) {
      const int h = 3 + int(2 * std::sin(x * 0.7) + 2 * std::cos(z * 0.5));
      for (int y = 0; y < h; ++y) g.set(x, y, z, int16_t(y == h - 1 ? 2 : 1));
      if ((x + 2 * z) % 5 == 0) g.set(x, h, z, -1);
      if ((x * z) % 11 == 3) g.set(x, h + 2, z, 3);
    }
  auto shape = slab_world(g, matte(Rgb(0.2f, 0.2f, 0.9f)));
  VoxelCubeDef top;
  top.id = 2;
  top.faces[2] = matte(Rgb(0.1f, 0.9f, 0.1f));
  shape->cubes = {top};
  return shape;
}

}  // namespace

TEST_CASE("voxel grid in a scene renders its per-id materials", "[voxel][render]") {
  SceneBuilder b;
  b.add_shape(voxel_desc(wall_shape(matte(Rgb(0.9f, 0.1f, 0.1f)), matte(Rgb(0.1f, 0.9f, 0.1f))), Transform()));
  b.add_light(test::uniform_sky(Rgb(1)));
  CameraDesc cam;
  cam.camera_to_world = look_at({0, 2, -12}, {0, 2, 0}, {0, 1, 0});
  cam.fov_degrees = 30;
  const auto scene = b.flatten();
  RenderSettings s;
  s.width = s.height = 32;
  s.spp = 8;
  s.integrator = IntegratorKind::Direct;
  const Image img = render(*scene, Camera(cam, s.width, s.height), s).image;
  // World +x is the image's left: ids 2 (green, x >= 0) on the left, 1 (red) on the right.
  const Rgb left = tile_mean(img, 6, 12, 14, 20), right = tile_mean(img, 18, 12, 26, 20);
  const Rgb corner = tile_mean(img, 0, 0, 3, 3);
  INFO("left " << left.r << " " << left.g << " " << left.b << " right " << right.r << " " << right.g << " "
               << right.b);
  CHECK(left.g > 3 * left.r);
  CHECK(right.r > 3 * right.g);
  CHECK(left.g > 0.2f);
  CHECK(right.r > 0.2f);
  CHECK(corner.g == Approx(1.0f).epsilon(1e-3));  // sky
}

TEST_CASE("voxel grid cell shapes and face materials through Scene::surface", "[voxel]") {
  SceneBuilder b;
  b.add_shape(voxel_desc(test_world(), Transform()));
  const auto scene = b.flatten();
  REQUIRE(scene->grids.size() == 1);
  // Straight down onto cell (0, h, 0): a slab cell ((0 + 0) % 5 == 0) with its top at h + 0.5.
  const int h = 3 + int(2 * std::sin(0.0) + 2 * std::cos(0.0));
  Ray r{{0.3f, 20, 0.6f}, {0, -1, 0}};
  Hit hit;
  REQUIRE(scene->intersect(r, &hit));
  CHECK(is_voxel_prim(hit.prim));
  CHECK(voxel_prim_is_cell(hit.prim));
  CHECK(hit.t == Approx(20 - (h + 0.5f)).epsilon(1e-5));
  SurfaceHit s = scene->surface(Ray{{0.3f, 20, 0.6f}, {0, -1, 0}}, hit);
  CHECK(s.p.y == Approx(h + 0.5f).epsilon(1e-5));
  CHECK(s.p.x == Approx(0.3f).epsilon(1e-5));
  CHECK(s.ng.y == Approx(1.0f));
  REQUIRE(s.material >= 0);
  CHECK(scene->materials.lambert[scene->material_overrides[size_t(s.material)].index].albedo.value.b ==
        Approx(0.9f));
  // A grass top (id 2, +y face has its own material) next to it.
  const int h1 = 3 + int(2 * std::sin(0.7) + 2 * std::cos(0.0));
  Ray r2{{1.25f, 20, 0.75f}, {0, -1, 0}};
  REQUIRE(scene->intersect(r2, &hit));
  CHECK(!voxel_prim_is_cell(hit.prim));
  CHECK(voxel_prim_id(hit.prim) == 2);
  CHECK(voxel_prim_face(hit.prim) == 2);
  s = scene->surface(Ray{{1.25f, 20, 0.75f}, {0, -1, 0}}, hit);
  CHECK(s.p.y == Approx(float(h1)));
  CHECK(s.uv.x == Approx(0.25f));
  CHECK(s.uv.y == Approx(0.75f));
  REQUIRE(s.material >= 0);
  CHECK(scene->materials.lambert[scene->material_overrides[size_t(s.material)].index].albedo.value.g ==
        Approx(0.9f));
  // Its side face uses the grid's own material.
  Ray r3{{-5, float(h) - 1.5f, 0.5f}, {1, 0, 0}};
  REQUIRE(scene->intersect(r3, &hit));
  CHECK(voxel_prim_id(hit.prim) == 1);
  s = scene->surface(Ray{{-5, float(h) - 1.5f, 0.5f}, {1, 0, 0}}, hit);
  CHECK(s.material == -1);
  CHECK(s.ng.x == Approx(-1.0f));
  CHECK(scene->occluded(Ray{{0.3f, 20, 0.6f}, {0, -1, 0}, 30}));
  CHECK(!scene->occluded(Ray{{0.3f, 20, 0.6f}, {0, -1, 0}, 5}));
}

TEST_CASE("voxel grid transformed and instanced equals the untransformed grid's hits mapped through", "[voxel]") {
  const auto world = test_world();
  const Transform t = translate({3, -2, 5}) * rotate(33, {0.3f, 1, 0.2f}) * scale({0.5f, 0.7f, 0.6f});
  SceneBuilder plain, moved, inst;
  plain.add_shape(voxel_desc(world, Transform()));
  moved.add_shape(voxel_desc(world, t));
  auto group = std::make_shared<SceneBuilder>();
  group->add_shape(voxel_desc(world, Transform()));
  inst.add_instance({group, t});
  const auto sp = plain.flatten(), sm = moved.flatten(), si = inst.flatten();
  Pcg32 rng(9);
  int hits = 0, mismatches = 0, n = 20000;
  for (int i = 0; i < n; ++i) {
    const Vec3f o(-5 + 30 * rng.next_float(), 12 * rng.next_float(), -5 + 30 * rng.next_float());
    const Vec3f target(20 * rng.next_float(), 4 * rng.next_float(), 20 * rng.next_float());
    const Vec3f d = normalize(target - o);
    Ray r{o, d};
    Hit h0;
    const bool hit0 = sp->intersect(r, &h0);
    for (const auto& scene : {sm, si}) {
      Ray w{t.apply_point(o), t.apply_vector(d)};
      Hit h1;
      const bool hit1 = scene->intersect(w, &h1);
      if (hit0 != hit1) {
        if (mismatches < 6)
          std::fprintf(stderr, "hit %d %d prim %x %x t %g %g o %g %g %g d %g %g %g\n", hit0, hit1, h0.prim, h1.prim,
                       h0.t, h1.t, o.x, o.y, o.z, d.x, d.y, d.z);
        ++mismatches;
        continue;
      }
      if (!hit0) continue;
      ++hits;
      const SurfaceHit s0 = sp->surface(Ray{o, d}, h0);
      const SurfaceHit s1 = scene->surface(Ray{t.apply_point(o), t.apply_vector(d)}, h1);
      const Vec3f n0 = normalize(t.apply_normal(s0.ng));
      const bool same = h0.prim == h1.prim && std::fabs(h0.t - h1.t) <= 1e-4f * (1 + h0.t) &&
                        length(t.apply_point(s0.p) - s1.p) < 1e-3f && dot(n0, s1.ng) > 0.999f &&
                        s0.material == s1.material;
      if (!same && mismatches < 40)
        std::fprintf(stderr, "prim %x %x t %g %g p %g n %g m %d %d o %.9g %.9g %.9g d %.9g %.9g %.9g\n", h0.prim, h1.prim, h0.t, h1.t,
                     length(t.apply_point(s0.p) - s1.p), dot(n0, s1.ng), s0.material, s1.material, o.x, o.y, o.z, d.x, d.y, d.z);
      if (!same) ++mismatches;
    }
  }
  INFO(hits << " hits, " << mismatches << " mismatches");
  CHECK(hits > n / 2);
  CHECK(mismatches <= n / 1000);  // float differences on edges only
}

TEST_CASE("voxel grid: coherent rays (packets) and single rays give the same scene hits and occlusion", "[voxel]") {
  // Camera rays in 4x4 pixel blocks over a rotated grid with cell shapes, plus a mesh in front clipping t_max.
  SceneBuilder b;
  b.add_shape(voxel_desc(test_world(), rotate(10, {0, 1, 0})));
  ShapeDesc panel;
  panel.mesh = std::make_shared<TriangleMesh>(make_polygon({{4, 4, 4}, {4, 9, 4}, {9, 9, 4}, {9, 4, 4}}));
  panel.material = matte(Rgb(0.5f));
  b.add_shape(panel);
  const auto scene = b.flatten();
  const int w = 64, h = 64;
  std::vector<float> o[3], d[3], tmax;
  for (int by = 0; by < h; by += 4)
    for (int bx = 0; bx < w; bx += 4)
      for (int y = by; y < by + 4; ++y)
        for (int x = bx; x < bx + 4; ++x) {
          const Vec3f eye{-8, 18, -10};
          const Vec3f dir = normalize(Vec3f{10, -10, 10} + Vec3f{float(x - w / 2), float(h / 2 - y), 0} * 0.25f);
          for (int a = 0; a < 3; ++a) {
            o[a].push_back(eye[a]);
            d[a].push_back(dir[a]);
          }
          tmax.push_back((x + y) % 7 == 0 ? 20.0f : kInfinity);  // some rays end early
        }
  const size_t n = tmax.size();
  const RaySoA rays{o[0].data(), o[1].data(), o[2].data(), d[0].data(), d[1].data(), d[2].data(), tmax.data()};
  std::vector<Hit> coherent(n), single(n);
  scene->intersect(rays, n, coherent.data(), true);
  scene->intersect(rays, n, single.data(), false);
  int voxel_hits = 0, mismatches = 0;
  for (size_t i = 0; i < n; ++i) {
    voxel_hits += is_voxel_prim(single[i].prim);
    if (coherent[i].prim != single[i].prim || coherent[i].t != single[i].t || coherent[i].b1 != single[i].b1 ||
        coherent[i].b2 != single[i].b2)
      ++mismatches;
  }
  CHECK(mismatches == 0);
  CHECK(voxel_hits > int(n) / 3);
  std::vector<uint8_t> occ_coherent(n), occ_single(n);
  scene->occluded(rays, n, occ_coherent.data(), true);
  scene->occluded(rays, n, occ_single.data(), false);
  CHECK(occ_coherent == occ_single);
}
