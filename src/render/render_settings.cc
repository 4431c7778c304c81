#include "render/render_settings.h"

#include <cmath>

#include "core/error.h"

namespace torte {

std::optional<SettingsProblem> find_settings_problem(const RenderSettings& s) {
  if (s.width <= 0 || s.height <= 0) return SettingsProblem{"width", "and 'height' must be positive"};
  const uint64_t pixels = uint64_t(s.width) * uint64_t(s.height);
  if (pixels > kMaxRenderPixels)
    return SettingsProblem{"width", "x 'height' = " + std::to_string(s.width) + "x" + std::to_string(s.height) + " = " +
                                        std::to_string(pixels) + " pixels, more than the limit of " +
                                        std::to_string(kMaxRenderPixels) + " (2^28)"};
  if (s.spp <= 0 || s.spp > kMaxSpp)
    return SettingsProblem{"spp", "must be in [1, " + std::to_string(kMaxSpp) + "], got " + std::to_string(s.spp)};
  if (s.max_depth < 0 || s.max_depth > 10000)
    return SettingsProblem{"max_depth", "must be in [0, 10000], got " + std::to_string(s.max_depth)};
  if (s.rr_depth < 0)
    return SettingsProblem{"rr_depth", "must be a non-negative number of bounces, got " + std::to_string(s.rr_depth)};
  if (s.tile_size <= 0 || s.tile_size > 1024)
    return SettingsProblem{"tile_size", "must be in [1, 1024], got " + std::to_string(s.tile_size)};
  if (s.vpl_sets < 1 || s.vpl_sets > 65536) return SettingsProblem{"vpl_sets", "must be in [1, 65536]"};
  if (s.light_paths < 1 || s.light_paths > (1 << 24)) return SettingsProblem{"light_paths", "must be in [1, 16777216]"};
  if (!(s.g_limit > 0))
    return SettingsProblem{"g_limit", "must be positive (relative to 1/R^2, R the scene's bounding radius; infinity "
                                      "disables the clamp)"};
  if (!(s.vpl_roulette >= 0 && s.vpl_roulette <= 1)) return SettingsProblem{"vpl_roulette", "must be in [0, 1]"};
  if (!(s.merge_radius > 0) || !std::isfinite(s.merge_radius))
    return SettingsProblem{"radius", "must be positive and finite (relative to the scene's bounding radius)"};
  if (!(s.merge_alpha > 0 && s.merge_alpha <= 1)) return SettingsProblem{"alpha", "must be in (0, 1]"};
  if (!(s.large_step > 0 && s.large_step <= 1))
    return SettingsProblem{"large_step", "must be in (0, 1] (the probability of a fresh path per mutation)"};
  if (s.chains < 0 || s.chains > (1 << 20))
    return SettingsProblem{"chains", "must be 0 (automatic) or a number of Markov chains up to 1048576"};
  if (!(s.noise_threshold >= 0) || !std::isfinite(s.noise_threshold))
    return SettingsProblem{"noise_threshold", "must be 0 (off) or a positive relative error such as 0.01"};
  if (s.noise_threshold > 0 && !supports_adaptive_sampling(s.integrator))
    return SettingsProblem{"noise_threshold",
                           std::string("works with integrators path, direct and igi only, not \"") +
                               integrator_name(s.integrator) +
                               "\" (its light paths splat into pixels other than their own sample's)"};
  if (s.adaptive_min_spp < 2 || s.adaptive_min_spp > kMaxSpp)
    return SettingsProblem{"adaptive_min_spp", "must be in [2, " + std::to_string(kMaxSpp) + "], got " +
                                                   std::to_string(s.adaptive_min_spp)};
  if (!(s.time_limit >= 0) || !std::isfinite(s.time_limit))
    return SettingsProblem{"time_limit", "must be 0 (none) or a positive number of seconds"};
  return std::nullopt;
}

void validate(const RenderSettings& s, const Camera& camera) {
  if (const auto p = find_settings_problem(s)) throw Error(p->message());
  if (camera.image_width() != float(s.width) || camera.image_height() != float(s.height))
    throw Error("the camera was made for a " + std::to_string(int(camera.image_width())) + "x" +
                std::to_string(int(camera.image_height())) + " image, the settings ask for " + std::to_string(s.width) +
                "x" + std::to_string(s.height));
  if (connects_to_camera(s.integrator))
    if (const std::string why = camera.connect_problem(); !why.empty())
      throw Error(std::string("integrator '") + integrator_name(s.integrator) + "': " + why);
}

}  // namespace torte
