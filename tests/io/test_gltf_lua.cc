// torte.gltf.load through the built binary: files written here (indices of every component type, embedded and
// external buffers, .glb), the node hierarchy, materials, cameras, KHR_lights_punctual lights, and damaged files
// as one-line errors.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "gltf_test_files.h"
#include "test_support.h"

using namespace torte::test;

namespace {

Result run(const TempDir& dir, const std::vector<std::string>& args) {
  return run_torte(dir, args, 60, dir.path.string());
}

const char kCheck[] = R"(
local g = torte.gltf.load(arg_file)
assert(#g.cameras == 1 and #g.lights == 1 and g.materials.red and g.materials.lamp, "objects")
local scene = torte.scene()
scene:add(torte.instance{group = g.group})
scene:add(torte.light.infinite{radiance = 1})
local img = torte.render{scene = scene, camera = g.cameras[1], width = 16, height = 16, spp = 16}
local centre, corner = img:pixel(8, 8), img:pixel(0, 0)
-- The quad (2 x 2 after its parent's scale) fills the middle of the view: red under the sky and the light.
assert(corner > 0.95 and corner < 1.05, "sky in the corner: " .. corner)
assert(centre < 0.8 * corner, "the quad in the middle: " .. centre)
print("ok")
)";

}  // namespace

TEST_CASE("gltf lua: every index type, embedded and external buffers, .glb", "[gltf]") {
  TempDir dir("gltf", "load");
  for (int type : {5121, 5123, 5125}) {
    INFO("index type " << type);
    const Gltf embedded = make(type, "data:application/octet-stream;base64," + base64(make(type, "x").bin));
    dir.write("embedded.gltf", embedded.json);
    const Gltf external = make(type, "quad.bin");
    dir.write("quad.bin", external.bin);
    dir.write("external.gltf", external.json);
    dir.write("quad.glb", glb(make(type, "")));
    for (const char* file : {"embedded.gltf", "external.gltf", "quad.glb"}) {
      INFO(file);
      const std::string script = dir.write("check.lua", std::string("local arg_file = '") + file + "'\n" + kCheck);
      const Result r = run(dir, {"--quiet", script});
      INFO("stderr: " << r.err);
      CHECK(r.code == 0);
      CHECK(r.out == "ok\n");
    }
  }
}

TEST_CASE("gltf lua: damaged files are one-line errors naming the file", "[gltf]") {
  TempDir dir("gltf", "damaged");
  const Gltf good = make(5123, "quad.bin");
  dir.write("quad.bin", good.bin);
  struct Case { const char* name; std::string json; const char* expect; };
  std::string past = good.json;
  past.replace(past.find("\"count\": 6"), 10, "\"count\": 60");
  std::string float_indices = good.json;
  float_indices.replace(float_indices.rfind("\"componentType\": 5123"), 21, "\"componentType\": 5122");  // signed short
  std::string bad_index = good.json;
  bad_index.replace(bad_index.find("\"indices\": 3"), 12, "\"indices\": 9");
  const Case cases[] = {
      {"truncated", good.json.substr(0, good.json.size() / 2), "bad.gltf"},
      {"past the end", past, "reaches past the end of its buffer"},
      {"signed indices", float_indices, "indices must be unsigned byte, short or int"},
      {"no accessor", bad_index, "bad.gltf"},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    dir.write("bad.gltf", c.json);
    const std::string script = dir.write("bad.lua", "-- line 1\nlocal g = torte.gltf.load('bad.gltf')\n");
    const std::string line = check_error(run(dir, {script}));
    CHECK_THAT(line, Catch::Contains(script + ":2: torte.gltf.load"));
    CHECK_THAT(line, Catch::Contains(c.expect));
  }
  const std::string script = dir.write("missing.lua", "local g = torte.gltf.load('nothing.glb')\n");
  CHECK_THAT(check_error(run(dir, {script})), Catch::Contains("nothing.glb"));
}

// `torte model.glb`: the embedded viewer (lua/torte/view_model.lua) renders the file with its camera or a framing
// one, adds a light rig when the file has no light, and takes the shipped scenes' arguments.
TEST_CASE("gltf lua: torte model.glb renders the file directly", "[gltf]") {
  TempDir dir("gltf", "view");
  Gltf unlit = make(5123, "");
  // Without its point light the file has no light of its own: the viewer adds the sky and the sun.
  unlit.json.replace(unlit.json.find("[0, 2, 3]"), 9, "[0, 2]");
  dir.write("quad.glb", glb(make(5123, "")));
  dir.write("unlit.glb", glb(unlit));
  // The rendered image through a texture lookup: the quad's middle against the corner.
  const std::string probe = dir.write("probe.lua", R"(
local t = torte.texture.image{file = arg_file}
local function lum(u, v) local c = t:eval{uv = {u, v}} return c[1] + c[2] + c[3] end
print(("%.4f %.4f"):format(lum(0.5, 0.5), lum(0.02, 0.02)))
)");
  auto centre_and_corner = [&](const std::string& exr) {
    const std::string script = dir.write("run_probe.lua", "arg_file = '" + exr + "'\n" + read_file(probe));
    const Result r = run(dir, {"--quiet", script});
    INFO(r.err);
    REQUIRE(r.code == 0);
    double centre = 0, corner = 0;
    std::istringstream(r.out) >> centre >> corner;
    return std::pair{centre, corner};
  };
  {
    const Result r = run(dir, {"--quiet", "quad.glb", "width=24", "height=16", "spp=4", "output=file_camera.exr"});
    INFO(r.err);
    CHECK(r.code == 0);
    CHECK(std::filesystem::exists(dir.path / "file_camera.exr"));
    CHECK(std::filesystem::exists(dir.path / "file_camera.png"));
  }
  {  // camera=0 frames the model: the quad is in the middle, the sky in the corner
    const Result r = run(dir, {"--quiet", "unlit.glb", "camera=0", "width=24", "height=16", "spp=8", "output=framed.exr"});
    INFO(r.err);
    REQUIRE(r.code == 0);
    const auto [centre, corner] = centre_and_corner("framed.exr");
    CHECK(corner > 0);             // the viewer's sky: the file has no light
    CHECK(centre != Approx(corner).epsilon(0.05));  // something other than sky in the middle
  }
  {  // sky=off and no light of the file's own: black, and torte warns about it
    const Result r = run(dir, {"unlit.glb", "sky=off", "width=8", "height=8", "spp=1", "output=dark.exr"});
    CHECK(r.code == 0);
    CHECK_THAT(r.err, Catch::Contains("warning"));
  }
  CHECK_THAT(check_error(run(dir, {"quad.glb", "camera=3", "width=8", "height=8"})),
             Catch::Contains("has 1 camera"));
  CHECK_THAT(check_error(run(dir, {"quad.glb", "sky=maybe"})), Catch::Contains("argument 'sky' must be auto, on or off"));
  CHECK_THAT(check_error(run(dir, {"quad.glb", "spp=four"})), Catch::Contains("argument 'spp' must be a number"));
  dir.write("broken.glb", "glTF not really");
  CHECK_THAT(check_error(run(dir, {"broken.glb"})), Catch::Contains("broken.glb"));
  {
    const Result r = run(dir, {"--list-args", "quad.glb"});
    CHECK(r.code == 0);
    CHECK_THAT(r.out, Catch::Contains("sky_strength"));
  }
}
