#include "render/integrator_direct.h"

#include "render/integrator_path.h"

namespace torte {

RenderOutput render_direct(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                           ProgressSink* progress, const std::atomic<bool>* cancel) {
  return render_camera_paths(scene, camera, settings, DirectSettings::from(settings).rules(), progress, cancel);
}

}  // namespace torte
