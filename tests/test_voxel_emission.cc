// Emitting voxels: the exposed faces of emitting cube ids and the emitting meshes of cell ids become one Patches
// light (light/emissive_patches.h). Checked here: the patch sampler against its pdf (chi-square), which faces
// count as exposed, light_pdf = sample pdf through real hits, and renders against the same emitters built as
// ordinary mesh area lights (an independent, already tested code path).
#include <catch2/catch.hpp>
#include <cmath>

#include "chi2.h"
#include "core/error.h"
#include "core/rng.h"
#include "light/light_emission.h"
#include "render/aov_pass.h"
#include "render/render.h"
#include "scene/builder.h"
#include "scene_helpers.h"
#include "test_random.h"

using namespace torte;
using torte::test::tile_mean;
using torte::test::matte;

namespace {

ShapeDesc voxel_desc(const VoxelGrid& grid, std::vector<VoxelCubeDef> cubes, std::vector<VoxelCellDef> cells,
                     const Transform& t = Transform()) {
  auto v = std::make_shared<VoxelShape>();
  v->tree = std::make_shared<VoxelTree>(VoxelTree::build(grid));
  v->cubes = std::move(cubes);
  v->cells = std::move(cells);
  ShapeDesc s;
  s.kind = ShapeDesc::Kind::Voxel;
  s.voxels = std::move(v);
  s.transform = t;
  s.material = matte(0.5f);
  return s;
}

VoxelCubeDef emitting_cube(int16_t id, Rgb radiance) {
  VoxelCubeDef d;
  d.id = id;
  d.emission = radiance;
  return d;
}

ShapeDesc mesh_shape(TriangleMesh mesh, const Transform& t, std::shared_ptr<MaterialDesc> m) {
  ShapeDesc s;
  s.mesh = std::make_shared<TriangleMesh>(std::move(mesh));
  s.transform = t;
  s.material = std::move(m);
  return s;
}

// A cell id whose group holds one emitting two-sided quad (a "flame" across the cell's diagonal) above a
// non-emitting stick.
VoxelCellDef flame_cell(int16_t id, Rgb radiance) {
  auto g = std::make_shared<SceneBuilder>();
  g->add_shape(mesh_shape(make_cube(), translate({0.5f, 0.2f, 0.5f}) * scale({0.05f, 0.2f, 0.05f}), matte(0.3f)));
  ShapeDesc flame = mesh_shape(make_polygon({{0.2f, 0.4f, 0.2f}, {0.8f, 0.4f, 0.8f}, {0.8f, 0.9f, 0.8f},
                                             {0.2f, 0.9f, 0.2f}}),
                               Transform(), matte(0.2f));
  flame.emission = radiance;
  g->add_shape(flame);
  VoxelCellDef c;
  c.id = id;
  c.shapes = g;
  return c;
}

const Light* patches_light(const Scene& scene) {
  for (const Light& l : scene.lights)
    if (l.kind == LightKind::Patches) return &l;
  return nullptr;
}

}  // namespace

