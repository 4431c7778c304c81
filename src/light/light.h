// Lights as plain data, one record type with a kind tag: sampling switches on the kind (a predictable branch,
// not a virtual call). Area lights reference a scene object (a mesh or a quadric).
#pragma once
#include <cstdint>

#include "core/rgb.h"
#include "core/sampling.h"
#include "core/vec.h"

namespace torte {

class Scene;
struct SurfaceHit;

enum class LightKind : uint8_t { Point, Area, Infinite };

struct Light {
  LightKind kind = LightKind::Point;
  Rgb radiance;          // point: intensity (W/sr); area: emitted radiance; infinite: radiance from every direction
  Vec3f position;        // point
  uint32_t object = 0;   // area: emitting scene object
  bool two_sided = false;  // area: emits on both sides
  float area = 0;        // area: total world area
  Distribution1D triangles;  // area light on a mesh: triangle selection by area
};

struct LightSample {
  Rgb radiance;     // arriving radiance (or intensity / d^2 for point lights)
  Vec3f wi;         // unit direction from the shading point towards the light
  float distance;   // to the light point (kInfinity for infinite lights)
  float pdf;        // solid-angle density; for delta lights the probability (1)
  bool delta;       // true for point lights: BSDF sampling cannot hit them
};

// Samples light `l` as seen from point p. Returns false when the sample carries no light.
bool sample_light(const Scene& scene, const Light& light, Vec3f p, Vec2f u, LightSample* s);
// Solid-angle density with which sample_light would have chosen direction wi from p, given that the ray hit
// `hit` on this area light (for area lights), or escaped (infinite lights).
float light_pdf(const Scene& scene, const Light& light, Vec3f p, Vec3f wi, const SurfaceHit* hit, float t);
// Radiance an area light emits from `hit` towards -w (w is the ray direction).
Rgb area_emission(const Light& light, const SurfaceHit& hit, Vec3f w);
// Total emitted power, used to weight light selection.
float light_power(const Scene& scene, const Light& light);

}  // namespace torte
