#include "core/interrupt.h"

namespace torte {

std::atomic<bool>& interrupt_flag() noexcept {
  static std::atomic<bool> flag{false};
  static_assert(std::atomic<bool>::is_always_lock_free, "the SIGINT handler needs a lock-free store");
  return flag;
}

}  // namespace torte
