// What every image writer does alike, compiled into both image modules (image_module.h): the checks of an image
// before it is written, the parent directories, the one-line error, and the display encoding (exposure, view
// transform, 8 bits) of PNG, JPEG and the other display formats.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/text.h"  // lower_extension
#include "film/image.h"
#include "film/image_io.h"

namespace torte {

/// Throws torte::Error "cannot write image 'path': reason".
[[noreturn]] void write_error(const std::string& path, const std::string& reason);
/// Throws (write_error) when the image has no pixels or its pixel array does not match its size.
void check_image_to_write(const Image& image, const std::string& path);
/// Throws (write_error) when a layer has no channels or not one value per channel and pixel (formats that keep
/// the layers: EXR).
void check_layers_to_write(const Image& image, const std::string& path);
/// Creates the missing parent directories of `path`; throws (write_error) naming the directory that failed.
void create_parent_directories(const std::string& path);
/// The image for a display: exposure, the view transform, then 8-bit quantisation; 3 bytes per pixel, rows top
/// to bottom.
std::vector<uint8_t> display_bytes(const Image& image, const WriteOptions& options);

}  // namespace torte
