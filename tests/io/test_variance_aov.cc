// The "variance" AOV (render/aov_pass.h): each pixel's mean-luminance variance from the film's moments, as a
// layer of the saved image; exact zero where every sample sees the same radiance, falling as 1/spp elsewhere, and
// a one-line error for integrators that splat light into other pixels.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "aov_support.h"

using namespace torte;
using namespace torte::test;

namespace {

// A matte sphere on a floor under a small sphere light, the sky uniform (one value for every sample).
const char kScene[] = R"(
local opt = torte.options{output = "x.exr", spp = 8, integrator = "path"}
local scene = torte.scene()
local m = torte.material.matte{color = {0.7, 0.7, 0.7}}
scene:add(torte.shape.sphere{radius = 0.5, material = m})
scene:add(torte.shape.cube{transform = torte.translate(0, -0.6, 0) * torte.scale(3, 0.1, 3), material = m})
scene:add(torte.shape.sphere{radius = 0.2, material = torte.material.matte{color = {0, 0, 0}},
                             emission = {30, 30, 30}, transform = torte.translate(1, 2, -1)})
scene:add(torte.light.infinite{radiance = {0.2, 0.2, 0.2}})
local camera = torte.camera.perspective{eye = {0, 0.3, -3}, look_at = {0, 0, 0}, fov = 60}
local img = torte.render{scene = scene, camera = camera, width = 32, height = 24, spp = opt.spp,
                         integrator = opt.integrator, aovs = {"variance"}}
torte.save(img, opt.output)
)";

}  // namespace

TEST_CASE("variance aov: the film's per-pixel variance, zero where samples agree, falling as 1/spp", "[aov][cli]") {
  TempDir dir("variance", "aov");
  const std::string script = dir.write("s.lua", kScene);
  const auto render = [&](int spp, const std::string& name) {
    return rendered_layer(dir, {script, "spp=" + std::to_string(spp), "output=" + (dir / name)}, dir / name,
                          "variance", {"Y"});
  };
  const ImageLayer v8 = render(8, "a.exr"), v32 = render(32, "b.exr");
  // The top row sees only the sky: every sample the same radiance, so no variance at all.
  for (int x = 0; x < 32; ++x) CHECK(v8.values[size_t(x)] == 0);
  double s8 = 0, s32 = 0;
  for (size_t i = 0; i < v8.values.size(); ++i) {
    REQUIRE(v8.values[i] >= 0);
    REQUIRE(std::isfinite(v8.values[i]));
    s8 += v8.values[i], s32 += v32.values[i];
  }
  INFO("summed variance at 8 spp " << s8 << ", at 32 spp " << s32);
  CHECK(s8 > 0);
  // Four times the samples: a quarter of the variance of the mean (the sum over 768 pixels varies by far less).
  CHECK(s32 / s8 == Approx(0.25).epsilon(0.3));

  SECTION("integrators that splat light into other pixels are refused, naming the key") {
    const std::string lt = check_error(run_torte(dir, {script, "integrator=lt"}, 30));
    CHECK_THAT(lt, Catch::Contains("aovs"));
    CHECK_THAT(lt, Catch::Contains("\"variance\" needs a camera integrator"));
    CHECK_THAT(lt, Catch::Contains("s.lua"));
  }
}
