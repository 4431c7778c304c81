// Material types and their parameter tables. The renderer shades hits in wavefronts: hits are counting-sorted by
// MaterialType and each type's queue is evaluated by one kernel templated on the type (see render/shade.h), so
// there is no virtual call per hit. Adding a material type = a parameter struct here + a BSDF kernel.
#pragma once
#include <cstdint>
#include <vector>

#include "core/rgb.h"

namespace torte {

enum class MaterialType : uint8_t { Lambert, Count };
constexpr int kMaterialTypeCount = int(MaterialType::Count);

// 8 bytes: which table and which row.
struct MaterialRef {
  MaterialType type = MaterialType::Lambert;
  uint32_t index = 0;
};

struct LambertParams {
  Rgb albedo{0.5f};
};

// One array per material type (structure of arrays across types).
struct MaterialTables {
  std::vector<LambertParams> lambert;
};

}  // namespace torte
