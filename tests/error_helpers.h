// Small helpers for tests of error paths, shared by the unit and I/O suites.
#pragma once
#include <cstdint>
#include <string>

#include "core/error.h"
#include "core/memory_budget.h"

namespace torte::test {

/// The message of the torte::Error that fn throws, or "(no error)" when it throws none.
template <class Fn>
std::string error_of(Fn&& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

/// Sets the process's memory limit for a scope; the default comes back afterwards.
struct ScopedMemoryLimit {
  explicit ScopedMemoryLimit(uint64_t bytes) { set_memory_limit(bytes); }
  ~ScopedMemoryLimit() { set_memory_limit(0); }
  ScopedMemoryLimit(const ScopedMemoryLimit&) = delete;
  ScopedMemoryLimit& operator=(const ScopedMemoryLimit&) = delete;
};

}  // namespace torte::test
