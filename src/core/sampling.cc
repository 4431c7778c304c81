#include "core/sampling.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include "core/error.h"

namespace torte {

namespace {

// Direction with the given cos(theta) and azimuth 2 pi u around +z; sin_theta is passed in so callers can compute
// it without cancellation.
Vec3f spherical_direction(float sin_theta, float cos_theta, float u) {
  const float phi = 2 * kPi * u;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

}  // namespace

Vec3f sample_uniform_sphere(Vec2f u) {
  const float z = 1 - 2 * u.x;
  return spherical_direction(std::sqrt(std::max(0.0f, 1 - z * z)), z, u.y);
}

Vec3f sample_uniform_hemisphere(Vec2f u) {
  const float z = u.x;
  return spherical_direction(std::sqrt(std::max(0.0f, 1 - z * z)), z, u.y);
}

Vec3f sample_uniform_cone(Vec2f u, float cos_theta_max) {
  // Work with a = 1 - cos(theta), uniform in [0, 1 - cos_theta_max]: sin^2 = a (2 - a) keeps full precision for the
  // narrow cones of small, distant lights, where 1 - cos^2 would cancel catastrophically.
  const float a = u.x * (1 - cos_theta_max);
  const float cos_theta = 1 - a;
  return spherical_direction(std::sqrt(std::max(0.0f, a * (2 - a))), cos_theta, u.y);
}

Distribution1D::Distribution1D(std::span<const float> weights) : func_(weights.begin(), weights.end()) {
  const size_t n = func_.size();
  if (n == 0) throw Error("a discrete distribution needs at least one weight");
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(func_[i]) || func_[i] < 0)
      throw Error("distribution weight " + std::to_string(i) + " is " + std::to_string(func_[i]) +
                  "; weights must be finite and non-negative");
  // Accumulate in double: with many bins (environment maps) a float running sum loses the small ones.
  std::vector<double> sum(n + 1, 0.0);
  for (size_t i = 0; i < n; ++i) sum[i + 1] = sum[i] + func_[i];
  const double total = sum[n];
  integral_ = float(total / double(n));
  // Decide "all zero" on the float integral that pmf() and the pdf divide by, so that weights so tiny their
  // average underflows give a consistent uniform distribution rather than a cdf that disagrees with the pmf.
  cdf_.resize(n + 1);
  for (size_t i = 0; i <= n; ++i)
    cdf_[i] = integral_ > 0 ? float(sum[i] / total) : float(double(i) / double(n));
  // Exact endpoints, so u in [0, 1) always falls inside the table.
  cdf_[0] = 0;
  cdf_[n] = 1;
  uniform_ = std::all_of(func_.begin(), func_.end(), [&](float w) { return w == func_[0]; });
  uniform_pmf_ = pmf(0);
}

float Distribution1D::pmf(int i) const {
  if (i < 0 || size_t(i) >= func_.size()) return 0;
  const float n = float(func_.size());
  return integral_ > 0 ? func_[size_t(i)] / (integral_ * n) : 1 / n;
}

int Distribution1D::sample_by_search(float u, float* pmf_out, float* u_remapped) const {
  const int n = int(func_.size());
  if (n == 0) {  // default-constructed: nothing to pick (e.g. a scene without lights)
    if (pmf_out) *pmf_out = 0;
    if (u_remapped) *u_remapped = 0;
    return -1;
  }
  if (!(u >= 0)) u = 0;  // also maps NaN to 0, so the result below is always a valid bin
  // The bin is the last i < n with cdf[i] <= u (cdf[0] = 0 <= u); zero-weight bins have cdf[i] == cdf[i+1] and
  // are skipped. u is random, so the branches of a search mispredict about half the time (std::upper_bound here
  // was 3 % of a Cornell render, whose light has two triangles): small tables count the bounds below u instead.
  const float* cdf = cdf_.data();
  int i = 0;
  if (n <= 16) {
    for (int j = 1; j < n; ++j) i += int(cdf[j] <= u);
  } else {
    size_t base = 0, len = cdf_.size();
    while (len > 1) {
      const size_t half = len / 2;
      if (cdf[base + half] <= u) base += half;
      len -= half;
    }
    i = std::min(int(base), n - 1);
  }
  // Only reachable for u outside [0, 1): step back from trailing empty bins so a zero-probability bin is never
  // returned.
  while (i > 0 && cdf_[size_t(i) + 1] == cdf_[size_t(i)]) --i;
  if (pmf_out) *pmf_out = pmf(i);
  if (u_remapped) {
    const float width = cdf_[size_t(i) + 1] - cdf_[size_t(i)];
    const float r = width > 0 ? (u - cdf_[size_t(i)]) / width : 0;
    *u_remapped = std::clamp(r, 0.0f, kOneMinusEpsilon);
  }
  return i;
}

float Distribution1D::sample_continuous(float u, float* pdf, int* bin) const {
  float du;
  const int i = sample_discrete(u, nullptr, &du);
  if (i < 0) {
    if (pdf) *pdf = 0;
    if (bin) *bin = -1;
    return 0;
  }
  const int n = int(func_.size());
  const float fn = float(n);
  float x = std::min((float(i) + du) / fn, kOneMinusEpsilon);
  // Rounding can put x a hair outside bin i (e.g. exactly on the next bin's left edge); nudge it back so that
  // int(x * n) == i. Callers that look a density up from x (texels of an environment map) then find the same bin
  // the pdf refers to, and never a zero-weight neighbour.
  while (int(x * fn) > i) x = std::nextafter(x, 0.0f);
  while (int(x * fn) < i) x = std::nextafter(x, 1.0f);
  if (pdf) *pdf = integral_ > 0 ? func_[size_t(i)] / integral_ : 1;
  if (bin) *bin = i;
  return x;
}

Distribution2D::Distribution2D(std::span<const float> weights, int nu, int nv) {
  if (nu <= 0 || nv <= 0 || weights.size() != size_t(nu) * size_t(nv))
    throw Error("a 2D distribution needs nu * nv weights (nu, nv > 0)");
  conditional_.reserve(size_t(nv));
  std::vector<float> rows(static_cast<size_t>(nv));
  for (int v = 0; v < nv; ++v) {
    conditional_.emplace_back(weights.subspan(size_t(v) * size_t(nu), size_t(nu)));
    rows[size_t(v)] = conditional_.back().integral();
  }
  marginal_ = Distribution1D(rows);
}

Vec2f Distribution2D::sample(Vec2f u, float* pdf) const {
  float pdf_v, pdf_u;
  int v;
  const float y = marginal_.sample_continuous(u.y, &pdf_v, &v);
  const float x = conditional_[size_t(v)].sample_continuous(u.x, &pdf_u);
  if (pdf) *pdf = pdf_u * pdf_v;
  return {x, y};
}

float Distribution2D::pdf(Vec2f p) const {
  const int nv_ = nv(), nu_ = nu();
  if (nv_ == 0) return 0;
  const int v = std::clamp(int(p.y * float(nv_)), 0, nv_ - 1);
  const int u = std::clamp(int(p.x * float(nu_)), 0, nu_ - 1);
  return conditional_[size_t(v)].pmf(u) * float(nu_) * marginal_.pmf(v) * float(nv_);
}

}  // namespace torte
