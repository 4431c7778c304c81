// torte's executor seam: every parallel loop, fork and reduction of the renderer goes through these templates.
// They forward to oneTBB (the scheduler of the product). In ThreadSanitizer builds they also make TBB's hand-offs
// visible to TSan: Debian's libtbb is not instrumented, so TSan cannot see that spawning a task orders what the
// spawner did before it, or that waiting for a loop orders its tasks before what follows, and every loop would be
// reported as races on its data and on the scheduler's recycled memory. tests/sanitizers/README.md has the details.
#pragma once
#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#if defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define TORTE_TSAN 1
#endif
#endif
#if defined(__SANITIZE_THREAD__)  // GCC's spelling
#define TORTE_TSAN 1
#endif
#ifdef TORTE_TSAN
#include <tbb/task_scheduler_observer.h>
extern "C" void __tsan_acquire(void* addr);
extern "C" void __tsan_release(void* addr);
extern "C" void __tsan_ignore_thread_begin();
extern "C" void __tsan_ignore_thread_end();
#endif

namespace torte {

/// The half-open index block [begin, end) a blocked loop body receives (the seam's stand-in for tbb::blocked_range).
template <class T>
class IndexRange {
 public:
  IndexRange(T begin, T end) : begin_(begin), end_(end) {}
  T begin() const { return begin_; }
  T end() const { return end_; }
  size_t size() const { return size_t(end_ - begin_); }

 private:
  T begin_, end_;
};

/// How a loop is cut into tasks: `automatic` lets the scheduler pick block sizes (at least the grain) and adapt
/// them to stealing; `each_block` makes every grain-sized block (every index, for the per-index loops) its own
/// task, for loops whose iterations vary a lot in cost (render tiles, voxel subtrees).
enum class Split { automatic, each_block };

/// Per-thread instances of T, created on a thread's first `local()` and iterable after the loops that used
/// them; what one thread's instance holds is visible to the code after the loop's join.
template <class T>
using PerThread = tbb::enumerable_thread_specific<T>;

namespace detail {

// TSan's view of the scheduler (annotations, no-ops elsewhere). Two things are added:
// - The happens-before edges of each fork-join, as TSan sync objects (ForkJoin: only its members' addresses
//   matter): released before any task is spawned and acquired by every task when it starts (`fork`); released by
//   every task when it ends, also by an exception, and acquired by the caller once the wait returns (`join`).
//   Tasks never acquire `join`, so sibling tasks stay unordered and races between them are still reported.
// - Threads ignore their own memory accesses while they run scheduler code, i.e. between entering TBB through
//   this seam and starting a task body, and between a body's end and the next. libtbb recycles task objects and
//   the waiting thread's stack; the inline half of TBB (its headers) does atomics on them after a body's end, and
//   without libtbb's side of those atomics TSan would pair them with torte's next use of that memory. Bodies,
//   and everything torte runs outside loops, stay fully checked.
#ifdef TORTE_TSAN
inline constexpr bool kAnnotateForTsan = true;
inline thread_local bool t_in_scheduler = false;  // this thread's accesses are being ignored
inline void hb_release(void* sync) { __tsan_release(sync); }
inline void hb_acquire(void* sync) { __tsan_acquire(sync); }
inline void scheduler_enter() {
  __tsan_ignore_thread_begin();
  t_in_scheduler = true;
}
inline void scheduler_leave() {
  __tsan_ignore_thread_end();
  t_in_scheduler = false;
}
// Worker threads are in scheduler code whenever they are in the arena outside a body: they ignore from entering
// it, and stop when they leave it (a thread must not exit ignoring: TSan aborts).
class WorkerIgnores : public tbb::task_scheduler_observer {
 public:
  WorkerIgnores() { observe(true); }
  void on_scheduler_entry(bool is_worker) override {
    if (is_worker && !t_in_scheduler) scheduler_enter();
  }
  void on_scheduler_exit(bool is_worker) override {
    if (is_worker && t_in_scheduler) scheduler_leave();
  }
};
// Before the first loop starts workers; never destroyed, as workers may leave the arena during exit.
inline void observe_workers() {
  [[maybe_unused]] static const WorkerIgnores* const observer = new WorkerIgnores;
}
#else
inline constexpr bool kAnnotateForTsan = false;
inline constexpr bool t_in_scheduler = true;
inline void hb_release(void*) {}
inline void hb_acquire(void*) {}
inline void scheduler_enter() {}
inline void scheduler_leave() {}
inline void observe_workers() {}
#endif

struct ForkJoin {
  char fork, join;  // never read or written (a store could pair with the scheduler's use of recycled stack)
  // The caller's side: the fork edge, then scheduler code until the wait returns, then the join edge.
  ForkJoin() {
    observe_workers();
    hb_release(&fork);
    scheduler_enter();
  }
  ~ForkJoin() {
    scheduler_leave();
    hb_acquire(&join);
  }
  ForkJoin(const ForkJoin&) = delete;
  ForkJoin& operator=(const ForkJoin&) = delete;

  // A task body's side.
  class Task {
   public:
    explicit Task(ForkJoin& fj) : fj_(fj) {
      if (t_in_scheduler) scheduler_leave();
      hb_acquire(&fj_.fork);
    }
    ~Task() {
      hb_release(&fj_.join);
      scheduler_enter();
    }
    Task(const Task&) = delete;
    Task& operator=(const Task&) = delete;

