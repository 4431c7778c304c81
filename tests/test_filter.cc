// Reconstruction filters: profile values, parameter checks, and filter importance sampling (offsets follow |f|,
// and the weighted estimate converges to the f-weighted average).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "chi2.h"
#include "core/error.h"
#include "core/rng.h"
#include "film/filter.h"

using namespace torte;

namespace {

// Composite Simpson's rule in double; n is rounded up to a multiple of 8, so for a Mitchell filter integrated over
// [-r, r] the kinks at +-r/2 fall on nodes that end Simpson panels.
double integrate(const std::function<double(double)>& g, double a, double b, int n = 4096) {
  n = (n + 7) / 8 * 8;
  const double h = (b - a) / n;
  double sum = g(a) + g(b);
  for (int i = 1; i < n; ++i) sum += g(a + i * h) * (i % 2 ? 4 : 2);
  return sum * h / 3;
}

struct Named {
  std::string name;
  Filter filter;
};

std::vector<Named> all_filters() {
  return {{"box", Filter::box()},
          {"box r=1.3", Filter::box(1.3f)},
          {"triangle", Filter::triangle()},
          {"triangle r=2", Filter::triangle(2)},
          {"gaussian", Filter::gaussian()},
          {"gaussian narrow", Filter::gaussian(2, 0.05f)},
          {"gaussian wide", Filter::gaussian(0.5f, 100)},
          {"mitchell", Filter::mitchell()},
          {"mitchell B=C=0", Filter::mitchell(2, 0, 0)},
          {"mitchell B=1 C=0", Filter::mitchell(1.5f, 1, 0)},
          {"mitchell B=0 C=0.5", Filter::mitchell(2, 0, 0.5f)}};
}

}  // namespace

TEST_CASE("Filter rejects invalid parameters", "[filter]") {
  const float nan = std::nanf("");
  CHECK_THROWS_AS(Filter::box(0), Error);
  CHECK_THROWS_AS(Filter::box(-1), Error);
  CHECK_THROWS_AS(Filter::box(nan), Error);
  CHECK_THROWS_AS(Filter::triangle(0), Error);
  CHECK_THROWS_AS(Filter::gaussian(0, 0.5f), Error);
  CHECK_THROWS_AS(Filter::gaussian(1.5f, 0), Error);
  CHECK_THROWS_AS(Filter::gaussian(1.5f, -0.5f), Error);
  CHECK_THROWS_AS(Filter::gaussian(1.5f, 1e-30f), Error);  // 1/(2 sigma^2) overflows
  CHECK_THROWS_AS(Filter::mitchell(0), Error);
  CHECK_THROWS_AS(Filter::mitchell(2, nan, 0.3f), Error);
  CHECK_THROWS_AS(Filter::mitchell(kInfinity), Error);
  CHECK_THROWS_WITH(Filter::gaussian(1.5f, -2), Catch::Contains("sigma"));
  CHECK_NOTHROW(Filter::box());
  CHECK_NOTHROW(Filter::mitchell(2, 0, 0));
}

TEST_CASE("Box filter is 1 inside its radius and 0 outside", "[filter]") {
  const Filter f = Filter::box(0.5f);
  CHECK(f.kind() == FilterKind::Box);
  CHECK(f.radius() == 0.5f);
  CHECK(f.eval_1d(0) == 1);
  CHECK(f.eval_1d(-0.49f) == 1);
  CHECK(f.eval_1d(0.5f) == 1);
  CHECK(f.eval_1d(0.51f) == 0);
  CHECK(f.eval_1d(-3) == 0);
  CHECK(f.evaluate({0.3f, -0.2f}) == 1);
  CHECK(f.evaluate({0.3f, 0.6f}) == 0);
}

TEST_CASE("Triangle filter peaks at the radius and falls to 0 at the edges", "[filter]") {
  const Filter f = Filter::triangle(2);
  CHECK(f.eval_1d(0) == 2);
  CHECK(f.eval_1d(1) == Approx(1));
  CHECK(f.eval_1d(-1.5f) == Approx(0.5));
  CHECK(f.eval_1d(2) == 0);
  CHECK(f.eval_1d(2.5f) == 0);
  CHECK(f.evaluate({1, -1.5f}) == Approx(0.5));
}

