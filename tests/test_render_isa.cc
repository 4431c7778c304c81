// The render loop's per-ISA copies (render/render_isa.h): each copy this CPU runs renders the material room (every
// shaded material type, area and point lights) deterministically at 1 and 2 threads, and agrees with the
// baseline copy within noise (FMA rounds differently, so not bitwise); Highway's forced targets pick the copy.
#include <hwy/targets.h>
#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <string>

#include "material_room.h"
#include "render/render_isa.h"
#include "scene_helpers.h"

using namespace torte;

namespace {

double channel(const Rgb& p, int c) { return c == 0 ? p.r : c == 1 ? p.g : p.b; }

Image render_with(const render_isa::Variant& v, const Scene& scene, const RenderSettings& s, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  const Camera camera(test::material_room_camera(), s.width, s.height);
  return v.entry(scene, camera, s, nullptr, nullptr).image;
}

// Tiles (8x8, per channel) where the mean of the pixel differences a - b is further from 0 than 4 standard
// errors (from the spread of the differences, in which the image's own structure cancels) plus 1 %.
int tile_outliers(const Image& a, const Image& b) {
  int outliers = 0;
  for (int y0 = 0; y0 < a.height; y0 += 8)
    for (int x0 = 0; x0 < a.width; x0 += 8)
      for (int c = 0; c < 3; ++c) {
        double sd = 0, qd = 0, sb = 0;
        int n = 0;
        for (int y = y0; y < std::min(y0 + 8, a.height); ++y)
          for (int x = x0; x < std::min(x0 + 8, a.width); ++x, ++n) {
            const double d = channel(a.at(x, y), c) - channel(b.at(x, y), c);
            sd += d, qd += d * d, sb += channel(b.at(x, y), c);
          }
        const double md = sd / n, se = std::sqrt(std::max(0.0, qd / n - md * md) / n);
        if (std::fabs(md) > 4 * se + 0.01 * std::fabs(sb / n) + 1e-5) ++outliers;
      }
  return outliers;
}

}  // namespace

TEST_CASE("every render ISA copy this CPU runs is deterministic and agrees with the baseline", "[render][isa]") {
  const auto scene = test::material_room();
  RenderSettings s;
  s.width = s.height = 32;
  s.spp = 32;
  s.max_depth = 8;
  const auto variants = render_isa::supported();
  REQUIRE(std::string(variants.front().name) == "baseline");
  const Image base = render_with(variants.front(), *scene, s, 1);
  for (const render_isa::Variant& v : variants) {
    INFO("render ISA " << v.name);
    const Image one = render_with(v, *scene, s, 1), two = render_with(v, *scene, s, 2);
    REQUIRE(one.pixels.size() == two.pixels.size());
    CHECK(std::memcmp(one.pixels.data(), two.pixels.data(), one.pixels.size() * sizeof(Rgb)) == 0);
    CHECK(tile_outliers(one, base) == 0);
  }
  SECTION("and the comparison can fail: a 5 % darker image is detected") {
    Image dark = base;
    for (Rgb& p : dark.pixels) p = p * 0.95f;
    CHECK(tile_outliers(dark, base) > 0);
  }
}

TEST_CASE("render() runs the best copy that Highway's dispatch allows", "[render][isa]") {
  struct Restore {
    ~Restore() { hwy::SetSupportedTargetsForTest(0); }
  } restore;
  const std::string best = render_isa::supported().back().name;
  CHECK(std::string(render_isa::selected_name()) == best);
#if HWY_ARCH_X86
  // A target without AVX2 (when Highway compiled one in) forces the baseline copy.
  if constexpr ((HWY_TARGETS & HWY_SSE4) != 0) {
    hwy::SetSupportedTargetsForTest(HWY_SSE4);
    CHECK(std::string(render_isa::selected_name()) == "baseline");
    CHECK(render_isa::supported().size() == 1);
  }
#endif
}
