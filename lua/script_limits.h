// The limits of a running scene script, each ending it with one line that names the script's file and line:
// the Lua memory cap (a lua_Alloc that counts), the Lua instruction budget (a count hook) and Ctrl-C (a hook the
// SIGINT handler arms in the running thread, so `while true do end` stops too). docs/security.md lists them.
#pragma once
#include <lua.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

namespace torte::lua {

struct ScriptLimitSettings {
  uint64_t instructions = 0;  // Lua VM instructions the script may run; 0: no limit (and no hook until Ctrl-C)
  uint64_t memory = 0;        // bytes the Lua heap may hold; 0: no cap
};

/// After Ctrl-C stopped a render, the script goes on for this long so it can save the partial image; then the
/// hook ends it like any interrupted script.
inline constexpr std::chrono::seconds kInterruptGrace{10};

class ScriptLimits {
 public:
  explicit ScriptLimits(const ScriptLimitSettings& settings) : settings_(settings) {}
  ~ScriptLimits() { stop(); }
  ScriptLimits(const ScriptLimits&) = delete;
  ScriptLimits& operator=(const ScriptLimits&) = delete;

  /// A new Lua state whose allocations count against the memory cap; nullptr when even that fails.
  lua_State* new_state();
  /// Makes L (from new_state) the running script: the hooks find these limits, interrupt_scripts() reaches L,
  /// and the instruction hook is installed when there is a budget. Needs the base library open.
  void start(lua_State* L);
  /// Undoes start; call before lua_close.
  void stop();

  /// When the memory cap (or the system) refused an allocation: "Lua memory limit of 1.0 GB reached ...",
  /// preceded by "<file>:<line>:" of the refusal when `with_location`; else "".
  std::string memory_error(bool with_location) const;
  /// What ended the script by Ctrl-C ("interrupted while running the script") and where, or "" if nothing did.
  const std::string& interrupt_message() const { return interrupt_message_; }
  const std::string& interrupt_location() const { return interrupt_location_; }

  uint64_t instructions() const { return instructions_; }
  uint64_t memory_used() const { return used_; }
  uint64_t memory_peak() const { return peak_; }
  const ScriptLimitSettings& settings() const { return settings_; }

  // For the hooks and the coroutine wrappers (script_limits.cc).
  void on_hook(lua_State* L, int event);
  void arm(lua_State* L);
  void note_render_interrupted();
  [[noreturn]] void raise_interrupt(lua_State* L, const std::string& what);
  std::atomic<lua_State*> main{nullptr}, current{nullptr};  // the main thread; the coroutine it runs, if any

 private:
  static void* allocate(void* ud, void* ptr, size_t osize, size_t nsize) noexcept;
  void refuse(size_t more, bool by_cap) noexcept;

  ScriptLimitSettings settings_;
  uint64_t instructions_ = 0;
  uint64_t used_ = 0, peak_ = 0;
  bool over_ = false;  // the cap refused an allocation and the heap has not shrunk below it since
  uint64_t refused_bytes_ = 0, refused_held_ = 0;  // the last refusal: asked for, and held at the time
  bool refused_by_cap_ = false;                     // by the cap, or by the system
  std::string refused_where_;
  bool render_interrupted_ = false;
  std::chrono::steady_clock::time_point render_interrupted_at_;
  std::string interrupt_message_, interrupt_location_;
};

/// The limits of the script L belongs to, or nullptr (a state that ScriptLimits::start did not set up).
ScriptLimits* script_limits(lua_State* L);

/// Async-signal-safe: arms a hook in the running script's thread (and in the coroutine it is resuming) that
/// ends the script at its next Lua instruction, unless a render has just given the script its grace period.
void interrupt_scripts() noexcept;
/// Raises the Lua error by which Ctrl-C ends the run ("<file>:<line>: interrupted while ..."); the runtime then
/// exits with 130 and prints the message without "error". For a state without limits, a plain Lua error.
[[noreturn]] void raise_interrupted(lua_State* L, const std::string& what);
/// torte.render calls this when it returns while Ctrl-C is pending: the script may go on for kInterruptGrace to
/// save what the render made.
void note_render_interrupted(lua_State* L);
/// "<file>:<line>:" of the innermost frame on L's stack that runs a script file (a chunk loaded from a file,
/// not the embedded library or a string), or "" when there is none.
std::string script_location(lua_State* L);
/// Replaces coroutine.resume and coroutine.wrap by versions that keep ScriptLimits::current up to date, so
/// Ctrl-C also stops a loop inside a coroutine. Needs the coroutine library open and start() done.
void track_coroutines(lua_State* L);

}  // namespace torte::lua
