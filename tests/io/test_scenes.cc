// Every scene in scenes/*.lua runs through the built binary at a tiny size and writes its EXR and the PNG preview
// beside it; scene-specific arguments (integrator, camera) work and unknown arguments are rejected by name.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "test_support.h"

namespace fs = std::filesystem;
using namespace torte::test;

namespace {

struct ScenesDir : TempDir {
  explicit ScenesDir(const std::string& name) : TempDir("scenes", name) {}
};

// Runs torte with `args` from the source directory; stdout and stderr go to files in `dir`.
Result run_in_source(const TempDir& dir, const std::vector<std::string>& args) {
  return run_torte(dir, args, 600, TORTE_SOURCE_DIR);
}

std::vector<fs::path> scene_scripts() {
  std::vector<fs::path> scenes;
  for (const auto& e : fs::directory_iterator(fs::path(TORTE_SOURCE_DIR) / "scenes"))
    if (e.is_regular_file() && e.path().extension() == ".lua" && !e.path().stem().string().starts_with("bench-"))
      scenes.push_back(e.path());  // bench-*.lua print tables, not images (tests/io/test_bench_lua.cc)
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

const std::vector<std::string> kTiny = {"width=32", "height=32", "spp=2"};

// Renders `scene` tiny with extra arguments; checks the run and that the EXR and its PNG exist.
void check_renders(const TempDir& dir, const fs::path& scene, const std::vector<std::string>& extra) {
  std::string stem = scene.stem().string();
  for (const std::string& a : extra) stem += "_" + a.substr(a.find('=') + 1);
  const std::string exr = dir / (stem + ".exr"), png = dir / (stem + ".png");
  std::vector<std::string> args{"--quiet", scene.string()};
  args.insert(args.end(), kTiny.begin(), kTiny.end());
  args.insert(args.end(), extra.begin(), extra.end());
  args.push_back("output=" + exr);
  const Result r = run_in_source(dir, args);
  INFO("scene " << scene << ", stderr: " << r.err);
  CHECK(r.code == 0);
  CHECK(r.err.empty());  // --quiet, no warnings (e.g. no NaN/Inf samples dropped)
  CHECK(fs::exists(exr));
  CHECK(fs::exists(png));
  if (fs::exists(exr)) CHECK(fs::file_size(exr) > 0);
  if (fs::exists(png)) CHECK(fs::file_size(png) > 0);
}

}  // namespace

// One test case per scene file (registered at start-up, so ctest lists them separately and each stays fast).
namespace {

void renders_tiny(const fs::path& scene) {
  ScenesDir dir("tiny_" + scene.stem().string());
  // lucy-scale.lua builds 28 M triangles by default; at reduced sizes (sanitizer builds) 1.8 M.
  const bool heavy = scene.filename() == "lucy-scale.lua" && reduced_test_sizes();
  check_renders(dir, scene, heavy ? std::vector<std::string>{"levels=2"} : std::vector<std::string>{});
}

void rejects_unknown_argument(const fs::path& scene) {
  ScenesDir dir("unknown_" + scene.stem().string());
  const std::string exr = dir / "never.exr";
  const Result r = run_in_source(dir, {"--quiet", scene.string(), "width=32", "widht=3", "output=" + exr});
  INFO("stderr: " << r.err);
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Catch::StartsWith("torte: error: "));
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);  // one line
  CHECK_THAT(r.err, Catch::Contains("'widht'"));
  CHECK_THAT(r.err, Catch::Contains(scene.filename().string()));
  CHECK(!fs::exists(exr));  // rejected before rendering
}

class SceneTest : public Catch::ITestInvoker {
 public:
  SceneTest(void (*body)(const fs::path&), fs::path scene) : body_(body), scene_(std::move(scene)) {}
  void invoke() const override { body_(scene_); }

 private:
  void (*body_)(const fs::path&);
  fs::path scene_;
};

