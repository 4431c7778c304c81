// Microfacet distributions (material/microfacet.h): normalisation of D and of the visible normal density by
// numerical quadrature, the Smith masking function's defining identity, and chi-square tests of sample_wm
// against pdf (tests/chi2.h).
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "chi2.h"
#include "core/rng.h"
#include "material/microfacet.h"

using namespace torte;
using torte::test::chi2_test;
using torte::test::Chi2Result;

namespace {

constexpr double kPiD = 3.14159265358979323846;

struct Config {
  MicrofacetDistribution d;
  std::string name;
};

std::vector<Config> configs() {
  using K = MicrofacetDistribution::Kind;
  std::vector<Config> c;
  for (K k : {K::GGX, K::Beckmann}) {
    const std::string kn = k == K::GGX ? "GGX" : "Beckmann";
    for (auto [ax, ay] : {std::pair{0.05f, 0.05f}, {0.3f, 0.3f}, {1.0f, 1.0f}, {0.05f, 0.5f}, {0.8f, 0.2f}})
      c.push_back({MicrofacetDistribution(k, ax, ay), kn + " alpha " + std::to_string(ax) + "/" + std::to_string(ay)});
  }
  return c;
}

// Integral of f(w) over the upper hemisphere. theta = (pi/2) s^2 puts the nodes close to the pole, where narrow
// lobes live; midpoint rule in s and phi (periodic, so the midpoint rule converges fast in phi).
double integrate_hemisphere(const std::function<double(Vec3f)>& f, int ns = 300, int nphi = 256) {
  double sum = 0;
  for (int i = 0; i < ns; ++i) {
    const double s = (i + 0.5) / ns, theta = kPiD / 2 * s * s, jac = kPiD * s * std::sin(theta) / ns;
    for (int j = 0; j < nphi; ++j) {
      const double phi = 2 * kPiD * (j + 0.5) / nphi;
      const Vec3f w(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                    float(std::cos(theta)));
      sum += f(w) * jac * (2 * kPiD / nphi);
    }
  }
  return sum;
}

Vec3f direction(float cos_theta, float phi) {
  const float s = std::sqrt(std::max(0.0f, 1 - cos_theta * cos_theta));
  return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

}  // namespace

TEST_CASE("Microfacet D(wm) cos(wm) integrates to one", "[microfacet]") {
  for (const Config& c : configs()) {
    INFO(c.name);
    const double i = integrate_hemisphere([&](Vec3f wm) { return double(c.d.D(wm)) * wm.z; });
    CHECK(i == Approx(1).epsilon(2e-3));
    CHECK(c.d.D(Vec3f(0, 0, -1)) == 0);
  }
}

TEST_CASE("Visible normal density D(w, wm) integrates to one", "[microfacet]") {
  for (const Config& c : configs()) {
    for (float cos_theta : {1.0f, 0.7f, 0.2f, 0.05f, -0.5f}) {
      const Vec3f w = direction(cos_theta, 0.7f);
      INFO(c.name << ", w.z = " << cos_theta);
      const double i = integrate_hemisphere([&](Vec3f wm) { return double(c.d.D(w, wm)); });
      CHECK(i == Approx(1).epsilon(3e-3));
      // The projected area of the microsurface seen from w equals the macro surface's (Heitz 2014, eq. 2), the
      // identity that defines Smith's Lambda: integral max(0, w.wm) D(wm) dwm = cos(w) (1 + Lambda(w)).
      const Vec3f wu(w.x, w.y, std::fabs(w.z));
      const double proj = integrate_hemisphere([&](Vec3f wm) { return std::max(0.0, double(dot(wu, wm))) * c.d.D(wm); });
      CHECK(proj == Approx(double(wu.z) * (1 + c.d.Lambda(wu))).epsilon(3e-3));
    }
  }
}

TEST_CASE("Microfacet G and effectively_smooth", "[microfacet]") {
  const auto d = MicrofacetDistribution::ggx(0.5f);
  const Vec3f n(0, 0, 1);
  CHECK(d.Lambda(n) == 0);
  CHECK(d.G1(n) == 1);
  const Vec3f w = direction(0.3f, 1), v = direction(0.6f, 2);
  CHECK(d.G(w, v) <= std::min(d.G1(w), d.G1(v)));
  CHECK(d.G(w, v) >= d.G1(w) * d.G1(v));
  CHECK(d.G(w, v) == d.G(v, w));
  CHECK(d.Lambda(Vec3f(w.x, w.y, -w.z)) == d.Lambda(w));
  CHECK(MicrofacetDistribution::ggx(1e-4f).effectively_smooth());
  CHECK(MicrofacetDistribution::beckmann(1e-4f, 0.2f).effectively_smooth() == false);
  CHECK_FALSE(MicrofacetDistribution::ggx(0.01f).effectively_smooth());
}

TEST_CASE("sample_wm follows pdf(w, wm)", "[microfacet][chi2]") {
  // Histogram in (s, phi) with theta = (pi/2) s^2 over the upper hemisphere; expected counts by 3x3 Gauss-Legendre
  // on 4x4 sub-cells of each bin (the pdfs are smooth inside a bin at this resolution).
  const std::vector<Config> cs = configs();
  const std::vector<float> cosines = {0.9f, 0.3f, -0.6f};
  const int tests = int(cs.size() * cosines.size());
  constexpr int ns = 24, nphi = 48, n = 100000;
  static constexpr double gx[3] = {-0.7745966692414834, 0, 0.7745966692414834};
  static constexpr double gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  uint64_t seed = 1;
  for (const Config& c : cs) {
    for (float cos_theta : cosines) {
      const Vec3f w = direction(cos_theta, 2.1f);
      std::vector<double> observed(ns * nphi + 1, 0.0), expected(ns * nphi + 1, 0.0);
      Pcg32 rng(seed++);
      for (int k = 0; k < n; ++k) {
        const float u0 = rng.next_float(), u1 = rng.next_float();
        const Vec3f wm = c.d.sample_wm(w, {u0, u1});
        if (!(std::fabs(length(wm) - 1) < 1e-4f) || wm.z < 0) {
          observed.back() += 1;
          continue;
        }
        const double theta = std::acos(std::min(1.0, double(wm.z)));
        double phi = std::atan2(double(wm.y), double(wm.x));
        if (phi < 0) phi += 2 * kPiD;
        const int is = std::min(int(std::sqrt(theta / (kPiD / 2)) * ns), ns - 1);
        const int ip = std::min(int(phi / (2 * kPiD) * nphi), nphi - 1);
        observed[size_t(is * nphi + ip)] += 1;
      }
      double total = 0;
      for (int is = 0; is < ns; ++is)
        for (int ip = 0; ip < nphi; ++ip) {
          double sum = 0;
          constexpr int sub = 4;
          for (int a = 0; a < sub; ++a)
            for (int b = 0; b < sub; ++b)
              for (int qa = 0; qa < 3; ++qa)
                for (int qb = 0; qb < 3; ++qb) {
                  const double ds = 1.0 / (ns * sub), dp = 2 * kPiD / (nphi * sub);
                  const double s = (is * sub + a + 0.5 + gx[qa] / 2) * ds;
                  const double phi = (ip * sub + b + 0.5 + gx[qb] / 2) * dp;
                  const double theta = kPiD / 2 * s * s;
                  const Vec3f wm(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                                 float(std::cos(theta)));
                  sum += gw[qa] * gw[qb] / 4 * ds * dp * kPiD * s * std::sin(theta) * c.d.pdf(w, wm);
                }
          expected[size_t(is * nphi + ip)] = n * sum;
          total += sum;
        }
      INFO(c.name << ", w.z = " << cos_theta);
      CHECK(total == Approx(1).epsilon(3e-3));
      const Chi2Result r = chi2_test(observed, expected, 0.01, tests);
      INFO(r.message);
      CHECK(r.passed);
    }
  }
}
