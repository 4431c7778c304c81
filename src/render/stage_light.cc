#include "render/stage_light.h"

#include "light/light_emission.h"
#include "render/shade.h"

namespace torte {

void trace_camera_connections(const Scene& scene, const CameraQueue& connections, const Film& film,
                              SplatBuffer& splats, std::vector<uint8_t>& occluded, RenderStats& stats) {
  const size_t n = connections.size();
  if (n == 0) return;
  occluded.resize(n);
  scene.occluded(connections.soa(), n, occluded.data(), false);
  for (size_t k = 0; k < n; ++k)
    if (!occluded[k] && !film.splat(splats, connections.raster[k], connections.contribution[k]))
      ++stats.dropped_samples;  // only a NaN or infinite value: connections land inside the image
  stats.shadow_rays += n;
}

}  // namespace torte
