// PNG output (image_write_png.cc): 8-bit sRGB after exposure and the view transform, the image's text
// attributes as tEXt chunks.
#pragma once
#include <string>

#include "film/image.h"
#include "film/image_io.h"

namespace torte {

/// Writes `image` to `path` as PNG, creating missing parent directories. Throws torte::Error naming the file.
void write_png(const Image& image, const std::string& path, const WriteOptions& options);

}  // namespace torte
