// The "traversal_cost" AOV (render/aov_pass.h): per pixel, the acceleration nodes visited and primitives tested by
// the AOV pass's closest-hit searches, as a layer `traversal_cost` of channels `nodes` and `prims` from
// torte.render{aovs = ...} and from --aovs; the sky above everything costs exactly the triangle BVH's root.
#include <catch2/catch.hpp>

#include <string>

#include "aov_support.h"

using namespace torte;
using namespace torte::test;

namespace {

// A mesh cube and an analytic sphere side by side, three instanced spheres behind, seen level so that the top row
// of pixels looks over everything.
const char kScene[] = R"(
local opt = torte.options{output = "x.exr", aovs = "lua"}
local scene = torte.scene()
local m = torte.material.matte{color = {0.7, 0.7, 0.7}}
scene:add(torte.shape.cube{transform = torte.translate(-0.8, 0, 0) * torte.scale(0.5, 0.5, 0.5), material = m})
scene:add(torte.shape.sphere{radius = 0.4, transform = torte.translate(0.8, 0, 0), material = m})
local group = torte.group()
group:add(torte.shape.sphere{radius = 0.3, material = m})
for i = -1, 1 do scene:add(torte.instance{group = group, transform = torte.translate(i, 0, 2)}) end
scene:add(torte.light.infinite{radiance = {0.5, 0.5, 0.5}})
local camera = torte.camera.perspective{eye = {0, 0, -4}, look_at = {0, 0, 0}, fov = 50}
local img = torte.render{scene = scene, camera = camera, width = 48, height = 32, spp = 2,
                         aovs = opt.aovs == "lua" and {"traversal_cost"} or nil}
torte.save(img, opt.output)
)";

}  // namespace

TEST_CASE("traversal_cost aov: nodes and primitive tests per pixel, from the script or the command line",
          "[aov][cli]") {
  TempDir dir("traversal_cost", "aov");
  const std::string script = dir.write("s.lua", kScene);
  const auto layer_of = [&](const std::vector<std::string>& args, const std::string& name) {
    std::vector<std::string> all = {script, "output=" + (dir / name)};
    all.insert(all.end(), args.begin(), args.end());
    return rendered_layer(dir, all, dir / name, "traversal_cost", {"nodes", "prims"});
  };
  const ImageLayer lua = layer_of({}, "a.exr");
  const ImageLayer cli = layer_of({"aovs=none", "--aovs", "traversal_cost"}, "b.exr");
  // The same pass either way (deterministic for a seed).
  CHECK(lua.values == cli.values);
  // The top row sees only the sky: the mesh BVH's root is visited and nothing else is entered.
  for (int x = 0; x < 48; ++x) {
    CHECK(lua.values[2 * size_t(x)] == 1);
    CHECK(lua.values[2 * size_t(x) + 1] == 0);
  }
  // The middle row crosses the cube, the sphere and the instances: more work, and a primitive test or more.
  float most_nodes = 0, most_prims = 0;
  for (int x = 0; x < 48; ++x) {
    const size_t p = size_t(16 * 48 + x);
    most_nodes = std::max(most_nodes, lua.values[2 * p]);
    most_prims = std::max(most_prims, lua.values[2 * p + 1]);
    CHECK(lua.values[2 * p] >= 1);
  }
  CHECK(most_nodes >= 2);
  CHECK(most_prims >= 2);
}