TEST_CASE("Gaussian filter is shifted to reach 0 at its radius", "[filter]") {
  const float r = 1.5f, sigma = 0.5f;
  const Filter f = Filter::gaussian(r, sigma);
  const auto expected = [&](double x) {
    return std::exp(-x * x / (2.0 * sigma * sigma)) - std::exp(-r * r / (2.0 * sigma * sigma));
  };
  CHECK(f.eval_1d(0) == Approx(expected(0)).epsilon(1e-6));
  CHECK(f.eval_1d(0.7f) == Approx(expected(0.7f)).epsilon(1e-5));
  CHECK(f.eval_1d(-1.2f) == Approx(expected(-1.2f)).epsilon(1e-4));
  CHECK(f.eval_1d(r) == 0);
  CHECK(f.eval_1d(-2) == 0);
  for (float x = 0; x + 0.01f < r; x += 0.01f) REQUIRE(f.eval_1d(x + 0.01f) < f.eval_1d(x));
  // sigma >> radius: both exponentials round to 1 in float; the profile must keep its relative precision.
  const Filter wide = Filter::gaussian(0.5f, 100);
  CHECK(wide.eval_1d(0) == Approx(-std::expm1(-0.25 / 20000.0)).epsilon(1e-5));
  CHECK(wide.eval_1d(0.25f) == Approx(std::exp(-0.0625 / 20000.0) - std::exp(-0.25 / 20000.0)).epsilon(1e-4));
}

// Convention: eval_1d(x) is the standard Mitchell-Netravali kernel k(t) at t = 2|x|/radius, unnormalized, so
// eval_1d(0) = k(0) = (6 - 2B)/6 for every radius, and f1 integrates to radius/2 (k integrates to 1 over [-2, 2]).
TEST_CASE("Mitchell filter matches the Mitchell-Netravali kernel stretched to its radius", "[filter]") {
  const float third = 1.0f / 3;
  for (float r : {2.0f, 3.0f, 0.8f}) {
    const Filter f = Filter::mitchell(r, third, third);
    CHECK(f.eval_1d(0) == Approx((6 - 2 * third) / 6));
    CHECK(f.eval_1d(r) == Approx(0).margin(1e-6));
    CHECK(f.eval_1d(1.01f * r) == 0);
    // Continuous at the kink t = 1 (x = r/2).
    CHECK(f.eval_1d(0.5f * r * (1 - 1e-6f)) == Approx(f.eval_1d(0.5f * r * (1 + 1e-6f))).margin(1e-5));
    // Negative lobes between r/2 and r.
    CHECK(f.eval_1d(0.75f * r) < 0);
    CHECK(f.eval_1d(-0.75f * r) < 0);
    const double integral = integrate([&](double x) { return f.eval_1d(float(x)); }, -r, r);
    CHECK(integral > 0);
    CHECK(integral == Approx(r / 2).epsilon(1e-4));
  }
  // k(1) = B/6 for every C (the kink value), from the formula's first piece.
  CHECK(Filter::mitchell(2, 0.6f, 0.2f).eval_1d(1) == Approx(0.6 / 6));
  // The cubic B-spline (B = 1, C = 0) has no negative lobes.
  const Filter bspline = Filter::mitchell(2, 1, 0);
  CHECK(bspline.eval_1d(0) == Approx(4.0 / 6));
  for (float x = 0; x <= 2; x += 0.01f) REQUIRE(bspline.eval_1d(x) >= 0);
}

