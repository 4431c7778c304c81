// Named complex refractive indices (eta, k) of common metals, as linear-RGB triples for the conductor BSDF.
#pragma once
#include <span>
#include <string_view>

#include "core/rgb.h"

namespace torte {

// Looks up a metal by name (case-sensitive; both chemical symbols such as "Au" and English names such as "gold"
// are accepted). Returns false and leaves the outputs untouched for unknown names.
bool metal_preset(std::string_view name, Rgb* eta, Rgb* k);

// Every accepted name, for error messages ("accepted: ...").
std::span<const std::string_view> metal_preset_names();

}  // namespace torte
