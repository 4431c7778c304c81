#include "distributed/work_queue.h"

#include <mpi.h>

#include <chrono>
#include <cstring>
#include <thread>

#include "core/error.h"
#include "distributed/session.h"

namespace torte::dist {

namespace {

enum Tag : int { kResult = 1, kWork = 2, kDone = 3, kStats = 4 };

// Messages are flat byte strings: appended and read in the same order on both sides (same build, same ABI).
struct Out {
  std::vector<char> bytes;
  void put(const void* p, size_t n) { bytes.insert(bytes.end(), (const char*)p, (const char*)p + n); }
  template <class T>
  void value(const T& v) { put(&v, sizeof v); }
};
struct In {
  const std::vector<char>& bytes;
  size_t at = 0;
  void get(void* p, size_t n) {
    if (at + n > bytes.size()) throw Error("distributed render: a message from another rank is cut short");
    std::memcpy(p, bytes.data() + at, n);
    at += n;
  }
  template <class T>
  T value() {
    T v;
    get(&v, sizeof v);
    return v;
  }
};

// The tile's rows of the film's sums, and of its luminance moments when it keeps them (every rank's film does or
// none does: the settings are the same), appended to or read from a message.
void put_tile(Out& o, const Film& film, const TileRect& r) {
  const size_t n = size_t(r.x1 - r.x0);
  for (int y = r.y0; y < r.y1; ++y) {
    const size_t at = size_t(y) * size_t(film.width()) + size_t(r.x0);
    o.put(&film.sums()[at], sizeof(PixelSum) * n);
    if (!film.moments().empty()) o.put(&film.moments()[at], sizeof(float) * n);
  }
}
void get_tile(In& in, Film& film, const TileRect& r) {
  const size_t n = size_t(r.x1 - r.x0);
  for (int y = r.y0; y < r.y1; ++y) {
    const size_t at = size_t(y) * size_t(film.width()) + size_t(r.x0);
    in.get(&film.sums()[at], sizeof(PixelSum) * n);
    if (!film.moments().empty()) in.get(&film.moments()[at], sizeof(float) * n);
  }
}

std::vector<char> receive(int source, int tag, MPI_Status* status_out = nullptr) {
  MPI_Status status;
  MPI_Probe(source, tag, MPI_COMM_WORLD, &status);
  int n = 0;
  MPI_Get_count(&status, MPI_BYTE, &n);
  std::vector<char> bytes(static_cast<size_t>(n));
  MPI_Recv(bytes.data(), n, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  if (status_out) *status_out = status;
  return bytes;
}

void send(const Out& o, int dest, int tag) {
  MPI_Send(o.bytes.data(), int(o.bytes.size()), MPI_BYTE, dest, tag, MPI_COMM_WORLD);
}

}  // namespace

Coordinator::Coordinator(std::vector<TileRect> tiles, std::vector<int> passes, size_t pass, std::vector<uint8_t> done,
                         Film& film, Hooks hooks)
    : tiles_(std::move(tiles)), passes_(std::move(passes)), pass_(pass), done_(std::move(done)), film_(film),
      hooks_(std::move(hooks)) {
  if (pass_ >= passes_.size()) return;
  hooks_.begin_pass(pass_);
  for (uint32_t t = 0; t < tiles_.size(); ++t)
    if (done_[t]) ++done_count_; else queue_.push_back(t);
}

bool Coordinator::over_locked() const { return stopped_ || pass_ >= passes_.size(); }

void Coordinator::advance_locked() {
  if (draining_ && out_ == 0) {  // a checkpoint was due: nothing is out now, the film is consistent
    hooks_.save();
    draining_ = false;
  }
  if (pass_ >= passes_.size() || done_count_ < tiles_.size()) return;
  hooks_.end_pass();
  ++pass_;
  std::fill(done_.begin(), done_.end(), uint8_t(0));
  done_count_ = 0;
  if (pass_ < passes_.size() && !hooks_.stop()) {
    hooks_.begin_pass(pass_);
    for (uint32_t t = 0; t < tiles_.size(); ++t) queue_.push_back(t);
  }
}

std::optional<std::vector<uint32_t>> Coordinator::take_locked(size_t n) {
  if (!stopped_ && hooks_.stop()) stopped_ = true;
  if (over_locked()) return std::vector<uint32_t>();
  if (!draining_ && out_ > 0 && hooks_.checkpoint_due()) draining_ = true;
  if (!draining_ && out_ == 0 && hooks_.checkpoint_due()) hooks_.save();
  if (draining_ || queue_.empty()) return std::nullopt;
  std::vector<uint32_t> out;
  while (out.size() < n && !queue_.empty()) {
    out.push_back(queue_.front());
    queue_.pop_front();
  }
  out_ += out.size();
  return out;
}

std::optional<std::pair<size_t, uint32_t>> Coordinator::next_local() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    const auto got = take_locked(1);
    if (got && got->empty()) return std::nullopt;
    if (got) return std::make_pair(pass_, (*got)[0]);
    changed_.wait_for(lock, std::chrono::milliseconds(20));  // also rechecks stop()
  }
}

void Coordinator::local_done(uint32_t tile) {
  const std::lock_guard<std::mutex> lock(mutex_);
  --out_;
  done_[tile] = 1;
  ++done_count_;
  hooks_.tile_done(tile);
  advance_locked();
  changed_.notify_all();
}

