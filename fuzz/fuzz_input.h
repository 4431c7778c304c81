// Reading structured values from a fuzz input: a cursor over the bytes that returns zeros once they run out,
// so every input decodes to some finite sequence and the same bytes always decode the same way.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace torte::fuzz {

class FuzzInput {
 public:
  FuzzInput(const uint8_t* data, size_t size) : p_(data), n_(size) {}

  bool empty() const { return i_ >= n_; }
  size_t remaining() const { return n_ - i_; }

  uint8_t byte() { return i_ < n_ ? p_[i_++] : 0; }
  uint16_t u16() { return uint16_t(byte() | (uint16_t(byte()) << 8)); }
  uint32_t u32() { return uint32_t(u16()) | (uint32_t(u16()) << 16); }
  uint64_t u64() { return uint64_t(u32()) | (uint64_t(u32()) << 32); }
  double f64() {
    const uint64_t bits = u64();
    double d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  }
  /// An index below `count` (0 when count is 0).
  size_t pick(size_t count) { return count == 0 ? 0 : (count <= 256 ? byte() : u16()) % count; }
  /// Up to `max` raw bytes: a length byte, then that many bytes (fewer at the end of the input).
  std::string_view bytes(size_t max) {
    size_t len = byte() % (max + 1);
    if (len > n_ - i_) len = n_ - i_;
    std::string_view s(reinterpret_cast<const char*>(p_ + i_), len);
    i_ += len;
    return s;
  }
  /// The rest of the input.
  std::string_view rest() {
    std::string_view s(reinterpret_cast<const char*>(p_ + i_), n_ - i_);
    i_ = n_;
    return s;
  }

 private:
  const uint8_t* p_;
  size_t n_;
  size_t i_ = 0;
};

}  // namespace torte::fuzz
