#include "film/image_write_common.h"

#include <cmath>
#include <filesystem>
#include <system_error>

#include "core/error.h"
#include "film/view_transform.h"

namespace torte {

namespace fs = std::filesystem;

float linear_to_srgb(float v) {
  if (!(v > 0)) return 0;  // also maps NaN to 0
  if (v >= 1) return 1;
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
}

float srgb_to_linear(float v) {
  if (!(v > 0)) return 0;
  if (v >= 1) return 1;
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

void write_error(const std::string& path, const std::string& reason) {
  throw Error("cannot write image '" + path + "': " + reason);
}

void check_image_to_write(const Image& image, const std::string& path) {
  if (image.width <= 0 || image.height <= 0 || image.pixels.size() != size_t(image.width) * size_t(image.height))
    write_error(path, "the image is empty or its pixel count does not match " + std::to_string(image.width) + "x" +
                          std::to_string(image.height));
}

void check_layers_to_write(const Image& image, const std::string& path) {
  const size_t n = image.pixels.size();
  for (const ImageLayer& l : image.layers)
    if (l.channels.empty() || l.values.size() != n * l.channels.size())
      write_error(path, "layer '" + l.name + "' does not hold " + std::to_string(l.channels.size()) +
                            " values for each of the " + std::to_string(n) + " pixels");
}

void create_parent_directories(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) write_error(path, "cannot create directory '" + parent.string() + "': " + ec.message());
}

std::vector<uint8_t> display_bytes(const Image& image, const WriteOptions& options) {
  // Exposure and the view transform are applied here rather than by a library's colour management, so the
  // output does not depend on how OpenImageIO or OpenColorIO were configured.
  std::vector<float> display;
  apply_view_transform(options.view, options.exposure, image, display);
  std::vector<uint8_t> bytes(display.size());
  for (size_t i = 0; i < display.size(); ++i) bytes[i] = static_cast<uint8_t>(std::lround(display[i] * 255));
  return bytes;
}

}  // namespace torte
