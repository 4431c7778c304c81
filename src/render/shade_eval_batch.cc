// eval_batch_simd for Lambert, Oren-Nayar and Conductor, and the MaterialTraits<T>::eval_batch members that use it
// (see render/shade_eval_batch.h): gather the light candidates into SoA arrays, run the SIMD kernel of
// simd/shade_eval.h, which writes f (as Rgb) and pdf straight into the scratch's output arrays.
#include "render/shade_eval_batch.h"

#include <vector>

#include "material/material_traits.h"
#include "render/shade.h"
#include "shade_eval.h"

namespace torte {

namespace {

// The kernels write f as 3 interleaved floats per candidate straight into std::vector<Rgb>.
static_assert(sizeof(Rgb) == 3 * sizeof(float) && alignof(Rgb) == alignof(float));

// SoA gather buffers, reused between queues (one set per thread: tiles render on TBB workers).
struct GatherBuffers {
  enum { kWoX, kWoY, kWoZ, kWiX, kWiY, kWiZ, kP0, kCount = kP0 + 8 };
  std::vector<float> a[kCount];
  std::vector<uint32_t> index;  // candidate index (conductor: the GGX ones)
  std::vector<float> out;       // kernel outputs to scatter (conductor queues mixing GGX and Beckmann)
  float* resize(int which, size_t n) {
    a[which].resize(n);
    return a[which].data();
  }
};

GatherBuffers& buffers() {
  thread_local GatherBuffers b;
  return b;
}

// Columns 0-5 of the gather buffers: wo and wi of candidate slot i (the EvalDirsSoA layout).
void put_directions(float* const* p, size_t i, Vec3f wo, Vec3f wi) {
  p[0][i] = wo.x;
  p[1][i] = wo.y;
  p[2][i] = wo.z;
  p[3][i] = wi.x;
  p[4][i] = wi.y;
  p[5][i] = wi.z;
}

}  // namespace

void eval_batch_simd(ShadeScratch<LambertBsdf>& sc) {
  const size_t n = sc.lights.size();
  if (n == 0) return;
  GatherBuffers& g = buffers();
  float* wo_z = g.resize(GatherBuffers::kWoZ, n);
  float* wi_z = g.resize(GatherBuffers::kWiZ, n);
  float* ar = g.resize(GatherBuffers::kP0, n);
  float* ag = g.resize(GatherBuffers::kP0 + 1, n);
  float* ab = g.resize(GatherBuffers::kP0 + 2, n);
  for (size_t k = 0; k < n; ++k) {
    const LightCandidate& c = sc.lights[k];
    const Rgb& albedo = sc.bsdf[c.slot].albedo;
    wo_z[k] = sc.wo_local[c.slot].z;
    wi_z[k] = c.wi_local.z;
    ar[k] = albedo.r;
    ag[k] = albedo.g;
    ab[k] = albedo.b;
  }
  EvalDirsSoA dirs{nullptr, nullptr, wo_z, nullptr, nullptr, wi_z};
  eval_lambert_soa(n, dirs, ar, ag, ab, &sc.f[0].r, sc.pdf.data());
}

void eval_batch_simd(ShadeScratch<OrenNayarBsdf>& sc) {
  const size_t n = sc.lights.size();
  if (n == 0) return;
  GatherBuffers& g = buffers();
  float* p[GatherBuffers::kP0 + 4];
  for (int j = 0; j < GatherBuffers::kP0 + 4; ++j) p[j] = g.resize(j, n);
  for (size_t k = 0; k < n; ++k) {
    const LightCandidate& c = sc.lights[k];
    const OrenNayarBsdf& b = sc.bsdf[c.slot];
    const Vec3f wo = sc.wo_local[c.slot];
    put_directions(p, k, wo, c.wi_local);
    p[6][k] = b.albedo.r;
    p[7][k] = b.albedo.g;
    p[8][k] = b.albedo.b;
    p[9][k] = b.sigma;
  }
  EvalDirsSoA dirs{p[0], p[1], p[2], p[3], p[4], p[5]};
  eval_oren_nayar_soa(n, dirs, p[6], p[7], p[8], p[9], &sc.f[0].r, sc.pdf.data());
}

void eval_batch_simd(ShadeScratch<ConductorBsdf>& sc) {
  const size_t n = sc.lights.size();
  if (n == 0) return;
  GatherBuffers& g = buffers();
  float* p[GatherBuffers::kCount];
  for (int j = 0; j < GatherBuffers::kCount; ++j) p[j] = g.resize(j, n);
  g.index.clear();
  // GGX candidates (isotropic or not) go to the kernel; Beckmann ones are evaluated by the scalar BSDF right away.
  size_t m = 0;
  for (size_t k = 0; k < n; ++k) {
    const LightCandidate& c = sc.lights[k];
    const ConductorBsdf& b = sc.bsdf[c.slot];
    const Vec3f wo = sc.wo_local[c.slot];
    if (b.distrib.kind != MicrofacetDistribution::Kind::GGX) {
      sc.f[k] = b.eval(wo, c.wi_local);
      sc.pdf[k] = b.pdf(wo, c.wi_local);
      continue;
    }
    g.index.push_back(uint32_t(k));
    put_directions(p, m, wo, c.wi_local);
    p[6][m] = b.eta.r;
    p[7][m] = b.eta.g;
    p[8][m] = b.eta.b;
    p[9][m] = b.k.r;
    p[10][m] = b.k.g;
    p[11][m] = b.k.b;
    p[12][m] = b.distrib.alpha_x;
    p[13][m] = b.distrib.alpha_y;
    ++m;
  }
  if (m == 0) return;
  const EvalDirsSoA dirs{p[0], p[1], p[2], p[3], p[4], p[5]};
  const ConductorParamsSoA params{p[6], p[7], p[8], p[9], p[10], p[11], p[12], p[13]};
  if (m == n) {  // all GGX: write in place
    eval_ggx_conductor_soa(n, dirs, params, &sc.f[0].r, sc.pdf.data());
    return;
  }
  // Mixed queue: evaluate into a buffer of its own, then scatter.
  g.out.resize(4 * m);
  float* f_out = g.out.data();
  float* pdf_out = f_out + 3 * m;
  eval_ggx_conductor_soa(m, dirs, params, f_out, pdf_out);
  for (size_t j = 0; j < m; ++j) {
    const uint32_t k = g.index[j];
    sc.f[k] = Rgb(f_out[3 * j], f_out[3 * j + 1], f_out[3 * j + 2]);
    sc.pdf[k] = pdf_out[j];
  }
}

}  // namespace torte
