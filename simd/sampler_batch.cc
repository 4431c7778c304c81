// Owen-scrambled Sobol points for many requests (see sampler_batch.h): the Highway kernel and its dispatch entry
// point. Each step is the scalar Sampler::get_2d's (core/sampler.h), lane for lane, so the results are the same bits.
#include "sampler_batch.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "core/sampler.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sampler_batch.cc"  // found through the simd/ include directory of torte_core
#include <hwy/foreach_target.h>                // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace torte::HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
using DU = hn::ScalableTag<uint32_t>;
using DI = hn::RebindToSigned<DU>;
using DF = hn::RebindToFloat<DU>;
using VU = hn::Vec<DU>;
using VF = hn::Vec<DF>;
constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(uint32_t);

// sampler_detail::reverse_bits: swap halves, then bytes, nibbles, pairs and bits.
HWY_INLINE VU ReverseBits(DU du, VU x) {
  x = hn::Or(hn::ShiftRight<16>(x), hn::ShiftLeft<16>(x));
  const auto swap = [&](VU v, uint32_t mask, auto shift) {
    constexpr int kShift = decltype(shift)::value;
    const VU m = hn::Set(du, mask);
    return hn::Or(hn::And(hn::ShiftRight<kShift>(v), m), hn::ShiftLeft<kShift>(hn::And(v, m)));
  };
  x = swap(x, 0x00ff00ffu, std::integral_constant<int, 8>());
  x = swap(x, 0x0f0f0f0fu, std::integral_constant<int, 4>());
  x = swap(x, 0x33333333u, std::integral_constant<int, 2>());
  return swap(x, 0x55555555u, std::integral_constant<int, 1>());
}

// sampler_detail::laine_karras_permutation.
HWY_INLINE VU LaineKarras(DU du, VU x, VU seed) {
  x = hn::Add(x, seed);
  x = hn::Xor(x, hn::Mul(x, hn::Set(du, 0x6c50b47cu)));
  x = hn::Xor(x, hn::Mul(x, hn::Set(du, 0xb82f1e52u)));
  x = hn::Xor(x, hn::Mul(x, hn::Set(du, 0xc7afe638u)));
  return hn::Xor(x, hn::Mul(x, hn::Set(du, 0x8d22f6e6u)));
}

// sampler_detail::to_unit_float. The two 16-bit halves convert exactly and their sum rounds once, as the scalar
// unsigned conversion does (signed conversion alone would misread values from 2^31).
HWY_INLINE VF ToUnitFloat(DU du, VU x) {
  const DF df;
  const DI di;
  const VF hi = hn::ConvertTo(df, hn::BitCast(di, hn::ShiftRight<16>(x)));
  const VF lo = hn::ConvertTo(df, hn::BitCast(di, hn::And(x, hn::Set(du, 0xffffu))));
  const VF v = hn::Add(hn::Mul(hi, hn::Set(df, 65536.0f)), lo);
  return hn::Min(hn::Mul(v, hn::Set(df, 0x1p-32f)), hn::Set(df, 0x1.fffffep-1f));
}

HWY_INLINE void Points(DU du, const uint32_t* sample, const uint32_t* shuffle, const uint32_t* a, const uint32_t* b,
                       float* x, float* y) {
  const DF df;
  const DI di;
  const VU r = LaineKarras(du, ReverseBits(du, hn::LoadU(du, sample)), hn::LoadU(du, shuffle));
  hn::StoreU(ToUnitFloat(du, ReverseBits(du, LaineKarras(du, ReverseBits(du, r), hn::LoadU(du, a)))), df, x);
  if (!y) return;
  const auto& u = sampler_detail::kReversedSobolDim1.u;
  const VU byte = hn::Set(du, 0xffu);
  VU t = hn::GatherIndex(du, u[0], hn::BitCast(di, hn::And(r, byte)));
  t = hn::Xor(t, hn::GatherIndex(du, u[1], hn::BitCast(di, hn::And(hn::ShiftRight<8>(r), byte))));
  t = hn::Xor(t, hn::GatherIndex(du, u[2], hn::BitCast(di, hn::And(hn::ShiftRight<16>(r), byte))));
  t = hn::Xor(t, hn::GatherIndex(du, u[3], hn::BitCast(di, hn::ShiftRight<24>(r))));
  hn::StoreU(ToUnitFloat(du, ReverseBits(du, LaineKarras(du, t, hn::LoadU(du, b)))), df, y);
}

void SobolPoints(size_t count, const uint32_t* HWY_RESTRICT sample, const uint32_t* HWY_RESTRICT shuffle,
                 const uint32_t* HWY_RESTRICT a, const uint32_t* HWY_RESTRICT b, float* HWY_RESTRICT x,
                 float* HWY_RESTRICT y) {
  const DU du;
  const size_t n = hn::Lanes(du);
  size_t i = 0;
  for (; i + n <= count; i += n) Points(du, sample + i, shuffle + i, a + i, b + i, x + i, y ? y + i : nullptr);
  if (i == count) return;
  // The remainder through zero-padded local copies (Highway 1.0 has no LoadN/StoreN).
  const size_t rest = count - i;
  HWY_ALIGN uint32_t in[4][kMaxLanes] = {};
  std::memcpy(in[0], sample + i, rest * sizeof(uint32_t));
  std::memcpy(in[1], shuffle + i, rest * sizeof(uint32_t));
  std::memcpy(in[2], a + i, rest * sizeof(uint32_t));
  std::memcpy(in[3], b + i, rest * sizeof(uint32_t));
  HWY_ALIGN float out_x[kMaxLanes], out_y[kMaxLanes];
  Points(du, in[0], in[1], in[2], in[3], out_x, y ? out_y : nullptr);
  std::memcpy(x + i, out_x, rest * sizeof(float));
  if (y) std::memcpy(y + i, out_y, rest * sizeof(float));
}

int64_t SamplerBatchTarget() { return HWY_TARGET; }

}  // namespace
}  // namespace torte::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace torte {

HWY_EXPORT(SobolPoints);
HWY_EXPORT(SamplerBatchTarget);

void sobol_points_soa(size_t count, const uint32_t* sample, const SobolSeedsSoA& seeds, float* x, float* y) {
  HWY_DYNAMIC_DISPATCH(SobolPoints)(count, sample, seeds.shuffle, seeds.a, seeds.b, x, y);
}

const char* sampler_batch_target_name() { return hwy::TargetName(HWY_DYNAMIC_DISPATCH(SamplerBatchTarget)()); }

}  // namespace torte
#endif  // HWY_ONCE
