// How a scene's triangles are laid out for tracing: the default layout (WideNode<8> + TriangleLeaves, fastest)
// or the compact one (QuantNode + PackedLeaves, accel/compact_bvh.h), picked by hand or by a memory budget.
#pragma once
#include <cstdint>
#include <string_view>

namespace torte {

enum class BvhLayout : uint8_t {
  kAuto,     // compact when the default layout's estimate exceeds the budget (resolve_layout), else default
  kDefault,
  kCompact,
};

/// The scene's choice (torte.scene{...} / torte.render{...}: bvh_layout, memory_budget).
struct AccelOptions {
  BvhLayout layout = BvhLayout::kAuto;
  uint64_t memory_budget = 0;  // bytes; 0: the process's memory limit (core/memory_budget.h)
  bool operator==(const AccelOptions&) const = default;
};

/// Bytes per triangle the default layout's acceleration data takes, for the estimate (nodes 6.8, leaves 36.1,
/// the dragon's figures in accel/shape_set.h, rounded up).
constexpr uint64_t kDefaultLayoutBytesPerTriangle = 44;

/// kDefault or kCompact: the options' layout when it is not kAuto; else kCompact when the process's resident
/// memory now (the meshes are loaded) plus `triangles` at kDefaultLayoutBytesPerTriangle exceeds the budget.
BvhLayout resolve_layout(const AccelOptions& options, uint64_t triangles);

/// "auto", "default", "compact".
const char* bvh_layout_name(BvhLayout layout);
/// The layout named `name`; throws torte::Error naming the accepted names otherwise.
BvhLayout parse_bvh_layout(std::string_view name);

}  // namespace torte
