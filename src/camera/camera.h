// Cameras map a continuous raster position (pixels, (0,0) = top-left corner of the image) to a world ray, and
// connect world points back to the lens for light paths (importance We, its densities, sample_wi).
// Camera space: +z forward, +y up, +x to the image's left (right-handed; see look_at).
#pragma once
#include <string>

#include "core/ray.h"
#include "core/transform.h"

namespace torte {

enum class CameraKind : uint8_t { Perspective, Orthographic };
// Which image side the perspective field of view (or orthographic extent) spans.
enum class FovAxis : uint8_t { Vertical, Horizontal, Diagonal };

struct CameraDesc {
  CameraKind kind = CameraKind::Perspective;
  Transform camera_to_world;
  float fov_degrees = 45;  // perspective: full angle across fov_axis
  float extent = 2;        // orthographic: world-space size of the image across fov_axis
  FovAxis fov_axis = FovAxis::Vertical;
  // Thin lens (both projections): lens radius in world units (0 = pinhole) and the distance along the view
  // axis of the plane in focus.
  float aperture_radius = 0;
  float focus_distance = 1;
};

/// A connection from a scene point to the camera (light tracing, BDPT): the direction and distance to a point
/// on the lens, where it lands on the image, and the importance it carries over the density of choosing it.
struct CameraWiSample {
  Vec3f wi;        // unit, from the reference point towards `lens`
  float distance;  // from the reference point to `lens`
  Vec3f lens;      // world point on the lens (the camera position for a perspective pinhole)
  Vec2f raster;    // where the ray from `lens` through the reference point meets the image
  float we;        // importance We of that ray (orthographic pinhole: 1 / image area, a delta in direction)
  float pdf;       // solid-angle density of wi at the reference point (orthographic pinhole: 1, a delta)
  bool delta;      // orthographic pinhole: wi is the only direction that reaches the camera
};

class Camera {
 public:
  Camera() = default;
  Camera(const CameraDesc& desc, int width, int height);
  // Unit-direction ray through the raster position (through the lens centre: a pinhole).
  Ray generate_ray(Vec2f raster) const;
  // Thin lens: lens_u in [0,1)^2 picks the point on the lens aperture (concentric disk map). With aperture 0
  // this equals generate_ray(raster).
  Ray generate_ray(Vec2f raster, Vec2f lens_u) const;
  bool has_lens() const { return desc_.aperture_radius > 0; }

  // Importance (pbrt-v4's PerspectiveCamera convention): We integrates to 1 over the rays the camera generates,
  // so a splat of beta * f * |cos| * We / pdf, summed over width*height*spp light paths and scaled by 1/spp, is
  // the pixel's mean radiance. Only cameras with a rigid placement can be connected to (connect_problem).

  /// Why light paths cannot connect to this camera ("" if they can): its placement must be a rotation and
  /// translation, since importance and densities are computed in camera space.
  std::string connect_problem() const;
  /// Importance of `ray` (world, unit direction) leaving the lens, and the raster position it lands on (0 when
  /// it misses the image or leaves backwards). Orthographic pinhole: 1 / image area for rays along the view
  /// axis (a delta in direction), 0 for any other direction.
  float we(const Ray& ray, Vec2f* raster = nullptr) const;
  /// Densities of generate_ray producing `ray`: over lens (or image, orthographic) area and over solid angle;
  /// their product is the joint density. Orthographic pinhole: pdf_dir = 1 (a delta). 0 outside the image.
  void pdf_we(const Ray& ray, float* pdf_pos, float* pdf_dir) const;
  /// Connects world point `p` to the camera, `u_lens` choosing the lens point (ignored by pinholes). False
  /// when p is behind the camera or projects outside the image.
  bool sample_wi(Vec3f p, Vec2f u_lens, CameraWiSample* out) const;
  const CameraDesc& desc() const { return desc_; }
  // The image size the camera was made for, in pixels.
  float image_width() const { return width_; }
  float image_height() const { return height_; }
  // Pixel footprint for texture filtering (a ray cone): world-space width of a pixel at the ray origin, and its
  // growth per unit distance (the angle a pixel subtends; 0 for orthographic cameras).
  float footprint_at_origin() const {
    return desc_.kind == CameraKind::Orthographic ? 2 * half_y_ / height_ : 0.0f;
  }
  float spread_angle() const { return desc_.kind == CameraKind::Perspective ? 2 * half_y_ / height_ : 0.0f; }

 private:
  CameraDesc desc_;
  float width_ = 1, height_ = 1;
  float half_x_ = 1, half_y_ = 1;  // image-plane half extents at z = 1 (perspective) or in world units (ortho)
  float lens_area() const;
  // Raster position of camera-space plane point (x, y) (at z = 1 for perspective, z = 0 for orthographic);
  // false outside the image.
  bool plane_to_raster(float x, float y, Vec2f* raster) const;
  // We of a camera-space ray (unit d) and its raster position; 0 outside the image.
  float we_camera(Vec3f o, Vec3f d, Vec2f* raster) const;
};

}  // namespace torte
