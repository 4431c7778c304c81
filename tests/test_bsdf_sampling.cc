// Sampling of every BSDF in src/material/ against its own pdf():
//  - chi-square goodness of fit (tests/chi2.h) of the non-delta samples over the whole sphere of wi, with the
//    expected bin counts integrated exactly (subdivided Gauss-Legendre quadrature of pdf());
//  - the integral of pdf() over the sphere equals the fraction of samples that were non-delta and succeeded;
//  - every sample's f and pdf equal eval() and pdf() for its direction;
//  - delta lobes: the sampled direction and the Fresnel selection probabilities.
// Deterministic seeds; the significance level is Sidak-corrected for the number of chi-square tests.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "chi2.h"
#include "core/rng.h"
#include "material/coated_diffuse.h"
#include "material/conductor.h"
#include "material/dielectric.h"
#include "material/fresnel.h"
#include "material/lambert.h"
#include "material/mirror.h"
#include "material/oren_nayar.h"

using namespace torte;
using torte::test::chi2_test;
using torte::test::Chi2Result;

namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr int kChi2Tests = 120;  // upper bound on the chi-square tests below (for the Sidak correction)
constexpr int kSamples = 100000;

using D = MicrofacetDistribution;

Vec3f direction(float cos_theta, float phi) {
  const float s = std::sqrt(std::max(0.0f, 1 - cos_theta * cos_theta));
  return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

// Histogram of directions over the whole sphere in a frame around `axis` (where the lobe under test peaks):
// polar bins uniform in t with theta' = pi t^2, so they are fine near the axis (narrow lobes) and still cover the
// sphere; azimuthal bins uniform. Solid angle: dw = 2 pi t sin(pi t^2) dt dphi.
struct SphereHistogram {
  Frame frame;
  int nt, np;
  std::vector<double> observed;

  SphereHistogram(Vec3f axis, int nt_, int np_)
      : frame(Frame::from_z(normalize(axis))), nt(nt_), np(np_), observed(size_t(nt_ * np_ + 1), 0.0) {}

  Vec3f dir(double t, double phi) const {
    const double th = kPiD * t * t;
    return frame.to_world(Vec3f(float(std::sin(th) * std::cos(phi)), float(std::sin(th) * std::sin(phi)),
                                float(std::cos(th))));
  }
  void add(Vec3f w) {
    if (!(std::fabs(length(w) - 1) < 1e-4f)) {
      observed.back() += 1;  // not a unit vector: lands in a bin with zero expected count
      return;
    }
    const Vec3f l = frame.to_local(w);
    const double th = std::acos(std::clamp(double(l.z), -1.0, 1.0));
    double phi = std::atan2(double(l.y), double(l.x));
    if (phi < 0) phi += 2 * kPiD;
    const int it = std::min(int(std::sqrt(th / kPiD) * nt), nt - 1), ip = std::min(int(phi / (2 * kPiD) * np), np - 1);
    observed[size_t(it * np + ip)] += 1;
  }
  // n times the integral of pdf over every bin; *total receives the integral over the sphere. Adaptive: a cell
  // is split in four until 3x3 Gauss-Legendre on the cell and on its four children agree to a small fraction of
  // the count's standard deviation, so narrow lobes far from the axis (where bins are coarse) and jumps of the pdf
  // across the horizon z = 0 are resolved where they matter, and smooth bins cost 45 evaluations.
  std::vector<double> expected(const std::function<double(Vec3f)>& pdf, double n, double* total) const {
    std::vector<double> e(observed.size(), 0.0);
    *total = 0;
    const double dt = 1.0 / nt, dp = 2 * kPiD / np;
    for (int it = 0; it < nt; ++it)
      for (int ip = 0; ip < np; ++ip) {
        const Cell cell{it * dt, (it + 1) * dt, ip * dp, (ip + 1) * dp};
        double sum = integrate(pdf, cell, gauss(pdf, cell), n, 0, 0);
        // Adaptive quadrature can miss a sliver of support at the edge of a bin entirely (coarse and fine
        // estimates both zero). If samples landed there, integrate the bin again on a fine uniform grid before
        // deciding that the sampler produced an impossible direction.
        if (sum == 0 && observed[size_t(it * np + ip)] > 0) sum = integrate(pdf, cell, 0, n, 0, 5);
        e[size_t(it * np + ip)] = n * sum;
        *total += sum;
      }
    return e;
  }

 private:
  struct Cell {
    double t0, t1, p0, p1;
  };
  double gauss(const std::function<double(Vec3f)>& pdf, const Cell& c) const {
    static constexpr double gx[3] = {-0.7745966692414834, 0, 0.7745966692414834};
    static constexpr double gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
    double sum = 0;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const double t = (c.t0 + c.t1) / 2 + gx[a] * (c.t1 - c.t0) / 2;
        const double phi = (c.p0 + c.p1) / 2 + gx[b] * (c.p1 - c.p0) / 2;
        sum += gw[a] * gw[b] * 2 * kPiD * t * std::sin(kPiD * t * t) * pdf(dir(t, phi));
      }
    return sum * (c.t1 - c.t0) * (c.p1 - c.p0) / 4;
  }
  double integrate(const std::function<double(Vec3f)>& pdf, const Cell& c, double coarse, double n, int depth,
                   int min_depth) const {
    const double tm = (c.t0 + c.t1) / 2, pm = (c.p0 + c.p1) / 2;
    const Cell child[4] = {{c.t0, tm, c.p0, pm}, {tm, c.t1, c.p0, pm}, {c.t0, tm, pm, c.p1}, {tm, c.t1, pm, c.p1}};
    double v[4], fine = 0;
    for (int i = 0; i < 4; ++i) fine += v[i] = gauss(pdf, child[i]);
    constexpr int kMaxDepth = 5;
    const double tolerance = (0.01 * std::sqrt(n * std::fabs(fine)) + 0.01) / n;  // in probability
    if (depth >= kMaxDepth || (depth >= min_depth && std::fabs(fine - coarse) <= tolerance)) return fine;
    double sum = 0;
    for (int i = 0; i < 4; ++i) sum += integrate(pdf, child[i], v[i], 2 * n, depth + 1, min_depth);  // children share the error budget
    return sum;
  }
};

