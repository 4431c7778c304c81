// The torte command line, end to end: runs the built binary (TORTE_BINARY) on small scripts written to a temp
// directory and checks exit codes, the one-line "torte: error:" messages, scene arguments, --spp, image files
// and Ctrl-C.
#include <catch2/catch.hpp>

#include <signal.h>

#include <chrono>
#include <filesystem>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "test_support.h"

namespace fs = std::filesystem;
using namespace torte::test;

namespace {

// Runs torte to the end, failing the test case after `timeout` seconds.
Result run(const TempDir& dir, const std::vector<std::string>& args, double timeout = 30) {
  return run_torte(dir, args, timeout);
}

// A fresh temp directory for a test case of this file.
struct CliDir : TempDir {
  explicit CliDir(const std::string& name) : TempDir("cli", name) {}
};

// A command-line usage error: one line like any error, ending with a pointer to --help.
std::string check_usage_error(const Result& r) {
  const std::string line = check_error(r);
  CHECK_THAT(line, Catch::EndsWith("(see 'torte --help')"));
  return line;
}

// A scene of nothing the camera can see, lit by a uniform sky: every camera ray misses, so the image is the sky
// colour and the ray count is exactly width * height * spp.
const char kSkyScene[] = R"(
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1, transform = torte.translate(0, 0, -10)})  -- behind the camera
scene:add(torte.light.infinite{radiance = {0.25, 0.5, 1}})
local camera = torte.camera.perspective{eye = {0, 0, 0}, look_at = {0, 0, 1}}
)";

}  // namespace

TEST_CASE("cli: a Lua syntax error names the script file and line", "[cli]") {
  CliDir dir("syntax");
  const std::string script = dir.write("syntax.lua", "local a = 1\nlocal b = = 2\n");
  const std::string line = check_error(run(dir, {script}));
  CHECK_THAT(line, Catch::Contains(script + ":2:"));
}

TEST_CASE("cli: an unknown keyword key names the key, the script file and line", "[cli]") {
  CliDir dir("unknown_key");
  const std::string script = dir.write("typo.lua", "local torte = require 'torte'\n\nlocal s = torte.shape.sphere{radis = 1}\n");
  const std::string line = check_error(run(dir, {script}));
  CHECK_THAT(line, Catch::Contains(script + ":3:"));
  CHECK_THAT(line, Catch::Contains("torte.shape.sphere"));
  CHECK_THAT(line, Catch::Contains("'radis'"));
  CHECK_THAT(line, Catch::Contains("radius"));  // the accepted keys are listed
}

TEST_CASE("cli: a keyword value of the wrong type names the key", "[cli]") {
  CliDir dir("wrong_type");
  const std::string script = dir.write("type.lua", "local s = torte.shape.sphere{radius = 'big'}\n");
  const std::string line = check_error(run(dir, {script}));
  CHECK_THAT(line, Catch::Contains(script + ":1:"));
  CHECK_THAT(line, Catch::Contains("'radius'"));
  CHECK_THAT(line, Catch::Contains("number"));
}

TEST_CASE("cli: a missing required key names it", "[cli]") {
  CliDir dir("required");
  const std::string script = dir.write("required.lua", "-- no position\nlocal l = torte.light.point{intensity = 1}\n");
  const std::string line = check_error(run(dir, {script}));
  CHECK_THAT(line, Catch::Contains(script + ":2:"));
  CHECK_THAT(line, Catch::Contains("'position'"));
  CHECK_THAT(line, Catch::Contains("required"));
}

TEST_CASE("cli: errors raised by scripts are one line", "[cli]") {
  CliDir dir("script_error");
  SECTION("a multi-line message") {
    const std::string script = dir.write("multi.lua", "error('first line\\nsecond line')\n");
    const std::string line = check_error(run(dir, {script}));
    CHECK_THAT(line, Catch::Contains(script + ":1:"));
    CHECK_THAT(line, Catch::Contains("first line"));
    CHECK_THAT(line, Catch::Contains("second line"));
  }
  SECTION("a non-string error value") {
    const std::string script = dir.write("table.lua", "error({})\n");
    check_error(run(dir, {script}));
  }
  SECTION("a runtime error in plain Lua") {
    const std::string script = dir.write("nil.lua", "local t = nil\nprint(t.x)\n");
    const std::string line = check_error(run(dir, {script}));
    CHECK_THAT(line, Catch::Contains(script + ":2:"));
  }
}

TEST_CASE("cli: a missing script file is named", "[cli]") {
  CliDir dir("missing");
  const std::string script = dir / "does-not-exist.lua";
  const std::string line = check_error(run(dir, {script}));
  CHECK_THAT(line, Catch::Contains("does-not-exist.lua"));
}

