// View transforms of display outputs (film/view_transform.h: standard sRGB and ACES filmic through OpenColorIO,
// AgX's analytic fit), --exposure/--tonemap and image:write's tonemap key, and the render attributes an EXR
// header records (lua/render_metadata.h).
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "film/image_io.h"
#include "film/view_transform.h"
#include "test_support.h"

using namespace torte;
using namespace torte::test;

namespace {

// Display values of a row of pixels.
std::vector<float> display(ViewTransform view, const std::vector<Rgb>& pixels, float exposure = 0) {
  Image image(int(pixels.size()), 1);
  image.pixels = pixels;
  std::vector<float> out;
  apply_view_transform(view, exposure, image, out);
  REQUIRE(out.size() == 3 * pixels.size());
  return out;
}

// A grey ramp from 2^-12 to 2^8 in quarter stops.
std::vector<Rgb> grey_ramp() {
  std::vector<Rgb> p;
  for (int q = -48; q <= 32; ++q) p.emplace_back(std::exp2(q / 4.0f));
  return p;
}

constexpr ViewTransform kAll[] = {ViewTransform::Standard, ViewTransform::Filmic, ViewTransform::Agx};

}  // namespace

TEST_CASE("view transform: standard is the sRGB encoding of the clamped value", "[view]") {
  std::vector<Rgb> p;
  for (int i = 0; i <= 240; ++i) p.emplace_back(i / 200.0f, i / 400.0f, i / 1000.0f);
  const std::vector<float> d = display(ViewTransform::Standard, p);
  for (size_t i = 0; i < p.size(); ++i) {
    INFO("pixel " << i);
    CHECK(d[3 * i] == Approx(linear_to_srgb(p[i].r)).margin(2e-4));
    CHECK(d[3 * i + 1] == Approx(linear_to_srgb(p[i].g)).margin(2e-4));
    CHECK(d[3 * i + 2] == Approx(linear_to_srgb(p[i].b)).margin(2e-4));
  }
  SECTION("exposure scales by 2^stops before the encoding") {
    const std::vector<float> e = display(ViewTransform::Standard, {Rgb(0.1f)}, 1.5f);
    CHECK(e[0] == Approx(linear_to_srgb(0.1f * std::exp2(1.5f))).margin(2e-4));
  }
}

TEST_CASE("view transform: every view maps black to black, greys to greys, increasing, into [0, 1]", "[view]") {
  const std::vector<Rgb> ramp = grey_ramp();
  for (ViewTransform v : kAll) {
    INFO(view_transform_name(v));
    const std::vector<float> d = display(v, ramp);
    for (size_t i = 0; i < ramp.size(); ++i) {
      INFO("grey " << ramp[i].r);
      CHECK(d[3 * i] >= 0);
      CHECK(d[3 * i] <= 1);
      CHECK(std::fabs(d[3 * i] - d[3 * i + 1]) < 2e-3f);  // neutral stays neutral
      CHECK(std::fabs(d[3 * i] - d[3 * i + 2]) < 2e-3f);
      if (i > 0) CHECK(d[3 * i] >= d[3 * (i - 1)] - 1e-6f);
    }
    CHECK(display(v, {Rgb(0)})[0] < 0.02f);
    const std::vector<float> bad = display(v, {Rgb(NAN, 1, 1), Rgb(INFINITY), Rgb(-1)});
    CHECK(bad[0] == display(v, {Rgb(0)})[0]);  // non-finite pixels are black
    CHECK(bad[3] == bad[0]);
    CHECK(bad[6] == bad[0]);  // negative light shows as black
  }
}

TEST_CASE("view transform: filmic and agx roll highlights off where standard clips", "[view]") {
  const std::vector<Rgb> bright = {Rgb(1.0f), Rgb(2.0f), Rgb(4.0f), Rgb(8.0f)};
  const std::vector<float> s = display(ViewTransform::Standard, bright);
  CHECK(s[3] == 1.0f);  // standard: everything above 1 is white
  CHECK(s[9] == 1.0f);
  for (ViewTransform v : {ViewTransform::Filmic, ViewTransform::Agx}) {
    INFO(view_transform_name(v));
    const std::vector<float> d = display(v, bright);
    CHECK(d[3] < 0.98f);         // 2 is not yet white
    CHECK(d[9] > d[6] + 0.005f);  // and 8 is still brighter than 4
    // Mid grey lands in the middle of the display range (ACES darker than AgX).
    const float mid = display(v, {Rgb(0.18f)})[0];
    CHECK(mid > 0.3f);
    CHECK(mid < 0.55f);
  }
  SECTION("agx desaturates a very bright saturated colour towards white") {
    const std::vector<float> red = display(ViewTransform::Agx, {Rgb(64, 0.5f, 0.5f)});
    CHECK(red[0] > 0.95f);
    CHECK(red[1] > 0.6f);  // standard would show (1, 0.74, 0.74) only by clipping red; agx lifts green and blue
    CHECK(red[1] == Approx(red[2]).margin(0.02));
  }
}

