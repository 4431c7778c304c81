#include "texture/color_map.h"

#include <algorithm>

namespace torte {

Rgb eval_spline(const Rgb* colors, const float* positions, int count, bool linear, float x) {
  if (count <= 0) return Rgb(0);
  if (count == 1 || !(x > positions[0])) return colors[0];  // also catches NaN
  if (x >= positions[count - 1]) return colors[count - 1];
  // Segment k: positions[k] <= x < positions[k + 1].
  const int k = int(std::upper_bound(positions, positions + count, x) - positions) - 1;
  const float t = (x - positions[k]) / (positions[k + 1] - positions[k]);
  const Rgb p1 = colors[k], p2 = colors[k + 1];
  if (linear) return p1 + (p2 - p1) * t;
  const Rgb p0 = colors[std::max(k - 1, 0)], p3 = colors[std::min(k + 2, count - 1)];
  const float t2 = t * t, t3 = t2 * t;
  // 0.5 * (2 p1 + (-p0 + p2) t + (2 p0 - 5 p1 + 4 p2 - p3) t^2 + (-p0 + 3 p1 - 3 p2 + p3) t^3)
  const Rgb c = (p1 * 2 + (p2 - p0) * t + (p0 * 2 - p1 * 5 + p2 * 4 - p3) * t2 + (p1 * 3 - p0 - p2 * 3 + p3) * t3) * 0.5f;
  return {std::max(c.r, 0.0f), std::max(c.g, 0.0f), std::max(c.b, 0.0f)};
}

}  // namespace torte
