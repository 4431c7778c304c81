// Analytic shapes placed by an arbitrary affine transform: sphere (centred at the origin), disk (in the z = 0
// plane, facing +z, optional inner radius) and cylinder (around the z axis, open, between z_min and z_max).
// Cubes and planar polygons are exact as triangles, so the scene builder turns them into meshes.
#pragma once
#include <cstdint>

#include "core/bounds.h"
#include "core/ray.h"
#include "core/transform.h"

namespace torte {

enum class QuadricKind : uint8_t { Sphere, Disk, Cylinder };

struct Quadric {
  QuadricKind kind = QuadricKind::Sphere;
  float radius = 1;
  float inner_radius = 0;      // disk only
  float z_min = -1, z_max = 1;  // cylinder only
  Transform to_world;           // object-to-world
};

struct SurfacePoint {
  Vec3f p;   // world position
  Vec3f n;   // unit geometric normal in world space, pointing outward (sphere, cylinder) or along +z (disk)
  Vec2f uv;  // surface parameterization in [0,1]^2 (phi/2pi and a second coordinate)
};

// Throws torte::Error for invalid parameters (non-positive radius, z_min >= z_max, inner >= outer radius).
void validate(const Quadric& q);
Bounds3f world_bounds(const Quadric& q);
// Intersects the world-space ray; on a hit with 0 < t < ray.t_max writes t (world ray parameter) and the
// surface uv, and returns true. Rays from inside the sphere/cylinder find the far surface.
bool intersect(const Quadric& q, const Ray& ray, float* t, Vec2f* uv);
// World-space surface point, normal and uv at parametric coordinates uv.
SurfacePoint surface_at(const Quadric& q, Vec2f uv);
// World-space surface area: exact for similarity transforms; for non-uniform scales an approximation (used only
// to weight light selection, never as a pdf).
float area(const Quadric& q);
// Samples a surface point. *pdf_area is the density with respect to world-space area, exact under any affine
// transform (the object-space density divided by the local area scale factor, Transform::area_scale).
SurfacePoint sample_area(const Quadric& q, Vec2f u, float* pdf_area);
// Density that sample_area would give to the point with parametric coordinates uv.
float pdf_area(const Quadric& q, Vec2f uv);

}  // namespace torte