bool close(double a, double b, double rel) { return std::fabs(a - b) <= rel * std::max(std::fabs(a), std::fabs(b)) + 1e-6; }
bool close(Rgb a, Rgb b, double rel) { return close(a.r, b.r, rel) && close(a.g, b.g, rel) && close(a.b, b.b, rel); }

// Samples `bsdf` from wo and runs every check above for its non-delta part; `axis` is where to centre the bins.
template <class Bsdf>
void check_sampling(const Bsdf& bsdf, Vec3f wo, Vec3f axis, const std::string& name, uint64_t seed) {
  INFO(name << ", wo = (" << wo.x << ", " << wo.y << ", " << wo.z << ")");
  SphereHistogram h(axis, 24, 36);
  Pcg32 rng(seed);
  int non_delta = 0, bad_eval = 0, bad_pdf = 0, bad_value = 0;
  for (int k = 0; k < kSamples; ++k) {
    BsdfSample s;
    const float uc = rng.next_float();
    const float u0 = rng.next_float(), u1 = rng.next_float();
    if (!bsdf.sample(wo, uc, {u0, u1}, &s)) continue;
    if (s.is_specular()) continue;
    ++non_delta;
    h.add(s.wi);
    if (!(s.pdf > 0) || !s.f.is_finite() || !std::isfinite(s.pdf)) ++bad_value;
    if (!close(bsdf.eval(wo, s.wi), s.f, 2e-3)) ++bad_eval;
    if (!close(bsdf.pdf(wo, s.wi), s.pdf, 2e-3)) ++bad_pdf;
  }
  CHECK(bad_value == 0);
  CHECK(bad_eval == 0);
  CHECK(bad_pdf == 0);
  double total = 0;
  const std::vector<double> expected =
      h.expected([&](Vec3f wi) { return double(bsdf.pdf(wo, wi)); }, kSamples, &total);
  // Fraction of non-delta successes: binomial standard deviation plus the quadrature's error.
  const double frac = double(non_delta) / kSamples;
  const double sigma = std::sqrt(std::max(frac * (1 - frac), 1e-4) / kSamples);
  // The slack covers the quadrature: some pdfs have integrable singularities, e.g. at the rim of the cone of
  // directions refracted into the denser medium, where dwm/dwi diverges.
  CHECK(std::fabs(total - frac) <= 5 * sigma + 6e-3);
  INFO("pdf integral " << total << ", non-delta fraction " << frac);
  if (non_delta == 0) return;
  const Chi2Result r = chi2_test(h.observed, expected, 0.01, kChi2Tests);
  INFO(r.message);
  CHECK(r.passed);
}

