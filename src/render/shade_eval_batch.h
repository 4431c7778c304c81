// Vectorised phase 2 of shade_queue (render/shade.h): eval_batch_simd gathers the light candidates of a queue into
// SoA arrays, runs the Highway kernel of simd/shade_eval.h (lanes = light samples) and writes f and pdf per
// candidate, equal to the scalar BSDFs' to a few ulps (tests/test_shade_eval.cc). Defined in
// render/shade_eval_batch.cc; one call per queue, not per hit, so the out-of-line call costs nothing.
//
// Which types use it (MaterialTraits<T>::kBatchEval in material/material_traits.h) follows the
// measurements in bench/RESULTS.md, "Shading" (phase 2 alone, gather included, AVX2):
//   Conductor (GGX):  about 3x the scalar loop (the kernel alone 8x; the gather of 14 floats per candidate is
//                     most of the rest): used. Beckmann candidates are evaluated by the scalar BSDF inside the batch.
//   Oren-Nayar:       about 1.3x (kernel alone 4.6x): used.
//   Lambert:          no gain, 0.94-1.0x (the scalar loop is a compare and a multiply; gathering costs as much as
//                     it): NOT used, Lambert keeps shade_queue's scalar loop. The overload stays for the benchmark
//                     and the tests.
// Phase 2 is about 1.5% of shading time on the benchmark scene (the sampler and light sampling dominate), so the
// vector path saves about 0.4% of shading there.
#pragma once

namespace torte {

template <class Bsdf>
struct ShadeScratch;
struct LambertBsdf;
struct OrenNayarBsdf;
struct ConductorBsdf;

// sc.f and sc.pdf must already hold sc.lights.size() entries (shade.h's eval_candidates resizes them).
void eval_batch_simd(ShadeScratch<LambertBsdf>& sc);
void eval_batch_simd(ShadeScratch<OrenNayarBsdf>& sc);
void eval_batch_simd(ShadeScratch<ConductorBsdf>& sc);

}  // namespace torte