std::vector<uint64_t> Coordinator::serve() {
  const int n = ranks();
  std::vector<uint64_t> totals(5, 0);
  std::vector<int> threads(size_t(n), 1);
  std::vector<int> waiting;
  int open = n - 1, stats_due = n - 1;  // ranks not told the render is over; ranks whose final counts are due
  while (open > 0 || stats_due > 0) {
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
    if (flag) {
      const std::vector<char> bytes = receive(status.MPI_SOURCE, status.MPI_TAG);
      In in{bytes};
      if (status.MPI_TAG == kStats) {
        for (uint64_t& t : totals) t += in.value<uint64_t>();
        --stats_due;
      } else if (status.MPI_TAG == kResult) {
        threads[size_t(status.MPI_SOURCE)] = std::max(1, in.value<int32_t>());
        const uint32_t count = in.value<uint32_t>();
        uint64_t counters[5];
        in.get(counters, sizeof counters);
        const std::lock_guard<std::mutex> lock(mutex_);
        uint64_t samples = 0;
        for (uint32_t i = 0; i < count; ++i) {
          const uint32_t t = in.value<uint32_t>();
          const bool rendered = in.value<uint8_t>() != 0;
          if (t >= tiles_.size()) throw Error("distributed render: a rank returned an unknown tile");
          --out_;
          if (!rendered) {  // the rank was stopped before this tile: it goes back to the queue
            queue_.push_front(t);
            continue;
          }
          get_tile(in, film_, tiles_[t]);
          ++remote_units_;
          SplatBuffer splats;
          const uint64_t ns = in.value<uint64_t>();
          for (uint64_t s = 0; s < ns; ++s) splats.append(in.value<SplatBuffer::Splat>());
          if (ns > 0) hooks_.splats(t, std::move(splats));
          done_[t] = 1;
          ++done_count_;
          hooks_.tile_done(t);
          const TileRect& r = tiles_[t];
          samples += uint64_t(r.x1 - r.x0) * uint64_t(r.y1 - r.y0) * uint64_t(passes_[pass_]);
        }
        hooks_.progress(samples, counters);
        advance_locked();
        changed_.notify_all();
        waiting.push_back(status.MPI_SOURCE);
      }
    }
    bool served = false;
    for (size_t i = 0; i < waiting.size();) {
      const int r = waiting[i];
      Out o;
      bool over = false;
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        const auto got = take_locked(size_t(threads[size_t(r)]));
        if (!got) {
          ++i;
          continue;
        }
        over = got->empty();
        if (!over) {
          int first = 0;
          for (size_t p = 0; p < pass_; ++p) first += passes_[p];
          o.value(uint32_t(pass_));
          o.value(int32_t(first));
          o.value(int32_t(passes_[pass_]));
          o.value(uint32_t(got->size()));
          for (const uint32_t t : *got) {
            o.value(t);
            put_tile(o, film_, tiles_[t]);
          }
        }
      }
      send(o, r, over ? kDone : kWork);
      if (over) --open;
      waiting.erase(waiting.begin() + ptrdiff_t(i));
      served = true;
    }
    if (!flag && !served) std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return totals;
}

Client::Client(std::vector<TileRect> tiles, Film& film, int threads)
    : tiles_(std::move(tiles)), film_(film), threads_(threads) {}

bool Client::next(Batch& batch) {
  Out o;
  o.value(int32_t(threads_));
  o.value(uint32_t(first_ ? 0 : batch_.tiles.size()));
  o.put(counters_, sizeof counters_);
  std::fill(counters_, counters_ + 5, uint64_t(0));
  if (!first_) {
    for (size_t i = 0; i < batch_.tiles.size(); ++i) {
      const uint32_t t = batch_.tiles[i];
      o.value(t);
      o.value(uint8_t(rendered_[i]));
      if (!rendered_[i]) continue;
      put_tile(o, film_, tiles_[t]);
      o.value(uint64_t(splats_[i].size()));
      o.put(splats_[i].splats().data(), splats_[i].splats().size_bytes());
    }
  }
  first_ = false;
  send(o, 0, kResult);
  MPI_Status status;
  const std::vector<char> bytes = receive(0, MPI_ANY_TAG, &status);
  if (status.MPI_TAG == kDone) return false;
  In in{bytes};
  batch_.pass = in.value<uint32_t>();
  batch_.first_sample = in.value<int32_t>();
  batch_.pass_spp = in.value<int32_t>();
  batch_.tiles.resize(in.value<uint32_t>());
  for (uint32_t& t : batch_.tiles) {
    t = in.value<uint32_t>();
    if (t >= tiles_.size()) throw Error("distributed render: rank 0 sent an unknown tile");
    get_tile(in, film_, tiles_[t]);
  }
  rendered_.assign(batch_.tiles.size(), 0);
  splats_.assign(batch_.tiles.size(), SplatBuffer());
  batch = batch_;
  return true;
}

void Client::rendered(size_t i, SplatBuffer* splats) {
  rendered_[i] = 1;
  if (splats) splats_[i] = std::move(*splats);
}

void Client::count(const uint64_t counters[5]) {
  for (int i = 0; i < 5; ++i) counters_[i] += counters[i];
}

void Client::finish(const uint64_t counters[5]) {
  Out o;
  o.put(counters, sizeof(uint64_t) * 5);
  send(o, 0, kStats);
}

}  // namespace torte::dist
