// Fresnel equations and the reflection/refraction of directions about a normal.
//
// Conventions follow pbrt-v4 (Pharr, Jakob, Humphreys, "Physically Based Rendering", 4th ed., section 9.3):
// eta is the relative index of refraction inside/outside, where "inside" is the side the normal does NOT point
// to. A negative cosine means the ray arrives from the inside, and the functions swap the media themselves.
#pragma once
#include <algorithm>
#include <cmath>

#include "core/rgb.h"
#include "core/vec.h"

namespace torte {

// Mirror direction of wo about n (both pointing away from the surface).
inline Vec3f reflect(Vec3f wo, Vec3f n) { return -wo + n * (2 * dot(wo, n)); }

// Refracts wi (pointing away from the surface) through the interface with normal n and relative index eta
// (inside/outside). When wi is on the inside (dot(wi, n) < 0) the interface is flipped. On success *etap
// receives the relative index actually crossed (eta or 1/eta) and *wt the transmitted direction (unit, on the
// other side); returns false on total internal reflection. Snell: sin(t) = sin(i) / etap.
inline bool refract(Vec3f wi, Vec3f n, float eta, float* etap, Vec3f* wt) {
  float cos_i = dot(n, wi);
  if (cos_i < 0) {
    eta = 1 / eta;
    cos_i = -cos_i;
    n = -n;
  }
  const float sin2_i = std::max(0.0f, 1 - cos_i * cos_i);
  const float sin2_t = sin2_i / (eta * eta);
  if (sin2_t >= 1) return false;
  const float cos_t = std::sqrt(1 - sin2_t);
  *wt = -wi / eta + n * (cos_i / eta - cos_t);
  if (etap) *etap = eta;
  return true;
}

// Unpolarised Fresnel reflectance of a dielectric interface. cos_i < 0 means the light arrives from the inside
// (then the relative index is 1/eta). Returns 1 under total internal reflection.
inline float fresnel_dielectric(float cos_i, float eta) {
  cos_i = std::clamp(cos_i, -1.0f, 1.0f);
  if (cos_i < 0) {
    eta = 1 / eta;
    cos_i = -cos_i;
  }
  const float sin2_t = (1 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1) return 1;
  const float cos_t = std::sqrt(std::max(0.0f, 1 - sin2_t));
  const float r_parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float r_perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return (r_parallel * r_parallel + r_perpendicular * r_perpendicular) / 2;
}

// Fresnel reflectance of a conductor with complex index eta + i k (relative to the outside medium), for one
// wavelength. This is the dielectric formula with complex arithmetic (pbrt-v4 section 9.3.6) written out in real
// arithmetic (the form of pbrt-v3's FrConductor; see also Lazanyi & Szirmay-Kalos 2005): with
// a^2 + b^2 = |eta^2 - sin^2|, a = Re sqrt(eta^2 - sin^2),
//   Rs = (a^2 + b^2 + cos^2 - 2 a cos) / (a^2 + b^2 + cos^2 + 2 a cos),
//   Rp = Rs (cos^2 (a^2 + b^2) + sin^4 - 2 a cos sin^2) / (cos^2 (a^2 + b^2) + sin^4 + 2 a cos sin^2).
// It avoids complex division, several times slower in -O3 without -ffast-math. Conductors are opaque, so the
// side is irrelevant: |cos_i| is used.
inline float fresnel_complex(float cos_i, float eta, float k) {
  cos_i = std::min(std::fabs(cos_i), 1.0f);
  const float cos2 = cos_i * cos_i, sin2 = 1 - cos2;
  const float eta2 = eta * eta, k2 = k * k;
  const float t0 = eta2 - k2 - sin2;
  const float a2_plus_b2 = std::sqrt(std::max(0.0f, t0 * t0 + 4 * eta2 * k2));
  const float a = std::sqrt(std::max(0.0f, (a2_plus_b2 + t0) / 2));
  const float t1 = a2_plus_b2 + cos2, t2 = 2 * cos_i * a;
  const float rs = (t1 - t2) / (t1 + t2);
  const float t3 = cos2 * a2_plus_b2 + sin2 * sin2, t4 = t2 * sin2;
  const float rp = rs * (t3 - t4) / (t3 + t4);
  return (rs + rp) / 2;
}

// Per-channel conductor Fresnel reflectance.
inline Rgb fresnel_conductor(float cos_i, Rgb eta, Rgb k) {
  return {fresnel_complex(cos_i, eta.r, k.r), fresnel_complex(cos_i, eta.g, k.g), fresnel_complex(cos_i, eta.b, k.b)};
}

// Hemispherical (cosine-weighted) average of the dielectric Fresnel reflectance for light arriving from the
// outside, Fdr = integral_0^1 F(mu) 2 mu dmu, for eta >= 1: the exact closed form for unpolarised light (Stern
// 1964; as quoted e.g. by d'Eon, "A Hitchhiker's Guide to Multiple Scattering", 2016). Evaluated in double
// precision because its terms cancel; below eta = 1.0001 (where that precision runs out) the reflectance is
// ~0.33 (eta - 1), so it is interpolated linearly to 0 at eta = 1.
inline float fresnel_diffuse_reflectance_outside(float eta_f) {
  const double n = eta_f;
  if (n <= 1) return 0;
  if (n < 1.0001) return float((n - 1) / 1e-4 * fresnel_diffuse_reflectance_outside(1.0001f));
  const double n2 = n * n, n3 = n2 * n, n4 = n2 * n2;
  const double r = 0.5 + (n - 1) * (3 * n + 1) / (6 * (n + 1) * (n + 1)) +
                   n2 * (n2 - 1) * (n2 - 1) / ((n2 + 1) * (n2 + 1) * (n2 + 1)) * std::log((n - 1) / (n + 1)) -
                   2 * n3 * (n2 + 2 * n - 1) / ((n2 + 1) * (n4 - 1)) +
                   8 * n4 * (n4 + 1) / ((n2 + 1) * (n4 - 1) * (n4 - 1)) * std::log(n);
  return float(r);
}

// Same average for light arriving from the side whose relative index is eta (any eta > 0). For eta < 1 (light
// inside the denser medium) it follows from the outside value by reciprocity/energy balance:
// 1 - Fdr(1/n) = (1 - Fdr(n)) / n^2, where n = 1/eta > 1 (the light escaping from inside is what enters).
inline float fresnel_diffuse_reflectance(float eta) {
  if (eta >= 1) return fresnel_diffuse_reflectance_outside(eta);
  const float n = 1 / eta;
  return 1 - (1 - fresnel_diffuse_reflectance_outside(n)) / (n * n);
}

}  // namespace torte
