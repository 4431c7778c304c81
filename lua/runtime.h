// Runs a scene script: a Lua state with the torte module, the script's key=value arguments, and errors
// reported as one line with the script location.
#pragma once
#include <lua.h>

#include <atomic>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "film/view_transform.h"
#include "render/aov_pass.h"

namespace torte::lua {

struct RunOptions {
  std::string script;
  std::vector<std::pair<std::string, std::string>> args;  // key=value from the command line
  int spp_override = -1;
  int64_t seed_override = -1;
  std::optional<double> time_limit_override;      // --time-limit SECONDS
  std::optional<float> noise_threshold_override;  // --noise-threshold X
  bool quiet = false;
  bool stats = false;  // --stats: a per-stage profile (render/stage_stats.h) on stderr after every render
  // --exposure, --tonemap: override what scripts pass to image:write / torte.save for display outputs.
  std::optional<float> exposure_override;
  std::optional<ViewTransform> tonemap_override;
  std::vector<Aov> aovs;  // --aovs: AOV layers added to every render
  bool denoise = false;   // --denoise: every render is denoised (its noisy image kept as a layer)
  const std::atomic<bool>* cancel = nullptr;  // renders stop when it becomes true (main: torte::interrupt_flag())
  // --checkpoint FILE, --checkpoint-every SECONDS, --resume FILE (render/render_control.h)
  std::string checkpoint, resume;
  double checkpoint_every = 60;
  std::string error_prefix;  // put before error messages ("rank 1: " under mpirun)
  // --sandbox (docs/security.md): the restricted libraries and the file policy of lua/sandbox.h.
  bool sandbox = false;
  std::vector<std::string> allow_read, allow_write;  // --allow-read DIR, --allow-write DIR
  // Lua instructions the script may run: -1 the default (kSandboxInstructions under --sandbox, else no
  // limit), 0 no limit.
  int64_t lua_instructions = -1;
  uint64_t lua_memory = 0;  // bytes the Lua heap may hold; 0: the default, half of torte::memory_limit()
  std::string outfile;     // -o/--outfile (main also passes it as the scene argument output=)
  bool quick = false;      // --quick: renders at a quarter of the size and at most kQuickSpp (torte.quick)
  bool list_args = false;  // --list-args: the script stops at torte.options, which prints its arguments
};

/// --quick: every torte.render's width and height divided by kQuickDivisor (rounded up) and spp at most kQuickSpp
/// (an explicit --spp still wins).
inline constexpr int kQuickDivisor = 4;
inline constexpr int kQuickSpp = 4;

/// The instruction budget of --sandbox unless --lua-instructions says otherwise: about 85 times what the
/// busiest shipped scene runs (minecraft.lua on the largest shipped world; docs/security.md has the numbers),
/// and about half a minute of Lua.
inline constexpr int64_t kSandboxInstructions = 10'000'000'000;

enum ExitCode { kExitOk = 0, kExitError = 1, kExitInterrupted = 130 };

struct RunContext;

/// Adds the torte module to L (global `torte` and `require "torte"`, the embedded Lua modules, torte.args from
/// `options`); the Lua standard libraries must be open. For run_script, fuzz harnesses and tests.
void open_torte_module(lua_State* L, const RunOptions& options);
/// Makes `ctx` the RunContext the bindings of L consult (run_context(L)); it must outlive L.
void set_run_context(lua_State* L, RunContext* ctx);

/// Runs the script; returns the process exit code. Errors are printed to stderr as one line, "torte: error:
/// <file>:<line>: <message>"; a run ended by Ctrl-C exits with kExitInterrupted and at most one line
/// ("torte: interrupted while ...").
int run_script(const RunOptions& options);

/// A path a script gives a loader (torte.mesh.load, shape.mesh{file}, image textures, environment maps; not the
/// file primitives of torte.data, which like io.open keep the working directory): absolute paths and "" are returned as they are; a relative one resolves against the script's own
/// directory (torte.script_dir), or against the working directory when it names nothing there but something
/// in the working directory (paths typed as scene arguments on the command line).
std::string resolve_script_path(lua_State* L, const std::string& path);

/// For the SIGINT handler, after torte::request_interrupt(): makes the running script stop at its next Lua
/// instruction (lua/script_limits.h; a render that is running stops between tiles by itself). Async-signal-safe.
void interrupt_running_script() noexcept;

}  // namespace torte::lua
