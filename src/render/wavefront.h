// Renders a batch of camera samples as wavefronts: trace all rays, add emission, counting-sort the hits by
// material type, run one shading kernel per type, trace the shadow rays, repeat with the surviving paths.
#pragma once
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

#include "camera/camera.h"
#include "core/sampler.h"
#include "film/film.h"
#include "render/path_state.h"
#include "render/render.h"
#include "render/shade.h"

namespace torte {

struct VplStore;  // render/igi.h

struct SampleRequest {
  uint32_t pixel;   // linear index
  uint32_t sample;  // index within the pixel
};

class WavefrontRenderer {
 public:
  // `vpls` (IntegratorKind::Igi only, else null): the virtual point lights camera hits gather from.
  WavefrontRenderer(const Scene& scene, const Camera& camera, const RenderSettings& settings, const Sampler& sampler,
                    const VplStore* vpls = nullptr)
      : scene_(scene), camera_(camera), settings_(settings), sampler_(sampler), vpls_(vpls) {}
  // Renders the requested samples and adds them to film (indexed by pixel). Counts rays and dropped samples.
  void render(const std::vector<SampleRequest>& requests, Film& film, RenderStats& stats);

 private:
  void generate_camera_rays(const std::vector<SampleRequest>& requests);
  void trace(RenderStats& stats);
  void add_emission_and_queue(RenderStats& stats);
  void shade();
  void trace_shadows(RenderStats& stats, bool coherent = false);
  void gather_vpls(RenderStats& stats);  // IGI: VPL light at the hits shade() recorded, traced in batches
  void compact();

  const Scene& scene_;
  const Camera& camera_;
  const RenderSettings& settings_;
  const Sampler& sampler_;
  const VplStore* vpls_;
  std::vector<VplHit> vpl_hits_;                          // IGI: hits recorded by shade(), grouped by type
  size_t vpl_hits_end_[kShadedMaterialTypeCount] = {};   // end of each type's group in vpl_hits_
  std::vector<uint32_t> vpl_order_;                       // IGI: gather scratch
  int max_depth_ = 0;
  float spread_ = 0;  // camera ray-cone spread angle
  PathState paths_;
  ShadowQueue shadows_;
  // Gathers the rays of `paths` (indices into paths_ or, for shadows, the shadow queue) into SoA arrays.
  template <class RayOf>
  RaySoA gather_rays(size_t count, RayOf&& ray_of);
  std::vector<uint32_t> active_;                   // paths still going
  std::vector<float> ray_buf_[7];                  // ox, oy, oz, dx, dy, dz, t_max for the trace kernels
  std::vector<Hit> hit_buf_;
  std::vector<uint8_t> occluded_buf_;
  std::vector<uint32_t> material_queue_;           // active hits sorted by material type
  uint32_t queue_begin_[kMaterialTypeCount + 1] = {};
  // Shading scratch, one per shaded material type (index = MaterialType).
  template <MaterialType T>
  using Scratch = ShadeScratch<typename MaterialTraits<T>::Bsdf>;
  PerShadedType<Scratch> scratch_;
};

}  // namespace torte
