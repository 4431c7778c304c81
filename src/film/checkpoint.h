// Checkpoints of a render: the film's raw sums at a point where every tile of the pass in progress is either
// done or not started, with what the tile loop needs to continue from there (render/tile_loop.h) to the same
// image, bit for bit, as a render that was never stopped.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "film/film.h"

namespace torte {

struct Checkpoint {
  /// What the image depends on, as "name=value" fields joined by ';' (settings, scene fingerprint); a resume
  /// refuses a checkpoint whose key differs.
  std::string key;
  uint32_t pass = 0;               // index of the pass in progress (the pass count once all are done)
  std::vector<uint8_t> tile_done;  // per tile: done in that pass
  // Splats of done tiles that are not merged yet (the tile loop merges in tile order), by tile index.
  std::vector<std::pair<uint32_t, SplatBuffer>> pending;
  // RenderStats counters so far: camera, extension and shadow rays, dropped samples, samples done.
  uint64_t counters[5] = {};
  Film film;
};

/// Writes `c` to `path` atomically: to "<path>.tmp", flushed to disk, then renamed over `path`, so an
/// interruption (or a crash) at any moment leaves the previous checkpoint or the new one. Throws torte::Error.
void write_checkpoint(const std::string& path, const Checkpoint& c);

/// Reads a checkpoint written by write_checkpoint. Throws torte::Error naming the file when it cannot be read,
/// is not a torte checkpoint or is cut short, and when its key differs from `expected_key` (naming the first
/// field that differs, with both values).
Checkpoint read_checkpoint(const std::string& path, const std::string& expected_key);

}  // namespace torte
