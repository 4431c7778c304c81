// PCG32 (O'Neill 2014): 16 bytes of state, period 2^64 per stream, 2^63 selectable streams.
#pragma once
#include <cstdint>

namespace torte {

class Pcg32 {
 public:
  explicit Pcg32(uint64_t seed = 0x853c49e6748fea9bULL, uint64_t stream = 0xda3e39cb94b95bdbULL) {
    set_sequence(seed, stream);
  }
  void set_sequence(uint64_t seed, uint64_t stream) {
    state_ = 0;
    inc_ = (stream << 1u) | 1u;
    next_u32();
    state_ += seed;
    next_u32();
  }
  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * 0x5851f42d4c957f2dULL + inc_;
    const uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
  }
  // Uniform in [0, 1): 24 random mantissa bits, never rounds up to 1.
  float next_float() { return float(next_u32() >> 8) * 0x1p-24f; }

 private:
  uint64_t state_, inc_;
};

// 64-bit mixing hash (MurmurHash3 finalizer) for deriving independent seeds from (seed, pixel, dimension).
constexpr uint64_t mix_bits(uint64_t v) {
  v ^= v >> 31;
  v *= 0x7fb5d329728ea185ULL;
  v ^= v >> 27;
  v *= 0x81dadef4bc2dd44dULL;
  v ^= v >> 33;
  return v;
}

}  // namespace torte
