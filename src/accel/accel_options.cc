#include "accel/accel_options.h"

#include <string>

#include "core/error.h"
#include "core/memory_budget.h"

namespace torte {

BvhLayout resolve_layout(const AccelOptions& options, uint64_t triangles) {
  if (options.layout != BvhLayout::kAuto) return options.layout;
  const uint64_t budget = options.memory_budget != 0 ? options.memory_budget : memory_limit();
  const uint64_t resident = resident_memory();
  if (resident + triangles * kDefaultLayoutBytesPerTriangle <= budget) return BvhLayout::kDefault;
  if (resident + triangles * kPackedLayoutBytesPerTriangle <= budget) return BvhLayout::kPacked;
  return BvhLayout::kCompact;
}

const char* bvh_layout_name(BvhLayout layout) {
  switch (layout) {
    case BvhLayout::kAuto: return "auto";
    case BvhLayout::kDefault: return "default";
    case BvhLayout::kPacked: return "packed";
    case BvhLayout::kCompact: return "compact";
  }
  return "?";
}

BvhLayout parse_bvh_layout(std::string_view name) {
  for (BvhLayout l : {BvhLayout::kAuto, BvhLayout::kDefault, BvhLayout::kPacked, BvhLayout::kCompact})
    if (name == bvh_layout_name(l)) return l;
  throw Error("must be \"auto\", \"default\", \"packed\" or \"compact\", got \"" + std::string(name) + "\"");
}

}  // namespace torte