TEST_CASE("cli: --help and --version", "[cli]") {
  CliDir dir("help");
  SECTION("--help") {
    const Result r = run(dir, {"--help"});
    check_no_crash(r);
    CHECK(r.code == 0);
    CHECK_THAT(r.out, Catch::Contains("usage: torte"));
    CHECK_THAT(r.out, Catch::Contains("--spp"));
    CHECK(r.err.empty());
  }
  SECTION("--version") {
    const Result r = run(dir, {"--version"});
    check_no_crash(r);
    CHECK(r.code == 0);
    INFO("stdout: " << r.out);
    // The first line; the lines after it are tested in test_cli11.cc.
    CHECK(std::regex_match(r.out.substr(0, r.out.find('\n') + 1), std::regex("torte [0-9]+\\.[0-9]+(\\.[0-9]+)?.*\n")));
    CHECK(r.err.empty());
  }
  SECTION("the version is torte.version") {
    const std::string script =
        dir.write("version.lua", "assert(type(torte.version) == 'string' and #torte.version > 0)\n"
                                  "io.write(torte.version, '\\n')\n");
    const Result r = run(dir, {script});
    check_no_crash(r);
    CHECK(r.code == 0);
    const Result v = run(dir, {"--version"});
    CHECK(v.out.substr(0, v.out.find('\n') + 1) == "torte " + r.out);
  }
}

TEST_CASE("cli: command-line usage errors", "[cli]") {
  CliDir dir("usage");
  const std::string script = dir.write("ok.lua", "-- does nothing\n");
  SECTION("the script itself runs without errors") {
    const Result r = run(dir, {script});
    check_no_crash(r);
    CHECK(r.code == 0);
    CHECK(r.err.empty());
  }
  SECTION("an unknown option") {
    const std::string line = check_usage_error(run(dir, {"--bogus", script}));
    CHECK_THAT(line, Catch::Contains("'--bogus'"));
  }
  SECTION("a scene argument without '='") {
    const std::string line = check_usage_error(run(dir, {script, "width=3", "bad"}));
    CHECK_THAT(line, Catch::Contains("'bad'"));
  }
  SECTION("a scene argument with an empty key") {
    const std::string line = check_usage_error(run(dir, {script, "=3"}));
    CHECK_THAT(line, Catch::Contains("'=3'"));
  }
}

TEST_CASE("cli: bad option values and a missing script", "[cli]") {
  CliDir dir("usage_values");
  const std::string script = dir.write("ok.lua", "-- does nothing\n");
  SECTION("no script") {
    check_usage_error(run(dir, {}));
  }
  SECTION("--spp without a value") {
    const std::string line = check_usage_error(run(dir, {script, "--spp"}));
    // Options may follow the script (CLI11): this --spp lacks its value.
    CHECK_THAT(line, Catch::Contains("--spp"));
  }
  SECTION("--spp with a bad value") {
    const std::string line = check_usage_error(run(dir, {"--spp", "zero", script}));
    CHECK_THAT(line, Catch::Contains("--spp"));
    CHECK_THAT(line, Catch::Contains("'zero'"));
  }
  SECTION("--spp 0") {
    check_usage_error(run(dir, {"--spp", "0", script}));
  }
}

TEST_CASE("cli: torte.options rejects an unknown scene argument, naming it", "[cli]") {
  CliDir dir("options");
  const std::string script = dir.write("opts.lua",
                                        "local torte = require 'torte'\n"
                                        "local opt = torte.options{width = 8, name = 'x'}\n");
  SECTION("unknown argument") {
    const std::string line = check_error(run(dir, {script, "width=4", "widht=3"}));
    CHECK_THAT(line, Catch::Contains("'widht'"));
    CHECK_THAT(line, Catch::Contains(script + ":2:"));
    CHECK_THAT(line, Catch::Contains("width"));  // the accepted arguments are listed
  }
  SECTION("a non-number for a number argument") {
    const std::string line = check_error(run(dir, {script, "width=wide"}));
    CHECK_THAT(line, Catch::Contains("'width'"));
    CHECK_THAT(line, Catch::Contains("wide"));
  }
  SECTION("known arguments are accepted") {
    const Result r = run(dir, {script, "width=4", "name=y"});
    check_no_crash(r);
    CHECK(r.code == 0);
  }
}

