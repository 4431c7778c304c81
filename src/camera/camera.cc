#include "camera/camera.h"

#include <cmath>

#include "core/error.h"

namespace torte {

Camera::Camera(const CameraDesc& desc, int width, int height)
    : desc_(desc), width_(float(width)), height_(float(height)) {
  if (width <= 0 || height <= 0) throw Error("image size must be positive");
  float half;  // half extent across the chosen axis
  if (desc.kind == CameraKind::Perspective) {
    if (!(desc.fov_degrees > 0 && desc.fov_degrees < 180)) throw Error("fov must be in (0, 180) degrees");
    half = std::tan(0.5f * desc.fov_degrees * kPi / 180);
  } else {
    if (!(desc.extent > 0)) throw Error("orthographic extent must be positive");
    half = 0.5f * desc.extent;
  }
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

}  // namespace torte
