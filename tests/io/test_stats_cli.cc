// torte --stats end to end: the per-stage table on stderr after every render (a line per stage and per material
// type shaded, counts that add up to the render's rays, times within threads x wall), and the same profile in
// Lua as image.stages (also without --stats, with torte.render{stats = true}).
#include <catch2/catch.hpp>

#include <map>
#include <regex>
#include <string>

#include "test_support.h"

using namespace torte::test;

namespace {

// A matte floor and a plastic sphere under a point light: two shaded material types. The script prints the
// render's ray count, and checks image.stages against the image's own counters.
const char kTwoMaterials[] = R"(
local opt = torte.options{stats = false}
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1, material = torte.material.plastic{color = {0.8, 0.3, 0.2}, roughness = 0.3}})
scene:add(torte.shape.cube{min = {-4, -1.2, -4}, max = {4, -1, 4}, material = torte.material.matte{color = 0.5}})
scene:add(torte.light.point{position = {2, 3, -3}, intensity = 30})
local camera = torte.camera.perspective{eye = {0, 1, -5}, look_at = {0, 0, 0}, fov = 40}
local img = torte.render{scene = scene, camera = camera, width = 24, height = 16, spp = 4, stats = opt.stats}
print("rays=" .. img.rays)
local st = img.stages
if st == nil then print("stages=nil") return end
local shaded = 0
for _, t in pairs(st.shade) do shaded = shaded + t.items end
assert(st.shade.lambert and st.shade.plastic, "both material types are listed")
assert(shaded == st.hits.items, "shaded " .. shaded .. " ~= queued " .. st.hits.items)
assert(st.trace.items + st.shadows.items == img.rays, "traced " .. st.trace.items + st.shadows.items)
assert(st.camera.items == 24 * 16 * 4 and st.film.items == 24 * 16 * 4, "camera and film items")
-- The sphere shades part of the floor: some of the shadow rays are blocked, not all.
assert(st.shadows.tested == st.shadows.items and st.shadows.blocked > 0 and st.shadows.blocked < st.shadows.tested,
       "blocked " .. tostring(st.shadows.blocked) .. " of " .. tostring(st.shadows.tested))
assert(st.trace.blocked == nil, "only shadow rays are counted as blocked")
print("stages=ok threads=" .. st.threads)
)";

struct Row {
  double seconds = 0;
  unsigned long long calls = 0, items = 0;
};

// The --stats table's rows by stage name ("trace", "shade plastic"); the total line under "total".
std::map<std::string, Row> parse_table(const std::string& err, double* total_budget) {
  std::map<std::string, Row> rows;
  const std::regex row(R"(^  ([a-z_]+(?: [a-z_]+)?) +([0-9.]+) s +([0-9.]+) % +([0-9]+) calls +([0-9]+) )");
  const std::regex total(R"(^  total +([0-9.]+) s of ([0-9]+) threads x ([0-9.]+) s wall)");
  for (const std::string& line : lines_of(err)) {
    std::smatch m;
    if (std::regex_search(line, m, row)) {
      rows[m[1]] = {std::stod(m[2]), std::stoull(m[4]), std::stoull(m[5])};
    } else if (std::regex_search(line, m, total)) {
      rows["total"] = {std::stod(m[1]), 0, 0};
      *total_budget = std::stod(m[2]) * std::stod(m[3]);
    }
  }
  return rows;
}

unsigned long long printed_rays(const std::string& out) {
  std::smatch m;
  REQUIRE(std::regex_search(out, m, std::regex("rays=([0-9]+)")));
  return std::stoull(m[1]);
}

}  // namespace

TEST_CASE("cli: --stats prints a line per stage whose counts add up", "[cli][stats]") {
  TempDir dir("cli", "stats");
  const std::string script = dir.write("two.lua", kTwoMaterials);
  for (const bool quiet : {false, true}) {
    INFO("quiet " << quiet);
    std::vector<std::string> args = {"--stats", "--threads", "2", script};
    if (quiet) args.insert(args.begin(), "--quiet");
    const Result r = run_torte(dir, args, 60);
    check_no_crash(r);
    INFO("stderr: " << r.err);
    REQUIRE(r.code == 0);
    CHECK_THAT(r.out, Catch::Contains("stages=ok threads="));  // --stats collects image.stages too
    double budget = 0;
    const auto rows = parse_table(r.err, &budget);
    for (const char* stage : {"camera", "trace", "hits", "emission", "shade lambert", "shade plastic", "shadows",
                              "film", "total"})
      CHECK(rows.count(stage) == 1);
    CHECK(rows.size() == 9);  // nothing else: no glass, no IGI stages
    if (rows.size() != 9) return;
    const unsigned long long rays = printed_rays(r.out);
    CHECK(rows.at("trace").items + rows.at("shadows").items == rays);
    CHECK(rows.at("shade lambert").items + rows.at("shade plastic").items == rows.at("hits").items);
    CHECK(rows.at("camera").items == 24 * 16 * 4);
    // The shadows line ends with the share of its rays that were blocked.
    const std::regex shadows_line(R"(\n  shadows .* rays, [0-9.]+ Mrays/s per thread, [0-9.]+ % blocked\n)");
    CHECK(std::regex_search(r.err, shadows_line));
    CHECK(rows.at("film").items == 24 * 16 * 4);
    double sum = 0;
    for (const auto& [name, row] : rows)
      if (name != "total") {
        CHECK(row.seconds >= 0);
        sum += row.seconds;
      }
    CHECK(rows.at("total").seconds == Approx(sum).margin(0.001));  // rows print 4 decimals
    CHECK(budget > 0);
    CHECK(rows.at("total").seconds <= budget + 0.002);
  }
}

TEST_CASE("cli: without --stats no table is printed and torte.render{stats = true} fills image.stages",
          "[cli][stats]") {
  TempDir dir("cli", "no_stats");
  const std::string script = dir.write("two.lua", kTwoMaterials);
  SECTION("off") {
    const Result r = run_torte(dir, {"--threads", "2", script}, 60);
    check_no_crash(r);
    INFO("stderr: " << r.err);
    REQUIRE(r.code == 0);
    CHECK_THAT(r.out, Catch::Contains("stages=nil"));
    CHECK_THAT(r.err, !Catch::Contains("stage profile"));
  }
  SECTION("asked for by the script") {
    const Result r = run_torte(dir, {"--threads", "2", script, "stats=true"}, 60);
    check_no_crash(r);
    INFO("stderr: " << r.err);
    REQUIRE(r.code == 0);
    CHECK_THAT(r.out, Catch::Contains("stages=ok threads="));
    CHECK_THAT(r.err, !Catch::Contains("stage profile"));  // printed with --stats only
  }
}
