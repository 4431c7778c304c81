// The one validation of RenderSettings. torte.render{} reports a problem under its keyword before the scene is
// built; render() refuses the same settings with the same rule, for callers that are not Lua.
#pragma once
#include <optional>
#include <string>

#include "camera/camera.h"
#include "render/render.h"

namespace torte {

/// One invalid setting: `key` names it as torte.render{} does ("spp"), `problem` ends the sentence
/// ("must be in [1, 16777216], got 0").
struct SettingsProblem {
  const char* key;
  std::string problem;
  /// The whole sentence, for errors outside Lua: "'spp' must be in [1, 16777216], got 0".
  std::string message() const { return "'" + std::string(key) + "' " + problem; }
};

/// The first setting of `s` that render() does not accept, or nothing when all are in range.
std::optional<SettingsProblem> find_settings_problem(const RenderSettings& s);

/// Throws torte::Error with the first problem's message, or when `camera` was made for an image size other than
/// the settings' (its rays would not cover the image).
void validate(const RenderSettings& s, const Camera& camera);

}  // namespace torte
