// End-to-end checks of the integrators against analytic answers (furnaces), against each other (direct vs path
// at depth 1) and for determinism across thread counts. Images are compared statistically, by tile means.
#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <memory>

#include "chi2.h"
#include "core/rng.h"
#include "render/render.h"
#include "scene/builder.h"
#include "scene_helpers.h"

using namespace torte;
using namespace torte::test;

namespace {

double mean_channel(const Image& img, int x0, int y0, int x1, int y1, int channel = 1) {
  double sum = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const Rgb& c = img.at(x, y);
      sum += channel == 0 ? c.r : channel == 1 ? c.g : c.b;
    }
  return sum / double((x1 - x0) * (y1 - y0));
}

// A closed room (a big box seen from inside) with two area lights of different shapes and a point light, plus
// a sphere and a box: enough variety to compare integrators.
std::shared_ptr<Scene> test_room() {
  SceneBuilder b;
  ShapeDesc room;
  room.kind = ShapeDesc::Kind::Mesh;
  room.mesh = std::make_shared<TriangleMesh>(make_cube());
  room.transform = scale({2, 1.5f, 2});
  room.material = matte(0.6f);
  b.add_shape(room);
  b.add_shape(sphere_shape(0.4f, translate({-0.5f, -1.1f, 0.3f}), matte(0.8f)));
  ShapeDesc block = room;
  block.transform = translate({0.7f, -1.2f, 0.2f}) * rotate(30, {0, 1, 0}) * scale({0.3f, 0.3f, 0.3f});
  block.material = matte(0.4f);
  b.add_shape(block);
  ShapeDesc lamp = sphere_shape(0.15f, translate({0.5f, 1.0f, 0.5f}), matte(0));
  lamp.emission = Rgb(20, 15, 10);
  b.add_shape(lamp);
  ShapeDesc panel;
  panel.kind = ShapeDesc::Kind::Mesh;
  panel.mesh = std::make_shared<TriangleMesh>(make_polygon({{-1, 1.45f, -1}, {-0.5f, 1.45f, -1}, {-0.5f, 1.45f, -0.5f}, {-1, 1.45f, -0.5f}}));
  panel.material = matte(0);
  panel.emission = Rgb(4);
  panel.two_sided = true;
  b.add_shape(panel);
  Light point;
  point.kind = LightKind::Point;
  point.position = {1.2f, 0.5f, -1.2f};
  point.radiance = Rgb(1.5f);
  b.add_light(point);
  return b.flatten();
}

const CameraDesc kRoomCamera = camera_at({0, 0, -1.9f}, {0, -0.3f, 0}, 70);

struct TileStats {
  double mean = 0, var_of_mean = 0;
};

// Per-tile mean of the green channel and the variance of that mean estimated from the pixel spread (which also
// contains image structure, so it over-estimates the noise: a conservative tolerance).
std::vector<TileStats> tile_stats(const Image& img, int tile) {
  std::vector<TileStats> out;
  for (int y0 = 0; y0 < img.height; y0 += tile)
    for (int x0 = 0; x0 < img.width; x0 += tile) {
      double s = 0, s2 = 0;
      int n = 0;
      for (int y = y0; y < std::min(y0 + tile, img.height); ++y)
        for (int x = x0; x < std::min(x0 + tile, img.width); ++x) {
          const double v = img.at(x, y).g;
          s += v;
          s2 += v * v;
          ++n;
        }
      const double mean = s / n;
      out.push_back({mean, std::max(0.0, s2 / n - mean * mean) / n});
    }
  return out;
}

}  // namespace

TEST_CASE("furnace: a Lambert sphere under a uniform infinite light renders its albedo", "[render][furnace]") {
  for (const float albedo : {0.25f, 0.8f}) {
    SceneBuilder b;
    b.add_shape(sphere_shape(1, Transform(), matte(albedo)));
    b.add_light(uniform_sky(Rgb(1)));
    const auto scene = b.flatten();
    RenderSettings s;
    s.width = s.height = 32;
    s.spp = 64;
    const Image img = render_view(*scene, furnace_camera(), s).image;
    // Pixels fully inside the sphere's silhouette (radius 1 of 1.25 half-extent) and the background corners.
    CHECK(furnace_sphere_mean_green(img) == Approx(albedo).epsilon(0.01));
    CHECK(img.at(0, 0).g == Approx(1.0f).epsilon(1e-5));
  }
}

TEST_CASE("furnace: inside a closed emitting Lambert sphere, depth k sees 1 - 0.8^(k+1)", "[render][furnace]") {
  const CameraDesc cam = shell_camera();
  const auto scene = emitting_shell();
  RenderSettings s;
  s.width = s.height = 16;
  s.spp = 64;
  for (int k = 0; k <= 4; ++k) {
    s.max_depth = k;
    const Image img = render_view(*scene, cam, s).image;
    const double expected = shell_radiance(k);
    INFO("max_depth " << k);
    CHECK(mean_channel(img, 0, 0, 16, 16) == Approx(expected).epsilon(0.01));
  }
  s.max_depth = 10000;  // Russian roulette ends the paths; the estimate must stay unbiased
  s.spp = 512;          // long paths: ~0.2 % standard error at this count
  const Image img = render_view(*scene, cam, s).image;
  CHECK(mean_channel(img, 0, 0, 16, 16) == Approx(1.0).epsilon(0.005));
}