const bool kSceneTestsRegistered = [] {
  std::vector<fs::path> scenes;
  try {
    scenes = scene_scripts();
  } catch (const std::exception&) {
    return false;  // no scenes directory: "the scenes directory holds the expected scenes" fails
  }
  for (const fs::path& scene : scenes) {
    const std::string file = scene.filename().string();
    const std::string tiny = "scenes: " + file + " renders at a tiny size and writes EXR and PNG";
    const std::string unknown = "scenes: " + file + " rejects an unknown argument, naming it";
    // The registry keeps the invokers for the whole run.
    Catch::AutoReg(new SceneTest(renders_tiny, scene), CATCH_INTERNAL_LINEINFO, Catch::StringRef(),
                   Catch::NameAndTags{tiny, "[scenes]"});
    Catch::AutoReg(new SceneTest(rejects_unknown_argument, scene), CATCH_INTERNAL_LINEINFO, Catch::StringRef(),
                   Catch::NameAndTags{unknown, "[scenes]"});
  }
  return true;
}();

}  // namespace

TEST_CASE("scenes: the scenes directory holds the expected scenes", "[scenes]") {
  std::vector<std::string> names;
  for (const fs::path& p : scene_scripts()) names.push_back(p.filename().string());
  INFO("found " << names.size() << " scenes");
  CHECK(kSceneTestsRegistered);
  for (const char* expected : {"cornell-box.lua", "shapes.lua", "lights.lua", "materials.lua", "textures.lua",
                               "instancing.lua"})
    CHECK(std::find(names.begin(), names.end(), expected) != names.end());
}

TEST_CASE("scenes: the Cornell box with the direct-lighting integrator", "[scenes]") {
  ScenesDir dir("cornell_direct");
  check_renders(dir, fs::path(TORTE_SOURCE_DIR) / "scenes" / "cornell-box.lua", {"integrator=direct"});
}

TEST_CASE("scenes: the Cornell box with instant global illumination and its parameters", "[scenes][igi]") {
  ScenesDir dir("cornell_igi");
  check_renders(dir, fs::path(TORTE_SOURCE_DIR) / "scenes" / "cornell-box.lua",
                {"integrator=igi", "vpl_sets=2", "light_paths=8", "g_limit=50"});
}

TEST_CASE("scenes: the Cornell box with light tracing", "[scenes][lt]") {
  ScenesDir dir("cornell_lt");
  check_renders(dir, fs::path(TORTE_SOURCE_DIR) / "scenes" / "cornell-box.lua", {"integrator=lt", "max_depth=3"});
}

TEST_CASE("scenes: the Cornell box with bidirectional path tracing", "[scenes][bdpt]") {
  ScenesDir dir("cornell_bdpt");
  check_renders(dir, fs::path(TORTE_SOURCE_DIR) / "scenes" / "cornell-box.lua", {"integrator=bdpt", "max_depth=3"});
}

TEST_CASE("scenes: the Cornell box with Metropolis light transport", "[scenes][mlt]") {
  ScenesDir dir("cornell_mlt");
  check_renders(dir, fs::path(TORTE_SOURCE_DIR) / "scenes" / "cornell-box.lua",
                {"integrator=mlt", "max_depth=3", "large_step=0.5"});
}

TEST_CASE("scenes: shapes.lua and lights.lua with direct lighting", "[scenes]") {
  ScenesDir dir("direct");
  const fs::path scenes = fs::path(TORTE_SOURCE_DIR) / "scenes";
  SECTION("shapes") { check_renders(dir, scenes / "shapes.lua", {"integrator=direct", "max_depth=1"}); }
  SECTION("lights") { check_renders(dir, scenes / "lights.lua", {"integrator=direct"}); }
}

TEST_CASE("scenes: the camera argument of lights.lua", "[scenes]") {
  ScenesDir dir("camera");
  const fs::path scenes = fs::path(TORTE_SOURCE_DIR) / "scenes";
  SECTION("orthographic") { check_renders(dir, scenes / "lights.lua", {"camera=orthographic"}); }
  SECTION("perspective") { check_renders(dir, scenes / "lights.lua", {"camera=perspective"}); }
  SECTION("lights, an unknown camera is rejected naming the argument") {
    const Result r = run_in_source(dir, {"--quiet", (scenes / "lights.lua").string(), "camera=fisheye",
                                         "output=" + (dir / "never.exr")});
    INFO("stderr: " << r.err);
    CHECK(r.code == 1);
    CHECK_THAT(r.err, Catch::StartsWith("torte: error: "));
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_THAT(r.err, Catch::Contains("'camera'"));
    CHECK_THAT(r.err, Catch::Contains("fisheye"));
  }
}
