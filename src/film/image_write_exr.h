// EXR output (image_write_exr.cc): 32-bit float RGB, linear, ZIP-compressed, the image's layers as channels
// <layer>.<channel> and its attributes in the header.
#pragma once
#include <string>

#include "film/image.h"

namespace torte {

/// Writes `image` to `path` as EXR, creating missing parent directories. Throws torte::Error naming the file.
void write_exr(const Image& image, const std::string& path);

}  // namespace torte
