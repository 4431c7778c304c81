#include "simd/simd_target.h"

#include <hwy/highway.h>  // HWY_TARGETS: the targets foreach_target compiled the kernels for
#include <hwy/targets.h>

#include "core/error.h"

namespace torte::simd {

namespace {

struct Group {
  const char* name;
  int64_t bits;  // the Highway targets torte counts as this target
};

// Best first, as Highway orders its bits (a lower bit is a better target).
constexpr Group kGroups[] = {
    {"avx512", HWY_AVX3 | HWY_AVX3_DL},
    {"avx2", HWY_AVX2},
    {"sse4", HWY_SSE4},
    {"ssse3", HWY_SSSE3},
    {"scalar", HWY_EMU128 | HWY_SCALAR},
};

std::string g_requested = "auto";

// What the CPU runs, without any restriction of ours: SetSupportedTargetsForTest(0) restores detection.
int64_t cpu_targets() {
  hwy::SetSupportedTargetsForTest(0);
  const int64_t cpu = hwy::SupportedTargets();
  return cpu;
}

}  // namespace

std::vector<TargetInfo> compiled_targets() {
  const int64_t restricted = g_requested == "auto" ? 0 : hwy::SupportedTargets();
  const int64_t cpu = cpu_targets();
  if (restricted) hwy::SetSupportedTargetsForTest(restricted);
  std::vector<TargetInfo> out;
  for (const Group& g : kGroups)
    if (g.bits & HWY_TARGETS) out.push_back({g.name, (g.bits & HWY_TARGETS & cpu) != 0});
  return out;
}

void use_target(const std::string& name) {
  if (name == "auto") {
    hwy::SetSupportedTargetsForTest(0);
    g_requested = name;
    return;
  }
  for (const Group& g : kGroups) {
    if (name != g.name) continue;
    if (!(g.bits & HWY_TARGETS)) throw Error("SIMD target '" + name + "' is not compiled into this build");
    const int64_t restricted = hwy::SupportedTargets();
    const int64_t cpu = cpu_targets();
    const int64_t mask = g.bits & HWY_TARGETS & cpu;
    if (!mask) {
      if (g_requested != "auto") hwy::SetSupportedTargetsForTest(restricted);  // keep the earlier choice
      throw Error("SIMD target '" + name + "' is not supported by this CPU (it runs: " + [&] {
        std::string list;
        for (const TargetInfo& t : compiled_targets())
          if (t.supported) list += (list.empty() ? "" : ", ") + t.name;
        return list;
      }() + ")");
    }
    hwy::SetSupportedTargetsForTest(mask);
    g_requested = name;
    return;
  }
  throw Error("unknown SIMD target '" + name + "' (known: " + kTargetChoices + ")");
}

std::string current_target() {
  const int64_t chosen = hwy::SupportedTargets() & HWY_TARGETS;
  const int64_t best = chosen & -chosen;  // Highway dispatches to the lowest bit
  for (const Group& g : kGroups)
    if (g.bits & best) return g.name;
  return hwy::TargetName(best);
}

const std::string& requested_target() { return g_requested; }

}  // namespace torte::simd