   private:
    ForkJoin& fj_;
  };
  // A reduction's join step combines results of finished tasks: it acquires `join` (so it sees them, and every
  // other task of this reduction finished so far) and releases its own result into it.
  class Combine {
   public:
    explicit Combine(ForkJoin& fj) : fj_(fj) {
      if (t_in_scheduler) scheduler_leave();
      hb_acquire(&fj_.fork);
      hb_acquire(&fj_.join);
    }
    ~Combine() {
      hb_release(&fj_.join);
      scheduler_enter();
    }
    Combine(const Combine&) = delete;
    Combine& operator=(const Combine&) = delete;

   private:
    ForkJoin& fj_;
  };
};

template <class It, class Less>
void merge_sort_for_tsan(It first, It last, const Less& less);

}  // namespace detail

/// Calls fn(i) for every i in [begin, end), concurrently, and returns when all calls have (an exception thrown by
/// a call is rethrown here, the remaining calls may or may not run). Calls must not depend on each other's order.
template <class T, class Fn>
void parallel_for(T begin, std::type_identity_t<T> end, const Fn& fn, Split split = Split::automatic) {
  if constexpr (detail::kAnnotateForTsan) {
    detail::ForkJoin fj;
    const auto task = [&](T i) {
      detail::ForkJoin::Task t(fj);
      fn(i);
    };
    if (split == Split::each_block)
      tbb::parallel_for(begin, end, task, tbb::simple_partitioner());
    else
      tbb::parallel_for(begin, end, task);
  } else if (split == Split::each_block) {
    tbb::parallel_for(begin, end, fn, tbb::simple_partitioner());
  } else {
    tbb::parallel_for(begin, end, fn);
  }
}

/// Calls fn(IndexRange<T>) on disjoint blocks covering [begin, end), concurrently; blocks hold at least `grain`
/// indices unless the range is shorter (`Split::each_block`: about `grain`). Exceptions as in parallel_for.
template <class T, class Fn>
void parallel_for_blocks(T begin, std::type_identity_t<T> end, size_t grain, const Fn& fn,
                         Split split = Split::automatic) {
  const tbb::blocked_range<T> range(begin, end, grain);
  if constexpr (detail::kAnnotateForTsan) {
    detail::ForkJoin fj;
    const auto task = [&](const tbb::blocked_range<T>& r) {
      detail::ForkJoin::Task t(fj);
      fn(IndexRange<T>(r.begin(), r.end()));
    };
    if (split == Split::each_block)
      tbb::parallel_for(range, task, tbb::simple_partitioner());
    else
      tbb::parallel_for(range, task);
  } else {
    const auto task = [&](const tbb::blocked_range<T>& r) { fn(IndexRange<T>(r.begin(), r.end())); };
    if (split == Split::each_block)
      tbb::parallel_for(range, task, tbb::simple_partitioner());
    else
      tbb::parallel_for(range, task);
  }
}

/// Reduces [begin, end) in blocks of at least `grain`: body(IndexRange<T>, const V& acc) returns acc with the
/// block folded in, join(V a, const V& b) returns a combined with b (a's block precedes b's), both starting from
/// copies of `identity`. How the range is cut varies from run to run: the result is deterministic only if the
/// combination is exact in any grouping (integer sums, min/max).
template <class T, class V, class Body, class Join>
V parallel_reduce(T begin, std::type_identity_t<T> end, size_t grain, const V& identity, const Body& body,
                  const Join& join) {
  const tbb::blocked_range<T> range(begin, end, grain);
  if constexpr (detail::kAnnotateForTsan) {
    detail::ForkJoin fj;
    return tbb::parallel_reduce(
        range, identity,
        [&](const tbb::blocked_range<T>& r, const V& acc) {
          detail::ForkJoin::Task t(fj);
          return body(IndexRange<T>(r.begin(), r.end()), acc);
        },
        [&](const V& a, const V& b) {
          detail::ForkJoin::Combine c(fj);
          return join(a, b);
        });
  } else {
    return tbb::parallel_reduce(
        range, identity, [&](const tbb::blocked_range<T>& r, const V& acc) { return body(IndexRange<T>(r.begin(), r.end()), acc); },
        [&](const V& a, const V& b) { return join(a, b); });
  }
}

/// Runs f() and g(), possibly concurrently, and returns when both have (exceptions as in parallel_for).
template <class F, class G>
void parallel_invoke(const F& f, const G& g) {
  if constexpr (detail::kAnnotateForTsan) {
    detail::ForkJoin fj;
    tbb::parallel_invoke(
        [&] {
          detail::ForkJoin::Task t(fj);
          f();
        },
        [&] {
          detail::ForkJoin::Task t(fj);
          g();
        });
  } else {
    tbb::parallel_invoke(f, g);
  }
}

/// Sorts [first, last) by `less` (a strict weak order), in parallel; not stable. Under TSan it is a merge sort
/// over parallel_invoke: tbb::parallel_sort moves elements inside TBB's uninstrumented range splitting, which no
/// fork-join annotation reaches. Both give the same order when no two elements are equivalent.
template <class It, class Less>
void parallel_sort(It first, It last, const Less& less) {
  if constexpr (detail::kAnnotateForTsan)
    detail::merge_sort_for_tsan(first, last, less);
  else
    tbb::parallel_sort(first, last, less);
}

namespace detail {

template <class It, class Less>
void merge_sort_for_tsan(It first, It last, const Less& less) {
  constexpr std::ptrdiff_t kSerial = 2048;
  if (last - first <= kSerial) {
    std::sort(first, last, less);
    return;
  }
  const It mid = first + (last - first) / 2;
  parallel_invoke([&] { merge_sort_for_tsan(first, mid, less); }, [&] { merge_sort_for_tsan(mid, last, less); });
  std::inplace_merge(first, mid, last, less);
}

}  // namespace detail

}  // namespace torte
