// --sandbox on the built binary: every shipped scene runs unchanged under it, a sandboxed script has none of
// the escapes (programs, C code, environment, the debug library), and every way to open a file obeys the file
// policy of lua/sandbox.h, also through symlinks, '..' and the files an OBJ names.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "sandbox.h"
#include "test_support.h"

namespace fs = std::filesystem;
using namespace torte::test;

namespace {

struct SandboxDir : TempDir {
  explicit SandboxDir(const std::string& name) : TempDir("sandbox", name) {}
};

std::vector<fs::path> shipped_scenes() {
  std::vector<fs::path> scenes;
  for (const auto& e : fs::directory_iterator(fs::path(TORTE_SOURCE_DIR) / "scenes"))
    if (e.is_regular_file() && e.path().extension() == ".lua" && !e.path().stem().string().starts_with("bench-"))
      scenes.push_back(e.path());  // bench-*.lua print tables: tests/io/test_bench_lua.cc runs them sandboxed
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

// A scene at 16x16, 1 spp under --sandbox from the source directory, as a user would run it, reading
// ../shared/data; its output goes to `dir` (allowed as the directory of output=).
void renders_sandboxed(const fs::path& scene) {
  SandboxDir dir("scene_" + scene.stem().string());
  const std::string exr = dir / (scene.stem().string() + ".exr");
  std::vector<std::string> args{"--quiet", "--sandbox", "--allow-read", "../shared/data", scene.string(),
                                "width=16", "height=16", "spp=1", "output=" + exr};
  if (scene.stem() == "lucy-scale") args.push_back("levels=0");
  if (scene.stem() == "minecraft") args.push_back("box=0,60,0,16,80,16");
  const Result r = run_torte(dir, args, 600, TORTE_SOURCE_DIR);
  check_no_crash(r);
  INFO("scene " << scene << ", stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK_THAT(r.err, !Catch::Contains("torte: error"));
  CHECK(fs::exists(exr));
  CHECK(fs::exists(dir / (scene.stem().string() + ".png")));
}

class SceneTest : public Catch::ITestInvoker {
 public:
  explicit SceneTest(fs::path scene) : scene_(std::move(scene)) {}
  void invoke() const override { renders_sandboxed(scene_); }

 private:
  fs::path scene_;
};

const bool kRegistered = [] {
  std::vector<fs::path> scenes;
  try {
    scenes = shipped_scenes();
  } catch (const std::exception&) {
    return false;
  }
  for (const fs::path& scene : scenes)
    Catch::AutoReg(new SceneTest(scene), CATCH_INTERNAL_LINEINFO, Catch::StringRef(),
                   Catch::NameAndTags{"sandbox: " + scene.filename().string() + " runs unchanged under --sandbox",
                                      "[sandbox][scenes]"});
  return true;
}();

// Runs `script` in `dir` (the working directory) with `flags`; returns the result.
Result run_in(const TempDir& dir, const std::vector<std::string>& flags, const std::string& script,
              const std::vector<std::string>& args = {}) {
  std::vector<std::string> argv = flags;
  argv.push_back("--quiet");
  argv.push_back(script);
  argv.insert(argv.end(), args.begin(), args.end());
  return run_torte(dir, argv, 60, dir.path.string());
}

// A script that checks whether each operation in `ops` (Lua expressions of functions) is allowed; it prints
// one line per operation, "name ok" or "name denied: <message>".
std::string probe_script(const std::vector<std::pair<std::string, std::string>>& ops) {
  std::string s = "local dir = debug.getinfo(1, 'S').source:match('^@(.*)/') or '.'\n";
  for (const auto& [name, code] : ops)
    s += "do local ok, err = pcall(function() " + code + " end)\n"
         "  print('" + name + "', ok and 'ok' or ('denied: ' .. tostring(err))) end\n";
  return s;
}

// The line of `out` for operation `name`.
std::string outcome(const std::string& out, const std::string& name) {
  for (const std::string& line : lines_of(out))
    if (line.rfind(name + "\t", 0) == 0) return line.substr(name.size() + 1);
  return "(no line)";
}

}  // namespace

TEST_CASE("sandbox: every shipped scene is registered", "[sandbox]") { CHECK(kRegistered); }

TEST_CASE("sandbox: a sandboxed script has no way to run programs, load C code or read the environment",
          "[sandbox]") {
  SandboxDir dir("escapes");
  const std::string script = dir.write("escapes.lua", R"lua(
local sandboxed = torte.sandboxed()
local reachable = {}
for _, name in ipairs{"os.execute", "os.exit", "os.getenv", "os.tmpname", "os.setlocale", "io.popen",
                      "io.tmpfile", "package.loadlib", "debug.sethook", "debug.getregistry", "debug.setmetatable",
                      "debug.getlocal", "debug.setupvalue", "debug.upvaluejoin"} do
  local lib, fn = name:match("(%w+)%.(%w+)")
  if _G[lib][fn] ~= nil then reachable[#reachable + 1] = name end
end
assert(debug.getinfo and debug.traceback and require("debug") == debug)
local ok = pcall(setmetatable, {}, {__gc = function() end})
print(tostring(sandboxed) .. " " .. #reachable .. " " .. #package.searchers .. " " .. tostring(ok))
)lua");
  SECTION("under --sandbox") {
    const Result r = run_in(dir, {"--sandbox"}, script);
    check_no_crash(r);
    INFO("stderr: " << r.err);
    CHECK(r.code == 0);
    CHECK(r.out == "true 0 2 false\n");
  }
  SECTION("without it everything is there") {
    const Result r = run_in(dir, {}, script);
    check_no_crash(r);
    INFO("stderr: " << r.err);
    CHECK(r.code == 0);
    CHECK(r.out == "false 13 4 true\n");  // only debug.getregistry is gone without --sandbox
  }
}

TEST_CASE("sandbox: reads and writes obey the file policy, through symlinks and '..'", "[sandbox]") {
  SandboxDir dir("policy");
  fs::create_directories(dir.path / "scene");
  fs::create_directories(dir.path / "data");
  fs::create_directories(dir.path / "out");
  fs::create_directories(dir.path / "results");
  fs::create_directories(dir.path / "extra");
  dir.write("secret.txt", "secret\n");
  dir.write("data/allowed.txt", "data\n");
  dir.write("scene/sibling.txt", "sibling\n");
  dir.write("scene/lib.lua", "return 1\n");
  dir.write("secret.lua", "return 2\n");
  fs::create_symlink("../secret.txt", dir.path / "scene/link.txt");      // a file link out of the script's dir
  fs::create_symlink("..", dir.path / "scene/up");                         // a directory link out of it
  fs::create_symlink("../secret-new.txt", dir.path / "out/dangling.txt");  // a write through it lands outside
  const std::string script = dir.write(
      "scene/probe.lua",
      probe_script({
          {"sibling", "assert(io.open(dir .. '/sibling.txt')):close()"},
          {"dotdot", "io.open(dir .. '/../secret.txt')"},
          {"symlink", "io.open(dir .. '/link.txt')"},
          {"dirlink", "io.open(dir .. '/up/secret.txt')"},
          {"absent", "assert(io.open(dir .. '/../absent.txt') == nil)"},
          {"data", "assert(torte.data.read_file('data/allowed.txt') == 'data\\n')"},
          {"list_dir", "torte.data.list_dir('data')"},
          {"lines", "for l in io.lines('secret.txt') do end"},
          {"input", "io.input('secret.txt')"},
          {"mesh", "torte.mesh.load('secret.txt')"},
          {"shape_file", "torte.shape.mesh{file = 'secret.txt'}"},
          {"texture", "torte.texture.image{file = 'secret.txt'}"},
          {"environment", "torte.light.environment{file = 'secret.txt'}"},
          {"loadfile", "loadfile('secret.lua')"},
          {"dofile", "dofile('secret.lua')"},
          {"require_outside", "package.path = './?.lua' require('secret')"},
          {"require_inside", "package.path = dir .. '/?.lua' assert(require('lib') == 1)"},
          {"write_out", "assert(io.open('out/new.txt', 'w')):close()"},
          {"read_back", "assert(io.open('out/new.txt')):close()"},
          {"write_dangling", "io.open('out/dangling.txt', 'w')"},
          {"write_cwd", "io.open('x.txt', 'w')"},
          {"append_secret", "io.open('secret.txt', 'a+')"},
          {"write_results", "assert(io.open('results/r.txt', 'w')):close()"},
          {"write_results_below", "io.open('results/sub/r.txt', 'w')"},
          {"write_extra", "assert(io.open('extra/sub.txt', 'w')):close()"},
          {"output", "io.output('x.txt')"},
          {"remove", "os.remove('secret.txt')"},
          {"rename", "os.rename('out/new.txt', 'moved.txt')"},
          {"save", "torte.save(torte.render{scene = torte.scene(), camera = torte.camera.perspective{}, "
                   "width = 2, height = 2, spp = 1}, 'elsewhere/x.exr')"},
          {"grid_save", "torte.voxel.grid{}:save('grid.bin')"},
      }));
  SECTION("without --sandbox everything is allowed") {
    const Result r = run_in(dir, {}, script, {"output=results/r.exr"});
    check_no_crash(r);
    INFO(r.out << r.err);
    CHECK(outcome(r.out, "dotdot") == "ok");
    CHECK(outcome(r.out, "symlink") == "ok");
    CHECK(outcome(r.out, "write_cwd") == "ok");
  }
  SECTION("under --sandbox") {
    const Result r = run_in(dir, {"--sandbox", "--allow-write", "extra"}, script, {"output=results/r.exr"});
    check_no_crash(r);
    INFO(r.out << r.err);
    CHECK(r.code == 0);
    for (const char* allowed : {"sibling", "absent", "require_inside", "write_out", "read_back", "write_results",
                                "write_extra"})
      CHECK(outcome(r.out, allowed) == "ok");
    for (const char* denied : {"dotdot", "symlink", "dirlink", "data", "list_dir", "lines", "input", "mesh",
                               "shape_file", "texture", "environment", "loadfile", "dofile", "require_outside",
                               "write_dangling", "write_cwd", "append_secret", "write_results_below", "output",
                               "remove", "rename", "save", "grid_save"}) {
      INFO(denied);
      CHECK_THAT(outcome(r.out, denied), Catch::StartsWith("denied: "));
      CHECK_THAT(outcome(r.out, denied), Catch::Contains("may not be"));
    }
    CHECK_THAT(outcome(r.out, "symlink"), Catch::Contains("(" + (dir / "secret.txt") + ") may not be read"));
    CHECK_THAT(outcome(r.out, "write_dangling"), Catch::Contains("secret-new.txt) may not be written"));
    CHECK_THAT(outcome(r.out, "data"), Catch::Contains("--allow-read DIR"));
    CHECK_THAT(outcome(r.out, "save"), Catch::Contains("--allow-write DIR"));
    CHECK(fs::exists(dir.path / "secret.txt"));
    CHECK(!fs::exists(dir.path / "secret-new.txt"));
    CHECK(!fs::exists(dir.path / "x.txt"));
  }
  SECTION("--allow-read adds a directory") {
    const Result r = run_in(dir, {"--sandbox", "--allow-read", "data"}, script);
    check_no_crash(r);
    INFO(r.out << r.err);
    CHECK(outcome(r.out, "data") == "ok");
    CHECK(outcome(r.out, "list_dir") == "ok");
    CHECK_THAT(outcome(r.out, "lines"), Catch::StartsWith("denied: "));
  }
}

TEST_CASE("sandbox: the files an OBJ names obey the policy too", "[sandbox]") {
  SandboxDir dir("mtllib");
  fs::create_directories(dir.path / "scene");
  // A FIFO outside the sandbox: opening it for reading would block until a writer comes, so a run that ends
  // shows that the reader never opened it.
  REQUIRE(mkfifo((dir / "pipe").c_str(), 0600) == 0);
  dir.write("scene/tri.obj", "mtllib ../pipe\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string script = dir.write("scene/obj.lua", R"(
local dir = debug.getinfo(1, "S").source:match("^@(.*)/")
local mesh = torte.mesh.load(dir .. "/tri.obj")
print(mesh.triangles)
)");
  const Result r = run_torte(dir, {"--quiet", "--sandbox", script}, 30, dir.path.string());
  check_no_crash(r);
  INFO("stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK(r.out == "1\n");
}

TEST_CASE("sandbox: resolve_path follows symlinks as the kernel does", "[sandbox]") {
  SandboxDir dir("resolve");
  fs::create_directories(dir.path / "a/b");
  fs::create_symlink(dir.path / "a/b", dir.path / "abs");
  fs::create_symlink("a/b", dir.path / "rel");
  fs::create_symlink("missing/target", dir.path / "dangling");
  fs::create_symlink("loop2", dir.path / "loop1");
  fs::create_symlink("loop1", dir.path / "loop2");
  const fs::path root = torte::lua::resolve_path(dir.path);
  CHECK(torte::lua::resolve_path(dir / "abs/../x") == root / "a/x");   // '..' after the link: the kernel's
  CHECK(torte::lua::resolve_path(dir / "rel/./c/../d") == root / "a/b/d");
  CHECK(torte::lua::resolve_path(dir / "dangling") == root / "missing/target");
  CHECK(torte::lua::resolve_path(dir / "nope/../../x") == root.parent_path() / "x");
  CHECK(torte::lua::resolve_path("/..") == fs::path("/"));
  CHECK_NOTHROW(torte::lua::resolve_path(dir / "loop1/x"));
  const fs::path cwd = fs::current_path();
  CHECK(torte::lua::resolve_path("x/y") == torte::lua::resolve_path(cwd) / "x/y");
}
