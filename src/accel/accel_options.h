// How a scene's triangles are laid out for tracing, from the fastest to the smallest: the default layout
// (WideNode<8> + TriangleLeaves), packed (WideNode<8> + PackedLeaves: the leaves' bytes halved for a few percent of
// speed) and compact (QuantNode + PackedLeaves, accel/compact_bvh.h: the nodes halved too, at a larger cost),
// picked by hand or by a memory budget.
#pragma once
#include <cstdint>
#include <string_view>

namespace torte {

enum class BvhLayout : uint8_t {
  kAuto,  // the fastest layout whose estimate fits the budget (resolve_layout), compact when none does
  kDefault,
  kPacked,
  kCompact,
};

/// The scene's choice (torte.scene{...} / torte.render{...}: bvh_layout, memory_budget).
struct AccelOptions {
  BvhLayout layout = BvhLayout::kAuto;
  uint64_t memory_budget = 0;  // bytes; 0: the process's memory limit (core/memory_budget.h)
  bool operator==(const AccelOptions&) const = default;
};

/// Bytes per triangle each layout's acceleration data takes, for the estimate (the dragon's figures in
/// accel/shape_set.h, rounded up): default nodes 6.8 + leaves 36.1, packed 6.8 + 18.9.
constexpr uint64_t kDefaultLayoutBytesPerTriangle = 44;
constexpr uint64_t kPackedLayoutBytesPerTriangle = 26;

/// The options' layout when it is not kAuto; else the first of kDefault and kPacked for which the process's
/// resident memory now (the meshes are loaded) plus `triangles` at its bytes per triangle fits the budget, and
/// kCompact when neither does.
BvhLayout resolve_layout(const AccelOptions& options, uint64_t triangles);

/// "auto", "default", "packed", "compact".
const char* bvh_layout_name(BvhLayout layout);
/// The layout named `name`; throws torte::Error naming the accepted names otherwise.
BvhLayout parse_bvh_layout(std::string_view name);

}  // namespace torte
