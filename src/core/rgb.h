// Linear RGB radiometric quantity (radiance, reflectance, power), 12 bytes.
#pragma once
#include <cmath>

namespace torte {

struct Rgb {
  float r = 0, g = 0, b = 0;
  constexpr Rgb() = default;
  constexpr explicit Rgb(float v) : r(v), g(v), b(v) {}
  constexpr Rgb(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
  constexpr Rgb operator+(Rgb o) const { return {r + o.r, g + o.g, b + o.b}; }
  constexpr Rgb operator-(Rgb o) const { return {r - o.r, g - o.g, b - o.b}; }
  constexpr Rgb operator*(Rgb o) const { return {r * o.r, g * o.g, b * o.b}; }
  constexpr Rgb operator*(float s) const { return {r * s, g * s, b * s}; }
  constexpr Rgb operator/(float s) const { return {r / s, g / s, b / s}; }
  constexpr Rgb& operator+=(Rgb o) { r += o.r; g += o.g; b += o.b; return *this; }
  constexpr Rgb& operator*=(Rgb o) { r *= o.r; g *= o.g; b *= o.b; return *this; }
  constexpr Rgb& operator*=(float s) { r *= s; g *= s; b *= s; return *this; }
  constexpr bool operator==(const Rgb&) const = default;
  constexpr bool is_black() const { return r == 0 && g == 0 && b == 0; }
  constexpr float max_component() const { return r > g ? (r > b ? r : b) : (g > b ? g : b); }
  constexpr float average() const { return (r + g + b) / 3; }
  // Rec. 709 luminance.
  constexpr float luminance() const { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }
  bool is_finite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
};

constexpr Rgb operator*(float s, Rgb c) { return c * s; }

}  // namespace torte