TEST_CASE("Filter samples lie inside the radius with finite, bounded weights", "[filter][sampling]") {
  const float below_one = 0x1.fffffep-1f, below_half = 0x1.fffffep-2f;
  const std::vector<float> edges = {0, 1e-7f, below_half, 0.5f, 0.5f + 1e-7f, below_one};
  for (const auto& [name, named_filter] : all_filters()) {
    const Filter& filter = named_filter;  // a reference the lambda below can capture (clang 14: not a binding)
    const float r = filter.radius();
    const bool exact = filter.kind() == FilterKind::Box || filter.kind() == FilterKind::Triangle;
    // Checked by hand and reported once: a REQUIRE per sample would dominate the run time.
    std::string failure;
    const auto check = [&](Vec2f u) {
      if (!failure.empty()) return;
      const Filter::Sample s = filter.sample(u);
      const float f = filter.evaluate(s.offset);
      const char* problem = nullptr;
      if (!(std::fabs(s.offset.x) <= r && std::fabs(s.offset.y) <= r))
        problem = "offset outside the radius";
      else if (!std::isfinite(s.weight))
        problem = "weight not finite";
      else if (exact && s.weight != 1)
        problem = "weight of an exactly sampled filter is not 1";
      else if (std::fabs(s.weight) > 1.05f)  // the tabulated density follows |f| to within a few percent
        problem = "weight too large";
      else if (f == 0 ? s.weight != 0 && !exact : (f > 0) != (s.weight > 0))
        problem = "weight and f differ in sign";
      if (problem)
        failure = std::string(problem) + ": u = (" + std::to_string(u.x) + ", " + std::to_string(u.y) +
                  ") -> offset (" + std::to_string(s.offset.x) + ", " + std::to_string(s.offset.y) + "), weight " +
                  std::to_string(s.weight) + ", f " + std::to_string(f);
    };
    for (float a : edges)
      for (float b : edges) check({a, b});
    Pcg32 rng(7);
    for (int i = 0; i < 50000; ++i) check({rng.next_float(), rng.next_float()});
    INFO(name << ": " << failure);
    CHECK(failure.empty());
  }
}

namespace {

constexpr int kChi2Tests = 4 * 3;  // filters x (x marginal, y marginal, 2D)

// Samples the filter and checks the offsets' x and y marginals (1D bins) and their joint distribution (2D bins)
// against |f| / integral of |f|, computed by quadrature.
void check_sample_distribution(const Filter& filter) {
  const int kSamples = 200000, kBins1 = 40, kBins2 = 16;
  const double r = filter.radius();
  const auto abs_f = [&](double x) { return std::fabs(double(filter.eval_1d(float(x)))); };
  const double total = integrate(abs_f, -r, r, 1 << 14);
  const auto bin_probs = [&](int bins) {
    std::vector<double> p(bins);
    for (int i = 0; i < bins; ++i)
      p[i] = integrate(abs_f, -r + 2 * r * i / bins, -r + 2 * r * (i + 1) / bins, 512) / total;
    return p;
  };
  const std::vector<double> p1 = bin_probs(kBins1), p2 = bin_probs(kBins2);
  const auto bin_of = [&](float x, int bins) { return std::clamp(int((x + r) / (2 * r) * bins), 0, bins - 1); };

  std::vector<double> obs_x(kBins1, 0), obs_y(kBins1, 0), obs_2d(kBins2 * kBins2, 0);
  Pcg32 rng(42, 3);
  for (int i = 0; i < kSamples; ++i) {
    const Vec2f o = filter.sample({rng.next_float(), rng.next_float()}).offset;
    obs_x[bin_of(o.x, kBins1)] += 1;
    obs_y[bin_of(o.y, kBins1)] += 1;
    obs_2d[bin_of(o.y, kBins2) * kBins2 + bin_of(o.x, kBins2)] += 1;
  }
  std::vector<double> exp_1d(kBins1), exp_2d(kBins2 * kBins2);
  for (int i = 0; i < kBins1; ++i) exp_1d[i] = kSamples * p1[i];
  for (int j = 0; j < kBins2; ++j)
    for (int i = 0; i < kBins2; ++i) exp_2d[j * kBins2 + i] = kSamples * p2[i] * p2[j];

  const auto rx = test::chi2_test(obs_x, exp_1d, 0.01, kChi2Tests);
  const auto ry = test::chi2_test(obs_y, exp_1d, 0.01, kChi2Tests);
  const auto r2 = test::chi2_test(obs_2d, exp_2d, 0.01, kChi2Tests);
  INFO("x: " << rx.message);
  CHECK(rx.passed);
  INFO("y: " << ry.message);
  CHECK(ry.passed);
  INFO("2D: " << r2.message);
  CHECK(r2.passed);
}

}  // namespace

TEST_CASE("Box filter samples are uniform (chi-square)", "[filter][sampling][chi2]") {
  check_sample_distribution(Filter::box(0.7f));
}
TEST_CASE("Triangle filter samples follow the triangle (chi-square)", "[filter][sampling][chi2]") {
  check_sample_distribution(Filter::triangle(1.5f));
}
TEST_CASE("Gaussian filter samples follow the Gaussian (chi-square)", "[filter][sampling][chi2]") {
  check_sample_distribution(Filter::gaussian(1.5f, 0.5f));
}
TEST_CASE("Mitchell filter samples follow |f| (chi-square)", "[filter][sampling][chi2]") {
  check_sample_distribution(Filter::mitchell(2, 1.0f / 3, 1.0f / 3));
}

