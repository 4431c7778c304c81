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
};

class Camera {
 public:
  Camera() = default;
  Camera(const CameraDesc& desc, int width, int height);
  // Unit-direction ray through the raster position.
  Ray generate_ray(Vec2f raster) const;
  const CameraDesc& desc() const { return desc_; }

 private:
  CameraDesc desc_;
  float width_ = 1, height_ = 1;
  float half_x_ = 1, half_y_ = 1;  // image-plane half extents at z = 1 (perspective) or in world units (ortho)
};

}  // namespace torte