TEST_CASE("cli: key=value arguments reach the script with Lua types", "[cli]") {
  CliDir dir("args");
  const std::string script = dir.write("args.lua", R"(
local args = ...
assert(args == torte.args, "the script's ... is torte.args")
assert(type(torte.args.n) == "number", "n is a " .. type(torte.args.n))
assert(torte.args.n == 3, "n is " .. tostring(torte.args.n))
assert(math.type(torte.args.n) == "integer")
assert(torte.args.x == 0.5)
assert(torte.args.flag == true and torte.args.off == false)
assert(torte.args.name == "hello" and type(torte.args.name) == "string")
assert(torte.args.path == "a=b", "the first '=' splits key from value")
assert(torte.args.empty == "")
local opt = torte.options{n = 1, x = 0, flag = false, off = true, name = "", path = "", empty = "z", extra = 7}
assert(opt.n == 3 and opt.extra == 7 and opt.flag == true and opt.empty == "")
)");
  SECTION("the expected values") {
    const Result r =
        run(dir, {script, "n=3", "x=0.5", "flag=true", "off=false", "name=hello", "path=a=b", "empty="});
    check_no_crash(r);
    INFO("stderr: " << r.err);
    CHECK(r.code == 0);
    CHECK(r.err.empty());
  }

  SECTION("a wrong value makes the script fail") {
    const std::string line = check_error(run(dir, {script, "n=4"}));
    CHECK_THAT(line, Catch::Contains("n is 4"));
  }
  SECTION("a value that is not a number stays a string") {
    const std::string line = check_error(run(dir, {script, "n=three"}));
    CHECK_THAT(line, Catch::Contains("n is a string"));
  }
}

TEST_CASE("cli: --spp overrides the script's samples per pixel", "[cli]") {
  CliDir dir("spp");
  const std::string script = dir.write("spp.lua", std::string(kSkyScene) + R"(
local opt = torte.options{expected_spp = 16}
local img = torte.render{scene = scene, camera = camera, width = 8, height = 8, spp = 16}
assert(img.width == 8 and img.height == 8, "size")
assert(img.rays == 8 * 8 * opt.expected_spp, "rays = " .. img.rays)
assert(img.dropped_samples == 0 and img.interrupted == false)
local r, g, b = img:mean()
assert(math.abs(r - 0.25) < 1e-4 and math.abs(g - 0.5) < 1e-4 and math.abs(b - 1) < 1e-4, "mean " .. r .. " " .. g .. " " .. b)
r, g, b = img:pixel(7, 0)
assert(math.abs(r - 0.25) < 1e-4 and math.abs(g - 0.5) < 1e-4 and math.abs(b - 1) < 1e-4, "pixel")
assert(type(img.render_seconds) == "number" and img.render_seconds >= 0)
assert(not pcall(img.pixel, img, 8, 0), "pixel outside the image")
)");
  SECTION("without --spp") {
    const Result r = run(dir, {"--quiet", script});
    check_no_crash(r);
    INFO("stderr: " << r.err);
    CHECK(r.code == 0);
    CHECK(r.err.empty());  // --quiet
  }
  SECTION("--spp 2") {
    const Result r = run(dir, {"--spp", "2", script, "expected_spp=2"});
    check_no_crash(r);
    INFO("stderr: " << r.err);
    CHECK(r.code == 0);
    CHECK_THAT(r.err, Catch::Contains("2 spp"));  // the summary
  }
  SECTION("the script's own assertion catches a wrong spp") {
    const std::string line = check_error(run(dir, {"--quiet", "--spp", "3", script}));
    CHECK_THAT(line, Catch::Contains("rays = 192"));
  }
}

TEST_CASE("cli: torte.save writes an EXR and a PNG beside it", "[cli]") {
  CliDir dir("save");
  const std::string script = dir.write("save.lua", R"(
local opt = torte.options{output = "x.exr"}
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1, material = torte.material.matte{color = {0.8, 0.3, 0.2}}})
scene:add(torte.light.point{position = {2, 3, -3}, intensity = 20})
local camera = torte.camera.perspective{eye = {0, 0, -4}, look_at = {0, 0, 0}, fov = 40}
local img = torte.render{scene = scene, camera = camera, width = 8, height = 8, spp = 2}
assert(torte.save(img, opt.output) == img)
local r = img:pixel(4, 4)
assert(r > 0, "the sphere is lit")
)");
  const std::string exr = dir / "sub/dir/tiny.exr", png = dir / "sub/dir/tiny.png";
  const Result r = run(dir, {script, "output=" + exr});
  check_no_crash(r);
  INFO("stderr: " << r.err);
  CHECK(r.code == 0);
  REQUIRE(fs::exists(exr));
  REQUIRE(fs::exists(png));
  CHECK(read_file(exr).substr(0, 4) == std::string("\x76\x2f\x31\x01", 4));  // OpenEXR magic
  CHECK(read_file(png).substr(0, 8) == std::string("\x89PNG\r\n\x1a\n", 8));
  CHECK_THAT(r.err, Catch::Contains("wrote " + exr));
  CHECK_THAT(r.err, Catch::Contains("wrote " + png));

  SECTION("a PNG output gets no second file") {
    const std::string only = dir / "only.png";
    const Result r2 = run(dir, {"--quiet", script, "output=" + only});
    check_no_crash(r2);
    CHECK(r2.code == 0);
    CHECK(fs::exists(only));
    CHECK(r2.err.empty());
  }
  SECTION("an unwritable path is one error line") {
    const std::string line = check_error(run(dir, {"--quiet", script, "output=" + script + "/x.exr"}));
    CHECK_THAT(line, Catch::Contains("x.exr"));
  }
}

