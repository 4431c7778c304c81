// Statistical tests for the warps and distributions in core/sampling.h and the Sobol sampler in core/sampler.h:
// Pearson chi-square goodness of fit against the documented pdfs (tests/chi2.h), plus the exact stratification
// properties a (0,2)-sequence guarantees. All random input comes from Pcg32 with fixed seeds, so the tests are
// deterministic; the significance level is still Sidak-corrected for the number of chi-square tests below, so a
// correct implementation passes with high probability under any other seeds too.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <vector>

#include "chi2.h"
#include "core/error.h"
#include "core/rng.h"
#include "core/sampler.h"
#include "core/sampling.h"
#include "test_random.h"

using namespace torte;
using torte::test::next_2d;
using torte::test::integrate;
using torte::test::chi2_test;
using torte::test::Chi2Result;

namespace {

// Number of chi-square tests in this file that are expected to pass (for the Sidak correction).
constexpr int kChi2Tests = 17;
constexpr double kSignificance = 0.01;
constexpr double kTwoPi = 2 * 3.14159265358979323846;

Chi2Result run_chi2(const std::vector<double>& observed, const std::vector<double>& expected) {
  return chi2_test(observed, expected, kSignificance, kChi2Tests);
}

// Directions binned by (cos theta, phi): n_cos bins over [cos_lo, cos_hi] and n_phi bins over [0, 2 pi). In this
// parameterization the solid-angle measure is d(cos theta) d(phi), so the expected count of a bin is the sample
// count times the double integral of pdf(cos theta, phi) over its rectangle. Directions with cos theta outside
// the range (beyond rounding), or not of unit length, go to a last bin with expected count zero, which fails the
// test outright.
struct DirectionHistogram {
  int n_cos, n_phi;
  double cos_lo, cos_hi;
  std::vector<double> observed;

  DirectionHistogram(int nc, int np, double lo, double hi)
      : n_cos(nc), n_phi(np), cos_lo(lo), cos_hi(hi), observed(size_t(nc * np + 1), 0.0) {}

  void add(Vec3f w) {
    const double len = std::sqrt(double(w.x) * w.x + double(w.y) * w.y + double(w.z) * w.z);
    const double tol = 1e-5 * (cos_hi - cos_lo) + 1e-6;
    double t = (w.z - cos_lo) / (cos_hi - cos_lo);
    if (std::fabs(len - 1) > 1e-5 || t < -tol || t > 1 + tol) {
      observed.back() += 1;
      return;
    }
    double phi = std::atan2(double(w.y), double(w.x));
    if (phi < 0) phi += kTwoPi;
    const int ic = std::clamp(int(t * n_cos), 0, n_cos - 1);
    const int ip = std::clamp(int(phi / kTwoPi * n_phi), 0, n_phi - 1);
    observed[size_t(ic * n_phi + ip)] += 1;
  }

  std::vector<double> expected(const std::function<double(double, double)>& pdf, double n_samples) const {
    std::vector<double> e(observed.size(), 0.0);
    for (int ic = 0; ic < n_cos; ++ic) {
      const double c0 = cos_lo + (cos_hi - cos_lo) * ic / n_cos, c1 = cos_lo + (cos_hi - cos_lo) * (ic + 1) / n_cos;
      for (int ip = 0; ip < n_phi; ++ip) {
        const double p0 = kTwoPi * ip / n_phi, p1 = kTwoPi * (ip + 1) / n_phi;
        const double integral =
            integrate([&](double c) { return integrate([&](double p) { return pdf(c, p); }, p0, p1); }, c0, c1);
        e[size_t(ic * n_phi + ip)] = n_samples * integral;
      }
    }
    return e;
  }
};

// Draws n directions from warp(u) with u from a seeded Pcg32 and tests them against pdf(cos theta, phi).
Chi2Result test_directions(const std::function<Vec3f(Vec2f)>& warp, const std::function<double(double, double)>& pdf,
                           double cos_lo, double cos_hi, int n = 1000000, uint64_t seed = 1) {
  DirectionHistogram h(20, 40, cos_lo, cos_hi);
  Pcg32 rng(seed);
  for (int i = 0; i < n; ++i) h.add(warp(next_2d(rng)));
  return run_chi2(h.observed, h.expected(pdf, n));
}

}  // namespace

