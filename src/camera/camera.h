// Cameras map a continuous raster position (pixels, (0,0) = top-left corner of the image) to a world ray.
// Camera space: +z forward, +y up, +x to the image's left (right-handed; see look_at).
#pragma once
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
};

}  // namespace torte