TEST_CASE("cli: bad transforms are one error line", "[cli]") {
  CliDir dir("render_error");
  const std::string prefix = std::string(kSkyScene) + "local settings = {scene = scene, camera = camera, width = 8, height = 8, spp = 1}\n";
  SECTION("a singular scale") {
    const std::string script = dir.write("scale0.lua", prefix + "scene:add(torte.shape.cube{transform = torte.scale(0)})\n");
    const std::string line = check_error(run(dir, {script}));
    CHECK_THAT(line, Catch::Contains(script + ":7:"));
    CHECK_THAT(line, Catch::Contains("non-zero"));
  }
  SECTION("a singular matrix") {
    const std::string script = dir.write(
        "matrix.lua", prefix + "local m = torte.matrix{1, 0, 0, 0,  0, 0, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1}\n"
                               "scene:add(torte.shape.sphere{transform = m})\n"
                               "torte.render(settings)\n");
    const std::string line = check_error(run(dir, {script}));
    CHECK_THAT(line, Catch::Contains(script + ":7:"));
    CHECK_THAT(line, Catch::Contains("singular"));
  }
}

TEST_CASE("cli: errors while rendering are one line", "[cli]") {
  CliDir dir("render_error2");
  const std::string prefix = std::string(kSkyScene) + "local settings = {scene = scene, camera = camera, width = 8, height = 8, spp = 1}\n";
  SECTION("an emitting mesh of zero area (found when the scene is built)") {
    const std::string script = dir.write(
        "zero_area.lua",
        prefix + "scene:add(torte.shape.mesh{positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, indices = {0, 1, 2}, "
                 "emission = 1})\n"
                 "torte.render(settings)\n");
    const std::string line = check_error(run(dir, {script}));
    CHECK_THAT(line, Catch::Contains(script + ":8:"));
    CHECK_THAT(line, Catch::Contains("zero area"));
  }
  SECTION("a max_depth the renderer refuses") {
    const std::string script =
        dir.write("depth.lua", prefix + "settings.max_depth = 20000\ntorte.render(settings)\n");
    const std::string line = check_error(run(dir, {script}));
    CHECK_THAT(line, Catch::Contains(script + ":8:"));
    CHECK_THAT(line, Catch::Contains("max_depth"));
  }
}

TEST_CASE("cli: bad torte.render settings name the key", "[cli]") {
  CliDir dir("render_settings");
  const std::string prefix = std::string(kSkyScene) + "local settings = {scene = scene, camera = camera, width = 8, height = 8, spp = 1}\n";
  SECTION("a bad integrator names the key") {
    const std::string script =
        dir.write("integrator.lua", prefix + "settings.integrator = 'bidir'\ntorte.render(settings)\n");
    const std::string line = check_error(run(dir, {script}));
    CHECK_THAT(line, Catch::Contains("'integrator'"));
    CHECK_THAT(line, Catch::Contains("bidir"));
  }
  SECTION("a missing camera names the key") {
    const std::string script =
        dir.write("camera.lua", prefix + "settings.camera = nil\ntorte.render(settings)\n");
    const std::string line = check_error(run(dir, {script}));
    CHECK_THAT(line, Catch::Contains("'camera'"));
  }
}

