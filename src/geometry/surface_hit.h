// What shading needs about a hit point, and its reconstruction from a hit on a triangle or a quadric. The
// acceleration structures (accel/) say which primitive was hit where; these functions rebuild the surface there.
#pragma once
#include <cstdint>

#include "core/vec.h"
#include "geometry/mesh.h"
#include "geometry/quadric.h"

namespace torte {

// Everything shading needs about a hit point.
struct SurfaceHit {
  Vec3f p;
  Vec3f ng;  // unit geometric normal, front side as defined by the shape (winding / outward)
  Vec3f ns;  // unit shading normal (interpolated vertex normals), on the same side as ng
  Vec2f uv;
  Vec3f dpdu, dpdv;  // surface tangents along the uv parameterization (textures, bump mapping)
  uint32_t object;
  // Material override: an index into Scene::material_overrides (voxel faces and cell shapes), -1 = the object's.
  int32_t material = -1;
};

/// The surface of triangle `idx` (three vertex indices into `mesh`'s normals and uvs) with vertices `p` at
/// barycentrics (b1, b2). Positions come from the caller (the BVH leaves hold them once the mesh released its own).
/// The hit records `object`.
SurfaceHit triangle_surface(const TriangleMesh& mesh, const uint32_t* idx, const Vec3f p[3], float b1, float b2,
                            uint32_t object);
/// The surface of quadric `q` at its parameter `uv` (a hit's (b1, b2)), recording `object`.
SurfaceHit quadric_surface(const Quadric& q, Vec2f uv, uint32_t object);

}  // namespace torte
