// The torte command line: torte [options] scene.lua [key=value ...], parsed with CLI11; options may come
// before or after the script, as `--opt value` or `--opt=value`.
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>

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
#include "simd/simd_target.h"
#include "version.h"

namespace {

void on_sigint(int) {
  // First Ctrl-C: renders stop between tiles, Lua code at its next instruction (a hook), scene building at its
  // next safe point; the script may still save a stopped render's image. A second one kills the process.
  torte::request_interrupt();
  torte::lua::interrupt_running_script();
  std::signal(SIGINT, SIG_DFL);
}

const char kUsageLine[] = "usage: torte [options] scene.lua|model.gltf|model.glb [key=value ...]";
const std::string kDescription =
    "Runs a Lua scene script. key=value pairs reach the script as the table torte.args (and as `...`); values\n"
    "that look like numbers or true/false are converted. Options may come before or after the script. A glTF\n"
    "file in the script's place is rendered directly (docs/formats.md; torte --list-args model.glb).";
const std::string kFooter =
    "Ctrl-C stops a render and still writes the image with the samples done so far; it stops Lua code and\n"
    "scene building too (exit code 130). A second Ctrl-C kills torte.";

// CLI11's help with torte's usage line first (CLI11 would print "Usage: torte [OPTIONS] ...").
class Formatter : public CLI::Formatter {
 public:
  std::string make_usage(const CLI::App*, std::string) const override {
    return std::string(kUsageLine) + "\n\n" + kDescription + "\n";
  }
};

[[noreturn]] void usage_error(const std::string& msg) {
  std::string line = msg;
  std::replace_if(line.begin(), line.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  std::fprintf(stderr, "torte: error: %s (see 'torte --help')\n", line.c_str());
  std::exit(torte::lua::kExitError);
}

// A decimal integer in [min, max], the whole of `value`; anything else (also a value that overflows 64 bits) is
// an error naming the option and the range.
int64_t parse_integer(const char* option, const std::string& value, int64_t min, int64_t max) {
  int64_t v = 0;
  const char* end = value.data() + value.size();
  const auto [ptr, ec] = std::from_chars(value.data(), end, v);
  if (ec != std::errc() || ptr != end || value.empty() || v < min || v > max)
    usage_error(std::string(option) + " expects an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                "], got '" + value + "'");
  return v;
}

// A number in [min, max], the whole of `value`; `what` names it in the error ("a number of stops").
double parse_number(const char* option, const std::string& value, double min, double max,
                    const char* what = "a number") {
  double v = 0;
  const char* end = value.data() + value.size();
  const auto [ptr, ec] = std::from_chars(value.data(), end, v);
  if (ec != std::errc() || ptr != end || value.empty() || !(v >= min && v <= max)) {
    char range[64];
    std::snprintf(range, sizeof range, " in [%g, %g]", min, max);
    usage_error(std::string(option) + " expects " + what + range + ", got '" + value + "'");
  }
  return v;
}

float parse_stops(const char* option, const std::string& value) {
  return float(parse_number(option, value, -64, 64, "a number of stops"));
}

uint64_t parse_size(const char* option, const std::string& value, uint64_t min) {
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

// The option values as given (strings, checked by the parsers above so errors read the same for every option).
struct Given {
  std::string aovs, threads, spp, seed, time_limit, noise_threshold, exposure, tonemap, checkpoint_every, max_memory, lua_memory,
      lua_instructions, simd = "auto";
  std::vector<std::string> positionals;  // the script, then key=value arguments
};

}  // namespace

int main(int argc, char** argv) {
  torte::dist::init(&argc, &argv);  // under mpirun or srun: this process is one rank of a distributed render
  torte::lua::RunOptions options;
  constexpr int64_t kIntMax = std::numeric_limits<int>::max();
  constexpr int64_t kInt64Max = std::numeric_limits<int64_t>::max();
  Given g;
  bool version = false;

  CLI::App app("", "torte");  // the description is part of the usage text (Formatter)
  app.formatter(std::make_shared<Formatter>());
  app.footer(kFooter);
  app.allow_extras();  // unknown options are reported below, one line naming them
  app.get_formatter()->column_width(30);
  app.set_help_flag("-h,--help", "show this help");
  app.add_flag("--version", version, "show the version, compiler, SIMD targets and build options");
  app.add_option("-o,--outfile", options.outfile,
                 "write the image to FILE: sets the scene argument output=FILE, over an output= given too")
      ->option_text("FILE");
  app.add_flag("--quick", options.quick,
               "a quick look: every torte.render at a quarter of its width and height and at most 4 spp "
               "(torte.quick is true for the script)");
  app.add_flag("--list-args", options.list_args,
               "print the scene's arguments (its torte.options) with defaults and types, and exit");
  app.add_option("--aovs", g.aovs,
                 "add AOV layers to every render's image, e.g. albedo,normal,depth (also position, material_id, "
                 "emission, samples, variance, traversal_cost, glossiness); "
                 "EXR outputs hold them as layers")
      ->option_text("LIST");
  app.add_flag("--denoise", options.denoise,
               "denoise every render (feature-guided; the noisy image is kept as layer 'noisy')");
  app.add_option("--threads", g.threads, "render with N threads (default: all cores)")->option_text("N");
  app.add_option("--spp", g.spp, "override every render's samples per pixel")->option_text("N");
  app.add_option("--seed", g.seed, "override every render's random seed")->option_text("N");
  app.add_option("--time-limit", g.time_limit,
                 "stop every render at the first pass boundary after S seconds (the image holds the passes done)")
      ->option_text("S");
  app.add_option("--noise-threshold", g.noise_threshold,
                 "adaptive sampling for every render: a pixel stops when its relative error is below X (e.g. 0.01)")
      ->option_text("X");
  app.add_option("--simd", g.simd,
                 std::string("the SIMD target of the kernels and the render loop: ") + torte::simd::kTargetChoices +
                     " (default auto: the best this CPU runs)")
      ->option_text("TARGET");
  app.add_flag("-q,--quiet", options.quiet, "no progress or summary on stderr");
  app.add_flag("--stats", options.stats,
               "scene statistics after each build (triangles, BVH nodes, bytes per triangle by part, build time, "
               "peak memory) and time, calls and rays per render stage after every render, on stderr");
  app.add_option("--exposure", g.exposure,
                 "display outputs (PNG, JPEG): scale by 2^STOPS (overrides the script's exposure)")
      ->option_text("STOPS");
  app.add_option("--tonemap", g.tonemap,
                 "display outputs: view transform standard, filmic (ACES) or agx (overrides the script's tonemap)")
      ->option_text("VIEW");
  app.add_option("--checkpoint", options.checkpoint,
                 "write each render's film to FILE every --checkpoint-every seconds and on Ctrl-C (atomically: "
                 "FILE.tmp, then renamed)")
      ->option_text("FILE");
  app.add_option("--checkpoint-every", g.checkpoint_every, "seconds between checkpoints (default: 60)")
      ->option_text("S");
  app.add_option("--resume", options.resume,
                 "continue the render FILE was written for (same script, arguments and settings) to the image an "
                 "uninterrupted render makes, bit for bit")
      ->option_text("FILE");
  app.add_option("--max-memory", g.max_memory, "the memory torte may use, e.g. 8G or 512M (default: 3/4 of the RAM)")
      ->option_text("SIZE");
  app.add_option("--lua-memory", g.lua_memory,
                 "the memory the script's Lua heap may hold (default: half of --max-memory)")
      ->option_text("SIZE");
  app.add_option("--lua-instructions", g.lua_instructions,
                 "stop the script after N Lua instructions (default: 0, no limit; under --sandbox " +
                     std::to_string(torte::lua::kSandboxInstructions) + ")")
      ->option_text("N");
  app.add_flag("--sandbox", options.sandbox,
               "run an untrusted script: no programs, C modules, environment or debug library; reads only below "
               "the script's directory, writes only below ./out and in the directory of output= "
               "(docs/security.md)");
  // One directory per --allow-read or --allow-write (repeatable): a vector option would swallow the script too.
  app.add_option("--allow-read", options.allow_read, "with --sandbox: the script may also read below DIR (repeatable)")
      ->option_text("DIR")
      ->allow_extra_args(false);
  app.add_option("--allow-write", options.allow_write,
                 "with --sandbox: the script may also write (and read) below DIR (repeatable)")
      ->option_text("DIR")
      ->allow_extra_args(false);
  app.add_option("script", g.positionals, "the scene script, then its key=value arguments")
      ->option_text("scene.lua|model.glb [key=value ...]");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::ParseError& e) {
    usage_error(e.what());
  }
  bool after_separator = false;  // CLI11 leaves "--" and what follows it to us: scene arguments
  for (const std::string& extra : app.remaining()) {
    if (after_separator) {
      g.positionals.push_back(extra);
    } else if (extra == "--") {
      after_separator = true;
    } else {
      const bool option = extra.size() > 1 && extra[0] == '-';
      usage_error(option ? "unknown option '" + extra.substr(0, extra.find('=')) + "'"  // --name=value: the name
                         : "unexpected argument '" + extra + "'");
    }
  }

  try {
    torte::simd::use_target(g.simd);
  } catch (const torte::Error& e) {
    usage_error(std::string("--simd: ") + e.what());
  }
  if (version) {
    std::fputs(torte::app::version_text().c_str(), stdout);
    return 0;
  }
  if (!g.aovs.empty()) {
    for (size_t start = 0; start <= g.aovs.size();) {
      const size_t comma = std::min(g.aovs.find(',', start), g.aovs.size());
      const std::string name = g.aovs.substr(start, comma - start);
      torte::Aov aov;
      if (!torte::parse_aov(name, aov))
        usage_error("--aovs: unknown AOV '" + name + "' (known: " + torte::kAovChoices + ")");
      options.aovs.push_back(aov);
      start = comma + 1;
    }
  }
  const int threads = g.threads.empty() ? 0 : int(parse_integer("--threads", g.threads, 1, 4096));
  if (!g.spp.empty()) options.spp_override = int(parse_integer("--spp", g.spp, 1, kIntMax));
  if (!g.seed.empty()) options.seed_override = parse_integer("--seed", g.seed, 0, kInt64Max);
  if (!g.time_limit.empty()) options.time_limit_override = parse_number("--time-limit", g.time_limit, 0, 1e9);
  if (!g.noise_threshold.empty())
    options.noise_threshold_override = float(parse_number("--noise-threshold", g.noise_threshold, 0, 1e3));
  if (!g.exposure.empty()) options.exposure_override = parse_stops("--exposure", g.exposure);
  if (!g.tonemap.empty()) {
    torte::ViewTransform view;
    if (!torte::parse_view_transform(g.tonemap, view))
      usage_error(std::string("--tonemap expects ") + torte::kViewTransformChoices + ", got '" + g.tonemap + "'");
    options.tonemap_override = view;
  }
  if (!g.checkpoint_every.empty())
    options.checkpoint_every = double(parse_integer("--checkpoint-every", g.checkpoint_every, 0, 1 << 30));
  if (!g.max_memory.empty()) torte::set_memory_limit(parse_size("--max-memory", g.max_memory, 1 << 20));
  if (!g.lua_memory.empty()) options.lua_memory = parse_size("--lua-memory", g.lua_memory, 1 << 20);
  if (!g.lua_instructions.empty())
    options.lua_instructions = parse_integer("--lua-instructions", g.lua_instructions, 0, kInt64Max);
  if ((!options.allow_read.empty() || !options.allow_write.empty()) && !options.sandbox)
    usage_error("--allow-read and --allow-write only apply with --sandbox (without it every path is allowed)");
  if (g.positionals.empty()) usage_error("no scene script given");
  options.script = g.positionals[0];
  for (size_t i = 1; i < g.positionals.size(); ++i) {
    const std::string& a = g.positionals[i];
    const size_t eq = a.find('=');
    if (eq == std::string::npos || eq == 0) usage_error("scene arguments must be key=value, got '" + a + "'");
    options.args.emplace_back(a.substr(0, eq), a.substr(eq + 1));
  }
  if (!options.outfile.empty()) {  // -o wins over output=: drop those, the runtime adds output=FILE
    std::erase_if(options.args, [](const auto& kv) { return kv.first == "output"; });
    options.args.emplace_back("output", options.outfile);
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
