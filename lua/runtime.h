// Runs a scene script: a Lua state with the torte module, the script's key=value arguments, and errors
// reported as one line with the script location.
#pragma once
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

// Returns the process exit code; errors are printed to stderr as "torte: error: <file>:<line>: <message>".
int run_script(const RunOptions& options);

}  // namespace torte::lua
