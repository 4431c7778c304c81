// Emission sampling for light tracing (instant global illumination's light paths, render/vpl.h): a ray leaving
// a light, with the weight Le * cos / pdf of having generated it. Reads Light's fields only; the shading-side
// sampling (sample_light) stays in light.cc.
#pragma once
#include "core/rgb.h"
#include "core/vec.h"
#include "light/light.h"

namespace torte {

struct EmissionSample {
  Vec3f origin;  // a point on the light (point, spot, area) or on a disk covering the scene (distant, infinite)
  Vec3f dir;     // unit direction the light travels
  Vec3f normal;  // area lights: the surface normal on the emitting side (for offsetting the origin); else 0
  Rgb weight;    // Le * |cos| / (pdf of origin * pdf of direction): flux carried by the ray
  float pdf_pos = 1;  // density of the origin: over area (area lights, patches, the disk of lights at infinity);
                      // 1 for point and spot lights (a delta in position)
  float pdf_dir = 1;  // solid-angle density of dir (1 for distant lights, a delta in direction)
};

// Samples a ray leaving `light`: area lights pick a point uniformly by area, then a cosine-distributed direction
// on the emitting side (either side with probability 1/2 when two-sided, uc chooses); point lights a uniform
// direction; spot lights a uniform direction in the cone; distant and infinite-like lights a direction (fixed,
// uniform or importance-sampled) and an origin on the disk of the scene's bounding sphere across it.
// Returns false when the sample carries nothing.
bool sample_emission(const EmitterView& scene, const Light& light, Vec2f u_pos, Vec2f u_dir, float uc, EmissionSample* s);

}  // namespace torte
