// The contract every reflection model (BSDF) in src/material/ follows. BSDFs are small value types with inline
// eval/pdf/sample, built per hit by the material kernel of their type (render/shade.h) — no virtual calls.
//
// Local shading frame: +z is the shading normal on the surface's FRONT side (outward for closed shapes, the
// winding side of meshes); it is NOT flipped towards wo, so wo.z < 0 means the ray arrived from the back/inside.
// Opaque BSDFs reflect on both sides (wo and wi in the same hemisphere, like pbrt's SameHemisphere); dielectrics
// use wo.z's sign to know whether the ray enters (wo.z > 0) or leaves the medium.
//
//   Rgb   eval(Vec3f wo, Vec3f wi) const;   // f(wo, wi), no cosine; 0 for delta (specular) lobes
//   float pdf(Vec3f wo, Vec3f wi) const;    // solid-angle pdf of sample() producing wi; 0 for delta lobes
//   bool  sample(Vec3f wo, float uc, Vec2f u, BsdfSample* s) const;  // uc picks a lobe, u samples it
//   bool  has_non_specular() const;         // false when every lobe is a delta (no light sampling needed)
//
// Directions point away from the surface and are unit length. Radiance transport (paths from the camera): the
// BTDF of a refractive boundary includes the 1/eta^2 radiance compression; TransportMode::Importance (paths from
// lights, e.g. instant GI's virtual point lights) leaves it out.
#pragma once
#include <cmath>
#include <cstdint>

#include "core/rgb.h"
#include "core/vec.h"

namespace torte {

enum class TransportMode : uint8_t { Radiance, Importance };

enum BsdfFlags : uint8_t {
  kBsdfReflection = 1,
  kBsdfTransmission = 2,
  kBsdfSpecular = 4,  // a delta lobe: wi is determined by wo, pdf is the discrete lobe probability
};

struct BsdfSample {
  Vec3f wi;        // sampled incident direction (local frame)
  Rgb f;           // BSDF value; for a delta lobe the delta's coefficient, so that weight() is right
  float pdf = 0;   // solid-angle pdf, or for a delta lobe the probability of having chosen it
  uint8_t flags = 0;
  float eta = 1;   // relative index of refraction crossed (transmission), 1 for reflection
  bool is_specular() const { return flags & kBsdfSpecular; }
  bool is_transmission() const { return flags & kBsdfTransmission; }
  // Throughput factor f |cos(wi)| / pdf.
  Rgb weight() const { return f * (std::fabs(wi.z) / pdf); }
};

inline bool same_hemisphere(Vec3f a, Vec3f b) { return a.z * b.z > 0; }

}  // namespace torte