TEST_CASE("chi2_test rejects samples drawn from the wrong distribution", "[sampling][chi2]") {
  // Without this the other tests could pass vacuously. Same binning and threshold as the real tests.
  const auto uniform_hemi = [](double, double) { return 1 / kTwoPi; };
  const auto cosine_hemi = [](double c, double) { return c / (kTwoPi / 2); };
  const Chi2Result a = test_directions(sample_uniform_hemisphere, cosine_hemi, 0, 1);
  INFO(a.message);
  CHECK_FALSE(a.passed);
  const Chi2Result b = test_directions(sample_cosine_hemisphere, uniform_hemi, 0, 1);
  INFO(b.message);
  CHECK_FALSE(b.passed);
  // A subtle bug: a sphere sampled with theta (not cos theta) uniform, which crowds the poles.
  const auto naive_sphere = [](Vec2f u) {
    const float theta = kPi * u.x, phi = 2 * kPi * u.y;
    return Vec3f(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
  };
  const Chi2Result c = test_directions(naive_sphere, [](double, double) { return 1 / (2 * kTwoPi); }, -1, 1);
  INFO(c.message);
  CHECK_FALSE(c.passed);
  // A cone sampler that forgot to shrink its range by cos_theta_max puts samples where the pdf is zero.
  const Chi2Result d = test_directions(sample_uniform_hemisphere,
                                       [](double, double) { return 1 / (kTwoPi * 0.5); }, 0.5, 1, 10000);
  INFO(d.message);
  CHECK_FALSE(d.passed);
}

TEST_CASE("Concentric disk sampling is uniform on the unit disk", "[sampling][chi2]") {
  // Polar bins with equal area: r^2 in 20 equal steps times 40 angular sectors.
  constexpr int nr = 20, nphi = 40, n = 1000000;
  std::vector<double> observed(nr * nphi + 1, 0.0), expected(nr * nphi + 1, double(n) / (nr * nphi));
  expected.back() = 0;  // outside the disk
  Pcg32 rng(11);
  for (int i = 0; i < n; ++i) {
    const Vec2f p = sample_uniform_disk_concentric(next_2d(rng));
    const double r2 = double(p.x) * p.x + double(p.y) * p.y;
    if (r2 > 1 + 1e-6) {
      observed.back() += 1;
      continue;
    }
    double phi = std::atan2(double(p.y), double(p.x));
    if (phi < 0) phi += kTwoPi;
    const int ir = std::min(int(r2 * nr), nr - 1), ip = std::min(int(phi / kTwoPi * nphi), nphi - 1);
    observed[size_t(ir * nphi + ip)] += 1;
  }
  const Chi2Result r = run_chi2(observed, expected);
  INFO(r.message);
  CHECK(r.passed);
  // The centre and the corners of the square map to the centre and the rim.
  const Vec2f c = sample_uniform_disk_concentric({0.5f, 0.5f});
  CHECK(c.x == 0);
  CHECK(c.y == 0);
  const Vec2f e = sample_uniform_disk_concentric({1, 0.5f});
  CHECK(e.x == Approx(1));
  CHECK(e.y == Approx(0).margin(1e-6));
}

TEST_CASE("Uniform sphere sampling", "[sampling][chi2]") {
  const Chi2Result r =
      test_directions(sample_uniform_sphere, [](double, double) { return double(uniform_sphere_pdf()); }, -1, 1);
  INFO(r.message);
  CHECK(r.passed);
  CHECK(uniform_sphere_pdf() == Approx(1 / (4 * kPi)));
}

TEST_CASE("Uniform hemisphere sampling", "[sampling][chi2]") {
  // Bins over the whole sphere: the lower half must stay empty.
  const Chi2Result r = test_directions(
      sample_uniform_hemisphere, [](double c, double) { return c >= 0 ? double(uniform_hemisphere_pdf()) : 0.0; },
      -1, 1);
  INFO(r.message);
  CHECK(r.passed);
  // And finely over the upper half alone.
  const Chi2Result r2 = test_directions(
      sample_uniform_hemisphere, [](double, double) { return double(uniform_hemisphere_pdf()); }, 0, 1, 1000000, 2);
  INFO(r2.message);
  CHECK(r2.passed);
}

TEST_CASE("Cosine-weighted hemisphere sampling", "[sampling][chi2]") {
  const Chi2Result r = test_directions(
      sample_cosine_hemisphere, [](double c, double) { return double(cosine_hemisphere_pdf(float(c))); }, 0, 1);
  INFO(r.message);
  CHECK(r.passed);
  CHECK(cosine_hemisphere_pdf(1) == Approx(kInvPi));
  CHECK(cosine_hemisphere_pdf(-0.5f) == 0);
  Pcg32 rng(3);
  for (int i = 0; i < 10000; ++i) REQUIRE(sample_cosine_hemisphere(next_2d(rng)).z >= 0);
}

TEST_CASE("Uniform cone sampling", "[sampling][chi2]") {
  uint64_t seed = 5;
  for (const float cos_max : {0.999f, 0.9f, 0.0f, -0.5f}) {
    // Bins span exactly the cone, so even the narrow 0.999 cone is resolved finely; samples outside it fail.
    const double pdf = uniform_cone_pdf(cos_max);
    const Chi2Result r = test_directions([cos_max](Vec2f u) { return sample_uniform_cone(u, cos_max); },
                                         [pdf](double, double) { return pdf; }, cos_max, 1, 500000, seed++);
    INFO("cos_theta_max = " << cos_max << ": " << r.message);
    CHECK(r.passed);
  }
  CHECK(uniform_cone_pdf(-1) == Approx(1 / (4 * kPi)));  // the full sphere
  const Vec3f axis = sample_uniform_cone({0, 0.3f}, 0.2f);
  CHECK(axis.z == 1);
  // The narrow cone keeps sin(theta) accurate: u.x = 1 gives the rim, sin^2 = 1 - 0.9999^2.
  const Vec3f rim = sample_uniform_cone({0x1.fffffep-1f, 0}, 0.9999f);
  CHECK(std::hypot(rim.x, rim.y) == Approx(std::sqrt(1 - 0.9999 * 0.9999)).epsilon(1e-3));
}

TEST_CASE("Uniform triangle barycentrics", "[sampling][chi2]") {
  // (b0, b1) lies in the triangle below the diagonal of the unit square, with density 2. On an n x n grid, cells
  // wholly below the diagonal (i + j < n - 1) expect 2/n^2 of the samples, the cells it cuts in half (i + j = n - 1)
  // 1/n^2, and those above it none.
  constexpr int g = 20, n = 1000000;
  std::vector<double> observed(g * g, 0.0), expected(g * g, 0.0);
  for (int i = 0; i < g; ++i)
    for (int j = 0; j < g; ++j)
      expected[size_t(i * g + j)] = i + j < g - 1 ? 2.0 * n / (g * g) : (i + j == g - 1 ? 1.0 * n / (g * g) : 0.0);
  Pcg32 rng(21);
  int bad = 0;
  for (int k = 0; k < n; ++k) {
    const Vec3f b = sample_uniform_triangle(next_2d(rng));
    if (b.x < 0 || b.y < 0 || b.z < 0 || std::fabs(b.x + b.y + b.z - 1) > 1e-6f) ++bad;
    const int i = std::min(int(b.x * g), g - 1), j = std::min(int(b.y * g), g - 1);
    observed[size_t(i * g + j)] += 1;
  }
  CHECK(bad == 0);
  const Chi2Result r = run_chi2(observed, expected);
  INFO(r.message);
  CHECK(r.passed);
}

namespace {
// Chi-square tests of Distribution1D::sample_discrete over weights `w`: the bins, the reported pmf (against the
// weights and against pmf()), and the remapped u.
void check_discrete_sampling(const std::vector<float>& w, uint64_t seed) {
  double sum = 0;
  for (float x : w) sum += x;
  const Distribution1D d(w);
  REQUIRE(d.size() == w.size());
  CHECK(d.integral() == Approx(sum / w.size()));
  double pmf_total = 0;
  for (size_t i = 0; i < w.size(); ++i) {
    CHECK(d.pmf(int(i)) == Approx(w[i] / sum));
    pmf_total += d.pmf(int(i));
  }
  CHECK(pmf_total == Approx(1));
  CHECK(d.pmf(-1) == 0);
  CHECK(d.pmf(int(w.size())) == 0);

  constexpr int n = 1000000, nu = 20;
  std::vector<double> observed(w.size(), 0.0), expected(w.size()), u_obs(nu, 0.0), u_exp(nu, double(n) / nu);
  for (size_t i = 0; i < w.size(); ++i) expected[i] = n * w[i] / sum;
  Pcg32 rng(seed);
  int bad_pmf = 0;
  for (int k = 0; k < n; ++k) {
    float pmf = -1, ur = -1;
    const int i = d.sample_discrete(rng.next_float(), &pmf, &ur);
    REQUIRE(i >= 0);
    REQUIRE(i < int(w.size()));
    REQUIRE(ur >= 0);
    REQUIRE(ur < 1);
    if (std::fabs(pmf - w[size_t(i)] / sum) > 1e-6 || pmf != d.pmf(i)) ++bad_pmf;
    observed[size_t(i)] += 1;
    u_obs[size_t(std::min(int(ur * nu), nu - 1))] += 1;
  }
  CHECK(bad_pmf == 0);
  const Chi2Result r = run_chi2(observed, expected);
  INFO(r.message);
  CHECK(r.passed);
  // The remapped u must be a fresh uniform variable (so it can be reused for the next decision).
  const Chi2Result ru = run_chi2(u_obs, u_exp);
  INFO(ru.message);
  CHECK(ru.passed);
}
}  // namespace

TEST_CASE("Distribution1D discrete sampling follows the weights", "[sampling][chi2][distribution]") {
  SECTION("unequal weights, empty bins") { check_discrete_sampling({0, 1, 3, 0.5f, 0, 2, 7, 0.25f, 0}, 31); }
  // Equal weights take the inline floor(u n) path instead of the search.
  SECTION("two equal weights (a quad light)") { check_discrete_sampling({2.5f, 2.5f}, 32); }
  SECTION("seven equal weights") { check_discrete_sampling(std::vector<float>(7, 0.3f), 33); }
}

TEST_CASE("Distribution1D continuous sampling has density func/integral", "[sampling][chi2][distribution]") {
  const std::vector<float> w = {0, 1, 3, 0.5f, 0, 2, 7, 0.25f, 0};
  const int nb = int(w.size());
  double sum = 0;
  for (float x : w) sum += x;
  const double avg = sum / nb;
  const Distribution1D d(w);
  // Four histogram bins per distribution bin: the density is constant inside each.
  constexpr int sub = 4, n = 1000000;
  std::vector<double> observed(size_t(nb * sub), 0.0), expected(size_t(nb * sub));
  for (int i = 0; i < nb * sub; ++i) expected[size_t(i)] = n * (w[size_t(i / sub)] / sum) / sub;
  Pcg32 rng(41);
  int bad = 0;
  for (int k = 0; k < n; ++k) {
    float pdf = -1;
    int bin = -1;
    const float x = d.sample_continuous(rng.next_float(), &pdf, &bin);
    REQUIRE(x >= 0);
    REQUIRE(x < 1);
    if (bin != int(x * nb) || std::fabs(pdf - w[size_t(bin)] / avg) > 1e-5) ++bad;
    observed[size_t(std::min(int(double(x) * nb * sub), nb * sub - 1))] += 1;
  }
  CHECK(bad == 0);
  const Chi2Result r = run_chi2(observed, expected);
  INFO(r.message);
  CHECK(r.passed);
}

TEST_CASE("Distribution1D edge cases", "[sampling][distribution]") {
  constexpr float kBelowOne = 0x1.fffffep-1f;
  SECTION("equal weights: u outside [0, 1) or NaN still gives a valid bin and a remapped u in [0, 1)") {
    for (size_t n : {size_t(2), size_t(3), size_t(1000)}) {
      const Distribution1D d(std::vector<float>(n, 1.0f));
      for (float u : {0.0f, kBelowOne, 1.0f, -0.5f, 2.0f, std::numeric_limits<float>::quiet_NaN()}) {
        INFO("n = " << n << ", u = " << u);
        float pmf = 0, ur = -1;
        const int i = d.sample_discrete(u, &pmf, &ur);
        CHECK(i >= 0);
        CHECK(i < int(n));
        CHECK(pmf == d.pmf(i));
        CHECK(ur >= 0);
        CHECK(ur < 1);
      }
      CHECK(d.sample_discrete(kBelowOne) == int(n) - 1);
      CHECK(d.sample_discrete(0.0f) == 0);
    }
  }
  SECTION("u at the ends of [0, 1) never selects an empty bin or returns 1") {
    const std::vector<float> w = {0, 0, 1, 0, 2, 0, 0};
    const Distribution1D d(w);
    for (float u : {0.0f, kBelowOne, 1.0f / 3, std::nextafter(1.0f / 3, 0.0f), 1.0f, -0.5f, 2.0f,
                    std::numeric_limits<float>::quiet_NaN()}) {
      INFO("u = " << u);
      float pmf = 0, ur = -1, pdf = 0;
      const int i = d.sample_discrete(u, &pmf, &ur);
      CHECK((i == 2 || i == 4));
      CHECK(pmf > 0);
      CHECK(ur >= 0);
      CHECK(ur < 1);
      int bin = -1;
      const float x = d.sample_continuous(u, &pdf, &bin);
      CHECK((bin == 2 || bin == 4));
      CHECK(x >= 0);
      CHECK(x < 1);
      CHECK(int(x * 7) == bin);
      CHECK(pdf > 0);
    }
    CHECK(d.sample_discrete(0) == 2);
    CHECK(d.sample_discrete(kBelowOne) == 4);
  }
  SECTION("random weights with many zeros, probed at and around every cdf step") {
    Pcg32 rng(55);
    for (int trial = 0; trial < 20; ++trial) {
      const int nb = 1 + int(rng.next_u32() % 1000);
      std::vector<float> w(size_t(nb), 0.0f);
      for (float& x : w)
        if (rng.next_float() < 0.3f) x = rng.next_float() * (rng.next_float() < 0.1f ? 1e-6f : 1.0f);
      w[rng.next_u32() % size_t(nb)] = 1;  // at least one non-zero weight
      const Distribution1D d(w);
      for (int k = 0; k <= nb; ++k) {
        const float edge = float(k) / float(nb);
        for (float u : {edge, std::nextafter(edge, 0.0f), std::nextafter(edge, 1.0f), rng.next_float()}) {
          if (!(u < 1)) u = kBelowOne;
          const int i = d.sample_discrete(u);
          REQUIRE(i >= 0);
          REQUIRE(i < nb);
          REQUIRE(w[size_t(i)] > 0);
          int bin = -1;
          const float x = d.sample_continuous(u, nullptr, &bin);
          REQUIRE(x < 1);
          REQUIRE(bin == i);
          REQUIRE(int(x * float(nb)) == bin);
        }
      }
    }
  }
  SECTION("all-zero weights fall back to uniform") {
    const std::vector<float> w(4, 0.0f);
    const Distribution1D d(w);
    CHECK(d.integral() == 0);
    float pmf = 0, pdf = 0;
    CHECK(d.sample_discrete(0.6f, &pmf) == 2);
    CHECK(pmf == Approx(0.25));
    CHECK(d.pmf(3) == Approx(0.25));
    CHECK(d.sample_continuous(0.6f, &pdf) == Approx(0.6));
    CHECK(pdf == Approx(1));
  }
  SECTION("a single bin is the identity") {
    const std::vector<float> w = {3};
    const Distribution1D d(w);
    float pdf = 0;
    CHECK(d.sample_continuous(0.37f, &pdf) == Approx(0.37));
    CHECK(pdf == Approx(1));
    CHECK(d.integral() == Approx(3));
  }
  SECTION("a default-constructed (empty) distribution returns -1 with probability 0") {
    const Distribution1D d;
    float pmf = 1, pdf = 1;
    int bin = 0;
    CHECK(d.size() == 0);
    CHECK(d.sample_discrete(0.5f, &pmf) == -1);
    CHECK(pmf == 0);
    CHECK(d.sample_continuous(0.5f, &pdf, &bin) == 0);
    CHECK(pdf == 0);
    CHECK(bin == -1);
    CHECK(d.pmf(0) == 0);
  }
  SECTION("invalid weights throw") {
    const std::vector<float> negative = {1, -1}, nan = {1, std::numeric_limits<float>::quiet_NaN()},
                             inf = {kInfinity, 1}, empty;
    CHECK_THROWS_AS(Distribution1D(negative), Error);
    CHECK_THROWS_AS(Distribution1D(nan), Error);
    CHECK_THROWS_AS(Distribution1D(inf), Error);
    CHECK_THROWS_AS(Distribution1D(empty), Error);
  }
}

TEST_CASE("power_heuristic", "[sampling]") {
  CHECK(power_heuristic(1, 2, 1, 2) == Approx(0.5));
  CHECK(power_heuristic(1, 3, 1, 1) == Approx(0.9));
  CHECK(power_heuristic(1, 3, 1, 1) + power_heuristic(1, 1, 1, 3) == Approx(1));
  CHECK(power_heuristic(1, kInfinity, 1, 5) == 1);
  CHECK(power_heuristic(1, 0, 1, 5) == 0);
}

// ---- Sobol sampler ----

namespace {

// True when every elementary interval of area 1/n (2^a x 2^(m-a) cells for all a) holds exactly one point.
bool is_02_net(const std::vector<Vec2f>& pts) {
  const int n = int(pts.size());
  int m = 0;
  while ((1 << m) < n) ++m;
  if ((1 << m) != n) return false;
  for (int a = 0; a <= m; ++a) {
    const int nx = 1 << a, ny = 1 << (m - a);
    std::vector<int> count(size_t(n), 0);
    for (const Vec2f& p : pts) {
      if (!(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1)) return false;
      ++count[size_t(int(p.x * nx) * ny + int(p.y * ny))];
    }
    for (int c : count)
      if (c != 1) return false;
  }
  return true;
}

Vec2f fixed_point(uint32_t x, uint32_t y) { return {float(x >> 8) * 0x1p-24f, float(y >> 8) * 0x1p-24f}; }

}  // namespace

TEST_CASE("Sobol building blocks", "[sampler]") {
  CHECK(sobol_dim0(0) == 0);
  CHECK(sobol_dim0(1) == 0x80000000u);
  CHECK(sobol_dim0(2) == 0x40000000u);
  CHECK(sobol_dim0(3) == 0xc0000000u);
  CHECK(sobol_dim0(0x80000000u) == 1);
  // Sobol's second dimension in natural (not Gray-code) order: 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8.
  const double dim1[8] = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
  for (uint32_t i = 0; i < 8; ++i) CHECK(sobol_dim1(i) * 0x1p-32 == dim1[i]);
  // The unscrambled pair is a (0,2)-sequence: the first 2^m points, and any aligned block of 2^m, form a net.
  for (int m = 0; m <= 10; ++m) {
    for (uint32_t start : {0u, 1u << m, 5u << m}) {
      std::vector<Vec2f> pts;
      for (uint32_t i = start; i < start + (1u << m); ++i) pts.push_back(fixed_point(sobol_dim0(i), sobol_dim1(i)));
      INFO("m = " << m << ", start = " << start);
      CHECK(is_02_net(pts));
    }
  }
}

TEST_CASE("owen_scramble is a nested uniform scramble", "[sampler]") {
  Pcg32 rng(8);
  for (int trial = 0; trial < 50; ++trial) {
    const uint32_t seed = rng.next_u32();
    // Nested: values sharing their top k bits map to values sharing their top k bits. (The scramble of a digit
    // depends only on the digits above it.)
    for (int k = 1; k < 32; ++k) {
      const uint32_t v = rng.next_u32();
      const uint32_t w = (v & ~(0xffffffffu >> k)) | (rng.next_u32() >> k);
      REQUIRE(owen_scramble(v, seed) >> (32 - k) == owen_scramble(w, seed) >> (32 - k));
    }
    // A permutation: distinct 12-bit prefixes map to distinct 12-bit prefixes.
    std::set<uint32_t> seen;
    for (uint32_t i = 0; i < 4096; ++i) seen.insert(owen_scramble(i << 20, seed) >> 20);
    CHECK(seen.size() == 4096);
  }
  // Different seeds give different scrambles.
  CHECK(owen_scramble(0x12345678u, 1) != owen_scramble(0x12345678u, 2));
  // Scrambling preserves the net property of the Sobol pair (each coordinate scrambled independently).
  for (uint32_t seed = 0; seed < 10; ++seed) {
    std::vector<Vec2f> pts;
    for (uint32_t i = 0; i < 256; ++i)
      pts.push_back(fixed_point(owen_scramble(sobol_dim0(i), seed * 2), owen_scramble(sobol_dim1(i), seed * 2 + 1)));
    CHECK(is_02_net(pts));
  }
}

TEST_CASE("Sampler: 2^m samples of a pixel and dimension are stratified", "[sampler]") {
  for (uint64_t seed : {0ull, 42ull}) {
    const Sampler s(seed);
    for (uint32_t pixel : {0u, 1u, 777u, 123456u}) {
      for (uint32_t dim : {0u, 1u, 2u, 17u}) {
        INFO("seed " << seed << ", pixel " << pixel << ", dimension " << dim);
        // 64 samples: each of the 8x8 strata gets exactly one (and every other 1/64 elementary interval).
        std::vector<Vec2f> pts;
        int strata[8][8] = {};
        for (uint32_t i = 0; i < 64; ++i) {
          pts.push_back(s.get_2d(pixel, i, dim));
          ++strata[int(pts.back().x * 8)][int(pts.back().y * 8)];
        }
        bool one_each = true;
        for (auto& row : strata)
          for (int c : row) one_each = one_each && c == 1;
        CHECK(one_each);
        CHECK(is_02_net(pts));
        // The next 64 (a renderer adding samples in a second pass) form a net as well, as do the first 256.
        std::vector<Vec2f> next;
        for (uint32_t i = 64; i < 128; ++i) next.push_back(s.get_2d(pixel, i, dim));
        CHECK(is_02_net(next));
        std::vector<Vec2f> many;
        for (uint32_t i = 0; i < 256; ++i) many.push_back(s.get_2d(pixel, i, dim));
        CHECK(is_02_net(many));
        // 1D: 64 samples, one in each interval of length 1/64.
        std::set<int> cells;
        for (uint32_t i = 0; i < 64; ++i) cells.insert(int(s.get_1d(pixel, i, dim) * 64));
        CHECK(cells.size() == 64);
      }
    }
  }
}

TEST_CASE("Sampler: uniform over sample indices, pixels and dimensions", "[sampler][chi2]") {
  const Sampler s(3);
  constexpr int g = 20;
  const auto grid_test = [&](int n, const std::function<Vec2f(int)>& point) {
    std::vector<double> observed(g * g, 0.0), expected(g * g, double(n) / (g * g));
    for (int k = 0; k < n; ++k) {
      const Vec2f p = point(k);
      REQUIRE(p.x >= 0);
      REQUIRE(p.x < 1);
      REQUIRE(p.y >= 0);
      REQUIRE(p.y < 1);
      observed[size_t(int(p.x * g) * g + int(p.y * g))] += 1;
    }
    return run_chi2(observed, expected);
  };
  // Along the sequence of one pixel and dimension (a non-power-of-two count, so the net property does not make
  // this trivially exact).
  const Chi2Result seq = grid_test(100000, [&](int k) { return s.get_2d(5, uint32_t(k), 4); });
  INFO("sequence: " << seq.message);
  CHECK(seq.passed);
  // Across pixels for a fixed sample index and dimension: the hash-derived scrambles must be random.
  const Chi2Result pix = grid_test(100000, [&](int k) { return s.get_2d(uint32_t(k), 3, 2); });
  INFO("pixels: " << pix.message);
  CHECK(pix.passed);
  // Across dimensions for a fixed pixel and sample index.
  const Chi2Result dims = grid_test(100000, [&](int k) { return s.get_2d(9, 0, uint32_t(k)); });
  INFO("dimensions: " << dims.message);
  CHECK(dims.passed);
  // Two different dimensions of the same samples are independent: their x coordinates, paired, fill the square
  // uniformly. Without padding (same index order in both) they would be strongly correlated.
  const Chi2Result pair = grid_test(100000, [&](int k) {
    return Vec2f(s.get_2d(5, uint32_t(k), 0).x, s.get_2d(5, uint32_t(k), 1).x);
  });
  INFO("dimension pairs: " << pair.message);
  CHECK(pair.passed);
}

TEST_CASE("Sampler: deterministic, and distinct per pixel, dimension and seed", "[sampler]") {
  const Sampler a(7), b(7), other_seed(8);
  CHECK(a.seed() == 7);
  // Stateless: the value depends only on the arguments, not on the call order or earlier calls.
  const Vec2f first = a.get_2d(10, 3, 4);
  for (uint32_t i = 0; i < 100; ++i) (void)a.get_2d(i, i, i);
  const Vec2f again = a.get_2d(10, 3, 4);
  CHECK(first.x == again.x);
  CHECK(first.y == again.y);
  int same_pixel = 0, same_dim = 0, same_seed = 0;
  for (uint32_t i = 0; i < 64; ++i) {
    const Vec2f p = a.get_2d(10, i, 4), q = b.get_2d(10, i, 4);
    REQUIRE(p.x == q.x);
    REQUIRE(p.y == q.y);
    REQUIRE(a.get_1d(10, i, 4) == b.get_1d(10, i, 4));
    const Vec2f px = a.get_2d(11, i, 4), dm = a.get_2d(10, i, 5), sd = other_seed.get_2d(10, i, 4);
    same_pixel += px.x == p.x || px.y == p.y;
    same_dim += dm.x == p.x || dm.y == p.y;
    same_seed += sd.x == p.x || sd.y == p.y;
  }
  CHECK(same_pixel == 0);
  CHECK(same_dim == 0);
  CHECK(same_seed == 0);
  // Values are in [0, 1) even when the 32-bit fixed-point value rounds up to 1 in float.
  for (uint32_t i = 0; i < 100000; ++i) {
    const float u = a.get_1d(i, i * 7, 3);
    REQUIRE(u >= 0);
    REQUIRE(u < 1);
  }
}
