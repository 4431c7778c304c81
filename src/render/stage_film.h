// Stage: finished camera paths to the film, in path order (a batch's pixels belong to its tile alone).
#pragma once
#include "film/film.h"
#include "render/path_state.h"
#include "render/render_settings.h"

namespace torte {

/// Adds every path's radiance to its pixel; non-finite estimates are counted and dropped.
inline void accumulate_samples(const PathState& paths, Film& film, RenderStats& stats) {
  for (size_t i = 0; i < paths.size(); ++i) {
    const Rgb& L = paths.radiance[i];
    ++stats.samples_done;
    if (!L.is_finite()) {
      ++stats.dropped_samples;
      continue;
    }
    film.add_sample(paths.pixel[i], L, paths.filter_weight[i]);
  }
}

}  // namespace torte
