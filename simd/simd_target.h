// The SIMD target torte runs on, chosen at run time: `--simd` and torte.simd.use restrict Highway's dispatch
// (every kernel in simd/) and with it the render loop's per-ISA copy (render/render_isa.h follows Highway's
// supported targets), so one binary can be compared against itself on every target the CPU has.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace torte::simd {

/// torte's names for the targets, best first: "avx512" (Highway AVX3 and up), "avx2", "sse4", "ssse3" and
/// "scalar" (Highway EMU128 or SCALAR). `--simd` and torte.simd.use take these and "auto".
inline constexpr const char* kTargetChoices = "auto, avx512, avx2, sse4, ssse3, scalar";

struct TargetInfo {
  std::string name;  // torte's name ("avx2")
  bool supported;    // this CPU runs it
};
/// The targets compiled into this binary (Highway's HWY_TARGETS), best first, each with whether the CPU runs it.
std::vector<TargetInfo> compiled_targets();

/// Restricts dispatch to `name` (one of kTargetChoices; "auto" lifts the restriction). Throws torte::Error
/// naming the choices for an unknown name, and saying so when the target is not compiled in or the CPU lacks it.
/// Not thread-safe: call between renders (main does it before the script runs).
void use_target(const std::string& name);

/// The target dispatch picks now, as torte names it ("avx2"); "auto" never.
std::string current_target();
/// What the user asked for: "auto" until use_target restricts dispatch.
const std::string& requested_target();

}  // namespace torte::simd
