// Core-side interface of image textures. The implementation lives in torte_io (image_texture_oiio.h), so that
// torte_core never sees OpenImageIO; a TextureTable holds its images as shared_ptr<const ImageSource>, and a
// lookup is the only virtual call in texture evaluation (OpenImageIO costs a call per lookup anyway).
#pragma once
#include <memory>
#include <string>

#include "core/rgb.h"
#include "core/vec.h"

namespace torte {

class ImageSource {
 public:
  virtual ~ImageSource() = default;
  // st: texture coordinates with (0, 0) at the image's BOTTOM-left and (1, 1) at its top-right (the OBJ / uv
  // convention). filter_width: width of the lookup footprint in st units; 0 = unknown, read the finest level.
  // Returns linear RGB.
  virtual Rgb lookup(Vec2f st, float filter_width) const = 0;
  // For messages and tostring().
  virtual std::string description() const { return "image"; }
  // Empty while every lookup succeeded; else why the first failed lookup failed, naming the file (a failed
  // lookup returns black, so the renderer checks this and fails instead of writing a wrong image).
  virtual std::string failure() const { return {}; }
};

struct ImageTextureOptions {
  enum class Wrap { Periodic, Clamp, Black, Mirror } wrap = Wrap::Periodic;
  // Closest: nearest texel of the finest level. Bilinear: bilinear on the one MIP level matching filter_width.
  // Trilinear: bilinear on the two nearest MIP levels, blended (MIP levels made on load for untiled files).
  enum class Filter { Closest, Bilinear, Trilinear } filter = Filter::Trilinear;
  // Auto: 8-bit images are sRGB-encoded colour unless the file says it is linear; others are linear.
  enum class ColorSpace { Auto, Srgb, Linear } color_space = ColorSpace::Auto;
  // The file's channel looked up as R (the next two as G and B): glTF packs roughness in G and metalness in B.
  int first_channel = 0;
};

}  // namespace torte
