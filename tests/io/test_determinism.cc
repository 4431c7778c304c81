// Determinism: every shipped scene (scenes/*.lua), rendered tiny with the same seed at --threads 1 and
// --threads 2 and again, gives the same pixels bit for bit. Each run is a new process, so each has its own Lua
// string-hash seed (Lua 5.4 randomises it per state): anything that lets pairs() order reach the scene shows up
// as runs that differ. Scenes whose data lives in ../shared/data fall back to simple shapes without it (checked
// anyway, with a note); the Minecraft worlds are skipped without it.
#include <catch2/catch.hpp>

#include <stdlib.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "film/image_io.h"
#include "test_support.h"

namespace fs = std::filesystem;
using namespace torte::test;

namespace {

struct Config {
  std::string scene;              // file in scenes/
  std::vector<std::string> args;  // scene arguments besides the size
  std::string needs;              // path below ../shared/data the scene reads ("" = none)
  bool skip_without_data = false; // without the data the run would be trivial (an empty sky): skip
  int runs = 3;                   // at most 4: runs use kThreads in order
  // Sanitizer builds only: run without LeakSanitizer's exit scan. clang 14's LSan tracer crashes on this
  // configuration ("Tracer caught signal 11" reading a garbage dynamic-TLS entry, "DTLS 16 at 0x2d57-...")
  // before it reports anything; ASan and UBSan stay on. To be found: what in the run leaves that DTV entry.
  bool lsan_tracer_crashes = false;
};

const fs::path kShared = fs::path(TORTE_SOURCE_DIR) / ".." / "shared" / "data";

// Every light type of lights.lua on its own is cheap at this size; the Minecraft boxes are the parts of their
// worlds with several biomes, where pairs() order used to change which voxel ids (and so which noise seeds) the
// tinted blocks got.
const std::vector<Config> kConfigs = {
    {"cornell-box.lua", {}},
    {"cornell-box.lua", {"integrator=direct"}},
    {"cornell-box.lua", {"integrator=igi", "vpl_sets=2", "light_paths=8"}},
    {"shapes.lua", {}},
    {"caustic.lua", {"integrator=vcm"}},
    {"mirror-lit.lua", {"integrator=bdpt"}},
    {"door-gap.lua", {}},
    {"many-lights.lua", {}},
    // Selection by power (one light per vertex). With integrator=direct this config sampled every one of the
    // 10,000 lights at each hit (direct's default), 19 s of the suite and 2 min under the sanitizers; summing
    // over all lights in a fixed order is checked by cornell-box.lua integrator=direct.
    {"many-lights.lua", {"light_sampler=power", "max_depth=2"}},
    {"lights.lua", {"light=mixed"}},
    {"lights.lua", {"light=spot", "camera=orthographic"}},
    {"lights.lua", {"light=directional"}},
    {"lights.lua", {"light=environment"}},
    {"lights.lua", {"light=sky", "aperture=0.2"}},
    {"lights.lua", {"light=all"}},
    {"materials.lua", {}, "meshes"},
    {"textures.lua", {}, "meshes"},
    {"instancing.lua", {"levels=1"}, "meshes"},
    {"lucy-scale.lua", {"levels=0"}, "meshes"},
    {"dragon-bench.lua", {"max_depth=8"}, "meshes"},
    {"minecraft.lua", {"world=prismarine-1.16", "box=100,0,-176,228,128,-48"}, "minecraft/prismarine-1.16", true, 4},
    {"minecraft.lua", {"world=prismarine-1.12.2", "box=120,0,-80,330,96,0"}, "minecraft/prismarine-1.12.2", true, 4},
    {"minecraft.lua", {"world=querz-nbt-1.18.2", "box=50,-64,50,150,112,150"}, "minecraft/querz-nbt-1.18.2", true,
     3, true},
    // The ancient city and the lava beside it (the box keeps the load short; it opens the cave to the sky).
    {"minecraft-cave.lua", {"box=0,-64,0,112,0,80"}, "minecraft/bluenbt-1.20.1-paper", true, 3},
};

// Thread counts of the runs: both counts, and a repeat at the same count.
constexpr int kThreads[] = {1, 2, 2, 1};

std::string describe(const Config& c) {
  std::string s = c.scene;
  for (const std::string& a : c.args) s += " " + a;
  return s;
}

// Where two renders differ: how many pixels, and the first one.
std::string difference(const torte::Image& a, const torte::Image& b) {
  if (a.width != b.width || a.height != b.height)
    return "sizes differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) + " vs " +
           std::to_string(b.width) + "x" + std::to_string(b.height);
  size_t n = 0, first = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    if (std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(torte::Rgb)) != 0 && n++ == 0) first = i;
  if (n == 0) return "";
  const torte::Rgb& p = a.pixels[first];
  const torte::Rgb& q = b.pixels[first];
  return std::to_string(n) + " of " + std::to_string(a.pixels.size()) + " pixels differ; first (" +
         std::to_string(first % size_t(a.width)) + ", " + std::to_string(first / size_t(a.width)) + "): (" +
         std::to_string(p.r) + ", " + std::to_string(p.g) + ", " + std::to_string(p.b) + ") vs (" +
         std::to_string(q.r) + ", " + std::to_string(q.g) + ", " + std::to_string(q.b) + ")";
}