TEST_CASE("EmissivePatches: chi-square of patch and position choice, pdf_area = pmf / area", "[light][voxel][chi2]") {
  EmissivePatches p;
  // Patches of different size, radiance and sidedness; two triangles.
  p.add_parallelogram({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, Rgb(1), false);
  p.add_parallelogram({2, 0, 0}, {2, 0, 0}, {0, 0.5f, 0}, {0, 0, 1}, Rgb(3, 1, 2), false);
  p.add_parallelogram({0, 3, 0}, {0.5f, 0, 0}, {0, 0, 0.5f}, {0, 1, 0}, Rgb(4), true);
  p.add_triangle({5, 0, 0}, {6, 0, 0}, {5, 1, 0}, Rgb(2), true);
  p.add_triangle({7, 0, 0}, {9, 0, 0}, {7, 1, 0}, Rgb(0.5f), false);
  p.add_triangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, Rgb(5), false);  // degenerate: dropped
  p.add_parallelogram({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, Rgb(0), false);  // black: dropped
  p.finish();
  REQUIRE(p.size() == 5);
  double w[5], W = 0;
  for (size_t k = 0; k < 5; ++k) {
    const EmissivePatch& q = p.patch(k);
    w[k] = q.area * q.radiance.average() * (q.two_sided ? 2 : 1);
    W += w[k];
  }
  CHECK(p.weight() == Approx(W).epsilon(1e-6));
  // Bins: for parallelograms a 3x3 grid over (s, t), for triangles one bin; expected = pmf * cell fraction.
  std::vector<double> expected, observed;
  std::vector<size_t> first(5);
  for (size_t k = 0; k < 5; ++k) {
    first[k] = expected.size();
    const int cells = p.patch(k).triangle ? 1 : 9;
    for (int c = 0; c < cells; ++c) expected.push_back(w[k] / W / cells);
  }
  observed.assign(expected.size(), 0);
  Pcg32 rng(7);
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const PatchPoint s = p.sample(test::next_2d(rng));
    size_t k = 5;
    for (size_t j = 0; j < 5 && k == 5; ++j) {
      const EmissivePatch& q = p.patch(j);
      // Solve q.p + a e1 + b e2 = s.q in the patch's plane (least squares with the 2x2 Gram matrix).
      const Vec3f d = s.q - q.p;
      const float g11 = dot(q.e1, q.e1), g12 = dot(q.e1, q.e2), g22 = dot(q.e2, q.e2);
      const float det = g11 * g22 - g12 * g12;
      const float a = (g22 * dot(d, q.e1) - g12 * dot(d, q.e2)) / det;
      const float b = (g11 * dot(d, q.e2) - g12 * dot(d, q.e1)) / det;
      if (length(d - q.e1 * a - q.e2 * b) > 1e-4f) continue;
      const float e = -1e-5f;
      if (a < e || b < e || (q.triangle ? a + b > 1 - e : (a > 1 - e || b > 1 - e))) continue;
      k = j;
      CHECK(s.pdf_area == Approx(float(w[j] / W) / q.area).epsilon(1e-4));
      CHECK(s.radiance == q.radiance);
      if (q.triangle) {
        observed[first[j]] += 1;
      } else {
        const int ca = std::min(2, int(a * 3)), cb = std::min(2, int(b * 3));
        observed[first[j] + size_t(ca * 3 + cb)] += 1;
      }
    }
    REQUIRE(k < 5);
  }
  for (double& e : expected) e *= n;
  const auto r = test::chi2_test(observed, expected);
  INFO(r.message);
  CHECK(r.passed);
}

namespace {

// Random small parallelograms and triangles (some two-sided) in a 40-unit box.
EmissivePatches random_patches(size_t count, uint64_t seed) {
  EmissivePatches p;
  Pcg32 rng(seed);
  const auto r = [&] { return rng.next_float(); };
  for (size_t i = 0; i < count; ++i) {
    const Vec3f o(r() * 40 - 20, r() * 40 - 20, r() * 40 - 20);
    const Vec3f e1(r() - 0.5f, r() - 0.5f, r() - 0.5f), e2(r() - 0.5f, r() - 0.5f, r() - 0.5f);
    const Rgb L(0.5f + 3 * r(), 0.5f + r(), 0.2f + r());
    if (i % 3 == 2) p.add_triangle(o, o + e1, o + e2, L, i % 2 == 0);
    else p.add_parallelogram(o, e1, e2, cross(e1, e2), L, i % 2 == 0);
  }
  p.finish();
  return p;
}

}  // namespace

