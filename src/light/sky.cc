#include "light/sky.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"

namespace torte {

namespace {

// Perez et al. 1993 luminance distribution: theta from the zenith, gamma the angle to the sun.
float perez_f(const float c[5], float cos_theta, float gamma, float cos_gamma) {
  const float ct = std::max(cos_theta, 1e-3f);
  return (1 + c[0] * std::exp(c[1] / ct)) * (1 + c[2] * std::exp(c[3] * gamma) + c[4] * cos_gamma * cos_gamma);
}

Rgb xyY_to_linear_srgb(float x, float y, float Y) {
  if (!(y > 0) || !(Y > 0)) return {};
  const float X = x / y * Y, Z = (1 - x - y) / y * Y;
  const float r = 3.2404542f * X - 1.5371385f * Y - 0.4985314f * Z;
  const float g = -0.9692660f * X + 1.8760108f * Y + 0.0415560f * Z;
  const float b = 0.0556434f * X - 0.2040259f * Y + 1.0572252f * Z;
  return {std::max(r, 0.0f), std::max(g, 0.0f), std::max(b, 0.0f)};
}

}  // namespace

Vec3f sample_cone_1mc(Vec2f u, float one_minus_cos) {
  const float a = u.x * one_minus_cos;  // 1 - cos(theta), uniform
  const float sin_theta = std::sqrt(std::max(0.0f, a * (2 - a)));
  const float phi = 2 * kPi * u.y;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), 1 - a};
}

bool SkyModel::in_sun(Vec3f d) const {
  return params.sun && 0.5f * length_squared(d - sun_dir) <= sun_one_minus_cos;
}

Rgb SkyModel::sky_radiance(Vec3f d) const {
  if (d.y <= 0) return {};
  const float cos_gamma = std::clamp(dot(d, sun_dir), -1.0f, 1.0f);
  // acos loses precision near the sun; the chord length gives gamma accurately there.
  const float gamma = cos_gamma > 0.9f ? 2 * std::asin(std::min(1.0f, 0.5f * length(d - sun_dir)))
                                       : std::acos(cos_gamma);
  float v[3];
  for (int k = 0; k < 3; ++k) v[k] = norm[k] * perez_f(perez[k], d.y, gamma, cos_gamma);
  return xyY_to_linear_srgb(v[1], v[2], v[0]) * params.scale;
}

Rgb SkyModel::radiance(Vec3f d) const {
  Rgb l = sky_radiance(d);
  if (in_sun(d)) l += sun_radiance;
  return l;
}

bool SkyModel::sample(Vec2f u, Vec3f* wi, float* pdf_out) const {
  if (u.x < sun_probability) {
    const Vec2f us(std::min(u.x / sun_probability, 0x1.fffffep-1f), u.y);
    *wi = normalize(Frame::from_z(sun_dir).to_world(sample_cone_1mc(us, sun_one_minus_cos)));
  } else {
    const Vec2f us(std::min((u.x - sun_probability) / (1 - sun_probability), 0x1.fffffep-1f), u.y);
    float p;
    if (!sampling.sample(us, wi, &p)) return false;
  }
  *pdf_out = pdf(*wi);
  return *pdf_out > 0;
}

float SkyModel::pdf(Vec3f d) const {
  float p = (1 - sun_probability) * sampling.pdf(d);
  if (sun_probability > 0 && in_sun(d)) p += sun_probability * cone_pdf_1mc(sun_one_minus_cos);
  return p;
}

