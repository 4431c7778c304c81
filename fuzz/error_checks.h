// Oracles shared by the harnesses: what a reader returns or throws must keep its documented promises, and a
// broken promise stops the fuzzer like a crash (with the reason on stderr).
#pragma once
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "geometry/mesh.h"

namespace torte::fuzz {

int report_fd();  // fuzz_support.h

[[noreturn]] inline void broken_promise(const std::string& what) {
  const std::string line = "fuzz: broken promise: " + what + "\n";
  (void)!write(report_fd(), line.data(), line.size());
  std::abort();
}

/// TORTE_FUZZ_STRICT_ERRORS=1: error messages are checked for the file name and for control bytes too.
inline bool strict_errors() {
  static const bool strict = [] {
    const char* s = std::getenv("TORTE_FUZZ_STRICT_ERRORS");
    return s && *s == '1';
  }();
  return strict;
}

/// Readers' errors start with the name they were given ("<name>: ..."; `name` may be a prefix of the file name,
/// e.g. a directory). With TORTE_FUZZ_STRICT_ERRORS=1 the message must also be one printable line (no control
/// bytes).
inline void check_error_message(std::string_view message, std::string_view name) {
  if (message.substr(0, name.size()) != name)
    broken_promise("error does not start with '" + std::string(name) + "': " + std::string(message));
  if (strict_errors())
    for (unsigned char c : message)
      if (c < 0x20 || c == 0x7f) broken_promise("error holds control byte " + std::to_string(c) + ": " + std::string(message));
}

/// A mesh a reader returned must pass TriangleMesh::validate.
inline void check_mesh(const TriangleMesh& mesh, const std::string& name) {
  try {
    mesh.validate(name);
  } catch (const std::exception& e) {
    broken_promise(std::string("the reader returned an invalid mesh: ") + e.what());
  }
}

}  // namespace torte::fuzz