TEST_CASE("EmissivePatches: parts, sample_part's density and find() of the points it samples", "[light][voxel][chi2]") {
  // One patch per part, then three per part above kMaxParts.
  for (const size_t count : {size_t(500), 2 * EmissivePatches::kMaxParts + 7}) {
    const EmissivePatches p = random_patches(count, count);
    INFO(count << " patches");
    const size_t per = count > EmissivePatches::kMaxParts ? 3 : 1;
    REQUIRE(p.part_count() == (p.size() + per - 1) / per);
    double sum = 0;
    for (uint32_t j = 0; j < p.part_count(); ++j) {
      sum += p.part_weight(j);
      REQUIRE(p.part_end(j) - p.part_begin(j) <= per);
      for (size_t k = p.part_begin(j); k < p.part_end(j); ++k) REQUIRE(p.part_of(k) == j);
    }
    CHECK(sum == Approx(p.weight()).epsilon(1e-4));
    Pcg32 rng(3);
    int found = 0;
    for (int i = 0; i < 4000; ++i) {
      const uint32_t j = uint32_t(rng.next_float() * float(p.part_count())) % uint32_t(p.part_count());
      const PatchPoint s = p.sample_part(j, test::next_2d(rng));
      const int64_t k = p.find(s.q);
      REQUIRE(k >= 0);
      REQUIRE(p.part_of(size_t(k)) == j);
      CHECK(s.pdf_area == Approx(p.pdf_area_in_part(size_t(k))).epsilon(1e-5));
      // A point off every patch's plane finds none (the patches are far apart for their size in this box).
      found += p.find(s.q + s.n * 0.05f) >= 0;
    }
    CHECK(found < 40);
  }
  // Within a part, patches are chosen by power: chi-square over the patches of a few three-patch parts.
  const EmissivePatches p = random_patches(2 * EmissivePatches::kMaxParts + 7, 5);
  Pcg32 rng(9);
  for (const uint32_t j : {0u, 17u, 4000u}) {
    std::vector<double> expected, observed(3);
    for (size_t k = p.part_begin(j); k < p.part_end(j); ++k) {
      const EmissivePatch& q = p.patch(k);
      expected.push_back(q.area * q.radiance.average() * (q.two_sided ? 2 : 1) / p.part_weight(j));
    }
    REQUIRE(expected.size() == 3);
    constexpr int kSamples = 30000;
    for (int i = 0; i < kSamples; ++i) observed[size_t(p.find(p.sample_part(j, test::next_2d(rng)).q)) - p.part_begin(j)] += 1;
    for (double& e : expected) e *= kSamples;
    const auto r = test::chi2_test(observed, expected);
    INFO(r.message);
    CHECK(r.passed);
  }
}

TEST_CASE("Voxel emitters: only exposed faces become patches; cell meshes emit per placement", "[light][voxel]") {
  VoxelGrid grid;
  // A 3x3x3 block of emitting id 1: 54 exposed faces (the centre and inner faces are buried).
  for (int x = 0; x < 3; ++x)
    for (int y = 0; y < 3; ++y)
      for (int z = 0; z < 3; ++z) grid.set(x, y, z, 1);
  // A non-emitting solid cube (id 2) hides one face of the block, a cell shape (id -1) hides nothing.
  grid.set(3, 1, 1, 2);
  grid.set(-1, 1, 1, -1);
  // Two separate flames (id -2): 2 placements x 2 triangles.
  grid.set(10, 0, 0, -2);
  grid.set(12, 0, 0, -2);
  auto slab_group = std::make_shared<SceneBuilder>();
  slab_group->add_shape(mesh_shape(make_cube(), translate({0.5f, 0.25f, 0.5f}) * scale({0.5f, 0.25f, 0.5f}),
                                   matte(0.5f)));
  VoxelCellDef slab;
  slab.id = -1;
  slab.shapes = slab_group;
  SceneBuilder b;
  b.add_shape(voxel_desc(grid, {emitting_cube(1, Rgb(2)), VoxelCubeDef{2, {}, Rgb(0)}},
                         {slab, flame_cell(-2, Rgb(3))}, scale({2, 1, 1})));
  const auto scene = b.flatten();
  const Light* l = patches_light(*scene);
  REQUIRE(l != nullptr);
  const EmissivePatches& p = *l->patches;
  size_t faces = 0, triangles = 0;
  float face_area = 0;
  for (size_t k = 0; k < p.size(); ++k) {
    if (p.patch(k).triangle) {
      ++triangles;
      CHECK(p.patch(k).two_sided);
    } else {
      ++faces;
      face_area += p.patch(k).area;
      CHECK_FALSE(p.patch(k).two_sided);
    }
  }
  CHECK(faces == 53);
  CHECK(triangles == 4);
  // Under scale(2, 1, 1): faces facing +-x keep area 1 (8 of them with the hidden one gone, 9 - 1 + 9), the
  // others double.
  CHECK(face_area == Approx(17 * 1 + 36 * 2));
  CHECK(light_power(*scene, *l) > 0);
}

