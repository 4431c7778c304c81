// Image files: EXR and PNG output through OpenEXR and libpng, everything else through OpenImageIO. Implemented
// in two modules, which executables load on first use (film/image_module.h): linking OIIO cost every process
// start ~0.2-0.5 s.
#pragma once
#include <string>

#include "film/image.h"
#include "film/view_transform.h"

namespace torte {

struct WriteOptions {
  float exposure = 0;  // stops; applied (x 2^exposure) before encoding display formats (PNG, JPEG, ...)
  ViewTransform view = ViewTransform::Standard;  // display formats only
};

// The extension picks the format: .exr (32-bit float, linear, no tone mapping, every image attribute in the
// header), .hdr (RGBE, linear), .png/.jpg/.tif/... (exposure and the view transform, 8 bits; non-finite pixels
// black; text attributes where the format holds them). Creates missing parent
// directories. Throws torte::Error naming the file on failure.
void write_image(const Image& image, const std::string& path, const WriteOptions& options = {});
// Reads any format OIIO knows into linear RGB (sRGB-encoded 8-bit formats are decoded). Throws torte::Error.
Image read_image(const std::string& path);
// sRGB transfer function (IEC 61966-2-1) of one linear value clamped to [0,1].
float linear_to_srgb(float v);
float srgb_to_linear(float v);
/// Executables only (image_io_loader.cc): starts loading the writing module on a background thread and returns
/// at once, so that a later write need not wait for it. Harmless when it is loaded or loading already.
void preload_image_io();

}  // namespace torte
