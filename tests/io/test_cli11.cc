// The command line parsed by CLI11 (src/app/main.cc), end to end on the built binary: options after the script
// and as --opt=value, the generated --help, --version's build report, -o/--outfile, --quick, --list-args,
// --simd (and torte.simd from Lua: one binary renders the same image within noise on every target the CPU
// runs), loader paths relative to the script, and the error for a misspelled torte function.
#include <catch2/catch.hpp>

#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "../scene_helpers.h"
#include "film/image_io.h"
#include "test_support.h"

namespace fs = std::filesystem;
using namespace torte::test;

namespace {

struct Cli11Dir : TempDir {
  explicit Cli11Dir(const std::string& name) : TempDir("cli11", name) {}
};

Result run_ok(const TempDir& dir, const std::vector<std::string>& args, double timeout = 60,
              const std::string& cwd = {}) {
  const Result r = run_torte(dir, args, timeout, cwd);
  check_no_crash(r);
  INFO("stderr: " << r.err << "\nstdout: " << r.out);
  REQUIRE(r.code == 0);
  return r;
}

std::string usage_error(const Result& r) {
  const std::string line = check_error(r);
  CHECK_THAT(line, Catch::EndsWith("(see 'torte --help')"));
  return line;
}

// The line of `text` that starts with `prefix`, without the prefix ("" if there is none).
std::string line_after(const std::string& text, const std::string& prefix) {
  for (const std::string& line : lines_of(text))
    if (line.rfind(prefix, 0) == 0) return line.substr(prefix.size());
  return {};
}

std::vector<std::string> split_list(const std::string& list) {
  std::vector<std::string> out;
  const std::regex word("[a-z0-9]+");
  for (std::sregex_iterator it(list.begin(), list.end(), word), end; it != end; ++it) out.push_back(it->str());
  return out;
}

// The targets this CPU runs, from --version.
std::vector<std::string> runnable_targets(const TempDir& dir) {
  return split_list(line_after(run_ok(dir, {"--version"}).out, "SIMD targets this CPU runs: "));
}

// A sphere on a floor under a point light and a dim sky: direct and indirect light, noise at low spp.
const char kScene[] = R"(
local opt = torte.options{output = "x.exr", width = 32, height = 32, spp = 16, color = 0.6}
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1, material = torte.material.plastic{color = {opt.color, 0.3, 0.2}, roughness = 0.3}})
scene:add(torte.shape.cube{min = {-4, -1.2, -4}, max = {4, -1, 4}, material = torte.material.matte{color = 0.5}})
scene:add(torte.light.point{position = {2, 3, -3}, intensity = 30})
scene:add(torte.light.infinite{radiance = 0.2})
local camera = torte.camera.perspective{eye = {0, 1, -5}, look_at = {0, 0, 0}, fov = 40}
local img = torte.render{scene = scene, camera = camera, width = opt.width, height = opt.height, spp = opt.spp}
print("size=" .. img.width .. "x" .. img.height .. " rays=" .. img.rays .. " quick=" .. tostring(torte.quick))
torte.save(img, opt.output)
)";

}  // namespace

TEST_CASE("cli11: options after the script and --opt=value", "[cli][cli11]") {
  Cli11Dir dir("order");
  const std::string script = dir.write("s.lua", kScene);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{script, "--spp", "2", "width=8", "height=8", "output=" + (dir / "a.exr")},
        std::vector<std::string>{"--spp=2", script, "width=8", "height=8", "output=" + (dir / "a.exr")},
        std::vector<std::string>{script, "width=8", "--spp=2", "height=8", "output=" + (dir / "a.exr")}}) {
    const Result r = run_ok(dir, args);
    CHECK_THAT(r.err, Catch::Contains("render 8x8, 2 spp"));
    CHECK_THAT(r.out, Catch::Contains("rays="));
  }
  SECTION("repeated --allow-read take one directory each, before or after the script") {
    const std::string ok = dir.write("ok.lua", "assert(torte.sandboxed())\n");
    run_ok(dir, {"--sandbox", "--allow-read", dir.path.string(), "--allow-read=/tmp", ok});
    run_ok(dir, {ok, "--sandbox", "--allow-read", dir.path.string(), "--allow-write", dir.path.string()});
  }
  SECTION("-- ends the options: what follows is the script or a scene argument") {
    const std::string args = dir.write("args.lua", "print(torte.args['--spp'], torte.args.n)\n");
    CHECK(run_ok(dir, {"--", args, "n=1"}).out == "nil\t1\n");
    CHECK(run_ok(dir, {args, "--", "--spp=2"}).out == "2\tnil\n");
    CHECK_THAT(usage_error(run_torte(dir, {args, "--", "--spp"}, 30)), Catch::Contains("key=value, got '--spp'"));
  }
}

