// The integrator switch, compiled once per ISA (render/render_isa.h): TORTE_RENDER_ISA names this copy's entry.
#include "render/render_isa.h"

#include "core/error.h"
#include "render/integrator_bdpt.h"
#include "render/integrator_direct.h"
#include "render/integrator_igi.h"
#include "render/integrator_lt.h"
#include "render/integrator_mlt.h"
#include "render/integrator_path.h"
#include "render/integrator_vcm.h"

#ifndef TORTE_RENDER_ISA
#define TORTE_RENDER_ISA baseline
#endif

namespace torte::render_isa {

RenderOutput TORTE_RENDER_ISA(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                              ProgressSink* progress, const std::atomic<bool>* cancel) {
  switch (settings.integrator) {
    case IntegratorKind::Path: return render_path(scene, camera, settings, progress, cancel);
    case IntegratorKind::Direct: return render_direct(scene, camera, settings, progress, cancel);
    case IntegratorKind::Igi: return render_igi(scene, camera, settings, progress, cancel);
    case IntegratorKind::Lt: return render_lt(scene, camera, settings, progress, cancel);
    case IntegratorKind::Bdpt: return render_bdpt(scene, camera, settings, progress, cancel);
    case IntegratorKind::Vcm:
    case IntegratorKind::Ppm: return render_vcm(scene, camera, settings, progress, cancel);
    case IntegratorKind::Mlt: return render_mlt(scene, camera, settings, progress, cancel);
  }
  throw Error("internal: unknown integrator");
}

}  // namespace torte::render_isa