TEST_CASE("cli: Ctrl-C stops the render, writes the partial image and exits with 130", "[cli][sigint]") {
  CliDir dir("sigint");
  const std::string output = dir / "partial.exr";
  // Far too many samples to finish: only Ctrl-C ends this render. The marker tells the test the render is
  // about to start (the signal handler is installed before the script runs).
  const std::string script = dir.write("long.lua", R"(
local opt = torte.options{output = "x.exr"}
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1, material = torte.material.matte{color = 0.5}})
scene:add(torte.shape.cube{transform = torte.translate(0, -2, 0) * torte.scale(5, 0.2, 5)})
scene:add(torte.light.infinite{radiance = 1})
local camera = torte.camera.perspective{eye = {0, 1, -5}, look_at = {0, 0, 0}}
io.stdout:write("rendering\n")
io.stdout:flush()
local img = torte.render{scene = scene, camera = camera, width = 256, height = 256, spp = 1000000}
assert(img.interrupted == true, "the image knows it was interrupted")
torte.save(img, opt.output)
io.stdout:write("saved\n")
)");
  Process p(dir, {"--quiet", script, "output=" + output});
  REQUIRE(p.wait_for_stdout("rendering", 20));
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  Result r;
  if (p.wait(0, &r)) FAIL("torte ended before Ctrl-C with code " << r.code << ", stderr: " << r.err);
  p.send(SIGINT);
  const auto sent = std::chrono::steady_clock::now();
  REQUIRE(p.wait(5, &r));
  const double exit_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  check_no_crash(r);
  INFO("stderr: " << r.err << "stdout: " << r.out);
  CHECK(r.code == 130);
  CHECK(exit_seconds < 3);
  CHECK_THAT(r.err, Catch::Contains("INTERRUPTED"));
  CHECK_THAT(r.err, !Catch::Contains("torte: error:"));
  CHECK_THAT(r.out, Catch::Contains("saved"));
  CHECK(fs::exists(output));
  CHECK(fs::exists(dir / "partial.png"));
  CHECK(fs::file_size(output) > 0);
}

TEST_CASE("cli: after Ctrl-C further renders are refused", "[cli][sigint]") {
  CliDir dir("sigint_twice");
  const std::string script = dir.write("twice.lua", std::string(kSkyScene) + R"(
scene:add(torte.shape.sphere{radius = 1, transform = torte.translate(0, 0, 5), material = torte.material.matte{}})
io.stdout:write("rendering\n")
io.stdout:flush()
local img = torte.render{scene = scene, camera = camera, width = 256, height = 256, spp = 1000000}
io.stdout:write("first done\n")
io.stdout:flush()
local ok, err = pcall(torte.render, {scene = scene, camera = camera, width = 8, height = 8, spp = 1})
assert(not ok and err:find("interrupted"), "second render refused: " .. tostring(err))
io.stdout:write("refused\n")
)");
  Process p(dir, {"--quiet", script});
  p.wait_for_stdout("rendering", 20);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  p.send(SIGINT);
  Result r;
  REQUIRE(p.wait(5, &r));
  check_no_crash(r);
  INFO("stderr: " << r.err << "stdout: " << r.out);
  CHECK(r.code == 130);
  CHECK_THAT(r.out, Catch::Contains("refused"));
}

TEST_CASE("cli: scripts cannot reach the metatables of torte objects", "[cli]") {
  CliDir dir("metatable");
  const Result r = run(dir, {"--quiet", dir.write("mt.lua", R"(
local s = torte.scene()
s:add(torte.light.infinite{})  -- not an empty scene, which would warn
assert(getmetatable(s) == "torte.scene", "metatable is hidden behind its name")
local img = torte.render{scene = s, camera = torte.camera.perspective{}, width = 2, height = 2, spp = 1}
assert(getmetatable(img) == "torte.image")
error("reached the end")
)")});
  const std::string line = check_error(r);
  CHECK_THAT(line, Catch::Contains("reached the end"));
}

TEST_CASE("cli: torte.save reports a write failure at the calling line", "[cli]") {
  CliDir dir("save_error");
  const Result r = run(dir, {"--quiet", dir.write("save.lua", R"(
local s = torte.scene():add(torte.light.infinite{})  -- not an empty scene, which would warn
local img = torte.render{scene = s, camera = torte.camera.perspective{}, width = 2, height = 2, spp = 1}
torte.save(img, "/dev/null/cannot/x.exr")
)")});
  const std::string line = check_error(r);
  CHECK_THAT(line, Catch::Contains(":4:"));
  CHECK_THAT(line, !Catch::Contains("prelude"));
}

TEST_CASE("cli: a NaN in a transform is an error, not a silently black image", "[cli]") {
  CliDir dir("nan_transform");
  const std::string line = check_error(run(dir, {"--quiet", dir.write("nan.lua", R"(
local s = torte.scene()
s:add(torte.shape.sphere{radius = 1, transform = torte.translate(0 / 0, 0, 0)})
)")}));
  CHECK_THAT(line, Catch::Contains("nan.lua:3:"));
  CHECK_THAT(line, Catch::Contains("finite"));
}
