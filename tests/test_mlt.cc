// Metropolis light transport (render/integrator_mlt.h) and its primary sample space (core/primary_samples.h):
// uniform coordinates (chi-square) fresh and after small steps, proposals that accept and reject exactly, and the
// integrator against path tracing on the Cornell-like box (mean and tile means), a white furnace, consistency,
// thread determinism and what it refuses.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "chi2.h"
#include "core/primary_samples.h"
#include "cornell_like.h"
#include "cornell_reference.h"
#include "material_room.h"
#include "render/render.h"
#include "scene_helpers.h"

using namespace torte;
using namespace torte::test;

namespace {

// Chi-square of values in [0, 1) against the uniform density, in `bins` equal bins.
test::Chi2Result uniform_chi2(const std::vector<float>& values, int bins) {
  std::vector<double> observed(size_t(bins), 0), expected(size_t(bins), double(values.size()) / bins);
  for (const float v : values) {
    REQUIRE(v >= 0.0f);
    REQUIRE(v < 1.0f);
    observed[size_t(std::min(bins - 1, int(v * float(bins))))] += 1;
  }
  return test::chi2_test(observed, expected);
}

}  // namespace

TEST_CASE("primary samples: fresh vectors and small-stepped ones are uniform (chi-square)", "[mlt][sampling]") {
  const uint32_t chains = 2000;
  PrimarySamples pss(3, 0, chains, 16);
  std::vector<float> fresh, stepped;
  for (uint32_t c = 0; c < chains; ++c) {
    pss.start_at(c, pss.bootstrap_key(c));
    for (uint32_t d : {0u, 5u, PrimarySamples::kLightRegion + 2, PrimarySamples::kSinglesRegion + 1}) {
      const Vec2f u = pss.get_2d(c, d);
      fresh.push_back(u.x);
      fresh.push_back(u.y);
    }
  }
  // Small steps accepted 300 times (a random walk on the torus: uniform stays uniform); one coordinate read in
  // every step, one only at the end (300 steps caught up at once). One value of each per chain: independent.
  for (int it = 0; it < 300; ++it)
    for (uint32_t c = 0; c < chains; ++c) {
      pss.propose(c, false);
      const float x = pss.get_2d(c, 5).x;
      if (it == 299) stepped.push_back(x);
      pss.accept(c);
    }
  for (uint32_t c = 0; c < chains; ++c) stepped.push_back(pss.get_2d(c, PrimarySamples::kLightRegion + 2).y);
  const auto a = uniform_chi2(fresh, 64), b = uniform_chi2(stepped, 64);
  INFO(a.message << " / " << b.message);
  CHECK(a.passed);
  CHECK(b.passed);
}

TEST_CASE("primary samples: steps, rejection and reading order", "[mlt][sampling]") {
  PrimarySamples pss(1, 0, 2, 16);
  pss.start_at(0, 77);
  pss.start_at(1, 77);
  const Vec2f x0 = pss.get_2d(0, 3), y0 = pss.get_2d(0, 9);
  CHECK(pss.get_2d(1, 9).x == y0.x);  // the same key gives the same vector, whatever is read first
  CHECK(pss.get_2d(1, 3).y == x0.y);

  // A small step moves a coordinate by about sigma; rejecting it restores the value exactly.
  pss.propose(0, false);
  const Vec2f x1 = pss.get_2d(0, 3);
  CHECK(x1.x != x0.x);
  CHECK(std::fabs(x1.x - x0.x) < 8 * PrimarySamples::kSigma);
  CHECK(pss.get_2d(0, 3).x == x1.x);  // read twice in one proposal: the same value
  pss.reject(0);
  CHECK(pss.get_2d(0, 3).x == x0.x);
  CHECK(pss.get_2d(0, 9).y == y0.y);

  // An accepted large step replaces every coordinate, also those it did not read.
  pss.propose(0, true);
  const Vec2f big = pss.get_2d(0, 3);
  pss.accept(0);
  CHECK(pss.get_2d(0, 3).x == big.x);
  CHECK(pss.get_2d(0, 9).x != y0.x);
  CHECK(pss.get_2d(0, 9).x == pss.get_2d(0, 9).x);
  // A dimension outside the regions is an error, not a silent alias.
  CHECK_THROWS_WITH(pss.get_2d(0, 16), Catch::Contains("outside"));
}