TEST_CASE("cli11: --help is generated and lists every option", "[cli][cli11]") {
  Cli11Dir dir("help");
  const Result r = run_ok(dir, {"--help"});
  CHECK(r.err.empty());
  CHECK_THAT(r.out, Catch::StartsWith("usage: torte [options] scene.lua|model.gltf|model.glb [key=value ...]"));
  for (const char* opt : {"--outfile", "-o", "--quick", "--list-args", "--stats", "--simd", "--version", "--spp",
                          "--seed", "--threads", "--aovs", "--denoise", "--exposure", "--tonemap", "--checkpoint",
                          "--resume", "--max-memory", "--lua-memory", "--lua-instructions", "--sandbox",
                          "--allow-read", "--allow-write", "--quiet"}) {
    INFO(opt);
    CHECK_THAT(r.out, Catch::Contains(opt));
  }
}

TEST_CASE("cli11: bad options are one line and a non-zero exit", "[cli][cli11]") {
  Cli11Dir dir("bad");
  const std::string script = dir.write("ok.lua", "-- nothing\n");
  CHECK_THAT(usage_error(run_torte(dir, {script, "--frobnicate"}, 30)), Catch::Contains("'--frobnicate'"));
  CHECK_THAT(usage_error(run_torte(dir, {"--frobnicate=3", script}, 30)), Catch::Contains("--frobnicate"));
  CHECK_THAT(usage_error(run_torte(dir, {script, "--threads"}, 30)), Catch::Contains("--threads"));
  CHECK_THAT(usage_error(run_torte(dir, {script, "--threads=lots"}, 30)), Catch::Contains("'lots'"));
  const std::string simd = usage_error(run_torte(dir, {"--simd", "neon", script}, 30));
  CHECK_THAT(simd, Catch::Contains("'neon'"));
  CHECK_THAT(simd, Catch::Contains("avx2"));  // the choices are listed
  CHECK_THAT(usage_error(run_torte(dir, {"--quick=maybe", script}, 30)), Catch::Contains("--quick"));
}

TEST_CASE("cli11: --version reports compiler, SIMD targets and build options", "[cli][cli11]") {
  Cli11Dir dir("version");
  const Result r = run_ok(dir, {"--version"});
  const std::vector<std::string> lines = lines_of(r.out);
  REQUIRE(lines.size() >= 6);
  CHECK(std::regex_match(lines[0], std::regex("torte [0-9]+\\.[0-9]+(\\.[0-9]+)?")));
  CHECK_THAT(line_after(r.out, "compiler: "), Catch::Matches("(clang|gcc) .+"));
  const auto compiled = split_list(line_after(r.out, "SIMD targets compiled: "));
  const auto runs = split_list(line_after(r.out, "SIMD targets this CPU runs: "));
  REQUIRE(!compiled.empty());
  REQUIRE(!runs.empty());
  for (const std::string& t : runs) CHECK(std::find(compiled.begin(), compiled.end(), t) != compiled.end());
  // By default the best target the CPU runs is chosen; --simd picks another, and --version shows it.
  CHECK_THAT(line_after(r.out, "SIMD target chosen: "), Catch::StartsWith(runs.front() + " (--simd auto)"));
  CHECK_THAT(line_after(r.out, "build options: "), Catch::Contains("CMAKE_BUILD_TYPE="));
  CHECK_THAT(line_after(r.out, "build options: "), Catch::Contains("TORTE_RENDER_ISAS="));
  const Result last = run_ok(dir, {"--simd", runs.back(), "--version"});
  CHECK_THAT(line_after(last.out, "SIMD target chosen: "), Catch::StartsWith(runs.back() + " (--simd " + runs.back()));
  if (std::find(runs.begin(), runs.end(), "sse4") != runs.end()) {  // the render loop's baseline copy then
    const Result sse4 = run_ok(dir, {"--simd=sse4", "--version"});
    CHECK_THAT(line_after(sse4.out, "render loop copies this CPU runs: "), Catch::EndsWith("(chosen: baseline)"));
  }
}

