// Vectorised BSDF evaluation (simd/shade_eval.h) on every Highway target compiled in and supported by this CPU,
// against the scalar BSDFs (material/lambert.h, oren_nayar.h, conductor.h): random directions on both sides,
// grazing angles, exactly opposite and equal directions, invalid combinations (opposite hemispheres, smooth
// conductors), every tail length; and shade_queue's phase 2 (gather, kernel, scatter) against the scalar
// loop of shade_queue's phase 2, including conductor queues that mix GGX and Beckmann.
#include <catch2/catch.hpp>
#include <hwy/highway.h>  // HWY_TARGETS
#include <hwy/targets.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "core/rng.h"
#include "render/shade.h"
#include "shade_eval.h"
#include "hwy_targets.h"
#include "test_random.h"

using namespace torte;
using torte::test::for_each_hwy_target;
using torte::test::random_direction;

namespace {


// A direction with the given z (unit length, random azimuth).
Vec3f direction_with_z(Pcg32& rng, float z) {
  const float phi = 2 * kPi * rng.next_float(), r = std::sqrt(std::max(0.0f, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Random pairs: mostly uniform on the sphere (half the pairs in opposite hemispheres), plus grazing angles,
// normal incidence, wi = wo, wi = -wo, mirror directions and the back side.
void random_pair(Pcg32& rng, Vec3f* wo, Vec3f* wi) {
  static const float kGrazing[] = {0.0f, 1e-7f, 1e-5f, 1e-3f, 0.02f, 0.9999f, 1.0f};
  const uint32_t kind = rng.next_u32() % 10;
  *wo = random_direction(rng);
  *wi = random_direction(rng);
  const float sign = rng.next_float() < 0.5f ? -1.0f : 1.0f;
  switch (kind) {
    case 0: *wo = direction_with_z(rng, sign * kGrazing[rng.next_u32() % 7]); break;
    case 1: *wi = direction_with_z(rng, sign * kGrazing[rng.next_u32() % 7]); break;
    case 2: *wi = *wo; break;
    case 3: *wi = -*wo; break;
    case 4: *wi = Vec3f(-wo->x, -wo->y, wo->z); break;  // mirror direction: wm = normal
    case 5:
      *wo = direction_with_z(rng, sign * kGrazing[rng.next_u32() % 7]);
      *wi = direction_with_z(rng, sign * kGrazing[rng.next_u32() % 7]);
      break;
    default: break;
  }
}

bool close(float vec, float ref) {
  if (vec == ref) return true;
  if (!std::isfinite(vec) || !std::isfinite(ref)) return false;
  return std::fabs(vec - ref) <= 1e-5f * std::max(std::fabs(vec), std::fabs(ref)) + 1e-30f;
}

struct Mismatch {
  int count = 0;
  std::string first;
};

template <class Bsdf>
void compare(const Bsdf& b, Vec3f wo, Vec3f wi, const float* f, float pdf, Mismatch& m) {
  const Rgb rf = b.eval(wo, wi);
  const float rp = b.pdf(wo, wi);
  if (close(f[0], rf.r) && close(f[1], rf.g) && close(f[2], rf.b) && close(pdf, rp)) return;
  if (m.count++ == 0) {
    std::ostringstream s;
    s.precision(9);
    s << "wo (" << wo.x << ", " << wo.y << ", " << wo.z << ") wi (" << wi.x << ", " << wi.y << ", " << wi.z
      << "): vector f (" << f[0] << ", " << f[1] << ", " << f[2] << ") pdf " << pdf << ", scalar f (" << rf.r
      << ", " << rf.g << ", " << rf.b << ") pdf " << rp;
    m.first = s.str();
  }
}

struct Dirs {
  std::vector<float> a[6];
  void push(Vec3f wo, Vec3f wi) {
    a[0].push_back(wo.x), a[1].push_back(wo.y), a[2].push_back(wo.z);
    a[3].push_back(wi.x), a[4].push_back(wi.y), a[5].push_back(wi.z);
  }
  EvalDirsSoA soa() const {
    return {a[0].data(), a[1].data(), a[2].data(), a[3].data(), a[4].data(), a[5].data()};
  }
  Vec3f wo(size_t i) const { return {a[0][i], a[1][i], a[2][i]}; }
  Vec3f wi(size_t i) const { return {a[3][i], a[4][i], a[5][i]}; }
};

Rgb random_albedo(Pcg32& rng) { return {rng.next_float(), rng.next_float(), rng.next_float()}; }

// Counts: a large batch (not a multiple of any vector width) and every short tail length.
const size_t kCounts[] = {20011, 1, 2, 3, 5, 7, 8, 9, 15, 16, 17, 31, 33};

}  // namespace

TEST_CASE("SIMD Lambert eval equals the scalar BSDF on every target", "[shade_eval][simd]") {
  for_each_hwy_target(&shade_eval_target_name, [](const std::string&) {
    for (const size_t n : kCounts) {
      Pcg32 rng(uint64_t(n) * 7 + 1);
      Dirs dirs;
      std::vector<float> ar, ag, ab;
      std::vector<LambertBsdf> bsdfs;
      for (size_t i = 0; i < n; ++i) {
        Vec3f wo, wi;
        random_pair(rng, &wo, &wi);
        dirs.push(wo, wi);
        bsdfs.push_back({random_albedo(rng)});
        ar.push_back(bsdfs.back().albedo.r), ag.push_back(bsdfs.back().albedo.g), ab.push_back(bsdfs.back().albedo.b);
      }
      std::vector<float> f(3 * n + 3, -7.0f), pdf(n + 1, -7.0f);
      eval_lambert_soa(n, dirs.soa(), ar.data(), ag.data(), ab.data(), f.data(), pdf.data());
      CHECK(f[3 * n] == -7.0f);  // nothing written past the end
      CHECK(pdf[n] == -7.0f);
      Mismatch m;
      for (size_t i = 0; i < n; ++i) compare(bsdfs[i], dirs.wo(i), dirs.wi(i), &f[3 * i], pdf[i], m);
      INFO("n " << n << ": " << m.first);
      CHECK(m.count == 0);
    }
  });
}

TEST_CASE("SIMD Oren-Nayar eval equals the scalar BSDF on every target", "[shade_eval][simd]") {
  for_each_hwy_target(&shade_eval_target_name, [](const std::string&) {
    for (const size_t n : kCounts) {
      Pcg32 rng(uint64_t(n) * 11 + 3);
      Dirs dirs;
      std::vector<float> ar, ag, ab, sigma;
      std::vector<OrenNayarBsdf> bsdfs;
      for (size_t i = 0; i < n; ++i) {
        Vec3f wo, wi;
        random_pair(rng, &wo, &wi);
        dirs.push(wo, wi);
        const float s = rng.next_u32() % 8 == 0 ? 0.0f : rng.next_float() * (kPi / 2);  // up to 90 degrees
        bsdfs.push_back({random_albedo(rng), s});
        ar.push_back(bsdfs.back().albedo.r), ag.push_back(bsdfs.back().albedo.g), ab.push_back(bsdfs.back().albedo.b);
        sigma.push_back(s);
      }
      std::vector<float> f(3 * n + 3, -7.0f), pdf(n + 1, -7.0f);
      eval_oren_nayar_soa(n, dirs.soa(), ar.data(), ag.data(), ab.data(), sigma.data(), f.data(), pdf.data());
      CHECK(f[3 * n] == -7.0f);
      CHECK(pdf[n] == -7.0f);
      Mismatch m;
      for (size_t i = 0; i < n; ++i) compare(bsdfs[i], dirs.wo(i), dirs.wi(i), &f[3 * i], pdf[i], m);
      INFO("n " << n << ": " << m.first);
      CHECK(m.count == 0);
    }
  });
}

TEST_CASE("SIMD GGX conductor eval equals the scalar BSDF on every target", "[shade_eval][simd]") {
  for_each_hwy_target(&shade_eval_target_name, [](const std::string&) {
    for (const size_t n : kCounts) {
      Pcg32 rng(uint64_t(n) * 13 + 5);
      Dirs dirs;
      std::vector<float> p[8];
      std::vector<ConductorBsdf> bsdfs;
      for (size_t i = 0; i < n; ++i) {
        Vec3f wo, wi;
        random_pair(rng, &wo, &wi);
        dirs.push(wo, wi);
        // eta in [0.05, 3.05], k in [0, 6] (k = 0: a dielectric-like interface); alpha from effectively smooth
        // (< 1e-3: result 0) through very rough, isotropic or not.
        const Rgb eta(0.05f + 3 * rng.next_float(), 0.05f + 3 * rng.next_float(), 0.05f + 3 * rng.next_float());
        Rgb k(6 * rng.next_float(), 6 * rng.next_float(), 6 * rng.next_float());
        if (rng.next_u32() % 8 == 0) k = Rgb(0);
        const uint32_t rough = rng.next_u32() % 10;
        float ax = rough == 0 ? 5e-4f * rng.next_float() : 0.001f + 1.2f * rng.next_float() * rng.next_float();
        float ay = rng.next_u32() % 2 ? ax : (rough == 0 ? 9e-4f : 0.001f + 1.2f * rng.next_float());
        bsdfs.emplace_back(eta, k, MicrofacetDistribution::ggx(ax, ay));
        const float v[8] = {eta.r, eta.g, eta.b, k.r, k.g, k.b, ax, ay};
        for (int j = 0; j < 8; ++j) p[j].push_back(v[j]);
      }
      std::vector<float> f(3 * n + 3, -7.0f), pdf(n + 1, -7.0f);
      const ConductorParamsSoA params{p[0].data(), p[1].data(), p[2].data(), p[3].data(),
                                      p[4].data(), p[5].data(), p[6].data(), p[7].data()};
      eval_ggx_conductor_soa(n, dirs.soa(), params, f.data(), pdf.data());
      CHECK(f[3 * n] == -7.0f);
      CHECK(pdf[n] == -7.0f);
      Mismatch m;
      int nonzero = 0;
      for (size_t i = 0; i < n; ++i) {
        compare(bsdfs[i], dirs.wo(i), dirs.wi(i), &f[3 * i], pdf[i], m);
        nonzero += pdf[i] > 0;
      }
      INFO("n " << n << ": " << m.first);
      CHECK(m.count == 0);
      if (n > 1000) CHECK(nonzero > int(n) / 4);  // the comparison is not only about zeros
    }
  });
}

TEST_CASE("the SIMD eval comparison can fail: a perturbed scalar value is detected", "[shade_eval][simd]") {
  const OrenNayarBsdf b{Rgb(0.5f), 0.4f};
  const Vec3f wo = normalize(Vec3f(0.3f, 0.1f, 0.8f)), wi = normalize(Vec3f(-0.2f, 0.4f, 0.7f));
  float f[3], pdf;
  const float wox = wo.x, woy = wo.y, woz = wo.z, wix = wi.x, wiy = wi.y, wiz = wi.z, a = 0.5f, s = 0.4f;
  eval_oren_nayar_soa(1, {&wox, &woy, &woz, &wix, &wiy, &wiz}, &a, &a, &a, &s, f, &pdf);
  Mismatch m;
  compare(b, wo, wi, f, pdf, m);
  CHECK(m.count == 0);
  f[1] *= 1 + 3e-5f;
  compare(b, wo, wi, f, pdf, m);
  CHECK(m.count == 1);
}

namespace {

// Fills a scratch as phase 1 of shade_queue would: per-hit BSDFs and wo, candidates with slots and wi.
template <class Bsdf, class Make>
ShadeScratch<Bsdf> make_scratch(Pcg32& rng, size_t hits, Make&& make) {
  ShadeScratch<Bsdf> sc;
  for (size_t h = 0; h < hits; ++h) {
    Vec3f wo, wi;
    random_pair(rng, &wo, &wi);
    sc.bsdf.push_back(make(rng));
    sc.wo_local.push_back(wo);
    const int lights = int(rng.next_u32() % 3);  // 0, 1 or 2 candidates per hit
    for (int l = 0; l < lights; ++l) {
      LightCandidate c{};
      c.slot = uint32_t(h);
      c.wi_local = l == 0 ? wi : random_direction(rng);
      sc.lights.push_back(c);
    }
  }
  sc.f.assign(sc.lights.size(), Rgb(-1));
  sc.pdf.assign(sc.lights.size(), -1);
  return sc;
}

// eval_batch_simd, and the same through shade_queue's phase 2 (detail::eval_candidates, which takes the SIMD path
// where MaterialTraits<T>::kBatchEval says so); both must equal the scalar BSDF.
template <MaterialType T, class Bsdf>
int batch_mismatches(ShadeScratch<Bsdf>& sc, std::string* first) {
  {
    detail::eval_candidates<T>(sc);
    Mismatch m;
    for (size_t k = 0; k < sc.lights.size(); ++k) {
      const LightCandidate& c = sc.lights[k];
      compare(sc.bsdf[c.slot], sc.wo_local[c.slot], c.wi_local, &sc.f[k].r, sc.pdf[k], m);
    }
    if (m.count) {
      *first = "through eval_candidates: " + m.first;
      return m.count;
    }
    for (size_t k = 0; k < sc.lights.size(); ++k) sc.f[k] = Rgb(-1), sc.pdf[k] = -1;
  }
  eval_batch_simd(sc);
  Mismatch m;
  for (size_t k = 0; k < sc.lights.size(); ++k) {
    const LightCandidate& c = sc.lights[k];
    compare(sc.bsdf[c.slot], sc.wo_local[c.slot], c.wi_local, &sc.f[k].r, sc.pdf[k], m);
  }
  *first = m.first;
  return m.count;
}

}  // namespace

TEST_CASE("eval_batch of Lambert, Oren-Nayar and Conductor equals the scalar phase 2", "[shade_eval][simd]") {
  // The renderer uses the vector path for Oren-Nayar and Conductor only (Lambert: no gain, see shade_eval_batch.h).
  STATIC_REQUIRE(MaterialTraits<MaterialType::OrenNayar>::kBatchEval);
  STATIC_REQUIRE(MaterialTraits<MaterialType::Conductor>::kBatchEval);
  STATIC_REQUIRE(!MaterialTraits<MaterialType::Lambert>::kBatchEval);
  for_each_hwy_target(&shade_eval_target_name, [](const std::string&) {
    for (const size_t hits : {size_t(0), size_t(1), size_t(5), size_t(3001)}) {
      Pcg32 rng(hits + 17);
      std::string first;
      auto lambert = make_scratch<LambertBsdf>(rng, hits, [](Pcg32& r) { return LambertBsdf{random_albedo(r)}; });
      {
        const int bad = batch_mismatches<MaterialType::Lambert>(lambert, &first);
        INFO("Lambert: " << first);
        CHECK(bad == 0);
      }
      auto on = make_scratch<OrenNayarBsdf>(rng, hits, [](Pcg32& r) {
        return OrenNayarBsdf{random_albedo(r), r.next_float()};
      });
      {
        const int bad = batch_mismatches<MaterialType::OrenNayar>(on, &first);
        INFO("Oren-Nayar: " << first);
        CHECK(bad == 0);
      }
      for (const bool mixed : {false, true}) {
        auto metal = make_scratch<ConductorBsdf>(rng, hits, [mixed](Pcg32& r) {
          const float a = 0.01f + r.next_float();
          const bool beckmann = mixed && r.next_u32() % 3 == 0;
          return ConductorBsdf(Rgb(0.2f, 0.9f, 1.1f), Rgb(3.9f, 2.4f, 2.2f),
                               beckmann ? MicrofacetDistribution::beckmann(a) : MicrofacetDistribution::ggx(a, 0.5f * a));
        });
        const int bad = batch_mismatches<MaterialType::Conductor>(metal, &first);
        INFO("conductor, mixed " << mixed << ": " << first);
        CHECK(bad == 0);
      }
    }
  });
}