TEST_CASE("the furnace test can fail: a wrong albedo is detected", "[render][furnace]") {
  SceneBuilder b;
  ShapeDesc shell = sphere_shape(1, Transform(), matte(0.7f));
  shell.emission = Rgb(0.2f);
  shell.two_sided = true;
  b.add_shape(shell);
  RenderSettings s;
  s.width = s.height = 16;
  s.spp = 32;
  s.max_depth = 3;
  const Image img = render_view(*b.flatten(), camera_at({0, 0, 0}, {0, 0, 1}, 60), s).image;
  CHECK(std::fabs(mean_channel(img, 0, 0, 16, 16) - (1 - std::pow(0.8, 4))) > 0.05);
}

TEST_CASE("direct equals path at max_depth 1 within noise (tile means)", "[render][integrator]") {
  const auto scene = test_room();
  RenderSettings s;
  s.width = s.height = 48;
  s.spp = 64;
  s.max_depth = 1;
  s.integrator = IntegratorKind::Path;
  const Image path = render_view(*scene, kRoomCamera, s).image;
  s.integrator = IntegratorKind::Direct;
  s.sample_all_lights = true;
  s.seed = 7;
  const Image direct = render_view(*scene, kRoomCamera, s).image;
  const auto a = tile_stats(path, 8), b = tile_stats(direct, 8);
  int outliers = 0;
  double total_a = 0, total_b = 0;
  for (size_t t = 0; t < a.size(); ++t) {
    const double se = std::sqrt(a[t].var_of_mean + b[t].var_of_mean) + 1e-4;
    if (std::fabs(a[t].mean - b[t].mean) > 4 * se) ++outliers;
    total_a += a[t].mean;
    total_b += b[t].mean;
  }
  CHECK(outliers == 0);
  CHECK(total_a / a.size() == Approx(total_b / b.size()).epsilon(0.02));
  CHECK(total_a / a.size() > 0.01);  // the scene is lit

  SECTION("and a real difference is detected: path at depth 3 is brighter") {
    s.integrator = IntegratorKind::Path;
    s.max_depth = 3;
    const Image deep = render_view(*scene, kRoomCamera, s).image;
    const auto c = tile_stats(deep, 8);
    double total_c = 0;
    for (const auto& t : c) total_c += t.mean;
    CHECK(total_c / c.size() > 1.1 * total_a / a.size());
  }
}

TEST_CASE("the same seed gives a bitwise identical image at 1 and 2 threads", "[render][determinism]") {
  const auto scene = test_room();
  RenderSettings s;
  s.width = 40;
  s.height = 24;
  s.spp = 8;
  s.max_depth = 8;
  s.filter = Filter::mitchell();
  check_thread_determinism(*scene, kRoomCamera, s);
}

TEST_CASE("max_depth 0 shows only what emits", "[render]") {
  const auto scene = test_room();
  RenderSettings s;
  s.width = s.height = 24;
  s.spp = 4;
  s.max_depth = 0;
  const Image img = render_view(*scene, kRoomCamera, s).image;
  int lit = 0;
  for (const Rgb& c : img.pixels) lit += c.g > 0;
  CHECK(lit > 0);
  CHECK(lit < int(img.pixels.size()) / 4);
}

TEST_CASE("light selection follows emitted power (chi-square)", "[render][sampling]") {
  const auto scene = test_room();
  REQUIRE(scene->lights.size() == 3);
  std::vector<double> expected(3), observed(3);
  double total = 0;
  for (size_t i = 0; i < 3; ++i) total += light_power(*scene, scene->lights[i]);
  const int n = 200000;
  for (size_t i = 0; i < 3; ++i) {
    expected[i] = n * light_power(*scene, scene->lights[i]) / total;
    CHECK(scene->light_selection.pmf(int(i)) == Approx(expected[i] / n).epsilon(1e-4));
  }
  Pcg32 rng(42);
  for (int k = 0; k < n; ++k) observed[size_t(scene->light_selection.sample_discrete(rng.next_float()))] += 1;
  const auto r = test::chi2_test(observed, expected);
  INFO(r.message);
  CHECK(r.passed);
}

TEST_CASE("NaN radiance never reaches the film and is counted", "[render]") {
  SceneBuilder b;
  ShapeDesc lamp = sphere_shape(1, Transform(), matte(0.5f));
  lamp.emission = Rgb(1);
  b.add_shape(lamp);
  // Input validation rejects NaN emission, so poison the flattened scene to make the integrator produce NaN.
  const auto scene = b.flatten();
  scene->lights[0].radiance = Rgb(NAN, 1, 1);
  RenderSettings s;
  s.width = s.height = 8;
  s.spp = 2;
  s.max_depth = 0;
  const RenderOutput out = render_view(*scene, camera_at({0, 0, -3}, {0, 0, 0}, 40), s);
  CHECK(out.stats.dropped_samples > 0);
  for (const Rgb& c : out.image.pixels) CHECK(c.is_finite());
}

TEST_CASE("a cancelled render stops early and keeps the samples done", "[render]") {
  const auto scene = test_room();
  RenderSettings s;
  s.width = s.height = 32;
  s.spp = 64;
  std::atomic<bool> cancel{true};
  const RenderOutput out = render_view(*scene, kRoomCamera, s, &cancel);
  CHECK(out.stats.interrupted);
  CHECK(out.stats.samples_done < uint64_t(32 * 32 * 64));
}
