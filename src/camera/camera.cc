#include "camera/camera.h"

#include <cmath>

#include "core/error.h"
#include "core/sampling.h"

namespace torte {

Camera::Camera(const CameraDesc& desc, int width, int height)
    : desc_(desc), width_(float(width)), height_(float(height)) {
  if (width <= 0 || height <= 0) throw Error("image size must be positive");
  const Transform& c2w = desc.camera_to_world;
  const float det = c2w.determinant3();
  if (!(std::fabs(det) > 0) || !std::isfinite(det) || !is_finite(c2w.apply_point({0, 0, 0})) ||
      !is_finite(c2w.apply_vector({0, 0, 1})))
    throw Error("the camera's placement is singular or not finite");
  float half;  // half extent across the chosen axis
  if (desc.kind == CameraKind::Perspective) {
    if (!(desc.fov_degrees > 0 && desc.fov_degrees < 180)) throw Error("fov must be in (0, 180) degrees");
    half = std::tan(0.5f * desc.fov_degrees * kPi / 180);
  } else {
    if (!(desc.extent > 0)) throw Error("orthographic extent must be positive");
    half = 0.5f * desc.extent;
  }
  if (!(desc.aperture_radius >= 0) || !std::isfinite(desc.aperture_radius))
    throw Error("aperture radius must be finite and non-negative");
  if (desc.aperture_radius > 0 && !(desc.focus_distance > 0 && std::isfinite(desc.focus_distance)))
    throw Error("focus distance must be positive");
  const float aspect = width_ / height_;
  switch (desc.fov_axis) {
    case FovAxis::Vertical: half_y_ = half; half_x_ = half * aspect; break;
    case FovAxis::Horizontal: half_x_ = half; half_y_ = half / aspect; break;
    case FovAxis::Diagonal: {
      const float diag = std::sqrt(aspect * aspect + 1);
      half_x_ = half * aspect / diag;
      half_y_ = half / diag;
      break;
    }
  }
}

Ray Camera::generate_ray(Vec2f raster) const {
  // Screen coordinates in [-1, 1]; raster x grows to the right, which is camera -x.
  const float sx = 1 - 2 * raster.x / width_;
  const float sy = 1 - 2 * raster.y / height_;
  const Transform& c2w = desc_.camera_to_world;
  if (desc_.kind == CameraKind::Perspective) {
    const Vec3f d{sx * half_x_, sy * half_y_, 1};
    return {c2w.apply_point({0, 0, 0}), normalize(c2w.apply_vector(d)), kInfinity};
  }
  const Vec3f o{sx * half_x_, sy * half_y_, 0};
  return {c2w.apply_point(o), normalize(c2w.apply_vector({0, 0, 1})), kInfinity};
}

Ray Camera::generate_ray(Vec2f raster, Vec2f lens_u) const {
  if (!(desc_.aperture_radius > 0)) return generate_ray(raster);
  const float sx = 1 - 2 * raster.x / width_;
  const float sy = 1 - 2 * raster.y / height_;
  const Vec2f lens = sample_uniform_disk_concentric(lens_u) * desc_.aperture_radius;
  const float fd = desc_.focus_distance;
  Vec3f o, focus;  // camera space
  if (desc_.kind == CameraKind::Perspective) {
    // The pinhole ray through the lens centre meets the plane z = focus_distance at d * fd (d has z = 1).
    focus = Vec3f{sx * half_x_, sy * half_y_, 1} * fd;
    o = Vec3f{lens.x, lens.y, 0};
  } else {
    const Vec3f centre{sx * half_x_, sy * half_y_, 0};
    focus = centre + Vec3f{0, 0, fd};
    o = centre + Vec3f{lens.x, lens.y, 0};
  }
  const Transform& c2w = desc_.camera_to_world;
  return {c2w.apply_point(o), normalize(c2w.apply_vector(focus - o)), kInfinity};
}

}  // namespace torte
