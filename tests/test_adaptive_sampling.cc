// Adaptive sampling (noise_threshold) and time limits: the adaptive image agrees with the full-spp one within
// noise while taking fewer samples, spends them where the image is noisy, stays bitwise deterministic, and
// integrators whose paths splat into other pixels refuse it.
#include <tbb/global_control.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>

#include "cornell_like.h"
#include "render/adaptive_sampling.h"
#include "render/render.h"
#include "render/render_settings.h"
#include "render/tile_loop.h"
#include "scene_helpers.h"

using namespace torte;
using namespace torte::test;

namespace {

RenderSettings box_settings(int spp, float threshold) {
  RenderSettings s = integrator_settings(IntegratorKind::Path, 40, spp);
  s.max_depth = 6;
  s.noise_threshold = threshold;
  return s;
}

// The first pass boundary (cumulative spp) at or after n samples.
int boundary_at_or_after(int spp, int n) {
  int done = 0;
  for (const int p : detail::make_passes(spp)) {
    done += p;
    if (done >= n) return done;
  }
  return done;
}

}  // namespace

TEST_CASE("adaptive sampling: the error estimate is the relative standard error of the mean", "[adaptive]") {
  // Two samples of weight 1 with luminance 0 and 2 (grey): mean 1, sample variance 2, error sqrt(2 / 2) / 1 = 1.
  PixelSum sum;
  sum.weighted = Rgb(2);
  sum.weight = 2;
  CHECK(AdaptiveSampler::pixel_error(sum, /*moment=*/4, 2) == Approx(1));
  // Eight equal samples have no spread.
  sum.weighted = Rgb(8 * 0.5f);
  sum.weight = 8;
  CHECK(AdaptiveSampler::pixel_error(sum, 8 * 0.25f, 8) == Approx(0).margin(1e-6));
  // A near-black pixel is measured against the dark floor, not its own tiny mean.
  sum.weighted = Rgb(0.001f);
  sum.weight = 2;
  const float dark = AdaptiveSampler::pixel_error(sum, 0.001f * 0.001f, 2);
  CHECK(dark == Approx(std::sqrt(0.001 * 0.001 / 4 * 2 / 2) / AdaptiveSampler::kDarkFloor).epsilon(1e-3));
  CHECK(AdaptiveSampler::pixel_error(sum, 0, 1) == 0);  // one sample says nothing about the spread
}

TEST_CASE("adaptive sampling matches the full-spp image within noise with fewer samples", "[adaptive][render]") {
  const auto scene = cornell_like();
  const int spp = 256;
  const RenderOutput full = render_view(*scene, box_camera(), box_settings(spp, 0));
  CHECK(full.pixel_spp.empty());
  const RenderOutput adaptive = render_view(*scene, box_camera(), box_settings(spp, 0.08f));
  const size_t pixels = size_t(40) * 40;
  REQUIRE(adaptive.pixel_spp.size() == pixels);

  // Fewer samples in all, spread unevenly, every pixel at least the minimum, the noisiest the whole budget.
  const auto [lo, hi] = std::minmax_element(adaptive.pixel_spp.begin(), adaptive.pixel_spp.end());
  const int min_spp = boundary_at_or_after(spp, RenderSettings{}.adaptive_min_spp);
  CHECK(int(*lo) == min_spp);
  CHECK(int(*hi) > 4 * min_spp);  // the noisiest pixels take (nearly) the whole budget
  uint64_t taken = 0;
  for (const uint32_t n : adaptive.pixel_spp) taken += n;
  CHECK(adaptive.stats.samples_done == taken);
  CHECK(double(taken) < 0.8 * double(pixels * spp));
  CHECK(adaptive.stats.spp_reached == spp);

  // Tile means agree with the full render (the adaptive image is noisier where it stopped, within its threshold).
  const auto a = tile_means(adaptive.image, 8), f = tile_means(full.image, 8);
  double worst = 0;
  for (size_t t = 0; t < a.size(); ++t) worst = std::max(worst, std::fabs(a[t] - f[t]) / std::max(f[t], 0.02));
  INFO("worst tile difference " << worst);
  CHECK(worst < 0.03);
  CHECK(image_mean(adaptive.image) == Approx(image_mean(full.image)).epsilon(0.01));

  SECTION("and a real difference is detected: a threshold of 1 stops everything at the minimum") {
    const RenderOutput rough = render_view(*scene, box_camera(), box_settings(spp, 1.0f));
    for (const uint32_t n : rough.pixel_spp) REQUIRE(int(n) == min_spp);
    const auto r = tile_means(rough.image, 8);
    double rough_worst = 0;
    for (size_t t = 0; t < r.size(); ++t)
      rough_worst = std::max(rough_worst, std::fabs(r[t] - f[t]) / std::max(f[t], 0.02));
    CHECK(rough_worst > worst);
  }
}

