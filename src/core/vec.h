// Small fixed-size vector types: Vec2f, Vec3f (used for points, vectors and normals alike; the
// transform decides how a value is mapped: apply_point / apply_vector / apply_normal).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace torte {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 0.31830988618379067154f;
constexpr float kInfinity = __builtin_huge_valf();

struct Vec2f {
  float x = 0, y = 0;
  constexpr Vec2f() = default;
  constexpr Vec2f(float x_, float y_) : x(x_), y(y_) {}
  constexpr Vec2f operator+(Vec2f b) const { return {x + b.x, y + b.y}; }
  constexpr Vec2f operator-(Vec2f b) const { return {x - b.x, y - b.y}; }
  constexpr Vec2f operator*(float s) const { return {x * s, y * s}; }
};

// 12 bytes; no padding so arrays of Vec3f are dense (SoA code uses separate float arrays instead).
struct Vec3f {
  float x = 0, y = 0, z = 0;
  constexpr Vec3f() = default;
  constexpr Vec3f(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  // Indexing by address: x, y, z are contiguous (standard layout, no padding); a ternary chain would cost
  // branches in the hot loops that index by a computed axis.
  float operator[](int i) const { return (&x)[i]; }
  float& operator[](int i) { return (&x)[i]; }
  constexpr Vec3f operator+(Vec3f b) const { return {x + b.x, y + b.y, z + b.z}; }
  constexpr Vec3f operator-(Vec3f b) const { return {x - b.x, y - b.y, z - b.z}; }
  constexpr Vec3f operator-() const { return {-x, -y, -z}; }
  constexpr Vec3f operator*(float s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3f operator/(float s) const { return {x / s, y / s, z / s}; }
  constexpr Vec3f& operator+=(Vec3f b) { x += b.x; y += b.y; z += b.z; return *this; }
  constexpr Vec3f& operator-=(Vec3f b) { x -= b.x; y -= b.y; z -= b.z; return *this; }
  constexpr Vec3f& operator*=(float s) { x *= s; y *= s; z *= s; return *this; }
  constexpr bool operator==(const Vec3f&) const = default;
};

static_assert(sizeof(Vec3f) == 12);
constexpr Vec3f operator*(float s, Vec3f v) { return v * s; }
constexpr float dot(Vec3f a, Vec3f b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3f cross(Vec3f a, Vec3f b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
constexpr Vec3f mul(Vec3f a, Vec3f b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
constexpr float length_squared(Vec3f v) { return dot(v, v); }
inline float length(Vec3f v) { return std::sqrt(dot(v, v)); }
inline Vec3f normalize(Vec3f v) { return v / length(v); }
inline float distance(Vec3f a, Vec3f b) { return length(a - b); }
inline Vec3f min(Vec3f a, Vec3f b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
inline Vec3f max(Vec3f a, Vec3f b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }
inline Vec3f abs(Vec3f v) { return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}; }
inline float max_component(Vec3f v) { return std::max(v.x, std::max(v.y, v.z)); }
inline int max_dimension(Vec3f v) { return v.x > v.y ? (v.x > v.z ? 0 : 2) : (v.y > v.z ? 1 : 2); }
inline bool is_finite(Vec3f v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
// Flips n to lie in the hemisphere of v.
inline Vec3f face_forward(Vec3f n, Vec3f v) { return dot(n, v) < 0 ? -n : n; }

// Orthonormal basis around a unit vector (Duff et al. 2017, "Building an orthonormal basis, revisited").
struct Frame {
  Vec3f s, t, n;
  static Frame from_z(Vec3f n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {Vec3f(1 + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3f(b, sign + n.y * n.y * a, -n.y), n};
  }
  Vec3f to_local(Vec3f v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  Vec3f to_world(Vec3f v) const { return s * v.x + t * v.y + n * v.z; }
};

}  // namespace torte
