#include "material/metals.h"

#include <array>

namespace torte {

namespace {

struct MetalPreset {
  std::string_view symbol, name;
  Rgb eta, k;
};

// Source: the RGB complex IORs of Tungsten (Benedikt Bitterli, src/core/bsdfs/ComplexIorData.hpp), which are the
// measured spectral data shipped with Mitsuba 0.5 (from PBRT-v3's spd files / Palik, "Handbook of Optical
// Constants of Solids") integrated against the CIE matching functions and converted to linear sRGB. The same
// numbers are used by many renderers' "Au", "Ag", ... presets, so scenes look alike across them.
constexpr std::array<MetalPreset, 10> kPresets = {{
    {"Au", "gold", {0.1431189557f, 0.3749570432f, 1.4424785571f}, {3.9831604247f, 2.3857207478f, 1.6032152899f}},
    {"Ag", "silver", {0.1552646489f, 0.1167232965f, 0.1383806959f}, {4.8283433224f, 3.1222459278f, 2.1469504455f}},
    {"Cu", "copper", {0.2004376970f, 0.9240334304f, 1.1022119527f}, {3.9129485033f, 2.4528477015f, 2.1421879552f}},
    {"Al", "aluminium", {1.6574599595f, 0.8803689579f, 0.5212287346f},
     {9.2238691996f, 6.2695232477f, 4.8370012281f}},
    {"Cr", "chromium", {4.3696828663f, 2.9167024892f, 1.6547005413f},
     {5.2064337956f, 4.2313645277f, 3.7549467933f}},
    {"W", "tungsten", {4.3707029924f, 3.3002972445f, 2.9982666528f}, {3.5006778591f, 2.6048652781f, 2.2731930614f}},
    {"Ni", "nickel", {2.3672753521f, 1.6633583302f, 1.4670554172f}, {4.4988329911f, 3.0501643957f, 2.3454274399f}},
    {"V", "vanadium", {4.2775126218f, 3.5131538236f, 2.7611257461f}, {3.4911844504f, 2.8893580874f, 3.1116965117f}},
    {"Ir", "iridium", {3.0864098394f, 2.0821938440f, 1.6178866805f}, {5.5921510077f, 4.0671757150f, 3.2672611269f}},
    {"Hg", "mercury", {2.3989314904f, 1.4400254917f, 0.9095512090f}, {6.3276269444f, 4.3719414152f, 3.4217899270f}},
}};

constexpr std::array<std::string_view, 2 * kPresets.size() + 1> make_names() {
  std::array<std::string_view, 2 * kPresets.size() + 1> names{};
  for (size_t i = 0; i < kPresets.size(); ++i) {
    names[2 * i] = kPresets[i].name;
    names[2 * i + 1] = kPresets[i].symbol;
  }
  names.back() = "aluminum";  // American spelling
  return names;
}

constexpr auto kNames = make_names();

}  // namespace

bool metal_preset(std::string_view name, Rgb* eta, Rgb* k) {
  if (name == "aluminum") name = "aluminium";
  for (const MetalPreset& p : kPresets) {
    if (name == p.symbol || name == p.name) {
      *eta = p.eta;
      *k = p.k;
      return true;
    }
  }
  return false;
}

std::span<const std::string_view> metal_preset_names() { return kNames; }

}  // namespace torte
