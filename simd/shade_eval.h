// Vectorised BSDF evaluation for the light samples of a shading queue (lanes = light samples): f(wo, wi) and the
// solid-angle pdf of the BSDF's own sampling, for Lambert, Oren-Nayar and the rough GGX conductor. Plain C++ API
// over structure-of-arrays float inputs (one entry per candidate); the kernels are Highway code (shade_eval.cc)
// dispatched at run time to the best target the CPU supports, like simd/traverse.h.
//
// The formulas are exactly those of the scalar BSDFs (material/lambert.h, oren_nayar.h, conductor.h with
// microfacet.h and fresnel.h), branch for branch: opposite hemispheres (wo.z * wi.z <= 0) give f = 0 and pdf = 0,
// a conductor whose roughness is effectively smooth (max(alpha_x, alpha_y) < 1e-3) gives 0, wi = -wo gives 0.
// Results agree with the scalar code to a few ulps (tests/test_shade_eval.cc checks 1e-5 relative on every target).
//
// Outputs: f_rgb receives 3 floats per candidate (r, g, b interleaved, i.e. an array of torte::Rgb), pdf one.
// `count` need not be a multiple of the vector width; inputs are read and outputs written for [0, count) only.
#pragma once
#include <cstddef>

namespace torte {

// Directions in the local shading frame (+z = shading normal), one entry per candidate.
struct EvalDirsSoA {
  const float *wo_x, *wo_y, *wo_z;
  const float *wi_x, *wi_y, *wi_z;
};

// Lambert: only wo_z, wi_z are read (wo_x etc. may be null).
void eval_lambert_soa(size_t count, const EvalDirsSoA& dirs, const float* albedo_r, const float* albedo_g,
                      const float* albedo_b, float* f_rgb, float* pdf);

// Oren-Nayar; sigma in radians.
void eval_oren_nayar_soa(size_t count, const EvalDirsSoA& dirs, const float* albedo_r, const float* albedo_g,
                         const float* albedo_b, const float* sigma, float* f_rgb, float* pdf);

// Rough conductor with the (possibly anisotropic) GGX distribution, Smith height-correlated G, exact conductor
// Fresnel per channel (complex IOR eta + i k) and the pdf of visible-normal sampling. Beckmann conductors are not
// handled here (callers use the scalar BSDF for them).
struct ConductorParamsSoA {
  const float *eta_r, *eta_g, *eta_b;
  const float *k_r, *k_g, *k_b;
  const float *alpha_x, *alpha_y;
};
void eval_ggx_conductor_soa(size_t count, const EvalDirsSoA& dirs, const ConductorParamsSoA& params, float* f_rgb,
                            float* pdf);

// Name of the Highway target these kernels dispatch to on this CPU (e.g. "AVX2", "SCALAR").
const char* shade_eval_target_name();

}  // namespace torte
