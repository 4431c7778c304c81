// The render loop compiled once per instruction set. The integrators, stages, light sampling, hit reconstruction
// and textures (TORTE_RENDER_ISA_SOURCES in CMakeLists.txt) are compiled for baseline x86-64 and again for each
// ISA in TORTE_RENDER_ISAS (AVX2 + FMA, AVX-512); scripts/isa-object.sh links each extra copy into one object
// whose symbols are all local except its entry here, so no inline function or template of another ISA can
// stand in for a baseline one. render() picks the variant once per call from Highway's CPU detection.
#pragma once
#include <atomic>
#include <vector>

#include "render/render.h"

namespace torte::render_isa {

/// Runs settings.integrator (settings validated, film reserved): one definition per compiled ISA.
using Entry = RenderOutput (*)(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                               ProgressSink* progress, const std::atomic<bool>* cancel);
RenderOutput baseline(const Scene&, const Camera&, const RenderSettings&, ProgressSink*, const std::atomic<bool>*);
RenderOutput avx2(const Scene&, const Camera&, const RenderSettings&, ProgressSink*, const std::atomic<bool>*);
RenderOutput avx512(const Scene&, const Camera&, const RenderSettings&, ProgressSink*, const std::atomic<bool>*);

struct Variant {
  Entry entry;
  const char* name;  // "baseline", "avx2", "avx512"
};
/// The variants compiled in that this CPU (and Highway's dispatch) allows, baseline first, the best last.
std::vector<Variant> supported();

/// The best variant compiled in that this CPU runs (and Highway's dispatch allows: tests that force a Highway
/// target also force the render loop's ISA), and its name ("baseline", "avx2", "avx512").
Entry select();
const char* selected_name();

}  // namespace torte::render_isa
