// Warping functions from [0,1)^n to common domains, their pdfs, discrete distributions and MIS weights.
// Every routine here has a chi-square test in tests/test_sampling.cc.
#pragma once
#include <span>
#include <vector>

#include "core/vec.h"

namespace torte {

Vec2f sample_uniform_disk_concentric(Vec2f u);  // unit disk, pdf 1/pi
Vec3f sample_uniform_sphere(Vec2f u);           // pdf 1/(4 pi)
constexpr float uniform_sphere_pdf() { return 1.0f / (4 * kPi); }
Vec3f sample_uniform_hemisphere(Vec2f u);       // z >= 0, pdf 1/(2 pi)
constexpr float uniform_hemisphere_pdf() { return 1.0f / (2 * kPi); }
Vec3f sample_cosine_hemisphere(Vec2f u);        // z >= 0, pdf cos(theta)/pi
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0 ? cos_theta * kInvPi : 0; }
// Uniform over the cone of directions around +z with cos(theta) >= cos_theta_max.
Vec3f sample_uniform_cone(Vec2f u, float cos_theta_max);
inline float uniform_cone_pdf(float cos_theta_max) { return 1.0f / (2 * kPi * (1 - cos_theta_max)); }
// Uniform barycentrics (b0, b1, b2) over a triangle (Heitz 2019 low-distortion map).
Vec3f sample_uniform_triangle(Vec2f u);

// Power heuristic with beta = 2 (Veach 1997).
inline float power_heuristic(float nf, float f_pdf, float ng, float g_pdf) {
  const float f = nf * f_pdf, g = ng * g_pdf;
  if (f == kInfinity) return 1;  // a delta strategy always wins
  if (f == 0) return 0;
  return (f * f) / (f * f + g * g);
}

// Piecewise-constant 1D distribution over n bins of [0,1) built from non-negative weights. If all weights are
// zero it falls back to uniform so sampling stays defined.
class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(std::span<const float> weights);
  size_t size() const { return func_.size(); }
  float integral() const { return integral_; }  // sum of weights / n (the average weight)
  // Picks bin i with probability weights[i] / sum; *pmf receives that probability, *u_remapped a fresh uniform.
  int sample_discrete(float u, float* pmf = nullptr, float* u_remapped = nullptr) const;
  float pmf(int i) const;
  // Continuous sample in [0,1) with density func/integral; *pdf receives it, *bin the bin index.
  float sample_continuous(float u, float* pdf = nullptr, int* bin = nullptr) const;

 private:
  std::vector<float> func_, cdf_;
  float integral_ = 0;
};

// Piecewise-constant 2D distribution over [0,1)^2 on an nu x nv grid of non-negative weights (row-major,
// weights[v * nu + u]): a marginal distribution over rows and one conditional distribution per row (pbrt's
// Distribution2D). Densities are with respect to area in [0,1)^2; pdf(p) equals the density sample() reports.
class Distribution2D {
 public:
  Distribution2D() = default;
  Distribution2D(std::span<const float> weights, int nu, int nv);
  int nu() const { return int(conditional_.size() ? conditional_[0].size() : 0); }
  int nv() const { return int(conditional_.size()); }
  float integral() const { return marginal_.integral(); }  // average weight
  // Continuous sample in [0,1)^2; *pdf receives its density.
  Vec2f sample(Vec2f u, float* pdf = nullptr) const;
  float pdf(Vec2f p) const;

 private:
  std::vector<Distribution1D> conditional_;  // one per row v
  Distribution1D marginal_;                   // over rows, weighted by the row averages
};

}  // namespace torte
