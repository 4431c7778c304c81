// Affine 4x4 transforms with their inverses kept alongside (2 x 64 bytes), so points, vectors and normals can be
// mapped both ways without inverting at use time.
#pragma once
#include "core/bounds.h"
#include "core/ray.h"
#include "core/vec.h"

namespace torte {

struct Mat4 {
  float m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
  static Mat4 identity() { return {}; }
  bool operator==(const Mat4&) const = default;
  bool is_identity() const { return *this == Mat4{}; }
};

Mat4 operator*(const Mat4& a, const Mat4& b);
Mat4 transpose(const Mat4& a);
// Inverse by Gauss-Jordan elimination with partial pivoting; throws torte::Error if singular.
Mat4 inverse(const Mat4& a);

class Transform {
 public:
  Transform() = default;
  explicit Transform(const Mat4& m);  // computes the inverse
  Transform(const Mat4& m, const Mat4& inv) : m_(m), inv_(inv) {}

  const Mat4& matrix() const { return m_; }
  const Mat4& inverse_matrix() const { return inv_; }
  Transform inverse() const { return {inv_, m_}; }
  bool is_identity() const { return m_.is_identity(); }
  Transform operator*(const Transform& o) const { return {m_ * o.m_, o.inv_ * inv_}; }

  Vec3f apply_point(Vec3f p) const { return point(m_, p); }
  Vec3f apply_vector(Vec3f v) const { return vector(m_, v); }
  // Normals map by the inverse transpose; the result is not normalized.
  Vec3f apply_normal(Vec3f n) const {
    return {inv_.m[0][0] * n.x + inv_.m[1][0] * n.y + inv_.m[2][0] * n.z,
            inv_.m[0][1] * n.x + inv_.m[1][1] * n.y + inv_.m[2][1] * n.z,
            inv_.m[0][2] * n.x + inv_.m[1][2] * n.y + inv_.m[2][2] * n.z};
  }
  Vec3f apply_inverse_point(Vec3f p) const { return point(inv_, p); }
  Vec3f apply_inverse_vector(Vec3f v) const { return vector(inv_, v); }
  Ray apply_inverse(const Ray& r) const { return {point(inv_, r.o), vector(inv_, r.d), r.t_max}; }
  Bounds3f apply(const Bounds3f& b) const;
  // Determinant of the linear 3x3 part; negative when the transform flips handedness.
  float determinant3() const;
  // Factor by which a surface element with local unit normal n grows in area: |det| * |M^-T n|.
  float area_scale(Vec3f local_normal) const { return std::fabs(determinant3()) * length(apply_normal(local_normal)); }

 private:
  static Vec3f point(const Mat4& a, Vec3f p) {
    return {a.m[0][0] * p.x + a.m[0][1] * p.y + a.m[0][2] * p.z + a.m[0][3],
            a.m[1][0] * p.x + a.m[1][1] * p.y + a.m[1][2] * p.z + a.m[1][3],
            a.m[2][0] * p.x + a.m[2][1] * p.y + a.m[2][2] * p.z + a.m[2][3]};
  }
  static Vec3f vector(const Mat4& a, Vec3f v) {
    return {a.m[0][0] * v.x + a.m[0][1] * v.y + a.m[0][2] * v.z,
            a.m[1][0] * v.x + a.m[1][1] * v.y + a.m[1][2] * v.z,
            a.m[2][0] * v.x + a.m[2][1] * v.y + a.m[2][2] * v.z};
  }
  Mat4 m_, inv_;
};

Transform translate(Vec3f d);
Transform scale(Vec3f s);
// Rotation by angle (degrees) about an arbitrary axis (normalized internally).
Transform rotate(float degrees, Vec3f axis);
// World-from-camera transform for a camera at eye looking at target. Camera space is right-handed: +z forward,
// +y up, so +x points to the image LEFT (as in the Cornell box frame). Throws torte::Error if up is parallel to the view.
Transform look_at(Vec3f eye, Vec3f target, Vec3f up);

}  // namespace torte
