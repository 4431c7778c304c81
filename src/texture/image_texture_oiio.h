// Image textures through OpenImageIO's TextureSystem (in torte_io; this header includes no OpenImageIO).
#pragma once
#include <memory>
#include <string>

#include "texture/image_texture.h"

namespace torte {

// Opens `path` (any format OpenImageIO reads) now, so a missing or unreadable file is reported at once:
// throws torte::Error naming the file.
//
// Lookups go through one process-wide TextureSystem (its own cache, MIP levels built on load for untiled
// files, grey images expanded to RGB), the file's TextureHandle resolved once here, and the calling thread's
// Perthread record. t is flipped so uv (0, 0) is the image's bottom-left. sRGB decoding: OpenImageIO 2.4's
// TextureOpt has no colour transform, so 8-bit sRGB images are filtered in their encoded values and the
// filtered result is decoded (exact for the closest filter; a small bias where texels of very different
// brightness are blended).
std::shared_ptr<const ImageSource> open_image_texture(const std::string& path, const ImageTextureOptions& options);

/// Drops what the process-wide texture cache holds for `path`, so that a file rewritten in place is read afresh
/// (fuzzing and tests rewrite one file). Sources opened before must not be used afterwards.
void invalidate_image_texture(const std::string& path);

}  // namespace torte