namespace {
// A 7x7 checker of emitting and dark cubes with an emitting cube above and two flame cells, rotated and scaled:
// emitting faces of many orientations and cells, for the tests that sample them and find them again by hits.
auto checkered_emitter_scene() {
  VoxelGrid grid;
  for (int x = -3; x <= 3; ++x)
    for (int z = -3; z <= 3; ++z) grid.set(x, 0, z, int16_t((x + z) % 3 == 0 ? 1 : 3));
  grid.set(0, 2, 0, 1);
  grid.set(2, 1, -1, -2);
  grid.set(-2, 1, 2, -2);
  SceneBuilder b;
  b.add_shape(voxel_desc(grid, {emitting_cube(1, Rgb(2, 1, 0.5f)), VoxelCubeDef{3, {}, Rgb(0)}},
                         {flame_cell(-2, Rgb(5))}, rotate(20, {1, 0.3f, 0}) * scale({1, 0.7f, 1.2f})));
  return b.flatten();
}
}  // namespace

TEST_CASE("Voxel emitters: light_pdf through a hit equals the sample pdf", "[light][voxel]") {
  const auto scene = checkered_emitter_scene();
  const Light* l = patches_light(*scene);
  REQUIRE(l != nullptr);
  const int li = int(l - scene->lights.data());
  Pcg32 rng(11);
  int checked = 0, cells = 0;
  for (const Vec3f p : {Vec3f{0.3f, 4, 0.2f}, Vec3f{-5, 3, 1}, Vec3f{2, 1.5f, 4}}) {
    for (int i = 0; i < 600; ++i) {
      LightSample s;
      if (!sample_light(*scene, *l, p, test::next_2d(rng), &s)) continue;
      REQUIRE_FALSE(s.delta);
      Ray ray{p, s.wi, kInfinity};
      Hit hit;
      if (!scene->intersect(ray, &hit)) continue;
      const SurfaceHit sh = scene->surface(ray, hit);
      const SurfaceEmission* e = patch_emission(*scene, sh);
      if (!e || std::fabs(hit.t - s.distance) > 1e-3f * s.distance) continue;  // something in front
      CHECK(e->light == li);
      CHECK(e->radiance == s.radiance);
      CHECK(light_pdf(*scene, *l, p, s.wi, &sh, hit.t) == Approx(s.pdf).epsilon(2e-3));
      ++checked;
      cells += e->two_sided ? 1 : 0;
    }
  }
  CHECK(checked > 400);
  CHECK(cells > 20);
}

TEST_CASE("Voxel emitters: the light BVH's part of a patch, sampled and found again through real hits",
          "[light][voxel][light_bvh]") {
  const auto scene = checkered_emitter_scene();
  const Light* l = patches_light(*scene);
  REQUIRE(l != nullptr);
  const int li = int(l - scene->lights.data());
  REQUIRE(l->patches->part_count() == l->patches->size());  // one leaf per patch
  Pcg32 rng(12);
  int checked = 0;
  for (const Vec3f p : {Vec3f{0.3f, 4, 0.2f}, Vec3f{-5, 3, 1}, Vec3f{2, 1.5f, 4}}) {
    for (int i = 0; i < 600; ++i) {
      float pmf = 0;
      uint32_t part = 0;
      const int chosen = scene->light_bvh.sample(p, {0, 0, 0}, rng.next_float(), &pmf, &part);
      if (chosen != li) continue;
      REQUIRE(pmf == Approx(scene->light_bvh.pmf(p, {0, 0, 0}, li, part)).epsilon(1e-4));
      LightSample s;
      if (!sample_light(*scene, *l, p, test::next_2d(rng), &s, part)) continue;
      Ray ray{p, s.wi, kInfinity};
      Hit hit;
      if (!scene->intersect(ray, &hit)) continue;
      const SurfaceHit sh = scene->surface(ray, hit);
      const SurfaceEmission* e = patch_emission(*scene, sh);
      if (!e || std::fabs(hit.t - s.distance) > 1e-3f * s.distance) continue;  // something in front
      uint32_t hit_part = 0;
      CHECK(patch_pdf_in_part(*l, p, s.wi, sh, hit.t, &hit_part) == Approx(s.pdf).epsilon(2e-3));
      CHECK(hit_part == part);
      ++checked;
    }
  }
  CHECK(checked > 400);
}