std::shared_ptr<const SkyModel> make_sky(const SkyParams& params) {
  const float len = length(params.sun_direction);
  if (!(len > 0) || !is_finite(params.sun_direction)) throw Error("sky: the sun direction must be non-zero");
  if (!(params.turbidity >= 1.7f && params.turbidity <= 10))
    throw Error("sky: turbidity must be in [1.7, 10], got " + std::to_string(params.turbidity));
  if (!(params.scale > 0) || !std::isfinite(params.scale)) throw Error("sky: scale must be positive");
  if (!(params.sun_radius_degrees > 0 && params.sun_radius_degrees < 45))
    throw Error("sky: sun radius must be in (0, 45) degrees");
  auto sky = std::make_shared<SkyModel>();
  SkyModel& s = *sky;
  s.params = params;
  s.sun_dir = params.sun_direction / len;
  if (s.sun_dir.y < -1e-6f) throw Error("sky: the sun must be above the horizon (the Preetham model)");
  const float T = params.turbidity;
  const float theta_s = std::acos(std::clamp(s.sun_dir.y, 0.0f, 1.0f));
  const float ts2 = theta_s * theta_s, ts3 = ts2 * theta_s;
  // Preetham et al. 1999, appendix A.2.
  const float coeffs[3][5] = {
      {0.1787f * T - 1.4630f, -0.3554f * T + 0.4275f, -0.0227f * T + 5.3251f, 0.1206f * T - 2.5771f,
       -0.0670f * T + 0.3703f},
      {-0.0193f * T - 0.2592f, -0.0665f * T + 0.0008f, -0.0004f * T + 0.2125f, -0.0641f * T - 0.8989f,
       -0.0033f * T + 0.0452f},
      {-0.0167f * T - 0.2608f, -0.0950f * T + 0.0092f, -0.0079f * T + 0.2102f, -0.0441f * T - 1.6537f,
       -0.0109f * T + 0.0529f}};
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 5; ++j) s.perez[k][j] = coeffs[k][j];
  const float chi = (4.0f / 9 - T / 120) * (kPi - 2 * theta_s);
  s.zenith[0] = std::max(0.0f, (4.0453f * T - 4.9710f) * std::tan(chi) - 0.2155f * T + 2.4192f);
  s.zenith[1] = T * T * (0.00166f * ts3 - 0.00375f * ts2 + 0.00209f * theta_s) +
                T * (-0.02903f * ts3 + 0.06377f * ts2 - 0.03202f * theta_s + 0.00394f) +
                (0.11693f * ts3 - 0.21196f * ts2 + 0.06052f * theta_s + 0.25886f);
  s.zenith[2] = T * T * (0.00275f * ts3 - 0.00610f * ts2 + 0.00317f * theta_s) +
                T * (-0.04214f * ts3 + 0.08970f * ts2 - 0.04153f * theta_s + 0.00516f) +
                (0.15346f * ts3 - 0.26756f * ts2 + 0.06670f * theta_s + 0.26688f);
  for (int k = 0; k < 3; ++k)
    s.norm[k] = s.zenith[k] / perez_f(s.perez[k], 1, theta_s, std::cos(theta_s));

  // The sun: white extraterrestrial luminance through Rayleigh and aerosol extinction (Preetham appendix A.1).
  const float r = params.sun_radius_degrees * kPi / 180;
  const float half_sin = std::sin(0.5f * r);
  s.sun_one_minus_cos = 2 * half_sin * half_sin;
  if (params.sun) {
    const float default_half = std::sin(0.5f * 0.2665f * kPi / 180);
    const float solid_ratio = (2 * default_half * default_half) / s.sun_one_minus_cos;
    const float theta_deg = theta_s * 180 / kPi;
    const float m = 1 / (std::cos(theta_s) + 0.15f * std::pow(93.885f - theta_deg, -1.253f));
    const float beta = 0.04608365822050f * T - 0.04586025928522f;
    const float lambda[3] = {0.610f, 0.550f, 0.465f};  // micrometres
    float tau[3];
    for (int k = 0; k < 3; ++k) {
      const float rayleigh = std::exp(-0.008735f * std::pow(lambda[k], -4.08f) * m);
      const float aerosol = std::exp(-beta * std::pow(lambda[k], -1.3f) * m);
      tau[k] = rayleigh * aerosol;
    }
    const float luminance = 1.883e6f * solid_ratio;  // kcd/m^2
    s.sun_radiance = Rgb(tau[0], tau[1], tau[2]) * (luminance * params.scale);
    s.sun_integral = s.sun_radiance.average() * 2 * kPi * s.sun_one_minus_cos;
  }

  // Sampling table: conservative per-texel maximum of 3x3 samples, times sin(theta) at the row centre.
  const int nu = std::max(4, params.table_width), nv = std::max(2, params.table_height);
  std::vector<float> weights(size_t(nu) * size_t(nv));
  double integral = 0;
  const double texel = (2 * M_PI / nu) * (M_PI / nv);
  for (int y = 0; y < nv; ++y) {
    const float sin_c = std::sin(kPi * (float(y) + 0.5f) / float(nv));
    for (int x = 0; x < nu; ++x) {
      float best = 0;
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
          const Vec2f uv((float(x) + 0.5f * float(i)) / float(nu), (float(y) + 0.5f * float(j)) / float(nv));
          best = std::max(best, s.sky_radiance(equirect_direction(uv)).average());
        }
      weights[size_t(y) * size_t(nu) + size_t(x)] = best * sin_c;
      integral += double(s.sky_radiance(equirect_direction({(float(x) + 0.5f) / float(nu),
                                                             (float(y) + 0.5f) / float(nv)}))
                             .average()) *
                  sin_c * texel;
    }
  }
  s.sky_integral = float(integral);
  s.sampling = SphericalDistribution(weights, nu, nv, Transform());
  const float total = s.sun_integral + s.sky_integral;
  s.sun_probability = params.sun && total > 0 ? s.sun_integral / total : 0;
  // Keep both strategies alive: the sky table covers the dome, the sun cone the disk.
  if (params.sun) s.sun_probability = std::clamp(s.sun_probability, 0.05f, 0.95f);
  if (!(s.sky_integral > 0)) s.sun_probability = params.sun ? 1.0f : 0.0f;
  return sky;
}

}  // namespace torte
