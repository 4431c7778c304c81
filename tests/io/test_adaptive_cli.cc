// Adaptive sampling and time limits from scripts and the command line: noise_threshold, time_limit, their
// --noise-threshold/--time-limit overrides, the summary's spp distribution, the "samples" layer, the image fields
// and the one-line errors.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "film/image_io.h"
#include "test_support.h"

using namespace torte;
using namespace torte::test;

namespace {

// A matte sphere on a bright floor under a small light: the floor converges fast, the sphere's shadow does not.
const char kScene[] = R"(
local opt = torte.options{output = "x.exr", spp = 64, noise_threshold = 0.05, integrator = "path", time_limit = 0}
local scene = torte.scene()
local m = torte.material.matte{color = {0.7, 0.7, 0.7}}
scene:add(torte.shape.sphere{radius = 0.5, material = m})
scene:add(torte.shape.cube{transform = torte.translate(0, -0.6, 0) * torte.scale(3, 0.1, 3), material = m})
scene:add(torte.shape.sphere{radius = 0.2, material = torte.material.matte{color = {0, 0, 0}},
                             emission = {30, 30, 30}, transform = torte.translate(1, 2, -1)})
local camera = torte.camera.perspective{eye = {0, 1, -3}, look_at = {0, 0, 0}, fov = 45}
local img = torte.render{scene = scene, camera = camera, width = 32, height = 24, spp = opt.spp,
                         integrator = opt.integrator, noise_threshold = opt.noise_threshold,
                         time_limit = opt.time_limit, aovs = {"samples"}}
print(string.format("spp:%d samples:%d time_limited:%s", img.spp, img.samples, tostring(img.time_limited)))
torte.save(img, opt.output)
)";

}  // namespace

TEST_CASE("adaptive cli: noise_threshold spreads samples, prints them and maps them as a layer", "[adaptive][cli]") {
  TempDir dir("adaptive", "cli");
  const std::string script = dir.write("s.lua", kScene);
  const Result r = run_torte(dir, {script, "output=" + (dir / "a.exr")}, 120);
  check_no_crash(r);
  INFO("stderr: " << r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains("adaptive sampling (noise_threshold 0.05): spp per pixel min"));
  CHECK_THAT(r.out, Catch::Contains("spp:64"));
  CHECK_THAT(r.out, Catch::Contains("time_limited:false"));
  const Image img = read_image(dir / "a.exr");
  const ImageLayer* samples = img.layer("samples");
  REQUIRE(samples);
  CHECK(samples->channels == std::vector<std::string>{"X"});
  const auto [lo, hi] = std::minmax_element(samples->values.begin(), samples->values.end());
  CHECK(*lo >= 16);
  CHECK(*hi == 64);
  CHECK(*lo < *hi);
  double total = 0;
  for (const float v : samples->values) total += v;
  CHECK_THAT(r.out, Catch::Contains("samples:" + std::to_string(uint64_t(total))));

  SECTION("--noise-threshold 0 turns it off: every pixel takes every sample") {
    const Result off = run_torte(dir, {"--noise-threshold", "0", script, "output=" + (dir / "b.exr")}, 120);
    check_no_crash(off);
    REQUIRE(off.code == 0);
    CHECK_THAT(off.err, !Catch::Contains("adaptive sampling"));
    CHECK_THAT(off.out, Catch::Contains("samples:" + std::to_string(32 * 24 * 64)));
    const Image b = read_image(dir / "b.exr");
    REQUIRE(b.layer("samples"));
    for (const float v : b.layer("samples")->values) REQUIRE(v == 64);
  }
  SECTION("--time-limit stops at a pass boundary and says so") {
    const Result t = run_torte(dir, {"--time-limit", "0.000001", script, "spp=100000", "noise_threshold=0",
                                     "output=" + (dir / "t.exr")}, 120);
    check_no_crash(t);
    INFO("stderr: " << t.err);
    REQUIRE(t.code == 0);
    CHECK_THAT(t.err, Catch::Contains("time_limit"));
    CHECK_THAT(t.err, Catch::Contains("reached: stopped after 1 of 100000 spp"));
    CHECK_THAT(t.out, Catch::Contains("time_limited:true"));
    CHECK_THAT(t.out, Catch::Contains("spp:1 "));
    CHECK(read_image(dir / "t.exr").width == 32);
  }
  SECTION("errors are one line naming the key") {
    const std::string bdpt = check_error(run_torte(dir, {script, "integrator=bdpt"}, 30));
    CHECK_THAT(bdpt, Catch::Contains("noise_threshold"));
    CHECK_THAT(bdpt, Catch::Contains("bdpt"));
    CHECK_THAT(bdpt, Catch::Contains("s.lua"));
    const std::string negative = check_error(run_torte(dir, {script, "time_limit=-2"}, 30));
    CHECK_THAT(negative, Catch::Contains("time_limit"));
    const std::string cli = check_error(run_torte(dir, {"--noise-threshold", "lots", script}, 30));
    CHECK_THAT(cli, Catch::Contains("--noise-threshold"));
    const std::string over = check_error(run_torte(dir, {"--noise-threshold", "0.1", script, "integrator=lt",
                                                         "noise_threshold=0"}, 30));
    CHECK_THAT(over, Catch::Contains("noise_threshold"));
  }
}
