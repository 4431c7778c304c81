// What `torte --version` prints: the version, the compiler, the SIMD targets compiled in and those this CPU
// runs (with the one chosen, after --simd), the render loop's per-ISA copies and the build options.
#pragma once
#include <string>

namespace torte::app {

/// Several lines, the first "torte <version>" (torte.version is the same string); each line ends with '\n'.
std::string version_text();

}  // namespace torte::app
