// Procedural daylight: the Preetham, Shirley & Smits 1999 analytic sky ("A Practical Analytic Model for
// Daylight") for the sky dome, plus the sun as a small disk (a cone of directions) of the model's attenuated solar
// radiance. World +y is up; below the horizon the sky is black (put a ground in the scene).
//
// Units: the model's luminance is in kcd/m^2 (zenith ~ 5-15 for a clear midday sky; the sun ~1e6 for a disk of
// 0.53 degrees, i.e. ~100 klux of illuminance). Radiance here is that luminance in kcd/m^2 times `scale` (default
// 1/40, which puts a white diffuse ground in the midday sun near 1 in the image). The sky colour comes from the
// model's CIE xy chromaticity, converted to linear sRGB; the sun's colour from the model's Rayleigh and aerosol
// (Angstrom) transmittance at 610/550/465 nm applied to a white extraterrestrial sun of 1.88e9 cd/m^2 (ozone and
// water vapour absorption are ignored).
//
// Sampling: the sky is tabulated at set-up into a SphericalDistribution (conservative: each texel's weight is the
// largest of 9 radiance samples over it, so the density is positive wherever the sky is bright); the sun is
// sampled uniformly in its cone. The two strategies are mixed with probability proportional to their power.
#pragma once
#include <memory>

#include "core/rgb.h"
#include "light/environment.h"

namespace torte {

struct SkyParams {
  Vec3f sun_direction{0, 1, 0};  // towards the sun (world, +y up); normalized by make_sky
  float turbidity = 3;           // 1.7 (very clear) .. 10 (hazy)
  float scale = 1.0f / 40;       // radiance units per kcd/m^2
  bool sun = true;               // add the sun disk
  float sun_radius_degrees = 0.2665f;  // angular radius; larger disks keep the sun's irradiance
  int table_width = 256, table_height = 128;  // sampling table resolution
};

struct SkyModel {
  SkyParams params;
  Vec3f sun_dir;
  float perez[3][5];           // Perez coefficients A..E for Y, x, y
  float zenith[3];             // Y (kcd/m^2), x, y at the zenith
  float norm[3];               // zenith / F(0, theta_s)
  Rgb sun_radiance;            // inside the sun's cone (already scaled)
  float sun_one_minus_cos = 0; // 1 - cos(sun angular radius)
  float sun_probability = 0;   // of sampling the sun rather than the sky table
  SphericalDistribution sampling;
  float sky_integral = 0;      // integral of the sky's average radiance over the sphere
  float sun_integral = 0;      // sun radiance average x its solid angle

  Rgb sky_radiance(Vec3f d) const;  // without the sun
  Rgb radiance(Vec3f d) const;      // with the sun disk
  bool in_sun(Vec3f d) const;
  bool sample(Vec2f u, Vec3f* wi, float* pdf) const;
  float pdf(Vec3f d) const;
};

// Throws torte::Error for a sun below the horizon, turbidity outside [1.7, 10], a non-positive scale or sun size.
std::shared_ptr<const SkyModel> make_sky(const SkyParams& params);

// Uniform cone sampling around +z parameterized by 1 - cos(theta_max) (exact for tiny cones such as the sun).
Vec3f sample_cone_1mc(Vec2f u, float one_minus_cos);
inline float cone_pdf_1mc(float one_minus_cos) { return 1 / (2 * kPi * one_minus_cos); }

}  // namespace torte
