// An ITT collector that tells ThreadSanitizer about the hand-offs inside Debian's libtbb, which is not built with
// TSan: without them every parallel_for looks like a race between the thread that prepared the data and the
// worker that reads it. libtbb loads this library when INTEL_LIBITTNOTIFY64 names it (the TSan build's ctest
// environment does) and then calls these functions; everything else in the ITT API stays unimplemented (null).
//
// The edges given to TSan:
// - fork: TBB notifies "releasing" on a task before spawning it (headers built with TBB_USE_PROFILING_TOOLS=1)
//   and enters every task through stack_callee_enter. Each release also goes to one process-wide clock that
//   every task start acquires, so a task sees everything its spawner (and every earlier spawner) did before.
// - join: a finished task "releases" its wait_context; the waiting thread "acquires" it when the wait returns.
// - TBB's internal locks, notified by libtbb the same way.
// Races between task bodies that run at the same time are still reported: nothing orders two running tasks. The
// process-wide clock is coarser than TBB's real edges (a task start is ordered after every earlier release,
// including other tasks' ends), so a conflict between two tasks that happened not to overlap can be missed.
#include <sanitizer/tsan_interface.h>

namespace {
char process_clock;  // the address TSan keeps the all-spawns clock for
char caller_id;      // a non-null __itt_caller, so libtbb calls stack_callee_enter
}  // namespace

extern "C" {
__attribute__((visibility("default"))) int __itt_api_version() { return 1; }  // ITT API v1: look every name up

__attribute__((visibility("default"))) void __itt_sync_releasing(void* addr) {
  __tsan_release(addr);
  __tsan_release(&process_clock);
}
__attribute__((visibility("default"))) void __itt_sync_acquired(void* addr) { __tsan_acquire(addr); }

__attribute__((visibility("default"))) void* __itt_stack_caller_create() { return &caller_id; }
__attribute__((visibility("default"))) void __itt_stack_caller_destroy(void*) {}
__attribute__((visibility("default"))) void __itt_stack_callee_enter(void*) { __tsan_acquire(&process_clock); }
__attribute__((visibility("default"))) void __itt_stack_callee_leave(void*) {}
}