Vec3f mirror_dir(Vec3f wo) { return {-wo.x, -wo.y, wo.z}; }

const std::vector<Vec3f>& opaque_wos() {
  static const std::vector<Vec3f> w = {direction(0.95f, 0.3f), direction(0.5f, 2.0f), direction(0.08f, 4.0f),
                                       direction(-0.7f, 1.0f)};
  return w;
}

}  // namespace

TEST_CASE("The BSDF chi-square harness rejects a wrong pdf", "[bsdf][chi2]") {
  // A Lambertian sampler checked against a uniform-hemisphere pdf must fail; otherwise the tests are vacuous.
  struct WrongLambert {
    LambertBsdf l{Rgb(0.5f)};
    Rgb eval(Vec3f wo, Vec3f wi) const { return l.eval(wo, wi); }
    float pdf(Vec3f wo, Vec3f wi) const { return same_hemisphere(wo, wi) ? float(1 / (2 * kPiD)) : 0; }
    bool sample(Vec3f wo, float uc, Vec2f u, BsdfSample* s) const {
      const bool ok = l.sample(wo, uc, u, s);
      s->pdf = pdf(wo, s->wi);
      return ok;
    }
  };
  const WrongLambert w;
  const Vec3f wo = direction(0.6f, 1);
  SphereHistogram h(Vec3f(0, 0, 1), 32, 48);
  Pcg32 rng(3);
  for (int k = 0; k < kSamples; ++k) {
    BsdfSample s;
    if (w.sample(wo, 0, {rng.next_float(), rng.next_float()}, &s)) h.add(s.wi);
  }
  double total = 0;
  const auto e = h.expected([&](Vec3f wi) { return double(w.pdf(wo, wi)); }, kSamples, &total);
  CHECK(total == Approx(1).epsilon(1e-3));
  CHECK_FALSE(chi2_test(h.observed, e, 0.01, kChi2Tests).passed);
}

TEST_CASE("Lambert and Oren-Nayar sampling", "[bsdf][chi2]") {
  uint64_t seed = 100;
  for (Vec3f wo : opaque_wos()) {
    const Vec3f axis(0, 0, wo.z > 0 ? 1.0f : -1.0f);
    check_sampling(LambertBsdf{Rgb(0.5f)}, wo, axis, "lambert", seed++);
    check_sampling(OrenNayarBsdf{Rgb(0.5f), 0.35f}, wo, axis, "oren-nayar sigma 0.35", seed++);
    check_sampling(OrenNayarBsdf{Rgb(0.5f), 1.2f}, wo, axis, "oren-nayar sigma 1.2", seed++);
  }
}

TEST_CASE("Rough conductor sampling", "[bsdf][chi2]") {
  Rgb eta, k;
  eta = Rgb(0.2f, 0.92f, 1.1f);
  k = Rgb(3.9f, 2.45f, 2.14f);
  const std::vector<std::pair<D, std::string>> ds = {
      {D::ggx(0.05f), "GGX 0.05"},          {D::ggx(0.3f), "GGX 0.3"},
      {D::ggx(1.0f), "GGX 1"},              {D::ggx(0.05f, 0.4f), "GGX 0.05/0.4"},
      {D::beckmann(0.05f), "Beckmann 0.05"}, {D::beckmann(0.4f), "Beckmann 0.4"},
      {D::beckmann(0.9f, 0.3f), "Beckmann 0.9/0.3"}};
  uint64_t seed = 200;
  for (const auto& [d, dn] : ds)
    for (Vec3f wo : opaque_wos()) check_sampling(ConductorBsdf(eta, k, d), wo, mirror_dir(wo), "conductor " + dn, seed++);
}

