#include "version.h"

#include "render/render_isa.h"
#include "simd/simd_target.h"

#ifndef TORTE_BUILD_OPTIONS
#define TORTE_BUILD_OPTIONS "unknown"
#endif

namespace torte::app {

namespace {

std::string compiler() {
#if defined(__clang__)
  std::string v = "clang " __clang_version__;
#elif defined(__GNUC__)
  std::string v = "gcc " __VERSION__;
#else
  std::string v = "unknown";
#endif
  while (!v.empty() && v.back() == ' ') v.pop_back();  // __clang_version__ ends with a space
  return v;
}

}  // namespace

std::string version_text() {
  std::string compiled, supported;
  for (const simd::TargetInfo& t : simd::compiled_targets()) {
    compiled += (compiled.empty() ? "" : ", ") + t.name;
    if (t.supported) supported += (supported.empty() ? "" : ", ") + t.name;
  }
  std::string loops;
  for (const render_isa::Variant& v : render_isa::supported()) loops += (loops.empty() ? "" : ", ") + std::string(v.name);
  std::string out = std::string("torte ") + TORTE_VERSION + "\n";
  out += "compiler: " + compiler() + "\n";
  out += "SIMD targets compiled: " + compiled + "\n";
  out += "SIMD targets this CPU runs: " + supported + "\n";
  out += "SIMD target chosen: " + simd::current_target() + " (--simd " + simd::requested_target() + ")\n";
  out += "render loop copies this CPU runs: " + loops + " (chosen: " + render_isa::selected_name() + ")\n";
  out += std::string("build options: ") + TORTE_BUILD_OPTIONS + "\n";
  return out;
}

}  // namespace torte::app
