// Auxiliary outputs (AOVs): per-pixel features of what the camera sees, for compositing and for denoisers
// (torte's own, film/denoise.h, and external ones such as OIDN, whose definitions these follow).
//
//   albedo         reflectance of the first non-specular surface (its BSDF's directional albedo, estimated by
//                  sampling it), seen through mirrors and glass (times their specular weight); escaped rays give
//                  the sky's radiance clamped to [0, 1]
//   normal         world-space shading normal at that surface, turned towards the viewer
//   depth          camera-space distance along the view axis to the first hit (+inf where nothing is hit)
//   position       world-space first hit (0 where nothing is hit)
//   emission       radiance the camera sees emitted at the first hit by area lights and emitting voxel faces or
//                  cell shapes (as Cycles' Emit pass; the sky is not in it): light without transport noise,
//                  which the denoiser keeps apart
//   material_id    1 + dense index of the first hit's material (as the script assigned it: a mix is one id), 0
//                  where nothing is hit; the most frequent id among the pixel's samples
//   samples        camera samples the pixel took (a heat map of adaptive sampling, noise_threshold); not traced
//                  by this pass but counted by the render (samples_layer)
//   variance       variance of the pixel's mean luminance, from its own samples' moments (the denoiser's noise
//                  level); not traced by this pass but kept by the render's film (RenderSettings::pixel_variance),
//                  camera integrators only
//   glossiness     pi times the BSDF's pdf of the mirror direction at that surface: cos(theta) <= 1 for a diffuse
//                  surface, far above 1 for glossy ones (what the denoiser needs to know: the lighting of a glossy
//                  surface changes with a few degrees of normal, a diffuse one's does not)
//   traversal_cost acceleration nodes visited (channel nodes) and primitives tested (channel prims) by the
//                  closest-hit searches of the pass's rays (the camera ray and the mirrors and glass it follows),
//                  per sample: a heat map of where the scene's BVH is expensive (Aggregate::intersect_counted)
//
// The pass traces its own camera samples (aov_samples per pixel, stratified over the pixel filter, and the lens),
// independently of the integrator, so every integrator gets the same AOVs; deterministic for a seed. Pixels whose
// samples disagree (outlines, creases) take four times as many again, and emitters' outlines are measured on a
// fine grid (render_aovs).
#pragma once
#include <atomic>
#include <string>
#include <string_view>
#include <vector>

#include "camera/camera.h"
#include "film/image.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace torte {

enum class Aov : uint8_t {
  Albedo, Normal, Depth, Position, MaterialId, Emission, Samples, Variance, TraversalCost, Glossiness
};

inline constexpr const char* kAovChoices =
    "\"albedo\", \"normal\", \"depth\", \"position\", \"material_id\", \"emission\", \"samples\", \"variance\", "
    "\"traversal_cost\" or \"glossiness\"";

/// The AOV named `name` (as torte.render{aovs = ...} and --aovs spell it); false when none has that name.
bool parse_aov(std::string_view name, Aov& out);
const char* aov_name(Aov aov);

/// The "samples" layer (channel X): `pixel_spp` when it has a count per pixel (adaptive sampling), else `spp`
/// everywhere.
ImageLayer samples_layer(int width, int height, const std::vector<uint32_t>& pixel_spp, int spp);

/// The layers of `aovs` (in that order, each once) for `camera`'s view at settings' size, filter and seed, from
/// `samples` camera samples per pixel (5 * samples where they disagree). Layer names and channels are as
/// multi-layer EXR readers expect (`albedo.R`, `normal.X`, `depth.Z`, `position.X`, `material_id.X`,
/// `emission.R`). Stops early (the rows not done stay zero) when `cancel` becomes true.
std::vector<ImageLayer> render_aovs(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                                    const std::vector<Aov>& aovs, int samples,
                                    const std::atomic<bool>* cancel = nullptr);

}  // namespace torte