TEST_CASE("Rough dielectric sampling", "[bsdf][chi2]") {
  const std::vector<std::pair<D, std::string>> ds = {
      {D::ggx(0.05f), "GGX 0.05"}, {D::ggx(0.3f), "GGX 0.3"}, {D::ggx(1.0f), "GGX 1"},
      {D::ggx(0.1f, 0.4f), "GGX 0.1/0.4"}, {D::beckmann(0.3f), "Beckmann 0.3"}};
  // Outside near normal, outside grazing, inside below the critical angle, inside beyond it (mostly TIR).
  const std::vector<Vec3f> wos = {direction(0.9f, 0.4f), direction(0.1f, 2.5f), direction(-0.85f, 1.3f),
                                  direction(-0.4f, 5.0f)};
  uint64_t seed = 300;
  for (float eta : {1.5f, 1 / 1.33f}) {
    for (const auto& [d, dn] : ds) {
      // eta < 1 (the outside is the denser medium) at a near-specular and a very rough setting only.
      if (eta < 1 && d.alpha_x != 0.05f && d.alpha_x != 1.0f) continue;
      for (Vec3f wo : wos) {
        const DielectricBsdf bsdf(eta, d, TransportMode::Radiance);
        const std::string name = "dielectric eta " + std::to_string(eta) + " " + dn;
        // Bins centred on the refracted direction when there is one (that lobe carries most samples), else on
        // the mirror direction.
        float etap;
        Vec3f wt;
        const bool refracts = refract(wo, Vec3f(0, 0, 1), eta, &etap, &wt);
        check_sampling(bsdf, wo, refracts ? wt : mirror_dir(wo), name, seed++);
        if (refracts && d.alpha_x < 0.2f) check_sampling(bsdf, wo, mirror_dir(wo), name + " (reflection bins)", seed++);
      }
    }
  }
}

TEST_CASE("Coated diffuse sampling", "[bsdf][chi2]") {
  const std::vector<std::pair<D, std::string>> ds = {{D::ggx(0), "smooth"},
                                                     {D::ggx(0.05f), "GGX 0.05"},
                                                     {D::ggx(0.3f), "GGX 0.3"},
                                                     {D::ggx(1.0f), "GGX 1"},
                                                     {D::ggx(0.05f, 0.5f), "GGX 0.05/0.5"},
                                                     {D::beckmann(0.3f), "Beckmann 0.3"}};
  uint64_t seed = 400;
  for (const auto& [d, dn] : ds)
    for (Vec3f wo : opaque_wos()) {
      check_sampling(CoatedDiffuseBsdf(Rgb(0.8f, 0.5f, 0.2f), 1.5f, d), wo, mirror_dir(wo), "coated " + dn, seed++);
    }
  // A dark base puts most samples on the coating.
  check_sampling(CoatedDiffuseBsdf(Rgb(0.02f), 1.5f, D::ggx(0.2f)), direction(0.7f, 1), mirror_dir(direction(0.7f, 1)),
                 "coated dark", seed++);
}

