// AOVs and denoising from scripts and the command line: torte.render{aovs, denoise}, --aovs, --denoise,
// image.layers / image:layer, torte.denoise, and the layers of a multi-layer EXR read back.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "film/image_io.h"
#include "test_support.h"

using namespace torte;
using namespace torte::test;

namespace {

const char kScene[] = R"(
local opt = torte.options{output = "x.exr", aovs = "", denoise = false}
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1, material = torte.material.matte{color = {0.8, 0.3, 0.2}}})
scene:add(torte.light.infinite{radiance = {0.25, 0.25, 0.25}})
local camera = torte.camera.perspective{eye = {0, 0, -4}, look_at = {0, 0, 0}, fov = 40}
local aovs = {}
for name in opt.aovs:gmatch("[^,]+") do aovs[#aovs + 1] = name end
local img = torte.render{scene = scene, camera = camera, width = 24, height = 16, spp = 4, aovs = aovs,
                         denoise = opt.denoise}
print("layers:" .. table.concat(img.layers, ","))
torte.save(img, opt.output)
)";

}  // namespace

TEST_CASE("aov cli: aovs become EXR layers that read back, in script and command line", "[aov][cli]") {
  TempDir dir("aov", "layers");
  const std::string script = dir.write("s.lua", kScene);
  const Result r = run_torte(dir, {"--quiet", script, "aovs=albedo,depth", "output=" + (dir / "a.exr")}, 60);
  check_no_crash(r);
  INFO("stderr: " << r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("layers:albedo,depth"));
  const Image img = read_image(dir / "a.exr");
  REQUIRE(img.layer("albedo"));
  REQUIRE(img.layer("depth"));
  CHECK(img.layer("albedo")->channels == std::vector<std::string>{"R", "G", "B"});
  CHECK(img.layer("depth")->channels == std::vector<std::string>{"Z"});
  // The centre looks at the matte sphere: its colour is the albedo there.
  const size_t centre = size_t(8) * 24 + 12;
  CHECK(img.layer("albedo")->at(centre)[0] == Approx(0.8f).margin(1e-4));
  CHECK(img.layer("albedo")->at(centre)[2] == Approx(0.2f).margin(1e-4));
  CHECK(img.layer("depth")->at(centre)[0] == Approx(3).margin(0.02));

  SECTION("--aovs adds layers to every render") {
    const Result r2 = run_torte(dir, {"--quiet", "--aovs", "normal,material_id", script, "aovs=albedo",
                                      "output=" + (dir / "b.exr")}, 60);
    check_no_crash(r2);
    REQUIRE(r2.code == 0);
    CHECK_THAT(r2.out, Catch::Contains("layers:albedo,normal,material_id"));
    const Image b = read_image(dir / "b.exr");
    CHECK(b.layer("normal"));
    CHECK(b.layer("material_id"));
  }
  SECTION("denoise = true and --denoise keep the noisy image as a layer") {
    const Result r3 = run_torte(dir, {"--quiet", "--denoise", script, "output=" + (dir / "d.exr")}, 60);
    check_no_crash(r3);
    REQUIRE(r3.code == 0);
    CHECK_THAT(r3.out, Catch::Contains("noisy"));
    const Image d = read_image(dir / "d.exr");
    REQUIRE(d.layer("noisy"));
    CHECK(d.layer("albedo"));
  }
  SECTION("bad names are one error line") {
    const std::string line = check_error(run_torte(dir, {"--quiet", script, "aovs=albedo,roughness"}, 30));
    CHECK_THAT(line, Catch::Contains("aovs"));
    CHECK_THAT(line, Catch::Contains("roughness"));
    CHECK_THAT(line, Catch::Contains("s.lua"));
    const std::string cli = check_error(run_torte(dir, {"--aovs", "albedo,", script}, 30));
    CHECK_THAT(cli, Catch::Contains("--aovs"));
  }
}

TEST_CASE("aov cli: image:layer, torte.denoise and their errors", "[aov][cli]") {
  TempDir dir("aov", "lua");
  const std::string script = dir.write("s.lua", R"(
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1, material = torte.material.matte{color = {0.8, 0.3, 0.2}}})
scene:add(torte.light.point{position = {2, 3, -3}, intensity = 20})
local camera = torte.camera.perspective{eye = {0, 0, -4}, look_at = {0, 0, 0}, fov = 40}
local img = torte.render{scene = scene, camera = camera, width = 16, height = 16, spp = 4,
                         aovs = {"albedo", "normal", "depth"}}
local albedo = img:layer("albedo")
local r, g, b = albedo:pixel(8, 8)
assert(math.abs(r - 0.8) < 1e-4 and math.abs(b - 0.2) < 1e-4, "albedo layer as an image")
local d = torte.denoise(img, {strength = 2})
assert(#d.layers == 4 and d.layers[4] == "noisy", "denoised image keeps features and adds noisy")
local ok, err = pcall(function() return img:layer("specular") end)
assert(not ok and err:find("has no layer 'specular'") and err:find("albedo, normal, depth"), err)
local plain = torte.render{scene = scene, camera = camera, width = 8, height = 8, spp = 1}
ok, err = pcall(torte.denoise, plain)
assert(not ok and err:find("no 'albedo' layer"), err)
ok, err = pcall(torte.denoise, img, {strength = -1})
assert(not ok and err:find("strength"), err)
print("ok")
)");
  const Result r = run_torte(dir, {"--quiet", script}, 60);
  check_no_crash(r);
  INFO("stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("ok"));
}
