// Runs a scene script: a Lua state with the torte module, the script's key=value arguments, and errors
// reported as one line with the script location.
#pragma once
#include <lua.h>

#include <atomic>
#include <string>
#include <utility>
#include <vector>

namespace torte::lua {

struct RunOptions {
  std::string script;
  std::vector<std::pair<std::string, std::string>> args;  // key=value from the command line
  int spp_override = -1;
  int64_t seed_override = -1;
  bool quiet = false;
  const std::atomic<bool>* cancel = nullptr;
};

enum ExitCode { kExitOk = 0, kExitError = 1, kExitInterrupted = 130 };

struct RunContext;

/// Adds the torte module to L (global `torte` and `require "torte"`, the embedded Lua modules, torte.args from
/// `options`); the Lua standard libraries must be open. For run_script, fuzz harnesses and tests.
void open_torte_module(lua_State* L, const RunOptions& options);
/// Makes `ctx` the RunContext the bindings of L consult (run_context(L)); it must outlive L.
void set_run_context(lua_State* L, RunContext* ctx);

// Returns the process exit code; errors are printed to stderr as "torte: error: <file>:<line>: <message>".
int run_script(const RunOptions& options);

}  // namespace torte::lua
