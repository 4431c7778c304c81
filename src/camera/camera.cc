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

std::string Camera::connect_problem() const {
  // The columns of the 3x3 part must be orthonormal (up to rounding): then distances, areas and angles are the
  // same in camera and world space.
  const Transform& c2w = desc_.camera_to_world;
  const Vec3f a = c2w.apply_vector({1, 0, 0}), b = c2w.apply_vector({0, 1, 0}), c = c2w.apply_vector({0, 0, 1});
  const float tol = 1e-3f;
  if (std::fabs(length(a) - 1) > tol || std::fabs(length(b) - 1) > tol || std::fabs(length(c) - 1) > tol ||
      std::fabs(dot(a, b)) > tol || std::fabs(dot(b, c)) > tol || std::fabs(dot(a, c)) > tol)
    return "the camera's placement scales or shears space; paths can only be connected to a camera placed by a "
           "rotation and translation (e.g. look_at)";
  return "";
}

float Camera::lens_area() const {
  return desc_.aperture_radius > 0 ? kPi * desc_.aperture_radius * desc_.aperture_radius : 1.0f;
}

bool Camera::plane_to_raster(float x, float y, Vec2f* raster) const {
  const float sx = x / half_x_, sy = y / half_y_;  // screen coordinates in [-1, 1] inside the image
  const Vec2f r{(1 - sx) * 0.5f * width_, (1 - sy) * 0.5f * height_};
  if (!(r.x >= 0 && r.y >= 0 && r.x < width_ && r.y < height_)) return false;
  *raster = r;
  return true;
}

float Camera::we_camera(Vec3f o, Vec3f d, Vec2f* raster) const {
  const float cos = d.z;
  if (!(cos > 0)) return 0;
  const float area = 4 * half_x_ * half_y_;  // image plane at z = 1 (perspective) or in world units
  Vec2f r;
  if (desc_.kind == CameraKind::Perspective) {
    // Through the lens centre to the same point of the plane in focus: that ray's z = 1 crossing.
    const Vec3f f = has_lens() ? (o + d * (desc_.focus_distance / cos)) / desc_.focus_distance : d / cos;
    if (!plane_to_raster(f.x, f.y, &r)) return 0;
    if (raster) *raster = r;
    const float cos2 = cos * cos;
    return 1 / (area * lens_area() * cos2 * cos2);
  }
  if (!has_lens()) {
    if (cos < 1 - 1e-6f || !plane_to_raster(o.x, o.y, &r)) return 0;
    if (raster) *raster = r;
    return 1 / area;
  }
  // Orthographic thin lens: image point c, lens offset l, ray from c + l towards c + (0, 0, fd); for a fixed
  // origin dw = cos^3 / fd^2 dl, so p(o, w) = fd^2 / (A La cos^3) and We = p / cos.
  const float fd = desc_.focus_distance;
  const Vec3f f = o + d * (fd / cos);
  if (!plane_to_raster(f.x, f.y, &r)) return 0;
  if (raster) *raster = r;
  const float cos2 = cos * cos;
  return fd * fd / (area * lens_area() * cos2 * cos2);
}

float Camera::we(const Ray& ray, Vec2f* raster) const {
  const Transform& c2w = desc_.camera_to_world;
  return we_camera(c2w.apply_inverse_point(ray.o), normalize(c2w.apply_inverse_vector(ray.d)), raster);
}

void Camera::pdf_we(const Ray& ray, float* pdf_pos, float* pdf_dir) const {
  *pdf_pos = *pdf_dir = 0;
  const Transform& c2w = desc_.camera_to_world;
  const Vec3f o = c2w.apply_inverse_point(ray.o), d = normalize(c2w.apply_inverse_vector(ray.d));
  Vec2f r;
  if (we_camera(o, d, &r) == 0) return;
  const float area = 4 * half_x_ * half_y_, cos = d.z;
  if (desc_.kind == CameraKind::Perspective) {
    *pdf_pos = 1 / lens_area();
    *pdf_dir = 1 / (area * cos * cos * cos);
  } else if (!has_lens()) {
    *pdf_pos = 1 / area;
    *pdf_dir = 1;
  } else {
    const float fd = desc_.focus_distance;
    *pdf_pos = 1 / area;
    *pdf_dir = fd * fd / (lens_area() * cos * cos * cos);
  }
}

bool Camera::sample_wi(Vec3f p_world, Vec2f u_lens, CameraWiSample* out) const {
  const Transform& c2w = desc_.camera_to_world;
  const Vec3f p = c2w.apply_inverse_point(p_world);
  if (!(p.z > 0)) return false;
  const Vec2f l = has_lens() ? sample_uniform_disk_concentric(u_lens) * desc_.aperture_radius : Vec2f(0, 0);
  Vec3f o;        // lens point, camera space
  float pdf_area; // its density over the lens plane
  if (desc_.kind == CameraKind::Perspective) {
    o = {l.x, l.y, 0};
    pdf_area = 1 / lens_area();
  } else if (!has_lens()) {
    Vec2f r;
    if (!plane_to_raster(p.x, p.y, &r)) return false;
    *out = {normalize(c2w.apply_vector({0, 0, -1})), p.z, c2w.apply_point({p.x, p.y, 0}), r, 1 / (4 * half_x_ * half_y_),
            1, true};
    return true;
  } else {
    // The ray from image point c + l through c + (0, 0, fd) passes p when c = p.xy - l (1 - p.z / fd): its
    // origin is p.xy + l p.z / fd, of density (fd / p.z)^2 / La for l uniform on the lens.
    const float k = p.z / desc_.focus_distance;
    o = {p.x + l.x * k, p.y + l.y * k, 0};
    pdf_area = 1 / (lens_area() * k * k);
  }
  const Vec3f to = o - p;
  const float dist = length(to);
  if (!(dist > 0)) return false;
  const Vec3f d = -to / dist;  // from the lens towards p
  Vec2f r;
  const float we = we_camera(o, d, &r);
  if (!(we > 0)) return false;
  const float pdf = pdf_area * dist * dist / d.z;  // area to solid angle at p (the lens faces +z)
  *out = {normalize(c2w.apply_vector(-d)), dist, c2w.apply_point(o), r, we, pdf, false};
  return std::isfinite(pdf) && pdf > 0;
}

}  // namespace torte