void renders_identically(const Config& c) {
  const bool have_data = c.needs.empty() || fs::exists(kShared / c.needs);
  if (!have_data && c.skip_without_data) {
    WARN("skipped: " << (kShared / c.needs).string() << " is absent (../shared/data not installed)");
    return;
  }
  if (!have_data) WARN((kShared / c.needs).string() << " is absent: " << c.scene << " is checked with its fallback shapes");
  std::string name = fs::path(c.scene).stem().string();
  for (const std::string& a : c.args) name += "_" + a.substr(a.find('=') + 1, 12);
  std::replace_if(name.begin(), name.end(), [](char ch) { return ch == ',' || ch == '.' || ch == '-'; }, '_');
  TempDir dir("determinism", name);
  const char* asan = std::getenv("ASAN_OPTIONS");
  const std::string asan_before = asan ? asan : "";
  if (c.lsan_tracer_crashes && reduced_test_sizes())
    setenv("ASAN_OPTIONS", (asan_before + ":detect_leaks=0").c_str(), 1);
  struct RestoreAsanOptions {
    bool had;
    std::string value;
    ~RestoreAsanOptions() { had ? setenv("ASAN_OPTIONS", value.c_str(), 1) : unsetenv("ASAN_OPTIONS"); }
  } restore{asan != nullptr, asan_before};
  std::vector<torte::Image> images;
  std::vector<int> threads;
  REQUIRE(c.runs <= int(std::size(kThreads)));
  // Sanitizer builds: two runs, one per thread count (two processes, so two Lua hash seeds as well). What they
  // check there is memory and UB in each scene's path; the repeats hunt rare orderings, which the normal build
  // does with every run.
  const int runs = reduced_test_sizes() ? std::min(c.runs, 2) : c.runs;
  for (int run = 0; run < runs; ++run) {
    const int t = kThreads[run];
    const std::string exr = dir / ("run" + std::to_string(run) + ".exr");
    std::vector<std::string> args{"--quiet", "--threads", std::to_string(t), "--seed", "7",
                                  (fs::path(TORTE_SOURCE_DIR) / "scenes" / c.scene).string(),
                                  "width=24", "height=24", "spp=2"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    args.push_back("output=" + exr);
    const Result r = run_torte(dir, args, 300, TORTE_SOURCE_DIR);
    INFO(describe(c) << ", run " << run << " at --threads " << t << ", stderr: " << r.err);
    REQUIRE(r.code == 0);
    images.push_back(torte::read_image(exr));
    threads.push_back(t);
  }
  REQUIRE(std::set<int>(threads.begin(), threads.end()).size() == 2);  // both thread counts were run
  for (size_t i = 1; i < images.size(); ++i) {
    INFO(describe(c) << ": run 0 (--threads 1) vs run " << i << " (--threads " << threads[i] << ")");
    CHECK(difference(images[0], images[i]) == "");
  }
}

class DeterminismTest : public Catch::ITestInvoker {
 public:
  explicit DeterminismTest(Config c) : config_(std::move(c)) {}
  void invoke() const override { renders_identically(config_); }

 private:
  Config config_;
};

// One test case per configuration, so ctest runs them side by side.
const bool kRegistered = [] {
  for (const Config& c : kConfigs)
    Catch::AutoReg(new DeterminismTest(c), CATCH_INTERNAL_LINEINFO, Catch::StringRef(),
                   Catch::NameAndTags{"determinism: " + describe(c) + " gives the same pixels at 1 and 2 threads and "
                                      "from run to run", "[determinism]"});
  return true;
}();

}  // namespace

TEST_CASE("determinism: every shipped scene is among the configurations", "[determinism]") {
  CHECK(kRegistered);
  for (const auto& e : fs::directory_iterator(fs::path(TORTE_SOURCE_DIR) / "scenes")) {
    if (e.path().extension() != ".lua") continue;
    const std::string file = e.path().filename().string();
    if (file.starts_with("bench-")) continue;  // benchmarks print timings, not images
    INFO("scenes/" << file << " has no determinism configuration in tests/io/test_determinism.cc");
    CHECK(std::any_of(kConfigs.begin(), kConfigs.end(), [&](const Config& c) { return c.scene == file; }));
  }
}
