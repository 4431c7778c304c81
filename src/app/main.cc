// The torte command line: torte [options] scene.lua [key=value ...]
#include <tbb/global_control.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include "runtime.h"

namespace {

std::atomic<bool> g_interrupted{false};

void on_sigint(int) {
  // First Ctrl-C: stop rendering and write what is there. A second one kills the process the default way.
  g_interrupted.store(true);
  std::signal(SIGINT, SIG_DFL);
}

const char kUsage[] =
    "usage: torte [options] scene.lua [key=value ...]\n"
    "\n"
    "Runs a Lua scene script. key=value pairs reach the script as the table torte.args (and as `...`);\n"
    "values that look like numbers or true/false are converted.\n"
    "\n"
    "options:\n"
    "  --threads N   render with N threads (default: all cores)\n"
    "  --spp N       override every render's samples per pixel\n"
    "  --seed N      override every render's random seed\n"
    "  --quiet       no progress or summary on stderr\n"
    "  --help        show this help\n"
    "  --version     show the version\n"
    "\n"
    "Ctrl-C stops a render and still writes the image with the samples done so far.\n";

[[noreturn]] void usage_error(const std::string& msg) {
  std::fprintf(stderr, "torte: error: %s (see 'torte --help')\n", msg.c_str());
  std::exit(torte::lua::kExitError);
}

long parse_count(const char* option, const char* value, long min) {
  if (!value) usage_error(std::string(option) + " needs a value");
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(value, &end, 10);
  if (errno != 0 || end == value || *end != '\0' || v < min)
    usage_error(std::string(option) + " expects an integer >= " + std::to_string(min) + ", got '" + value + "'");
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  torte::lua::RunOptions options;
  int threads = 0;
  int i = 1;
  for (; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (a == "--version") {
      std::printf("torte %s\n", TORTE_VERSION);
      return 0;
    } else if (a == "--quiet" || a == "-q") {
      options.quiet = true;
    } else if (a == "--threads") {
      threads = int(parse_count("--threads", i + 1 < argc ? argv[++i] : nullptr, 1));
    } else if (a == "--spp") {
      options.spp_override = int(parse_count("--spp", i + 1 < argc ? argv[++i] : nullptr, 1));
    } else if (a == "--seed") {
      options.seed_override = parse_count("--seed", i + 1 < argc ? argv[++i] : nullptr, 0);
    } else if (a == "--") {
      ++i;
      break;
    } else if (a.size() > 1 && a[0] == '-') {
      usage_error("unknown option '" + a + "'");
    } else {
      break;
    }
  }
  if (i >= argc) usage_error("no scene script given");
  options.script = argv[i++];
  for (; i < argc; ++i) {
    const std::string a = argv[i];
    const size_t eq = a.find('=');
    if (eq == std::string::npos || eq == 0)
      usage_error("scene arguments must be key=value, got '" + a + "'");
    options.args.emplace_back(a.substr(0, eq), a.substr(eq + 1));
  }

  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(threads));
  options.cancel = &g_interrupted;
  std::signal(SIGINT, on_sigint);
  const int code = torte::lua::run_script(options);
  if (g_interrupted.load() && code == torte::lua::kExitOk) return torte::lua::kExitInterrupted;
  return code;
}