TEST_CASE("Voxel emitters: light paths (IGI) leave with the emitted flux, on the emitting side", "[light][voxel][igi]") {
  VoxelGrid grid;
  grid.set(0, 0, 0, 1);
  grid.set(1, 0, 0, 1);
  grid.set(5, 0, 0, 2);
  grid.set(0, 3, 0, -2);
  SceneBuilder b;
  b.add_shape(voxel_desc(grid, {emitting_cube(1, Rgb(2, 1, 0.5f)), emitting_cube(2, Rgb(4))},
                         {flame_cell(-2, Rgb(5))}, scale({1, 2, 1})));
  const auto scene = b.flatten();
  const Light* l = patches_light(*scene);
  REQUIRE(l != nullptr);
  Pcg32 rng(5);
  const int n = 400000;
  double flux = 0;
  int away = 0;
  for (int i = 0; i < n; ++i) {
    EmissionSample s;
    if (!sample_emission(*scene, *l, test::next_2d(rng), test::next_2d(rng), rng.next_float(), &s)) continue;
    flux += s.weight.average();
    away += dot(s.dir, s.normal) > 0;
  }
  CHECK(away == n);
  // Power = pi * sum of area * average radiance * sides: the mean flux a light path carries.
  CHECK(flux / n == Approx(light_power(*scene, *l)).epsilon(0.01));
  // Under scale(1, 2, 1) x and z faces have area 2, y faces 1. The two joined cubes of id 1 show 2 x, 4 y and 4 z
  // faces (area 16); the lone id 2 cube 2 + 2 + 2 (area 10); the flame quad is 0.6 sqrt(2) by 0.5 * 2 and emits on
  // both sides.
  const float expected = kPi * (16 * 3.5f / 3 + 10 * 4 + 0.6f * std::sqrt(2.0f) * 0.5f * 2 * 2 * 5);
  CHECK(light_power(*scene, *l) == Approx(expected).epsilon(1e-4));
}

TEST_CASE("Voxel emitters render like the same emitters as mesh area lights", "[light][voxel][render]") {
  // A floor (solid ids 3) with one emitting cube and one flame cell above it, against the same geometry built
  // from meshes: the cube as an emitting box mesh, the flame as an emitting two-sided quad.
  VoxelGrid grid;
  for (int x = -6; x < 6; ++x)
    for (int z = -6; z < 6; ++z) grid.set(x, 0, z, 3);
  grid.set(-2, 2, 0, 1);
  grid.set(2, 1, 0, -2);
  const Rgb cube_radiance(3, 2, 1), flame_radiance(6);
  SceneBuilder voxels, meshes;
  voxels.add_shape(voxel_desc(grid, {emitting_cube(1, cube_radiance), VoxelCubeDef{3, {}, Rgb(0)}},
                              {flame_cell(-2, flame_radiance)}));
  VoxelGrid floor_only;
  for (int x = -6; x < 6; ++x)
    for (int z = -6; z < 6; ++z) floor_only.set(x, 0, z, 3);
  meshes.add_shape(voxel_desc(floor_only, {VoxelCubeDef{3, {}, Rgb(0)}}, {}));
  ShapeDesc box = mesh_shape(make_cube(), translate({-1.5f, 2.5f, 0.5f}) * scale({0.5f, 0.5f, 0.5f}), matte(0.5f));
  box.emission = cube_radiance;
  meshes.add_shape(box);
  meshes.add_shape(mesh_shape(make_cube(), translate({2.5f, 1.2f, 0.5f}) * scale({0.05f, 0.2f, 0.05f}), matte(0.3f)));
  ShapeDesc flame = mesh_shape(make_polygon({{2.2f, 1.4f, 0.2f}, {2.8f, 1.4f, 0.8f}, {2.8f, 1.9f, 0.8f},
                                             {2.2f, 1.9f, 0.2f}}),
                               Transform(), matte(0.2f));
  flame.emission = flame_radiance;
  flame.two_sided = true;
  meshes.add_shape(flame);
  const CameraDesc cam = test::camera_at({0, 7, -7}, {0, 0.5f, 0}, 50);
  const auto a = voxels.flatten(), c = meshes.flatten();
  for (IntegratorKind kind : {IntegratorKind::Path, IntegratorKind::Direct}) {
    RenderSettings s;
    s.width = s.height = 48;
    s.spp = 64;
    s.max_depth = 4;
    s.integrator = kind;
    const Image ia = test::render_view(*a, cam, s).image;
    s.seed = 99;
    const Image ic = test::render_view(*c, cam, s).image;
    // Tiles of 8x8 pixels: the floor lit by both emitters, and the emitters themselves.
    int compared = 0;
    for (int ty = 0; ty < 6; ++ty)
      for (int tx = 0; tx < 6; ++tx) {
        const Rgb ma = tile_mean(ia, tx * 8, ty * 8, tx * 8 + 8, ty * 8 + 8);
        const Rgb mc = tile_mean(ic, tx * 8, ty * 8, tx * 8 + 8, ty * 8 + 8);
        INFO("integrator " << int(kind) << " tile " << tx << "," << ty << ": " << ma.r << " " << ma.g << " "
                           << ma.b << " vs " << mc.r << " " << mc.g << " " << mc.b);
        const float tol = 0.06f * std::max(mc.average(), 0.05f) + 0.01f;
        CHECK(std::fabs(ma.average() - mc.average()) < tol);
        ++compared;
      }
    CHECK(compared == 36);
    CHECK(tile_mean(ia, 0, 0, 48, 48).average() > 0.05f);
  }
}

