// Colour maps: a scalar in, a colour out.
#pragma once
#include <vector>

#include "core/rgb.h"

namespace torte {

// A colour spline through (positions[i], colors[i]), positions strictly increasing. x is clamped to
// [positions.front(), positions.back()]. Catmull-Rom (uniform in each segment's parameter, end points repeated)
// passes through every knot with a continuous first derivative; it can overshoot, so results are clamped at 0.
// Linear interpolates between neighbouring knots.
Rgb eval_spline(const Rgb* colors, const float* positions, int count, bool linear, float x);

}  // namespace torte
