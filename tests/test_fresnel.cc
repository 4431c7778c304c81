// Fresnel equations and refraction (material/fresnel.h) and the metal presets (material/metals.h).
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>

#include "core/rng.h"
#include "core/sampling.h"
#include "material/fresnel.h"
#include "material/metals.h"

using namespace torte;

namespace {

// Reference: straightforward double-precision Fresnel from Snell's law via angles, light from the outside.
double reference_fresnel(double cos_i, double n) {
  const double ti = std::acos(cos_i), st = std::sin(ti) / n;
  if (st >= 1) return 1;
  const double tt = std::asin(st);
  const double rs = (std::cos(ti) - n * std::cos(tt)) / (std::cos(ti) + n * std::cos(tt));
  const double rp = (n * std::cos(ti) - std::cos(tt)) / (n * std::cos(ti) + std::cos(tt));
  return (rs * rs + rp * rp) / 2;
}

float min_channel(Rgb c) { return std::min(c.r, std::min(c.g, c.b)); }

// Reference: the dielectric formula in complex double arithmetic (pbrt-v4 section 9.3.6).
double reference_conductor(double cos_i, double eta, double k) {
  using C = std::complex<double>;
  const C n(eta, k);
  const double sin2 = 1 - cos_i * cos_i;
  const C cos_t = std::sqrt(C(1) - sin2 / (n * n));
  const C rpar = (n * cos_i - cos_t) / (n * cos_i + cos_t), rperp = (cos_i - n * cos_t) / (cos_i + n * cos_t);
  return (std::norm(rpar) + std::norm(rperp)) / 2;
}

}  // namespace

TEST_CASE("Dielectric Fresnel at normal incidence and grazing", "[fresnel]") {
  for (float eta : {1.0f, 1.33f, 1.5f, 2.4f, 0.75f}) {
    const float r0 = (eta - 1) / (eta + 1);
    INFO("eta " << eta);
    CHECK(fresnel_dielectric(1, eta) == Approx(r0 * r0).margin(1e-7));
    CHECK(fresnel_dielectric(-1, eta) == Approx(r0 * r0).margin(1e-7));  // same from the inside at normal
    CHECK(fresnel_dielectric(1e-6f, eta) == Approx(1).margin(1e-3));
    CHECK(fresnel_dielectric(0, eta) == Approx(1));
  }
  for (float c = 0.02f; c <= 1; c += 0.07f) CHECK(fresnel_dielectric(c, 1.5f) == Approx(reference_fresnel(c, 1.5)).epsilon(1e-4));
  // Brewster's angle: the parallel polarisation vanishes, so R = r_perp^2 / 2.
  const double tb = std::atan(1.5), tt = std::asin(std::sin(tb) / 1.5);
  const double rs = (std::cos(tb) - 1.5 * std::cos(tt)) / (std::cos(tb) + 1.5 * std::cos(tt));
  CHECK(fresnel_dielectric(float(std::cos(tb)), 1.5f) == Approx(rs * rs / 2).epsilon(1e-4));
}

TEST_CASE("Dielectric Fresnel from the inside: symmetry and total internal reflection", "[fresnel]") {
  const float eta = 1.5f;
  const float cos_critical = std::sqrt(1 - 1 / (eta * eta));
  // Beyond the critical angle (cos below cos_critical) everything reflects.
  for (float c : {0.01f, 0.3f, 0.5f, cos_critical * 0.999f}) CHECK(fresnel_dielectric(-c, eta) == 1);
  CHECK(fresnel_dielectric(-cos_critical * 1.01f, eta) < 1);
  // Inside at cos -c equals outside with 1/eta, and reciprocity: R is the same for the refracted pair.
  for (float c = 0.05f; c <= 1; c += 0.05f) {
    CHECK(fresnel_dielectric(-c, eta) == Approx(fresnel_dielectric(c, 1 / eta)));
    const float sin_t = std::sqrt(1 - c * c) / eta, cos_t = std::sqrt(1 - sin_t * sin_t);
    CHECK(fresnel_dielectric(c, eta) == Approx(fresnel_dielectric(-cos_t, eta)).epsilon(1e-4));
  }
}

