#include "core/transform.h"

#include <cmath>
#include <utility>

#include "core/error.h"

namespace torte {

Mat4 operator*(const Mat4& a, const Mat4& b) {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += double(a.m[i][k]) * b.m[k][j];
      r.m[i][j] = float(s);
    }
  return r;
}

Mat4 transpose(const Mat4& a) {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = a.m[j][i];
  return r;
}

Mat4 inverse(const Mat4& a) {
  double m[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      m[i][j] = a.m[i][j];
      m[i][j + 4] = i == j ? 1 : 0;
    }
  for (int c = 0; c < 4; ++c) {
    int pivot = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::fabs(m[r][c]) > std::fabs(m[pivot][c])) pivot = r;
    if (std::fabs(m[pivot][c]) < 1e-30) throw Error("transform is singular (it cannot be inverted)");
    if (pivot != c)
      for (int j = 0; j < 8; ++j) std::swap(m[c][j], m[pivot][j]);
    const double inv = 1.0 / m[c][c];
    for (int j = 0; j < 8; ++j) m[c][j] *= inv;
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      const double f = m[r][c];
      if (f == 0) continue;
      for (int j = 0; j < 8; ++j) m[r][j] -= f * m[c][j];
    }
  }
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = float(m[i][j + 4]);
  return r;
}

Transform::Transform(const Mat4& m) : m_(m), inv_(torte::inverse(m)) {}

Bounds3f Transform::apply(const Bounds3f& b) const {
  Bounds3f r;
  if (b.empty()) return r;
  for (int i = 0; i < 8; ++i)
    r.extend(apply_point({(i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z}));
  return r;
}

float Transform::determinant3() const {
  const auto& a = m_.m;
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

Transform translate(Vec3f d) {
  Mat4 m, inv;
  m.m[0][3] = d.x; m.m[1][3] = d.y; m.m[2][3] = d.z;
  inv.m[0][3] = -d.x; inv.m[1][3] = -d.y; inv.m[2][3] = -d.z;
  return {m, inv};
}

Transform scale(Vec3f s) {
  if (s.x == 0 || s.y == 0 || s.z == 0) throw Error("scale factors must be non-zero");
  Mat4 m, inv;
  m.m[0][0] = s.x; m.m[1][1] = s.y; m.m[2][2] = s.z;
  inv.m[0][0] = 1 / s.x; inv.m[1][1] = 1 / s.y; inv.m[2][2] = 1 / s.z;
  return {m, inv};
}

Transform rotate(float degrees, Vec3f axis) {
  if (length_squared(axis) == 0) throw Error("rotation axis must be non-zero");
  const Vec3f a = normalize(axis);
  const double th = double(degrees) * 3.14159265358979323846 / 180.0;
  const float s = float(std::sin(th)), c = float(std::cos(th));
  Mat4 m;
  m.m[0][0] = a.x * a.x + (1 - a.x * a.x) * c;
  m.m[0][1] = a.x * a.y * (1 - c) - a.z * s;
  m.m[0][2] = a.x * a.z * (1 - c) + a.y * s;
  m.m[1][0] = a.x * a.y * (1 - c) + a.z * s;
  m.m[1][1] = a.y * a.y + (1 - a.y * a.y) * c;
  m.m[1][2] = a.y * a.z * (1 - c) - a.x * s;
  m.m[2][0] = a.x * a.z * (1 - c) - a.y * s;
  m.m[2][1] = a.y * a.z * (1 - c) + a.x * s;
  m.m[2][2] = a.z * a.z + (1 - a.z * a.z) * c;
  return {m, transpose(m)};  // rotations are orthogonal
}

Transform look_at(Vec3f eye, Vec3f target, Vec3f up) {
  const Vec3f fwd = target - eye;
  if (length_squared(fwd) == 0) throw Error("look_at: eye and target are the same point");
  const Vec3f z = normalize(fwd);
  const Vec3f xc = cross(normalize(up), z);
  if (length_squared(xc) < 1e-12f) throw Error("look_at: up is parallel to the viewing direction");
  const Vec3f x = normalize(xc);  // camera +x = up × forward: points to the image's LEFT
  const Vec3f y = cross(z, x);
  Mat4 m;
  for (int r = 0; r < 3; ++r) {
    m.m[r][0] = x[r];
    m.m[r][1] = y[r];
    m.m[r][2] = z[r];
    m.m[r][3] = eye[r];
  }
  return Transform(m);
}

}  // namespace torte
