// Microfacet normal distributions: GGX (Trowbridge-Reitz) and Beckmann, both anisotropic, with the Smith
// height-correlated masking-shadowing function (Heitz 2014, "Understanding the Masking-Shadowing Function in
// Microfacet-Based BRDFs"). Directions are in the local shading frame, the macro normal along +z.
//
// alpha_x, alpha_y are the slope roughnesses along x and y (GGX: the scale of the ellipsoid of normals; Beckmann:
// sqrt(2) times the RMS slope). They are taken as given: the scene layer maps artist roughness to alpha.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/vec.h"

namespace torte {

struct MicrofacetDistribution {
  enum class Kind : uint8_t { GGX, Beckmann };
  Kind kind = Kind::GGX;
  float alpha_x = 0, alpha_y = 0;

  MicrofacetDistribution() = default;
  MicrofacetDistribution(Kind k, float ax, float ay) : kind(k), alpha_x(ax), alpha_y(ay) {}
  static MicrofacetDistribution ggx(float ax, float ay) { return {Kind::GGX, ax, ay}; }
  static MicrofacetDistribution ggx(float alpha) { return {Kind::GGX, alpha, alpha}; }
  static MicrofacetDistribution beckmann(float ax, float ay) { return {Kind::Beckmann, ax, ay}; }
  static MicrofacetDistribution beckmann(float alpha) { return {Kind::Beckmann, alpha, alpha}; }

  // Below this roughness the lobe is narrower than float precision can sample reliably; BSDFs switch to their
  // delta (perfectly smooth) form instead.
  bool effectively_smooth() const { return std::max(alpha_x, alpha_y) < 1e-3f; }

  // Distribution of normals D(wm), normalised so that the projected area integrates to one:
  // integral D(wm) cos(theta_m) dwm = 1 over the upper hemisphere.
  float D(Vec3f wm) const {
    if (wm.z <= 0) return 0;
    const float x = wm.x / alpha_x, y = wm.y / alpha_y, z2 = wm.z * wm.z;
    if (kind == Kind::GGX) {
      // 1 / (pi ax ay cos^4 (1 + tan^2 (cos^2 phi / ax^2 + sin^2 phi / ay^2))^2), with the cos^4 folded in.
      const float t = x * x + y * y + z2;
      return 1 / (kPi * alpha_x * alpha_y * t * t);
    }
    // Beckmann: exp(-tan^2 (cos^2 phi / ax^2 + sin^2 phi / ay^2)) / (pi ax ay cos^4).
    if (z2 < 1e-12f) return 0;  // the exponential has long vanished; avoid 0/0
    return std::exp(-(x * x + y * y) / z2) / (kPi * alpha_x * alpha_y * z2 * z2);
  }

  // Smith's auxiliary function: G1(w) = 1 / (1 + Lambda(w)). Symmetric in w.z's sign.
  float Lambda(Vec3f w) const {
    const float z2 = w.z * w.z;
    const float a2_tan2 = (alpha_x * alpha_x * w.x * w.x + alpha_y * alpha_y * w.y * w.y) / z2;  // alpha^2 tan^2
    if (!(a2_tan2 < kInfinity)) return kInfinity;  // exactly grazing: fully masked
    if (kind == Kind::GGX) return (std::sqrt(1 + a2_tan2) - 1) / 2;
    if (a2_tan2 <= 0) return 0;
    // Exact Beckmann Lambda (Walter et al. 2007, eq. 27 with a = 1 / (alpha tan)), not the rational fit, so the
    // visible normal density integrates to one exactly.
    const float a = 1 / std::sqrt(a2_tan2);
    return (-std::erfc(a) + std::exp(-a * a) / (a * 1.7724538509055159f)) / 2;
  }
  float G1(Vec3f w) const { return 1 / (1 + Lambda(w)); }
  // Height-correlated masking-shadowing.
  float G(Vec3f wo, Vec3f wi) const { return 1 / (1 + Lambda(wo) + Lambda(wi)); }

  // Distribution of normals visible from w (Heitz 2014, eq. 3): G1(w) max(0, w.wm) D(wm) / cos(w); it integrates
  // to one over wm. For w below the surface (w.z < 0) it is the density seen from -w, which is what a ray
  // arriving from inside a dielectric sees.
  float D(Vec3f w, Vec3f wm) const {
    if (w.z == 0) return 0;
    const float cos_wm = w.z > 0 ? dot(w, wm) : -dot(w, wm);
    if (cos_wm <= 0) return 0;
    return G1(w) / std::fabs(w.z) * D(wm) * cos_wm;
  }

  // Density of sample_wm(w, .) with respect to solid angle of wm.
  float pdf(Vec3f w, Vec3f wm) const {
    if (kind == Kind::GGX) return D(w, wm);
    return D(wm) * std::max(0.0f, wm.z);
  }

  // Samples a microfacet normal (always wm.z > 0).
  //  GGX: visible normals from w (or -w when w.z < 0), Heitz 2018, "Sampling the GGX Distribution of Visible
  //    Normals": stretch to the unit-roughness configuration, sample the projected hemisphere, unstretch.
  //  Beckmann: D(wm) cos(theta_m), independent of w, by sampling the slope distribution (a Gaussian) directly.
  //    Callers must reject normals facing away from w.
  Vec3f sample_wm(Vec3f w, Vec2f u) const {
    if (kind == Kind::GGX) {
      Vec3f wh = normalize(Vec3f(alpha_x * w.x, alpha_y * w.y, w.z));
      if (wh.z < 0) wh = -wh;
      const float len2 = wh.x * wh.x + wh.y * wh.y;
      const Vec3f t1 = len2 > 0 ? Vec3f(-wh.y, wh.x, 0) / std::sqrt(len2) : Vec3f(1, 0, 0);
      const Vec3f t2 = cross(wh, t1);
      // Uniform point on the disk, then squash the half that is hidden by the tilted hemisphere.
      const float r = std::sqrt(u.x), phi = 2 * kPi * u.y;
      const float p1 = r * std::cos(phi);
      float p2 = r * std::sin(phi);
      const float s = (1 + wh.z) / 2;
      p2 = (1 - s) * std::sqrt(std::max(0.0f, 1 - p1 * p1)) + s * p2;
      const float pz = std::sqrt(std::max(0.0f, 1 - p1 * p1 - p2 * p2));
      const Vec3f nh = t1 * p1 + t2 * p2 + wh * pz;
      return normalize(Vec3f(alpha_x * nh.x, alpha_y * nh.y, std::max(1e-6f, nh.z)));
    }
    // Slopes (-x/z, -y/z) of Beckmann normals are Gaussian with density exp(-(sx/ax)^2 - (sy/ay)^2)/(pi ax ay),
    // and D(wm) cos(theta_m) dwm equals that density d(slope) (the slope Jacobian is 1/cos^3).
    const float r = std::sqrt(-std::log1p(-std::min(u.x, 0.99999994f))), phi = 2 * kPi * u.y;
    const float sx = alpha_x * r * std::cos(phi), sy = alpha_y * r * std::sin(phi);
    return normalize(Vec3f(-sx, -sy, 1));
  }
};

}  // namespace torte