TEST_CASE("cli11: -o and --outfile override the script's output", "[cli][cli11]") {
  Cli11Dir dir("outfile");
  const std::string script = dir.write("s.lua", kScene);
  run_ok(dir, {"--quiet", script, "width=8", "height=8", "spp=1", "output=" + (dir / "given.exr"), "-o",
               dir / "o.exr"});
  CHECK(fs::exists(dir / "o.exr"));
  CHECK(fs::exists(dir / "o.png"));
  CHECK(!fs::exists(dir / "given.exr"));
  run_ok(dir, {"--quiet", "--outfile=" + (dir / "long.png"), script, "width=8", "height=8", "spp=1"});
  CHECK(fs::exists(dir / "long.png"));
  CHECK(!fs::exists(dir / "x.exr"));
  SECTION("a scene without an output argument says so") {
    const std::string other = dir.write("no_output.lua", "local opt = torte.options{width = 8}\n");
    const std::string line = check_error(run_torte(dir, {"-o", dir / "z.exr", other}, 30));
    CHECK_THAT(line, Catch::Contains("'output'"));
  }
}

TEST_CASE("cli11: --quick renders at a quarter of the size and few samples", "[cli][cli11]") {
  Cli11Dir dir("quick");
  const std::string script = dir.write("s.lua", kScene);
  const std::vector<std::string> base = {script, "width=64", "height=30", "spp=64", "output=" + (dir / "q.exr")};
  const Result full = run_ok(dir, base);
  CHECK_THAT(full.out, Catch::Contains("size=64x30"));
  CHECK_THAT(full.out, Catch::Contains("quick=false"));
  std::vector<std::string> quick = base;
  quick.insert(quick.begin(), "--quick");
  const Result q = run_ok(dir, quick);
  CHECK_THAT(q.out, Catch::Contains("size=16x8"));  // 30 / 4 rounded up
  CHECK_THAT(q.out, Catch::Contains("quick=true"));
  CHECK_THAT(q.err, Catch::Contains("render 16x8, 4 spp"));
  quick.insert(quick.begin(), "--spp=9");  // an explicit --spp wins
  CHECK_THAT(run_ok(dir, quick).err, Catch::Contains("render 16x8, 9 spp"));
}

TEST_CASE("cli11: --list-args prints the scene's arguments and stops", "[cli][cli11]") {
  Cli11Dir dir("list_args");
  const std::string script = dir.write("s.lua", R"(
local opt = torte.options{width = 64, exposure = 0.5, name = "cornell", fast = false}
error("not reached under --list-args")
)");
  const Result r = run_ok(dir, {script, "--list-args"});
  CHECK(r.err.empty());
  const std::vector<std::string> lines = lines_of(r.out);
  REQUIRE(lines.size() == 4);
  CHECK(std::regex_match(lines[0], std::regex("exposure +number +default 0\\.5")));
  CHECK(std::regex_match(lines[1], std::regex("fast +boolean +default false")));
  CHECK(std::regex_match(lines[2], std::regex("name +string +default \"cornell\"")));
  CHECK(std::regex_match(lines[3], std::regex("width +integer +default 64")));
  SECTION("without --list-args the script runs on") {
    CHECK_THAT(check_error(run_torte(dir, {script}, 30)), Catch::Contains("not reached"));
  }
  SECTION("a scene without torte.options stops at its first render") {
    const std::string none = dir.write("none.lua", R"(
local s = torte.scene():add(torte.light.infinite{})
torte.render{scene = s, camera = torte.camera.perspective{}, width = 2, height = 2, spp = 1}
error("not reached either")
)");
    const Result n = run_ok(dir, {"--list-args", none});
    CHECK(n.out == "this scene declares no arguments (torte.options)\n");
    CHECK(n.err.empty());  // no render summary: nothing was rendered
  }
  SECTION("the shipped Cornell box") {
    const Result c = run_ok(dir, {"--list-args", std::string(TORTE_SOURCE_DIR) + "/scenes/cornell-box.lua"});
    CHECK(std::regex_search(c.out, std::regex("\nintegrator +string +default \"path\"\n")));
    CHECK(std::regex_search(c.out, std::regex("\nspp +integer +default 256\n")));
  }
}