TEST_CASE("Conductor Fresnel", "[fresnel]") {
  // With k = 0 the complex formula reduces to the dielectric one.
  for (float eta : {1.2f, 1.5f, 2.0f})
    for (float c = 0.01f; c <= 1; c += 0.03f) {
      const Rgb f = fresnel_conductor(c, Rgb(eta), Rgb(0));
      CHECK(f.r == Approx(fresnel_dielectric(c, eta)).epsilon(1e-5));
    }
  // The real-arithmetic form equals the complex formula.
  for (auto [n, k] : {std::pair{0.2f, 3.9f}, {1.66f, 9.2f}, {4.37f, 5.2f}, {0.5f, 0.1f}, {2.0f, 0.0f}})
    for (float c = 0.0f; c <= 1; c += 0.05f) CHECK(fresnel_conductor(c, Rgb(n), Rgb(k)).r == Approx(reference_conductor(c, n, k)).epsilon(1e-4));
  // Normal incidence: ((n-1)^2 + k^2) / ((n+1)^2 + k^2).
  const float n = 0.2f, k = 3.9f;
  CHECK(fresnel_conductor(1, Rgb(n), Rgb(k)).r == Approx(((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k)));
  CHECK(fresnel_conductor(0, Rgb(n), Rgb(k)).g == Approx(1));
  CHECK(fresnel_conductor(-0.5f, Rgb(n), Rgb(k)).b == fresnel_conductor(0.5f, Rgb(n), Rgb(k)).b);
  // Gold at normal incidence against the published linear-sRGB F0 (1.00, 0.77, 0.34) of Hoffman 2013, "Physics
  // and Math of Shading" (SIGGRAPH course): a sanity check of the preset and the complex formula together.
  Rgb eta, kk;
  REQUIRE(metal_preset("gold", &eta, &kk));
  const Rgb gold = fresnel_conductor(1, eta, kk);
  CHECK(gold.r == Approx(1.0).margin(0.04));
  CHECK(gold.g == Approx(0.77).margin(0.04));
  CHECK(gold.b == Approx(0.34).margin(0.03));
  CHECK(gold.r > gold.g);
  CHECK(gold.g > gold.b);
  // Every metal reflects strongly and goes to 1 at grazing.
  for (std::string_view name : metal_preset_names()) {
    INFO(name);
    REQUIRE(metal_preset(name, &eta, &kk));
    const Rgb r = fresnel_conductor(1, eta, kk);
    CHECK(min_channel(r) > 0.3f);
    CHECK(r.max_component() < 1);
    CHECK(min_channel(fresnel_conductor(1e-4f, eta, kk)) > 0.99f);
  }
  CHECK_FALSE(metal_preset("unobtainium", &eta, &kk));
  Rgb e2, k2;
  REQUIRE(metal_preset("Au", &e2, &k2));
  CHECK(e2.r == Approx(0.1431189557f));
  REQUIRE(metal_preset("aluminum", &eta, &kk));
  REQUIRE(metal_preset("Al", &e2, &k2));
  CHECK(eta == e2);
  CHECK(kk == k2);
}

TEST_CASE("refract obeys Snell's law and round-trips", "[fresnel]") {
  Pcg32 rng(17);
  const Vec3f n(0, 0, 1);
  for (int i = 0; i < 1000; ++i) {
    const Vec3f wi = sample_uniform_sphere({rng.next_float(), rng.next_float()});
    if (std::fabs(wi.z) < 1e-3f) continue;
    const float eta = 1.1f + rng.next_float();
    float etap = 0;
    Vec3f wt;
    const bool ok = refract(wi, n, eta, &etap, &wt);
    const float sin_i = std::sqrt(std::max(0.0f, 1 - wi.z * wi.z));
    if (!ok) {
      // Only from inside, beyond the critical angle.
      REQUIRE(wi.z < 0);
      REQUIRE(sin_i * eta >= 0.999f);
      REQUIRE(fresnel_dielectric(wi.z, eta) == 1);
      continue;
    }
    REQUIRE(etap == Approx(wi.z > 0 ? eta : 1 / eta));
    REQUIRE(length(wt) == Approx(1).epsilon(1e-5));
    REQUIRE(wt.z * wi.z < 0);  // other side
    const float sin_t = std::sqrt(std::max(0.0f, 1 - wt.z * wt.z));
    REQUIRE(sin_i == Approx(etap * sin_t).margin(1e-4));
    // Coplanar with the normal and wi, on the opposite azimuth.
    REQUIRE(wi.x * wt.y - wi.y * wt.x == Approx(0).margin(1e-5));
    REQUIRE(wi.x * wt.x + wi.y * wt.y <= 1e-6f);
    // Back through the interface gives wi again.
    float etap2 = 0;
    Vec3f back;
    REQUIRE(refract(wt, n, eta, &etap2, &back));
    REQUIRE(etap2 * etap == Approx(1));
    REQUIRE(back.x == Approx(wi.x).margin(1e-4));
    REQUIRE(back.y == Approx(wi.y).margin(1e-4));
    REQUIRE(back.z == Approx(wi.z).margin(1e-4));
  }
  // reflect mirrors about the normal.
  const Vec3f r = reflect(Vec3f(0.6f, 0, 0.8f), n);
  CHECK(r.x == Approx(-0.6f));
  CHECK(r.z == Approx(0.8f));
}

TEST_CASE("Hemispherical Fresnel reflectance matches quadrature", "[fresnel]") {
  for (float eta : {1.00005f, 1.0005f, 1.01f, 1.33f, 1.5f, 2.0f, 3.0f, 0.9f, 1 / 1.5f}) {
    // Midpoint rule in mu^2 (removes the sqrt behaviour at grazing): Fdr = integral F(mu) d(mu^2).
    double sum = 0;
    constexpr int n = 200000;
    for (int i = 0; i < n; ++i) {
      const double mu = std::sqrt((i + 0.5) / n);
      sum += fresnel_dielectric(float(mu), eta);
    }
    INFO("eta " << eta);
    CHECK(fresnel_diffuse_reflectance(eta) == Approx(sum / n).margin(2e-5));
  }
}
