// The MPI work queue of a distributed render (docs/distributed.md). Work units are (tile, pass): rank 0 hands
// them out on request, in batches, from the tiles of the pass in progress; a rank gets the tiles' current sums
// with the batch and returns them with the batch's samples added (and its splats), so every pixel sums its
// samples in the same order as a render in one process, whatever rank renders which unit: the image is the same,
// bit for bit, for any number of ranks. Passes are barriers (integrators such as IGI draw per-pass state).
// Only the server thread of rank 0 and the main thread of the other ranks call MPI during a render.
#pragma once
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <vector>

#include "film/film.h"

namespace torte::dist {

struct TileRect {
  int x0, y0, x1, y1;
};

/// Rank 0's side: the queue of the pass's tiles, shared by its own render threads and, through serve(), by
/// the other ranks. Every hook runs with the queue's lock held, so hooks need no locking of their own.
class Coordinator {
 public:
  struct Hooks {
    std::function<void(size_t pass)> begin_pass;       // before any tile of `pass` is handed out
    std::function<void()> end_pass;                    // every tile of the pass is done
    std::function<void(uint32_t tile)> tile_done;      // one tile of the pass is done (its sums are in the film)
    std::function<void(uint32_t tile, SplatBuffer&&)> splats;  // a remote tile's splats, before tile_done
    std::function<bool()> stop;                        // Ctrl-C or a failure: hand out nothing more
    std::function<bool()> checkpoint_due;              // stop handing out, and once nothing is out, save()
    std::function<void()> save;
    // A remote batch's samples and counters (camera, extension, shadow rays, dropped samples, samples done).
    std::function<void(uint64_t samples, const uint64_t counters[5])> progress;
  };
  /// `done`: per tile, done in pass `pass` already (a resumed render); `film` is rank 0's film.
  Coordinator(std::vector<TileRect> tiles, std::vector<int> passes, size_t pass, std::vector<uint8_t> done,
              Film& film, Hooks hooks);

  /// For rank 0's render threads: the next (pass, tile), waiting while the pass's last tiles are out; nothing
  /// once the render is over (all passes done, or stopped).
  std::optional<std::pair<size_t, uint32_t>> next_local();
  void local_done(uint32_t tile);
  /// The server loop (a thread of its own): answers the other ranks until each has been told the render is
  /// over; returns the counts their drivers add at the end (Client::finish), summed.
  std::vector<uint64_t> serve();
  size_t pass() const { return pass_; }
  /// Units rendered by the other ranks and returned so far (the summary's load balance).
  uint64_t remote_units() const { return remote_units_; }
  const std::vector<uint8_t>& done() const { return done_; }

 private:
  void advance_locked();
  bool over_locked() const;
  std::optional<std::vector<uint32_t>> take_locked(size_t n);  // nothing: wait; empty: the render is over

  std::vector<TileRect> tiles_;
  std::vector<int> passes_;
  size_t pass_;
  std::vector<uint8_t> done_;
  Film& film_;
  Hooks hooks_;
  std::mutex mutex_;
  std::condition_variable changed_;
  uint64_t remote_units_ = 0;
  std::deque<uint32_t> queue_;  // tiles of the pass not handed out
  size_t out_ = 0;              // tiles handed out, not returned
  size_t done_count_ = 0;
  bool stopped_ = false;
  bool draining_ = false;       // a checkpoint is due: nothing handed out until the units out are back
};

/// The other ranks' side: asks rank 0 for batches of units and returns their results.
class Client {
 public:
  Client(std::vector<TileRect> tiles, Film& film, int threads);
  struct Batch {
    size_t pass;
    int first_sample, pass_spp;
    std::vector<uint32_t> tiles;
  };
  /// Sends the results of the previous batch (or the first request) and receives the next batch, whose tiles'
  /// sums are then in the film; false when rank 0 says the render is over.
  bool next(Batch& batch);
  /// Records tile `i` of the batch as rendered (with its splats, for integrators that splat).
  void rendered(size_t i, SplatBuffer* splats);
  /// Adds to the counters sent with the batch's results (rays, dropped samples, samples done).
  void count(const uint64_t counters[5]);
  /// After next() returned false: sends the driver's own counts (e.g. IGI's light paths) to rank 0.
  void finish(const uint64_t counters[5]);

 private:
  std::vector<TileRect> tiles_;
  Film& film_;
  int threads_;
  bool first_ = true;
  Batch batch_;
  std::vector<uint8_t> rendered_;
  std::vector<SplatBuffer> splats_;
  uint64_t counters_[5] = {};
};

}  // namespace torte::dist