TEST_CASE("view transform: --tonemap and --exposure on the command line and the tonemap key of image:write",
          "[view][cli]") {
  TempDir dir("view", "cli");
  const std::string script = dir.write("s.lua", R"(
local opt = torte.options{output = "x.exr", tonemap = "standard"}
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1, material = torte.material.matte{color = {0.8, 0.3, 0.2}}})
scene:add(torte.light.point{position = {2, 3, -3}, intensity = 200})
local camera = torte.camera.perspective{eye = {0, 0, -4}, look_at = {0, 0, 0}, fov = 40}
local img = torte.render{scene = scene, camera = camera, width = 16, height = 16, spp = 4}
torte.save(img, opt.output, {tonemap = opt.tonemap})
)");
  const auto render = [&](const std::vector<std::string>& args) {
    const Result r = run_torte(dir, args, 60);
    check_no_crash(r);
    INFO("stderr: " << r.err);
    REQUIRE(r.code == 0);
  };
  render({"--quiet", script, "output=" + (dir / "standard.exr")});
  render({"--quiet", script, "output=" + (dir / "agx.exr"), "tonemap=agx"});
  render({"--quiet", "--tonemap", "agx", script, "output=" + (dir / "agx_cli.png")});
  render({"--quiet", "--tonemap", "filmic", "--exposure", "-1", script, "output=" + (dir / "filmic.png")});
  const std::string standard = read_file(dir / "standard.png"), agx = read_file(dir / "agx.png");
  CHECK(standard != agx);
  CHECK(read_image(dir / "agx.png").pixels == read_image(dir / "agx_cli.png").pixels);
  CHECK(read_image(dir / "filmic.png").pixels != read_image(dir / "agx.png").pixels);
  // The EXR beside a PNG stays linear whatever the view.
  CHECK(read_image(dir / "standard.exr").pixels == read_image(dir / "agx.exr").pixels);

  SECTION("the EXR header records the render") {
    const std::string header = read_file(dir / "standard.exr").substr(0, 4096);
    for (const char* name : {"torte:spp", "torte:integrator", "torte:seed", "torte:render_seconds", "torte:camera",
                             "torte:simd_target", "torte:max_depth", "worldToCamera", "Software"}) {
      INFO(name);
      CHECK(header.find(std::string(name) + '\0') != std::string::npos);
    }
    CHECK(header.find("perspective fov 40") != std::string::npos);
    CHECK(header.find("torte ") != std::string::npos);
    CHECK(header.find(std::string("path")) != std::string::npos);
  }
  SECTION("bad values are one error line naming the option or key") {
    CHECK_THAT(check_error(run_torte(dir, {"--tonemap", "reinhard", script}, 30)), Catch::Contains("'reinhard'"));
    CHECK_THAT(check_error(run_torte(dir, {"--exposure", "lots", script}, 30)), Catch::Contains("--exposure"));
    CHECK_THAT(check_error(run_torte(dir, {"--exposure", "nan", script}, 30)), Catch::Contains("--exposure"));
    const std::string line =
        check_error(run_torte(dir, {"--quiet", script, "tonemap=filmik", "output=" + (dir / "b.png")}, 30));
    CHECK_THAT(line, Catch::Contains("tonemap"));
    CHECK_THAT(line, Catch::Contains("filmik"));
    CHECK_THAT(line, Catch::Contains("s.lua"));
  }
}

TEST_CASE("output: EXR and PNG are written without OpenImageIO and keep the render's metadata", "[view][cli]") {
  TempDir dir("view", "writers");
  // The script looks at its own process after saving: the writing module only, not OpenImageIO's ~250 libraries
  // (~120 MB resident, image_module.h).
  const std::string script = dir.write("s.lua", R"(
local opt = torte.options{output = "x.exr"}
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1, material = torte.material.matte{color = {0.8, 0.3, 0.2}}})
scene:add(torte.light.point{position = {2, 3, -3}, intensity = 200})
local camera = torte.camera.perspective{eye = {0, 0, -4}, look_at = {0, 0, 0}, fov = 40}
local img = torte.render{scene = scene, camera = camera, width = 16, height = 12, spp = 2, aovs = {"albedo", "depth"}}
torte.save(img, opt.output)
local maps = io.open("/proc/self/maps"):read("a")
print("oiio " .. tostring(maps:find("libOpenImageIO", 1, true) ~= nil))
print("writer " .. tostring(maps:find("libtorte_write", 1, true) ~= nil))
)");
  const std::string exr = dir / "out.exr";
  const Result r = run_torte(dir, {"--quiet", script, "output=" + exr}, 60);
  check_no_crash(r);
  INFO("stderr: " << r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("oiio false"));
  CHECK_THAT(r.out, Catch::Contains("writer true"));
  // Read back through OpenImageIO: the layers as channels, the settings as typed attributes, text in the PNG.
  const Image back = read_image(exr);
  CHECK(back.width == 16);
  REQUIRE(back.layers.size() == 2);
  CHECK(back.layers[0].name == "albedo");
  CHECK(back.layers[0].channels == std::vector<std::string>{"R", "G", "B"});
  CHECK(back.layers[1].name == "depth");
  const std::string header = read_file(exr).substr(0, 4096);
  CHECK(header.find(std::string("torte:spp") + '\0' + "int") != std::string::npos);
  CHECK(header.find(std::string("torte:render_seconds") + '\0' + "float") != std::string::npos);
  CHECK(header.find(std::string("worldToCamera") + '\0' + "m44f") != std::string::npos);
  CHECK(header.find(std::string("compression") + '\0' + "compression") != std::string::npos);
  const std::string png = read_file(dir / "out.png");
  CHECK(png.find("sRGB") != std::string::npos);
  CHECK(png.find(std::string("tEXtSoftware") + '\0' + "torte ") != std::string::npos);
  CHECK(png.find(std::string("tEXttorte:integrator") + '\0' + "path") != std::string::npos);
}
