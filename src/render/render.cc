#include "render/render.h"

#include <algorithm>

#include <hwy/targets.h>

#include "core/memory_budget.h"
#include "film/film.h"
#include "render/render_isa.h"
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
  // The film, then the image made from it; light tracing's film also holds a splat sum per pixel.
  const uint64_t splats = s.integrator == IntegratorKind::Lt ? sizeof(Rgb) : 0;
  return pixels * (sizeof(PixelSum) + sizeof(Rgb) + splats);
}

RenderOutput render(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                    ProgressSink* progress, const std::atomic<bool>* cancel) {
  validate(settings, camera);  // render/render_settings.cc
  reserve_memory(render_memory_bytes(settings),
                 "the " + std::to_string(settings.width) + "x" + std::to_string(settings.height) + " image's film");
  return render_isa::select()(scene, camera, settings, progress, cancel);
}

namespace render_isa {

// Highway's AVX2 target needs AVX2, FMA, BMI1/2, F16C and LZCNT, its AVX3 target AVX-512 F/VL/DQ/BW: the flags
// the render loop's copies are compiled with (CMakeLists.txt).
std::vector<Variant> supported() {
  std::vector<Variant> out{{&baseline, "baseline"}};
  [[maybe_unused]] const int64_t targets = hwy::SupportedTargets();
#if defined(TORTE_RENDER_ISA_AVX2) && HWY_ARCH_X86
  if (targets & (HWY_AVX2 | HWY_AVX3)) out.push_back({&avx2, "avx2"});
#endif
#if defined(TORTE_RENDER_ISA_AVX512) && HWY_ARCH_X86
  if (targets & HWY_AVX3) out.push_back({&avx512, "avx512"});
#endif
  return out;
}

Entry select() { return supported().back().entry; }
const char* selected_name() { return supported().back().name; }

}  // namespace render_isa

}  // namespace torte