TEST_CASE("cli11: loader paths resolve against the script's directory", "[cli][cli11]") {
  Cli11Dir dir("script_dir");
  fs::create_directories(dir.path / "scene");
  dir.write("scene/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string script = dir.write("scene/s.lua", R"(
print("script_dir=" .. torte.script_dir)
local m = torte.mesh.load("tri.obj")             -- beside the script, whatever the working directory
local s = torte.shape.mesh{file = "tri.obj"}
assert(#torte.data.read_file(torte.script_dir .. "/tri.obj") > 0)
local ok, err = pcall(torte.mesh.load, "missing.obj")
assert(not ok)
print("missing: " .. err)
)");
  const Result r = run_ok(dir, {"scene/s.lua"}, 30, dir.path.string());  // run from the parent directory
  CHECK_THAT(r.out, Catch::Contains("script_dir=" + (dir.path / "scene").string() + "\n"));
  // A file that is nowhere is reported where it was looked for: beside the script.
  CHECK_THAT(r.out, Catch::Contains((dir.path / "scene" / "missing.obj").string()));
  SECTION("a path on the command line relative to the working directory still works") {
    dir.write("other.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string arg = dir.write("scene/arg.lua", "local opt = torte.options{mesh = ''}\n"
                                                       "torte.mesh.load(opt.mesh)\n");
    run_ok(dir, {"scene/arg.lua", "mesh=other.obj"}, 30, dir.path.string());
  }
}

TEST_CASE("cli11: a misspelled torte function names the table, the file and line and the known names",
          "[cli][cli11]") {
  Cli11Dir dir("strict");
  const std::string script = dir.write("typo.lua", "local m = torte.material.matte{}\n"
                                                   "local p = torte.material.plastik{}\n");
  const std::string line = check_error(run_torte(dir, {script}, 30));
  CHECK_THAT(line, Catch::Contains(script + ":2:"));
  CHECK_THAT(line, Catch::Contains("torte.material has no 'plastik' (known: "));
  CHECK_THAT(line, Catch::Contains("plastic"));
  CHECK_THAT(line, Catch::Contains("matte"));
  const std::string top = dir.write("top.lua", "\n\nlocal s = torte.scen()\n");
  const std::string l2 = check_error(run_torte(dir, {top}, 30));
  CHECK_THAT(l2, Catch::Contains(top + ":3: torte has no 'scen' (known: "));
  CHECK_THAT(l2, Catch::Contains("scene"));
  SECTION("torte.args stays a plain table: absent arguments are nil") {
    run_ok(dir, {dir.write("args.lua", "assert(torte.args.nothing == nil)\nassert(rawget(torte, 'nope') == nil)\n")});
  }
}

TEST_CASE("cli11: torte.simd lists and picks targets from Lua", "[cli][cli11][simd]") {
  Cli11Dir dir("simd_lua");
  const std::vector<std::string> runs = runnable_targets(dir);
  REQUIRE(!runs.empty());
  const Result r = run_ok(dir, {dir.write("simd.lua", R"(
local t = torte.simd.targets()
print("targets=" .. table.concat(t, ","))
print("current=" .. torte.simd.current())
assert(torte.simd.use(t[#t]) == t[#t])
print("after=" .. torte.simd.current())
local ok, err = pcall(torte.simd.use, "mmx")
print("bad=" .. tostring(err))
assert(torte.simd.use("auto") == t[1])
)")});
  std::string joined;
  for (const std::string& t : runs) joined += (joined.empty() ? "" : ",") + t;
  CHECK_THAT(r.out, Catch::Contains("targets=" + joined + "\n"));
  CHECK_THAT(r.out, Catch::Contains("current=" + runs.front() + "\n"));
  CHECK_THAT(r.out, Catch::Contains("after=" + runs.back() + "\n"));
  CHECK_THAT(r.out, Catch::Contains("bad=torte.simd.use: unknown SIMD target 'mmx' (known: auto, "));
}

TEST_CASE("cli11: a target this CPU lacks is a clear error", "[cli][cli11][simd]") {
  Cli11Dir dir("simd_missing");
  const Result v = run_ok(dir, {"--version"});
  const auto compiled = split_list(line_after(v.out, "SIMD targets compiled: "));
  const auto runs = split_list(line_after(v.out, "SIMD targets this CPU runs: "));
  for (const std::string& t : compiled)
    if (std::find(runs.begin(), runs.end(), t) == runs.end()) {
      const std::string line = usage_error(run_torte(dir, {"--simd", t, "--version"}, 30));
      CHECK_THAT(line, Catch::Contains("'" + t + "' is not supported by this CPU"));
      return;
    }
  for (const char* t : {"avx512", "avx2", "sse4", "ssse3", "scalar"})
    if (std::find(compiled.begin(), compiled.end(), t) == compiled.end()) {
      CHECK_THAT(usage_error(run_torte(dir, {"--simd", t, "--version"}, 30)), Catch::Contains("not compiled"));
      return;
    }
  WARN("every SIMD target is compiled in and runs on this CPU: the refusal is not exercised here");
}

TEST_CASE("cli11: one binary renders the same image within noise on every SIMD target", "[cli][cli11][simd]") {
  Cli11Dir dir("simd_images");
  const std::string script = dir.write("s.lua", kScene);
  const std::vector<std::string> runs = runnable_targets(dir);
  const auto render = [&](const std::string& target, const std::string& name, const std::string& color) {
    const std::string out = dir / (name + ".exr");
    const Result r = run_ok(dir, {"--simd=" + target, script, "spp=64", "color=" + color, "-o", out}, 120);
    CHECK_THAT(r.err, Catch::Contains("SIMD " + target + " (render loop "));  // the summary names it
    // The EXR header records the chosen target.
    const std::string header = read_file(out).substr(0, 4096);
    const size_t at = header.find(std::string("torte:simd_target") + '\0');
    REQUIRE(at != std::string::npos);
    CHECK(header.substr(at, 48).find(target) != std::string::npos);
    return torte::read_image(out);
  };
  const torte::Image reference = render(runs.front(), "reference", "0.6");
  for (const std::string& t : runs) {
    INFO("target " << t);
    const torte::Image img = render(t, t, "0.6");
    // 8x8 tiles at 64 spp: noise is a few percent of a tile mean; a wrong kernel changes whole tiles.
    CHECK(max_tile_error(img, reference, 8) < 0.05);
    CHECK(std::fabs(image_mean(img) / image_mean(reference) - 1) < 0.01);
  }
  // The comparison can fail: a sphere 15% redder on the last target is caught.
  const torte::Image redder = render(runs.back(), "redder", "0.69");
  CHECK(max_tile_error(redder, reference, 8) > 0.05);
}

TEST_CASE("cli11: --stats prints the scene's statistics and scene:stats() returns them", "[cli][cli11][stats]") {
  Cli11Dir dir("scene_stats");
  const std::string script = dir.write("s.lua", R"(
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1})
scene:add(torte.shape.cube{min = {-4, -1.2, -4}, max = {4, -1, 4}})
scene:add(torte.light.point{position = {2, 3, -3}, intensity = 30})
local st = scene:stats()
print(("lua: triangles %d primitives %d nodes %d lights %d"):format(st.triangles, st.primitives, st.nodes, st.lights))
assert(st.bytes_per_triangle.nodes > 0 and st.bytes_per_triangle.leaves > 0, "bytes per triangle")
assert(st.build_seconds >= 0 and st.reused == false and st.peak_memory > 0 and st.accel_bytes > 0)
local camera = torte.camera.perspective{eye = {0, 1, -5}, look_at = {0, 0, 0}}
torte.render{scene = scene, camera = camera, width = 8, height = 8, spp = 1}
assert(scene:stats().reused, "the render left the built scene in the cache")
)");
  const Result r = run_ok(dir, {"--quiet", "--stats", script});
  std::smatch lua, cli;
  REQUIRE(std::regex_search(r.out, lua, std::regex("lua: triangles (\\d+) primitives (\\d+) nodes (\\d+) lights (\\d+)")));
  CHECK(lua[1] == "12");  // the cube's triangles; the sphere is a quadric
  CHECK(lua[2] == "13");
  CHECK(std::stoi(lua[3]) >= 1);
  CHECK(lua[4] == "1");
  CHECK_THAT(r.err, Catch::Contains("scene statistics:\n  primitives 13 (triangles 12)"));
  REQUIRE(std::regex_search(r.err, cli, std::regex("triangle BVH: (\\d+) nodes of width")));
  CHECK(cli[1] == lua[3].str());
  CHECK_THAT(r.err, Catch::Contains("; default layout\n"));
  CHECK_THAT(r.err, Catch::Contains("bytes per triangle: nodes "));
  CHECK_THAT(r.err, Catch::Contains("(scene unchanged, reused); peak resident "));
  SECTION("without --stats no statistics are printed") {
    CHECK_THAT(run_ok(dir, {"--quiet", script}).err, !Catch::Contains("scene statistics"));
  }
}
