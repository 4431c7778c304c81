// Ctrl-C as one process-wide flag: the first SIGINT sets it (a lock-free atomic store, safe in a signal
// handler), and long work polls it at safe points: the Lua hook between instructions, scene building between
// meshes and BVH subtrees, rendering between tiles. What has been finished up to then is kept and written.
#pragma once
#include <atomic>

#include "core/error.h"

namespace torte {

/// The flag itself; renderers that take a `const std::atomic<bool>*` cancel pointer get this one.
std::atomic<bool>& interrupt_flag() noexcept;

/// Sets the flag. Async-signal-safe.
inline void request_interrupt() noexcept { interrupt_flag().store(true, std::memory_order_relaxed); }
inline bool interrupt_requested() noexcept { return interrupt_flag().load(std::memory_order_relaxed); }
/// Clears the flag (tests; a host program that runs several scripts).
inline void clear_interrupt() noexcept { interrupt_flag().store(false, std::memory_order_relaxed); }

/// Thrown at a safe point once the flag is set; `what()` says what was stopped ("interrupted while building
/// the scene"). The command line turns it into exit code 130 without an error line.
struct Interrupted : Error {
  using Error::Error;
};

/// Throws Interrupted("interrupted while <doing>") when the flag is set.
inline void throw_if_interrupted(const char* doing) {
  if (interrupt_requested()) throw Interrupted(std::string("interrupted while ") + doing);
}

}  // namespace torte
