// Instant global illumination (render/integrator_igi.h) against path tracing on a small closed diffuse Cornell-like box:
// convergence with a loose clamp and many VPLs, the clamping bias shrinking as g_limit grows, direct <= igi <=
// path, consistency with the defaults, and determinism across thread counts. Images are compared by tile means
// (8x8-pixel tiles), or by pixel errors where the noise is what is measured.
#include <tbb/global_control.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <memory>

#include "render/render.h"
#include "scene/builder.h"
#include "cornell_like.h"
#include "cornell_reference.h"
#include "scene_helpers.h"

using namespace torte;
using torte::test::box_camera;
using torte::test::check_thread_determinism;
using torte::test::cornell_like;

namespace {

RenderOutput render_box(const Scene& scene, const RenderSettings& s) {
  return torte::test::render_view(scene, box_camera(), s);
}

RenderSettings settings(IntegratorKind k, int spp) {
  RenderSettings s;
  s.width = s.height = 32;
  s.spp = spp;
  s.integrator = k;
  s.sample_all_lights = k != IntegratorKind::Path;
  s.tile_size = 8;  // 16 tiles: both cores busy
  return s;
}

// Per-tile means of the channel average over 8x8 tiles.
std::vector<double> tile_means(const Image& img) {
  std::vector<double> out;
  for (int y0 = 0; y0 < img.height; y0 += 8)
    for (int x0 = 0; x0 < img.width; x0 += 8) {
      double s = 0;
      for (int y = y0; y < y0 + 8; ++y)
        for (int x = x0; x < x0 + 8; ++x) s += img.at(x, y).average();
      out.push_back(s / 64);
    }
  return out;
}

double mean(const Image& img) {
  double s = 0;
  for (const Rgb& c : img.pixels) s += c.average();
  return s / double(img.pixels.size());
}

// Largest relative difference of tile means.
double max_tile_error(const Image& a, const Image& reference) {
  const auto ta = tile_means(a), tr = tile_means(reference);
  double worst = 0;
  for (size_t t = 0; t < ta.size(); ++t) worst = std::max(worst, std::fabs(ta[t] - tr[t]) / tr[t]);
  return worst;
}

// The reference: path tracing of the same box and camera, 16384 samples per pixel (tile means to about 0.25 %;
// 2048 in sanitizer builds), rendered at 64x64 once for the whole suite (cornell_reference.h).
const Image& path_reference() { return torte::test::path_reference_32(); }

}  // namespace

TEST_CASE("igi with a loose clamp and many VPLs converges to path (tile means within 4 percent)", "[render][igi]") {
  const auto scene = cornell_like();
  RenderSettings s = settings(IntegratorKind::Igi, 16);
  s.vpl_sets = 16;
  s.light_paths = 256;
  s.g_limit = 1e4f;  // clamps only closer than about R/100 for facing surfaces
  s.seed = 3;
  const Image igi = render_box(*scene, s).image;
  const Image& ref = path_reference();
  INFO("igi mean " << mean(igi) << ", path mean " << mean(ref) << ", worst tile " << max_tile_error(igi, ref));
  CHECK(mean(igi) == Approx(mean(ref)).epsilon(0.015));
  CHECK(max_tile_error(igi, ref) < 0.04);
}

TEST_CASE("the clamping bias of igi shrinks as g_limit grows", "[render][igi]") {
  const auto scene = cornell_like();
  const double ref = mean(path_reference());
  RenderSettings s = settings(IntegratorKind::Igi, 8);
  s.vpl_sets = 16;
  s.light_paths = 128;
  std::vector<double> errors;
  for (const float g : {2.0f, 20.0f, 200.0f}) {
    s.g_limit = g;
    const double m = mean(render_box(*scene, s).image);
    errors.push_back(std::fabs(m - ref) / ref);
    INFO("g_limit " << g << ": igi mean " << m << ", path " << ref);
    CHECK(m < ref * 1.01);  // clamping only removes energy
  }
  INFO("relative errors " << errors[0] << ", " << errors[1] << ", " << errors[2]);
  CHECK(errors[0] > errors[1]);
  CHECK(errors[1] > errors[2]);
  CHECK(errors[0] > 0.03);   // a tight clamp is visibly biased
  CHECK(errors[2] < 0.02);   // a loose one hardly (measured: 9.0 %, 2.3 %, 1.1 % for g_limit 2, 20, 200)
}

TEST_CASE("direct below igi below path on a closed diffuse box and all equal at depths 1 and 2", "[render][igi]") {
  const auto scene = cornell_like();
  const Image& path = path_reference();
  RenderSettings s = settings(IntegratorKind::Direct, 64);
  const double direct = mean(render_box(*scene, s).image);
  s = settings(IntegratorKind::Igi, 16);  // defaults: 4 sets x 64 light paths, g_limit 20
  const Image igi = render_box(*scene, s).image;
  INFO("direct " << direct << ", igi " << mean(igi) << ", path " << mean(path));
  CHECK(direct < 0.75 * mean(igi));  // a closed box: indirect light is a large part
  CHECK(mean(igi) < 1.01 * mean(path));
  // Default clamp (g_limit 20): the corners lose some light (documented bias: 3.2 % here, measured).
  CHECK(mean(igi) == Approx(mean(path)).epsilon(0.05));

  // Depth 1: igi has no VPL to use and is direct; depth 2: VPLs of the first bounce only, against path at depth 2.
  for (const int depth : {1, 2}) {
    RenderSettings p = settings(IntegratorKind::Path, 512);
    p.max_depth = depth;
    const Image path_d = render_box(*scene, p).image;
    RenderSettings g = settings(IntegratorKind::Igi, 16);
    g.max_depth = depth;
    g.vpl_sets = 16;
    g.light_paths = 256;
    g.g_limit = 1e4f;
    const Image igi_d = render_box(*scene, g).image;
    RenderSettings d = settings(IntegratorKind::Direct, 64);
    d.max_depth = depth;
    const Image direct_d = render_box(*scene, d).image;
    INFO("depth " << depth << ": path " << mean(path_d) << ", igi " << mean(igi_d) << ", direct " << mean(direct_d)
                  << ", worst igi tile " << max_tile_error(igi_d, path_d));
    CHECK(mean(igi_d) == Approx(mean(path_d)).epsilon(0.02));
    CHECK(max_tile_error(igi_d, path_d) < 0.05);
    if (depth == 1) CHECK(mean(direct_d) == Approx(mean(path_d)).epsilon(0.02));
  }
}

