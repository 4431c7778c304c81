// A linear RGB float image, row-major, (0,0) at the top left.
#pragma once
#include <array>
#include <string>
#include <variant>
#include <vector>

#include "core/rgb.h"

namespace torte {

/// A named value a file records beside the pixels: an EXR header attribute, a PNG text chunk. A matrix is 16
/// floats in row-major order (EXR's worldToCamera convention: row vectors, p' = p M).
struct ImageAttribute {
  std::string name;
  std::variant<int, float, std::string, std::array<float, 16>> value;
};

/// An extra layer of an image (an AOV): `channels` values per pixel, interleaved, row-major like the pixels.
/// Multi-layer EXR files name its channels `<name>.<channel>` (albedo.R, normal.X, depth.Z).
struct ImageLayer {
  std::string name;
  std::vector<std::string> channels;
  std::vector<float> values;  // channels.size() per pixel
  const float* at(size_t pixel) const { return values.data() + pixel * channels.size(); }
};

struct Image {
  int width = 0, height = 0;
  std::vector<Rgb> pixels;
  std::vector<ImageAttribute> attributes;  // written by image files that can hold them (EXR: all; PNG: text)
  std::vector<ImageLayer> layers;          // written by EXR only (as extra channels); other formats drop them
  /// The layer named `name`, or null.
  const ImageLayer* layer(const std::string& name) const {
    for (const ImageLayer& l : layers)
      if (l.name == name) return &l;
    return nullptr;
  }
  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h)) {}
  Rgb& at(int x, int y) { return pixels[size_t(y) * width + x]; }
  const Rgb& at(int x, int y) const { return pixels[size_t(y) * width + x]; }
};

}  // namespace torte
