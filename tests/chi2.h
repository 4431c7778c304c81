// Pearson chi-square goodness-of-fit test for sampling routines: bin the samples, compare with the expected
// counts from integrating the pdf over each bin, and reject when the p-value falls below a significance level
// corrected for the number of tests (Sidak), as in pbrt's and Mitsuba's warp tests. Bins with a small expected
// count are pooled so the chi-square approximation holds.
#pragma once
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace torte::test {

// 4-point Gauss-Legendre quadrature over [a, b], for the expected counts of histogram bins: exact for polynomials
// up to degree 7 (many pdfs are polynomials in cos(theta)), and it never evaluates the endpoints, so a pdf that
// jumps at a bin edge (the hemisphere's rim, a cone's boundary) is integrated from the correct side.
inline double integrate(const std::function<double(double)>& f, double a, double b) {
  static constexpr double x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  static constexpr double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  const double half = (b - a) / 2, mid = (a + b) / 2;
  double s = 0;
  for (int i = 0; i < 4; ++i) s += w[i] * f(mid + half * x[i]);
  return s * half;
}

// Regularized upper incomplete gamma Q(a, x) (Numerical Recipes: series for x < a + 1, continued fraction else).
inline double gamma_q(double a, double x) {
  if (x <= 0) return 1;
  const double gln = std::lgamma(a);
  if (x < a + 1) {
    double ap = a, sum = 1 / a, del = sum;
    for (int n = 0; n < 10000; ++n) {
      ap += 1;
      del *= x / ap;
      sum += del;
      if (std::fabs(del) < std::fabs(sum) * 1e-15) break;
    }
    return 1 - sum * std::exp(-x + a * std::log(x) - gln);
  }
  double b = x + 1 - a, c = 1 / 1e-300, d = 1 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::fabs(d) < 1e-300) d = 1e-300;
    c = b + an / c;
    if (std::fabs(c) < 1e-300) c = 1e-300;
    d = 1 / d;
    const double del = d * c;
    h *= del;
    if (std::fabs(del - 1) < 1e-15) break;
  }
  return std::exp(-x + a * std::log(x) - gln) * h;
}

struct Chi2Result {
  double statistic = 0;
  int dof = 0;
  double p_value = 1;
  bool passed = false;
  std::string message;  // human-readable summary for failing assertions
};

// observed[i]: samples that fell in bin i; expected[i]: sample count times the pdf's integral over bin i.
// Bins whose expected count is below min_expected are pooled together. Samples that landed in a bin with
// (numerically) zero expected count fail the test outright: the sampler produced an impossible value.
inline Chi2Result chi2_test(const std::vector<double>& observed, const std::vector<double>& expected,
                            double significance = 0.01, int test_count = 1, double min_expected = 5) {
  Chi2Result r;
  std::vector<size_t> order(observed.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });
  double pooled_obs = 0, pooled_exp = 0;
  int pooled_bins = 0, cells = 0;
  for (size_t k : order) {
    if (expected[k] == 0) {
      if (observed[k] > 0) {
        r.message = "a sample fell into bin " + std::to_string(k) + " where the pdf integrates to zero";
        return r;
      }
      continue;
    }
    if (expected[k] < min_expected) {
      pooled_obs += observed[k];
      pooled_exp += expected[k];
      ++pooled_bins;
    } else if (pooled_exp > 0 && pooled_exp < min_expected) {
      // Fold what is pooled so far into this bin so every cell has enough expected samples.
      const double o = observed[k] + pooled_obs, e = expected[k] + pooled_exp;
      r.statistic += (o - e) * (o - e) / e;
      ++cells;
      pooled_obs = pooled_exp = 0;
    } else {
      const double d = observed[k] - expected[k];
      r.statistic += d * d / expected[k];
      ++cells;
    }
  }
  if (pooled_exp > 0) {
    const double d = pooled_obs - pooled_exp;
    r.statistic += d * d / pooled_exp;
    ++cells;
  }
  r.dof = cells - 1;
  if (r.dof < 1) {
    r.message = "too few bins with enough expected samples";
    return r;
  }
  r.p_value = gamma_q(r.dof / 2.0, r.statistic / 2.0);
  const double alpha = 1 - std::pow(1 - significance, 1.0 / test_count);
  r.passed = r.p_value >= alpha;
  r.message = "chi2 = " + std::to_string(r.statistic) + ", dof = " + std::to_string(r.dof) +
              ", p = " + std::to_string(r.p_value) + " (reject below " + std::to_string(alpha) + ")";
  return r;
}

}  // namespace torte::test
