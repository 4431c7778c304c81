// What the harnesses share: a scratch directory per process, and a Lua state set up as lua/runtime.cc does
// (standard libraries, the torte module, torte.prelude) with bounded work: a Lua instruction budget and a cap
// on the Lua allocator, so a fuzzed script that loops or grows tables fails with a Lua error instead of a
// libFuzzer timeout or out-of-memory report.
#pragma once
#include <lua.h>

#include <cstdint>
#include <string>
#include <string_view>

#include "types.h"

namespace torte::fuzz {

/// A directory private to this process ($TMPDIR, else /dev/shm, else /tmp: torte-fuzz-<pid>), created on first
/// use and removed at exit. Harnesses write the files they need only here.
const std::string& scratch_dir();
/// scratch_dir() + "/" + name.
std::string scratch_path(std::string_view name);
/// Writes `bytes` to `path` (throws std::runtime_error when it cannot).
void write_file(const std::string& path, std::string_view bytes);
/// TORTE_FUZZ_VERBOSE=1: harnesses print what each input did (errors raised, results), to check by hand that
/// seeds reach what they should.
bool verbose();
/// A copy of the process's stderr taken before any QuietStderr (src/core/quiet_stderr.h) points fd 2 at
/// /dev/null around OpenImageIO calls: broken promises and sanitizer reports are written there, so a crash inside
/// such a call is still explained.
int report_fd();
/// Limits for every harness process: one TBB worker and one OpenImageIO thread (deterministic, and fair to the
/// other processes on the machine), quiet progress, and torte's memory budget lowered below libFuzzer's RSS
/// limit so over-large requests fail with torte's own error.
void init_process();

class FuzzLua {
 public:
  /// `lua_memory_cap`: bytes the Lua allocator may hold at once. With `line_coverage`, in libFuzzer builds, a
  /// line hook reports the Lua lines run as extra coverage counters (the Lua library itself is not instrumented),
  /// so the fuzzer sees progress through Lua code such as lua/minecraft/*.lua; harnesses whose Lua is only
  /// their own glue leave it off (every loop count would be a new feature).
  explicit FuzzLua(size_t lua_memory_cap = size_t(256) << 20, bool line_coverage = false);
  ~FuzzLua();
  FuzzLua(const FuzzLua&) = delete;
  FuzzLua& operator=(const FuzzLua&) = delete;

  lua_State* state() const { return L_; }
  /// Allows `instructions` more Lua VM instructions (counted in steps of 1000) before the hook raises
  /// "instruction budget exhausted".
  void set_instruction_budget(uint64_t instructions) { budget_ = instructions; }
  bool budget_exhausted() const { return budget_ == 0; }
  /// Calls `fn` (light userdata `ud` as its one argument) protected; false and the message when it raised.
  bool call(lua_CFunction fn, void* ud, std::string* error = nullptr);
  /// Runs Lua source (a chunk returning at most one value, left on the stack on success).
  bool run(std::string_view source, std::string* error = nullptr);
  size_t lua_bytes() const { return used_; }

 private:
  static void* alloc(void* ud, void* ptr, size_t osize, size_t nsize);
  static void hook(lua_State* L, lua_Debug*);
  lua_State* L_ = nullptr;
  lua::RunContext ctx_;
  size_t cap_, used_ = 0;
  uint64_t budget_ = 10'000'000;
};

}  // namespace torte::fuzz