TEST_CASE("igi gives a bitwise identical image at 1 and 2 threads", "[render][igi][determinism]") {
  const auto scene = cornell_like();
  RenderSettings s = settings(IntegratorKind::Igi, 4);
  s.width = 40;
  s.height = 24;
  s.vpl_sets = 3;
  s.light_paths = 32;
  s.filter = Filter::mitchell();
  check_thread_determinism(*scene, box_camera(), s);
}

TEST_CASE("igi settings are validated", "[render][igi]") {
  const auto scene = cornell_like();
  RenderSettings s = settings(IntegratorKind::Igi, 1);
  s.vpl_sets = 0;
  CHECK_THROWS(render_box(*scene, s));
  s = settings(IntegratorKind::Igi, 1);
  s.g_limit = 0;
  CHECK_THROWS(render_box(*scene, s));
  s = settings(IntegratorKind::Igi, 1);
  s.vpl_roulette = 1.5f;
  CHECK_THROWS(render_box(*scene, s));
}

namespace {
// Root-mean-square pixel error (channel average) relative to the reference's mean.
double relative_rmse(const Image& a, const Image& reference) {
  double s = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const double d = a.pixels[i].average() - reference.pixels[i].average();
    s += d * d;
  }
  return std::sqrt(s / double(a.pixels.size())) / mean(reference);
}

// Median over pixels of |a - reference| in luminance, relative to the reference's mean luminance: the noise of a
// typical pixel, blind to the few pixels (corners) where the clamp's bias or a VPL spike would dominate an RMS.
double median_error(const Image& a, const Image& reference) {
  std::vector<double> d;
  double ref_sum = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    d.push_back(std::fabs(double(a.pixels[i].luminance()) - reference.pixels[i].luminance()));
    ref_sum += reference.pixels[i].luminance();
  }
  std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(d.size() / 2), d.end());
  return d[d.size() / 2] / (ref_sum / double(d.size()));
}
}  // namespace

TEST_CASE("igi with its defaults is consistent: its error against path falls with spp", "[render][igi]") {
  // Issue 23's acceptance (bench/igi_convergence.lua on the Cornell box) at 32x32: VPL families are drawn afresh
  // per sample index (render/vpl.h), so against a path reference the median pixel error at 64 spp must be at most
  // 0.6x that at 8 spp (noise alone: 1/sqrt(8) = 0.35, plus the reference's noise and the clamp's bias). With
  // one VPL family for every sample the VPLs' error is the same in every sample and the ratio stays near 1.
  const auto scene = cornell_like();
  // The reference's own median pixel error must stay well below igi's at 64 spp (with 1024 spp it was about 0.9 %,
  // half of igi's): 16384 spp (2048 in sanitizer builds), of another seed than igi's, so that the two do not share
  // camera samples.
  const Image& path = path_reference();
  const Image igi8 = render_box(*scene, settings(IntegratorKind::Igi, 8)).image;
  const Image igi64 = render_box(*scene, settings(IntegratorKind::Igi, 64)).image;
  const double e8 = median_error(igi8, path), e64 = median_error(igi64, path);
  // Measured ratio 0.47 (0.36 to 0.47 over igi seeds 0 to 3); with one VPL family for every sample 0.91. At 64
  // spp the 8x8 tile means carry little noise (about 0.2 %), so they show the clamp's remaining bias (g_limit 20):
  // -2.1 % in the mean, 5.7 % in the worst tile; a 256-spp render of another seed measured -1.8 % and
  // 5.0 %, and with g_limit 1e4 it is within 0.6 % in every tile (-0.1 % in the mean).
  INFO("igi median pixel error against path: 8 spp " << e8 << ", 64 spp " << e64 << " (ratio " << e64 / e8
                                                     << "); igi 64 spp against path: mean "
                                                     << mean(igi64) / mean(path) - 1 << ", worst tile "
                                                     << max_tile_error(igi64, path));
  CHECK(e64 <= 0.6 * e8);
  CHECK(max_tile_error(igi64, path) < 0.07);
  CHECK(std::fabs(mean(igi64) / mean(path) - 1) < 0.03);
}

TEST_CASE("igi with a loose clamp converges to path as spp grows", "[render][igi]") {
  // Without the clamp's bias, igi's error against path itself falls with spp (measured on this box: pixel RMSE
  // 7.0 % at 8 spp, 3.7 % at 64; path 1024 spp against another seed: 2.1 %).
  const auto scene = cornell_like();
  const Image& path = path_reference();
  RenderSettings s = settings(IntegratorKind::Igi, 8);
  s.g_limit = 1e4f;
  const double e8 = relative_rmse(render_box(*scene, s).image, path);
  s.spp = 64;
  const double e64 = relative_rmse(render_box(*scene, s).image, path);
  INFO("igi rmse against path: 8 spp " << e8 << ", 64 spp " << e64);
  CHECK(e64 <= 0.6 * e8);
}
