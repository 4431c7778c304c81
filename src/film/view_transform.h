// View transforms: how the linear scene light of a render becomes the display values of an 8-bit output
// (PNG, JPEG, ...). EXR and HDR files stay linear and carry no view transform.
#pragma once
#include <string_view>
#include <vector>

#include "film/image.h"

namespace torte {

enum class ViewTransform {
  Standard,  // the sRGB display encoding (IEC 61966-2-1) of the clamped linear value: what torte always wrote
  Filmic,    // the ACES 1.0 SDR-video output transform on an sRGB display: highlights roll off instead of clipping
  Agx,       // AgX (Sobotka), the published analytic fit of its base contrast: hues desaturate towards white
};

inline constexpr const char* kViewTransformChoices = "\"standard\", \"filmic\" (or \"aces\") or \"agx\"";

/// The transform named `name` (ASCII, as scripts and the command line spell it); false when none has that name.
inline bool parse_view_transform(std::string_view name, ViewTransform& out) {
  if (name == "standard" || name == "srgb") out = ViewTransform::Standard;
  else if (name == "filmic" || name == "aces") out = ViewTransform::Filmic;
  else if (name == "agx") out = ViewTransform::Agx;
  else return false;
  return true;
}

inline const char* view_transform_name(ViewTransform v) {
  switch (v) {
    case ViewTransform::Filmic: return "filmic";
    case ViewTransform::Agx: return "agx";
    case ViewTransform::Standard: break;
  }
  return "standard";
}

/// Display values in [0, 1] (RGB interleaved, `3 * pixels` floats in `out`) of `image` scaled by 2^exposure,
/// ready for 8-bit quantisation; non-finite pixels become black. Implemented in the image module (OpenColorIO):
/// executables reach it through the loader like the image readers. Throws torte::Error if OCIO fails.
void apply_view_transform(ViewTransform view, float exposure, const Image& image, std::vector<float>& out);

}  // namespace torte
