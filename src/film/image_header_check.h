// A check of OpenEXR and PNG headers before OpenImageIO opens a file: their libraries allocate from declared sizes
// before reading the bytes, and OpenImageIO gives no hook to bound that. OpenEXR 3.1 (Debian 12): a string
// attribute's declared size (up to 2 GB), and decoding buffers of a whole block of scanlines (up to 256 lines of the
// data window's width) or of a tile. libpng 1.6 (Debian 12, built without a chunk allocation limit): a buffer of each
// ancillary chunk's declared length (up to 2 GB). A few hundred bytes can claim gigabytes.
#pragma once
#include <cstdint>
#include <string>

namespace torte {

struct ImageHeaderCheck {
  /// What is wrong ("corrupt OpenEXR header: attribute 'x' (string) claims 2147483647 bytes, 380 are left in the
  /// file"), or "" when the headers are sound or the file is neither OpenEXR nor PNG.
  std::string problem;
  /// Bytes OpenEXR will allocate to decode one block of scanlines or one tile (the largest over all parts), to be
  /// checked against the memory budget; 0 for other formats.
  uint64_t decode_bytes = 0;
};

/// When the file at `path` starts with the OpenEXR magic number, walks its header(s): every attribute's name and
/// type must be terminated and its value must end inside the file. A PNG file's chunks other than IDAT must end
/// inside the file (a cut IDAT is left to libpng, which reports the pixel data as truncated). Files of other
/// formats, and unreadable files, pass (the image reader reports those).
ImageHeaderCheck check_image_header(const std::string& path);

}  // namespace torte
