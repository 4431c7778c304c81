// The torte command line: torte [options] scene.lua [key=value ...]
#include <tbb/global_control.h>

#include <charconv>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <limits>
#include <memory>
#include <string>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/memory_budget.h"
#include "distributed/session.h"
#include "runtime.h"

namespace {

void on_sigint(int) {
  // First Ctrl-C: renders stop between tiles, Lua code at its next instruction (a hook), scene building at its
  // next safe point; the script may still save a stopped render's image. A second one kills the process.
  torte::request_interrupt();
  torte::lua::interrupt_running_script();
  std::signal(SIGINT, SIG_DFL);
}

const std::string kUsage =
    "usage: torte [options] scene.lua [key=value ...]\n"
    "\n"
    "Runs a Lua scene script. key=value pairs reach the script as the table torte.args (and as `...`);\n"
    "values that look like numbers or true/false are converted.\n"
    "\n"
    "options:\n"
    "  --aovs LIST             add AOV layers to every render's image, e.g. albedo,normal,depth (also position,\n"
    "                          material_id); EXR outputs hold them as layers\n"
    "  --denoise               denoise every render (feature-guided; the noisy image is kept as layer 'noisy')\n"
    "  --threads N             render with N threads (default: all cores)\n"
    "  --spp N                 override every render's samples per pixel\n"
    "  --seed N                override every render's random seed\n"
    "  --quiet                 no progress or summary on stderr\n"
    "  --stats                 after every render, time, calls and rays per render stage on stderr\n"
    "  --exposure STOPS        display outputs (PNG, JPEG): scale by 2^STOPS (overrides the script's exposure)\n"
    "  --tonemap VIEW          display outputs: view transform standard, filmic (ACES) or agx (overrides the\n"
    "                          script's tonemap)\n"
    "  --checkpoint FILE       write each render's film to FILE every --checkpoint-every seconds and on Ctrl-C\n"
    "                          (atomically: FILE.tmp, then renamed)\n"
    "  --checkpoint-every S    seconds between checkpoints (default: 60)\n"
    "  --resume FILE           continue the render FILE was written for (same script, arguments and settings)\n"
    "                          to the image an uninterrupted render makes, bit for bit\n"
    "  --max-memory SIZE       the memory torte may use, e.g. 8G or 512M (default: 3/4 of the RAM)\n"
    "  --lua-memory SIZE       the memory the script's Lua heap may hold (default: half of --max-memory)\n"
    "  --lua-instructions N    stop the script after N Lua instructions (default: 0, no limit; under\n"
    "                          --sandbox " + std::to_string(torte::lua::kSandboxInstructions) + ")\n"
    "  --sandbox               run an untrusted script: no programs, C modules, environment or debug\n"
    "                          library; reads only below the script's directory, writes only below ./out\n"
    "                          and in the directory of output= (docs/security.md)\n"
    "  --allow-read DIR        with --sandbox: the script may also read below DIR (repeatable)\n"
    "  --allow-write DIR       with --sandbox: the script may also write (and read) below DIR (repeatable)\n"
    "  --help                  show this help\n"
    "  --version               show the version\n"
    "\n"
    "Ctrl-C stops a render and still writes the image with the samples done so far; it stops Lua code and\n"
    "scene building too (exit code 130). A second Ctrl-C kills torte.\n";

[[noreturn]] void usage_error(const std::string& msg) {
  std::fprintf(stderr, "torte: error: %s (see 'torte --help')\n", msg.c_str());
  std::exit(torte::lua::kExitError);
}

// The value after `option`; advances i.
const char* option_value(int argc, char** argv, int& i, const char* option) {
  if (i + 1 >= argc) usage_error(std::string(option) + " needs a value");
  return argv[++i];
}

// A decimal integer in [min, max], the whole of `value`; anything else (also a value that overflows 64 bits) is
// an error naming the option and the range.
int64_t parse_integer(const char* option, const char* value, int64_t min, int64_t max) {
  int64_t v = 0;
  const char* end = value + std::strlen(value);
  const auto [ptr, ec] = std::from_chars(value, end, v);
  if (ec != std::errc() || ptr != end || end == value || v < min || v > max)
    usage_error(std::string(option) + " expects an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                "], got '" + value + "'");
  return v;
}

// A finite number of stops in [-64, 64], the whole of `value`.
float parse_stops(const char* option, const char* value) {
  double v = 0;
  const char* end = value + std::strlen(value);
  const auto [ptr, ec] = std::from_chars(value, end, v);
  if (ec != std::errc() || ptr != end || end == value || !(v >= -64 && v <= 64))
    usage_error(std::string(option) + " expects a number of stops in [-64, 64], got '" + value + "'");
  return float(v);
}

uint64_t parse_size(const char* option, const char* value, uint64_t min) {
  uint64_t bytes = 0;
  try {
    bytes = torte::parse_byte_size(value);
  } catch (const torte::Error& e) {
    usage_error(std::string(option) + ": " + e.what());
  }
  if (bytes < min)
    usage_error(std::string(option) + " expects a size of at least " + torte::format_bytes(min) + ", got '" + value +
                "'");
  return bytes;
}

}  // namespace