TEST_CASE("Delta lobes: directions and Fresnel selection probabilities", "[bsdf]") {
  Pcg32 rng(500);
  const auto u2 = [&] { return Vec2f(rng.next_float(), rng.next_float()); };
  for (Vec3f wo : {direction(0.9f, 0.4f), direction(0.2f, 2.0f), direction(-0.6f, 4.0f), direction(-0.3f, 1.0f)}) {
    INFO("wo.z = " << wo.z);
    BsdfSample s;
    // Mirror: wi is the mirror direction, weight = tint.
    REQUIRE(MirrorBsdf{Rgb(0.9f)}.sample(wo, 0.5f, u2(), &s));
    CHECK(s.is_specular());
    CHECK(s.wi.x == -wo.x);
    CHECK(s.wi.z == wo.z);
    CHECK(s.weight().r == Approx(0.9f));
    CHECK_FALSE(MirrorBsdf{}.has_non_specular());
    // Smooth conductor: weight = conductor Fresnel.
    const ConductorBsdf metal(Rgb(0.2f), Rgb(3.9f), D::ggx(0));
    REQUIRE(metal.sample(wo, 0.5f, u2(), &s));
    CHECK(s.is_specular());
    CHECK(s.wi.y == -wo.y);
    CHECK(s.weight().r == Approx(fresnel_conductor(wo.z, Rgb(0.2f), Rgb(3.9f)).r));
    CHECK(metal.eval(wo, s.wi).is_black());
    CHECK(metal.pdf(wo, s.wi) == 0);
    // Smooth dielectric: the fraction of reflections is R; directions obey the law of reflection and Snell.
    for (float eta : {1.5f, 1.0f}) {
      const DielectricBsdf glass(eta, D::ggx(0), TransportMode::Importance);
      CHECK_FALSE(glass.has_non_specular());
      const float r = fresnel_dielectric(wo.z, eta);
      constexpr int n = 20000;
      int reflected = 0;
      for (int k = 0; k < n; ++k) {
        REQUIRE(glass.sample(wo, rng.next_float(), u2(), &s));
        REQUIRE(s.is_specular());
        if (s.is_transmission()) {
          REQUIRE(s.wi.z * wo.z < 0);
          const float sin_o = std::sqrt(1 - wo.z * wo.z), sin_i = std::sqrt(1 - s.wi.z * s.wi.z);
          REQUIRE(sin_o == Approx(s.eta * sin_i).margin(1e-5));
          REQUIRE(s.eta == Approx(wo.z > 0 ? eta : 1 / eta));
          REQUIRE(s.pdf == Approx(1 - r));
          REQUIRE(s.weight().r == Approx(1));  // importance mode: T / (1 - R)
        } else {
          ++reflected;
          REQUIRE(s.wi.x == -wo.x);
          REQUIRE(s.wi.z == wo.z);
          REQUIRE(s.pdf == Approx(r));
          REQUIRE(s.weight().r == Approx(1));
        }
      }
      const double sigma = std::sqrt(r * (1 - r) / n) + 1e-9;
      CHECK(std::fabs(double(reflected) / n - r) <= 5 * sigma);
      if (eta == 1) {
        CHECK(reflected == 0);
        REQUIRE(glass.sample(wo, 0.5f, u2(), &s));
        CHECK(s.wi == -wo);
      }
    }
    // Thin dielectric: straight through or mirrored, reflection with probability R'.
    const ThinDielectricBsdf pane(1.5f);
    const float r = pane.reflectance(wo.z);
    const float r1 = fresnel_dielectric(std::fabs(wo.z), 1.5f);
    CHECK(r == Approx(r1 + (1 - r1) * (1 - r1) * r1 / (1 - r1 * r1)));
    constexpr int n = 20000;
    int reflected = 0;
    for (int k = 0; k < n; ++k) {
      REQUIRE(pane.sample(wo, rng.next_float(), u2(), &s));
      if (s.is_transmission()) {
        REQUIRE(s.wi == -wo);
        REQUIRE(s.eta == 1);
      } else {
        ++reflected;
        REQUIRE(s.wi.z == wo.z);
      }
      REQUIRE(s.weight().r == Approx(1));
    }
    CHECK(std::fabs(double(reflected) / n - r) <= 5 * std::sqrt(r * (1 - r) / n));
    // Smooth coating: the delta lobe is chosen with specular_probability and weighs F / p.
    const CoatedDiffuseBsdf plastic(Rgb(0.5f), 1.5f, D::ggx(0));
    const float ps = plastic.specular_probability(std::fabs(wo.z));
    int spec = 0;
    for (int k = 0; k < n; ++k) {
      REQUIRE(plastic.sample(wo, rng.next_float(), u2(), &s));
      if (s.is_specular()) {
        ++spec;
        REQUIRE(s.wi == mirror_dir(wo));
        REQUIRE(s.pdf == Approx(ps));
        REQUIRE(s.weight().r == Approx(fresnel_dielectric(std::fabs(wo.z), 1.5f) / ps));
      }
    }
    CHECK(std::fabs(double(spec) / n - ps) <= 5 * std::sqrt(ps * (1 - ps) / n));
  }
}
