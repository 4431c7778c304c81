// The "glossiness" AOV (render/aov_pass.h): pi times the BSDF's pdf of the mirror direction at the first
// non-specular surface, about cos(theta) <= 1 on a diffuse surface and far above 1 on a glossy one; written by
// denoise = true for the denoiser's normal weights (film/denoise.h).
#include <catch2/catch.hpp>

#include <string>

#include "aov_support.h"

using namespace torte;
using namespace torte::test;

namespace {

// A matte sphere at x = -1, rough gold at x = +1, the sky above.
const char kScene[] = R"(
local opt = torte.options{output = "x.exr", denoise = false}
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 0.8, transform = torte.translate(-1, 0, 0),
                             material = torte.material.matte{color = {0.7, 0.7, 0.7}}})
scene:add(torte.shape.sphere{radius = 0.8, transform = torte.translate(1, 0, 0),
                             material = torte.material.metal{metal = "gold", roughness = 0.1}})
scene:add(torte.light.infinite{radiance = {0.5, 0.5, 0.5}})
local camera = torte.camera.perspective{eye = {0, 0, -4}, look_at = {0, 0, 0}, fov = 60}
local img = torte.render{scene = scene, camera = camera, width = 48, height = 32, spp = 4, denoise = opt.denoise,
                         aovs = not opt.denoise and {"glossiness"} or nil}
torte.save(img, opt.output)
)";

}  // namespace

TEST_CASE("glossiness aov: at most about 1 on a matte surface, far above on rough metal, written by denoise",
          "[aov][cli]") {
  TempDir dir("glossiness", "aov");
  const std::string script = dir.write("s.lua", kScene);
  for (const char* denoise : {"false", "true"}) {
    INFO("denoise=" << denoise);
    const std::string out = dir / (std::string(denoise) + ".exr");
    const ImageLayer g =
        rendered_layer(dir, {script, std::string("denoise=") + denoise, "output=" + out}, out, "glossiness", {"Y"});
    const auto at = [&](int x, int y) { return g.values[size_t(y) * 48 + size_t(x)]; };
    CHECK(at(24, 0) == 0);  // the sky: no surface
    const float matte = at(31, 16), metal = at(17, 16);  // x = -1 is on the image's right
    INFO("matte " << matte << ", metal " << metal);
    CHECK(matte > 0.5f);
    CHECK(matte <= 1.0f);
    CHECK(metal > 20);
  }
}