int main(int argc, char** argv) {
  torte::dist::init(&argc, &argv);  // under mpirun or srun: this process is one rank of a distributed render
  torte::lua::RunOptions options;
  constexpr int64_t kIntMax = std::numeric_limits<int>::max();
  constexpr int64_t kInt64Max = std::numeric_limits<int64_t>::max();
  int threads = 0;
  bool restricted_paths = false;  // --allow-read / --allow-write given
  int i = 1;
  for (; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage.c_str(), stdout);
      return 0;
    } else if (a == "--version") {
      std::printf("torte %s\n", TORTE_VERSION);
      return 0;
    } else if (a == "--quiet" || a == "-q") {
      options.quiet = true;
    } else if (a == "--stats") {
      options.stats = true;
    } else if (a == "--exposure") {
      options.exposure_override = parse_stops("--exposure", option_value(argc, argv, i, "--exposure"));
    } else if (a == "--tonemap") {
      const char* v = option_value(argc, argv, i, "--tonemap");
      torte::ViewTransform view;
      if (!torte::parse_view_transform(v, view))
        usage_error(std::string("--tonemap expects ") + torte::kViewTransformChoices + ", got '" + v + "'");
      options.tonemap_override = view;
    } else if (a == "--aovs") {
      const std::string list = option_value(argc, argv, i, "--aovs");
      for (size_t start = 0; start <= list.size();) {
        const size_t comma = std::min(list.find(',', start), list.size());
        const std::string name = list.substr(start, comma - start);
        torte::Aov aov;
        if (!torte::parse_aov(name, aov))
          usage_error("--aovs: unknown AOV '" + name + "' (known: " + torte::kAovChoices + ")");
        options.aovs.push_back(aov);
        start = comma + 1;
      }
    } else if (a == "--denoise") {
      options.denoise = true;
    } else if (a == "--threads") {
      threads = int(parse_integer("--threads", option_value(argc, argv, i, "--threads"), 1, 4096));
    } else if (a == "--spp") {
      options.spp_override = int(parse_integer("--spp", option_value(argc, argv, i, "--spp"), 1, kIntMax));
    } else if (a == "--seed") {
      options.seed_override = parse_integer("--seed", option_value(argc, argv, i, "--seed"), 0, kInt64Max);
    } else if (a == "--checkpoint") {
      options.checkpoint = option_value(argc, argv, i, "--checkpoint");
    } else if (a == "--checkpoint-every") {
      options.checkpoint_every =
          double(parse_integer("--checkpoint-every", option_value(argc, argv, i, "--checkpoint-every"), 0, 1 << 30));
    } else if (a == "--resume") {
      options.resume = option_value(argc, argv, i, "--resume");
    } else if (a == "--max-memory") {
      torte::set_memory_limit(parse_size("--max-memory", option_value(argc, argv, i, "--max-memory"), 1 << 20));
    } else if (a == "--lua-memory") {
      options.lua_memory = parse_size("--lua-memory", option_value(argc, argv, i, "--lua-memory"), 1 << 20);
    } else if (a == "--lua-instructions") {
      options.lua_instructions =
          parse_integer("--lua-instructions", option_value(argc, argv, i, "--lua-instructions"), 0, kInt64Max);
    } else if (a == "--sandbox") {
      options.sandbox = true;
    } else if (a == "--allow-read") {
      options.allow_read.push_back(option_value(argc, argv, i, "--allow-read"));
      restricted_paths = true;
    } else if (a == "--allow-write") {
      options.allow_write.push_back(option_value(argc, argv, i, "--allow-write"));
      restricted_paths = true;
    } else if (a == "--") {
      ++i;
      break;
    } else if (a.size() > 1 && a[0] == '-') {
      usage_error("unknown option '" + a + "'");
    } else {
      break;
    }
  }
  if (restricted_paths && !options.sandbox)
    usage_error("--allow-read and --allow-write only apply with --sandbox (without it every path is allowed)");
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
  options.cancel = &torte::interrupt_flag();
  std::signal(SIGINT, on_sigint);
  if (torte::dist::distributed()) {
    // mpirun turns Ctrl-C into SIGTERM for every rank: stop the same way, so rank 0 writes the partial image.
    std::signal(SIGTERM, on_sigint);
    options.error_prefix = "rank " + std::to_string(torte::dist::rank()) + ": ";
    if (torte::dist::rank() != 0) options.quiet = true;  // rank 0 prints the progress and the summary
  }
  return torte::dist::finish(torte::lua::run_script(options));
}
