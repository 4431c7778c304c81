// A linear RGB float image, row-major, (0,0) at the top left.
#pragma once
#include <vector>

#include "core/rgb.h"

namespace torte {

struct Image {
  int width = 0, height = 0;
  std::vector<Rgb> pixels;
  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h)) {}
  Rgb& at(int x, int y) { return pixels[size_t(y) * width + x]; }
  const Rgb& at(int x, int y) const { return pixels[size_t(y) * width + x]; }
};

}  // namespace torte