TEST_CASE("adaptive sampling is bitwise deterministic at 1 and 2 threads", "[adaptive][determinism]") {
  const auto scene = cornell_like();
  RenderSettings s = box_settings(64, 0.08f);
  s.adaptive_min_spp = 4;
  s.filter = Filter::mitchell();
  RenderOutput one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = render_view(*scene, box_camera(), s);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = render_view(*scene, box_camera(), s);
  }
  REQUIRE(one.image.pixels.size() == two.image.pixels.size());
  CHECK(std::memcmp(one.image.pixels.data(), two.image.pixels.data(), one.image.pixels.size() * sizeof(Rgb)) == 0);
  CHECK(one.pixel_spp == two.pixel_spp);
  CHECK(*std::min_element(one.pixel_spp.begin(), one.pixel_spp.end()) <
        *std::max_element(one.pixel_spp.begin(), one.pixel_spp.end()));
}

TEST_CASE("adaptive sampling works for direct and igi and is refused where paths splat", "[adaptive]") {
  RenderSettings s = box_settings(16, 0.05f);
  for (IntegratorKind k : {IntegratorKind::Path, IntegratorKind::Direct, IntegratorKind::Igi}) {
    s.integrator = k;
    CHECK_FALSE(find_settings_problem(s));
  }
  for (IntegratorKind k : {IntegratorKind::Lt, IntegratorKind::Bdpt, IntegratorKind::Vcm, IntegratorKind::Ppm}) {
    s.integrator = k;
    const auto problem = find_settings_problem(s);
    REQUIRE(problem);
    CHECK(std::string(problem->key) == "noise_threshold");
    CHECK_THAT(problem->message(), Catch::Contains(integrator_name(k)));
  }
  s.integrator = IntegratorKind::Path;
  s.noise_threshold = -0.1f;
  CHECK(find_settings_problem(s));
  s.noise_threshold = NAN;
  CHECK(find_settings_problem(s));
  s.noise_threshold = 0.05f;
  s.adaptive_min_spp = 1;
  CHECK(find_settings_problem(s));
  s.adaptive_min_spp = 16;
  s.time_limit = -1;
  CHECK(find_settings_problem(s));
  s.time_limit = INFINITY;
  CHECK(find_settings_problem(s));
}

TEST_CASE("time_limit stops at a pass boundary with a valid image", "[adaptive][render]") {
  const auto scene = cornell_like();
  RenderSettings s = box_settings(1024, 0);
  s.time_limit = 1e-9;  // over before the first pass ends: exactly one pass is rendered
  const RenderOutput out = render_view(*scene, box_camera(), s);
  CHECK(out.stats.time_limited);
  CHECK_FALSE(out.stats.interrupted);
  const int first_pass = detail::make_passes(s.spp).front();
  CHECK(out.stats.spp_reached == first_pass);
  CHECK(out.stats.samples_done == uint64_t(40 * 40 * first_pass));
  for (const Rgb& c : out.image.pixels) REQUIRE(c.is_finite());
  // Every pixel has the same samples: the image is the unbiased (noisy) box, not a darkened partial one.
  s.spp = first_pass;
  s.time_limit = 0;
  const RenderOutput same = render_view(*scene, box_camera(), s);
  CHECK_FALSE(same.stats.time_limited);
  CHECK(std::memcmp(out.image.pixels.data(), same.image.pixels.data(), out.image.pixels.size() * sizeof(Rgb)) == 0);

  SECTION("a limit the render does not reach changes nothing") {
    s.spp = 8;
    s.time_limit = 1e6;
    const RenderOutput whole = render_view(*scene, box_camera(), s);
    CHECK_FALSE(whole.stats.time_limited);
    CHECK(whole.stats.spp_reached == 8);
  }
}