namespace {

// The film estimates a pixel as sum(w L) / sum(w). For a smooth test function g this ratio must converge to
// integral(f g) / integral(f): the tabulated pdf may differ from |f|, but f/pdf corrects for it exactly.
void check_unbiased(const Filter& filter) {
  // g(x, y) = a(x) b(y) + c(y): asymmetric in x and y, so a sign or mirroring error in the sampler shows.
  const auto a = [](double x) { return 1 + 0.5 * std::sin(1.7 * x + 0.3); };
  const auto b = [](double y) { return 1 + 0.4 * std::cos(2.1 * y - 0.2); };
  const auto c = [](double y) { return 0.6 * y * y - 0.3 * y; };
  const double r = filter.radius();
  const auto f1 = [&](double x) { return double(filter.eval_1d(float(x))); };
  const auto moment = [&](auto h) { return integrate([&](double x) { return f1(x) * h(x); }, -r, r, 1 << 14); };
  const double i_f = moment([](double) { return 1.0; });
  const double reference = (moment(a) * moment(b) + i_f * moment(c)) / (i_f * i_f);

  const int kSamples = 300000;
  std::vector<std::pair<double, double>> wg(kSamples);  // (w, w g) per sample
  double sum_w = 0, sum_wg = 0;
  Pcg32 rng(1234, 5);
  for (auto& s : wg) {
    const Filter::Sample fs = filter.sample({rng.next_float(), rng.next_float()});
    const double x = fs.offset.x, y = fs.offset.y;
    s = {fs.weight, fs.weight * (a(x) * b(y) + c(y))};
    sum_w += s.first;
    sum_wg += s.second;
  }
  const double estimate = sum_wg / sum_w;
  // Standard error of the ratio estimator (delta method).
  double sum_sq = 0;
  for (const auto& [w, v] : wg) sum_sq += (v - estimate * w) * (v - estimate * w);
  const double std_error = std::sqrt(sum_sq / kSamples) / (sum_w / kSamples * std::sqrt(double(kSamples)));
  INFO("estimate " << estimate << ", reference " << reference << ", standard error " << std_error);
  CHECK(std_error < 2e-3);
  CHECK(std::fabs(estimate - reference) < 4 * std_error);
  // Where f has negative lobes, the |f|-weighted average is a different answer, many standard errors away, so a
  // sampler that lost the sign of f fails the check above.
  if (filter.eval_1d(0.75f * filter.radius()) < 0) {
    const auto abs_moment = [&](auto h) {
      return integrate([&](double x) { return std::fabs(f1(x)) * h(x); }, -r, r, 1 << 14);
    };
    const double i_abs = abs_moment([](double) { return 1.0; });
    const double abs_reference = (abs_moment(a) * abs_moment(b) + i_abs * abs_moment(c)) / (i_abs * i_abs);
    INFO("|f|-weighted reference " << abs_reference);
    CHECK(std::fabs(abs_reference - reference) > 10 * std_error);
  }
}

}  // namespace

TEST_CASE("Box and triangle filter sampling is unbiased", "[filter][sampling]") {
  for (const Filter& f : {Filter::box(), Filter::box(1.3f), Filter::triangle(), Filter::triangle(2)}) {
    INFO("kind " << int(f.kind()) << ", radius " << f.radius());
    check_unbiased(f);
  }
}

TEST_CASE("Gaussian filter sampling is unbiased", "[filter][sampling]") {
  for (const Filter& f : {Filter::gaussian(), Filter::gaussian(2, 0.05f), Filter::gaussian(0.5f, 100)}) {
    INFO("radius " << f.radius());
    check_unbiased(f);
  }
}

TEST_CASE("Mitchell filter sampling is unbiased", "[filter][sampling]") {
  for (const Filter& f :
       {Filter::mitchell(), Filter::mitchell(2, 0, 0), Filter::mitchell(1.5f, 1, 0), Filter::mitchell(2, 0, 0.5f)}) {
    INFO("radius " << f.radius() << ", f(0) " << f.eval_1d(0));
    check_unbiased(f);
  }
}
