#include "render/render.h"

#include <algorithm>

#include "core/error.h"
#include "core/memory_budget.h"
#include "film/film.h"
#include "render/integrator_bdpt.h"
#include "render/integrator_direct.h"
#include "render/integrator_igi.h"
#include "render/integrator_lt.h"
#include "render/integrator_path.h"
#include "render/tile_loop.h"

namespace torte {

namespace detail {

std::vector<Tile> make_tiles(int width, int height, int size) {
  std::vector<Tile> tiles;
  for (int y = 0; y < height; y += size)
    for (int x = 0; x < width; x += size) tiles.push_back({x, y, std::min(x + size, width), std::min(y + size, height)});
  return tiles;
}

std::vector<int> make_passes(int spp) {
  std::vector<int> passes;
  int done = 0, size = 1;
  while (done < spp) {
    const int n = std::min(size, spp - done);
    passes.push_back(n);
    done += n;
    size = std::min(size * 2, 16);
  }
  return passes;
}

std::string texture_failure(const Scene& scene) {
  for (const auto& image : scene.textures.images())
    if (std::string f = image->failure(); !f.empty()) return f;
  return {};
}

}  // namespace detail

uint64_t render_memory_bytes(const RenderSettings& s) {
  const uint64_t pixels = uint64_t(std::max(s.width, 0)) * uint64_t(std::max(s.height, 0));
  // The film, then the image made from it; light tracing's and BDPT's film also holds a splat sum per pixel.
  const uint64_t splats = splats_to_film(s.integrator) ? sizeof(Rgb) : 0;
  return pixels * (sizeof(PixelSum) + sizeof(Rgb) + splats);
}

RenderOutput render(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                    ProgressSink* progress, const std::atomic<bool>* cancel) {
  validate(settings, camera);  // render/render_settings.cc
  reserve_memory(render_memory_bytes(settings),
                 "the " + std::to_string(settings.width) + "x" + std::to_string(settings.height) + " image's film");
  switch (settings.integrator) {
    case IntegratorKind::Path: return render_path(scene, camera, settings, progress, cancel);
    case IntegratorKind::Direct: return render_direct(scene, camera, settings, progress, cancel);
    case IntegratorKind::Igi: return render_igi(scene, camera, settings, progress, cancel);
    case IntegratorKind::Lt: return render_lt(scene, camera, settings, progress, cancel);
    case IntegratorKind::Bdpt: return render_bdpt(scene, camera, settings, progress, cancel);
  }
  throw Error("internal: unknown integrator");
}

}  // namespace torte