TEST_CASE("mlt converges to path on the Cornell-like box (mean and 16x16 tile means of a 64x64 image)",
          "[render][mlt]") {
  const Image& path = path_reference();
  const RenderOutput mlt =
      render_view(*cornell_like(), box_camera(), integrator_settings(IntegratorKind::Mlt, 64, reduced() ? 64 : 512));
  INFO("mlt mean " << image_mean(mlt.image) << ", path mean " << image_mean(path) << ", worst tile "
                   << max_tile_error(mlt.image, path, 16));
  CHECK(image_mean(mlt.image) == Approx(image_mean(path)).epsilon(reduced() ? 0.03 : 0.01));
  CHECK(max_tile_error(mlt.image, path, 16) < (reduced() ? 0.08 : 0.03));
  CHECK(mlt.stats.shadow_rays > 0);
  CHECK(mlt.stats.spp_reached == (reduced() ? 64 : 512));
}

TEST_CASE("mlt error falls with the mutations (the spread of two seeds' images)", "[render][mlt]") {
  // The bias is the convergence test's; here the variance: two independent renders differ by sqrt(2) x their
  // error, which must fall as 1/sqrt(mutations) (4x at 16x). No reference needed, so it is cheap.
  const auto scene = cornell_like();
  const auto spread = [&](int spp) {
    // Sanitizer builds: a quarter of the pixels (the ratio does not depend on the image size).
    RenderSettings a = integrator_settings(IntegratorKind::Mlt, reduced() ? 32 : 64, spp), b = a;
    b.seed = 1;
    return rmse(render_view(*scene, box_camera(), a).image, render_view(*scene, box_camera(), b).image);
  };
  const double e4 = spread(4), e64 = spread(64);
  INFO("spread at 4 mutations per pixel " << e4 << ", at 64 " << e64);
  CHECK(e64 < 0.4 * e4);
}

TEST_CASE("mlt furnace: inside a closed emitting Lambert sphere, depth k sees 1 - 0.8^(k+1)", "[render][mlt][furnace]") {
  const auto scene = emitting_shell();
  for (const int depth : {1, 4}) {
    RenderSettings s = integrator_settings(IntegratorKind::Mlt, 32, 32);
    s.max_depth = depth;
    s.rr_depth = 100;
    const Image img = render_view(*scene, shell_camera(), s).image;
    INFO("depth " << depth);
    CHECK(image_mean(img) == Approx(shell_radiance(depth)).epsilon(0.01));
    // Every pixel sees the same radiance: no pixel is left without mutations.
    int black = 0;
    for (const Rgb& c : img.pixels) black += c.is_black();
    CHECK(black == 0);
  }
}

TEST_CASE("mlt gives a bitwise identical image at 1 and 2 threads", "[render][mlt][determinism]") {
  RenderSettings s = integrator_settings(IntegratorKind::Mlt, 40, 8);
  s.height = 24;
  s.chains = 1500;  // two groups, the second partial
  check_thread_determinism(*material_room(), material_room_camera(), s);
}

TEST_CASE("mlt refuses what bdpt refuses, naming itself, and checks its keys", "[render][mlt]") {
  SceneBuilder b;
  b.add_shape(sphere_shape(1, Transform(), matte(0.5f)));
  b.add_light(uniform_sky(Rgb(1)));
  const auto scene = b.flatten();
  RenderSettings s = integrator_settings(IntegratorKind::Mlt, 8, 1);
  CHECK_THROWS_WITH(render_view(*scene, camera_at({0, 0, -4}, {0, 0, 0}, 40), s),
                    Catch::Contains("integrator 'mlt'") && Catch::Contains("infinite"));
  s.large_step = 0;
  REQUIRE(find_settings_problem(s));
  CHECK(std::string(find_settings_problem(s)->key) == "large_step");
  s.large_step = 0.3f;
  s.chains = -1;
  REQUIRE(find_settings_problem(s));
  CHECK(std::string(find_settings_problem(s)->key) == "chains");
  s.chains = 0;
  s.noise_threshold = 0.1f;
  CHECK(find_settings_problem(s));  // its mutations splat anywhere: no adaptive sampling
}