TEST_CASE("Voxel emitters: instanced emitting grids and emitting analytic cell shapes are errors", "[light][voxel]") {
  VoxelGrid grid;
  grid.set(0, 0, 0, 1);
  {
    auto group = std::make_shared<SceneBuilder>();
    group->add_shape(voxel_desc(grid, {emitting_cube(1, Rgb(1))}, {}));
    SceneBuilder b;
    b.add_instance({group, translate({1, 0, 0})});
    CHECK_THROWS_WITH(b.flatten(), Catch::Contains("cannot be instanced"));
  }
  {
    grid.set(1, 0, 0, -1);
    auto cell = std::make_shared<SceneBuilder>();
    ShapeDesc ball = test::sphere_shape(0.3f, translate({0.5f, 0.5f, 0.5f}), matte(0.5f));
    ball.emission = Rgb(1);
    cell->add_shape(ball);
    VoxelCellDef c;
    c.id = -1;
    c.shapes = cell;
    SceneBuilder b;
    b.add_shape(voxel_desc(grid, {}, {c}));
    CHECK_THROWS_WITH(b.flatten(), Catch::Contains("only meshes"));
  }
}

TEST_CASE("Voxel emitters: the emission AOV holds an emitting cube's radiance where the camera sees it",
          "[light][voxel][aov]") {
  // A 3x3 floor of plain cubes with one emitting cube in the middle, seen from nearly straight above.
  VoxelGrid grid;
  for (int x = -1; x <= 1; ++x)
    for (int z = -1; z <= 1; ++z) grid.set(x, 0, z, int16_t(x == 0 && z == 0 ? 1 : 3));
  SceneBuilder b;
  b.add_shape(voxel_desc(grid, {emitting_cube(1, Rgb(2, 1, 0.5f)), VoxelCubeDef{3, {}, Rgb(0)}}, {}));
  const auto scene = b.flatten();
  RenderSettings s;
  s.width = s.height = 15;  // odd: the centre pixel looks at the emitting cube's top face
  const auto layers = render_aovs(*scene, Camera(test::camera_at({0.5f, 6, 0.3f}, {0.5f, 0, 0.5f}, 25), s.width, s.height),
                                  s, {Aov::Emission}, 4);
  REQUIRE(layers.size() == 1);
  const ImageLayer& e = layers[0];
  const auto at = [&](int x, int y) { return e.at(size_t(y) * size_t(s.width) + size_t(x)); };
  CHECK(at(7, 7)[0] == Approx(2));
  CHECK(at(7, 7)[2] == Approx(0.5f));
  CHECK(at(0, 0)[0] == 0);  // a corner: a plain cube's top (the view spans 2.2 cells), which emits nothing
  CHECK(at(0, 7)[0] == 0);
}
