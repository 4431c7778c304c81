#include "runtime.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string_view>

#include "core/interrupt.h"
#include "core/memory_budget.h"
#include "core/text.h"
#include "distributed/session.h"
#include "progress.h"
#include "sandbox.h"
#include "script_libs.h"
#include "script_limits.h"
#include "text_chunks.h"
#include "types.h"

namespace torte {
struct EmbeddedLua {
  const char* name;
  const char* source;
};
extern const EmbeddedLua kEmbeddedLua[];  // generated from lua/torte/*.lua and lua/minecraft/*.lua by scripts/embed-lua.cmake
}  // namespace torte

namespace torte::lua {

namespace {

const char kContextKey = 0;  // its address keys the RunContext in the Lua registry

// Converts a command-line value: numbers and true/false get their Lua types, anything else stays a string.
void push_arg_value(lua_State* L, const std::string& v) {
  if (v == "true" || v == "false") {
    lua_pushboolean(L, v == "true");
    return;
  }
  if (!v.empty() && lua_stringtonumber(L, v.c_str()) == v.size() + 1) return;
  lua_pushstring(L, v.c_str());
}

// The values of output=FILE arguments: the sandbox lets the script write in their directories.
std::vector<std::string> output_arguments(const RunOptions& options) {
  std::vector<std::string> out;
  for (const auto& [key, value] : options.args)
    if (key == "output" && !value.empty()) out.push_back(value);
  return out;
}

int load_embedded(lua_State* L) {
  const char* name = lua_tostring(L, 1);
  for (const EmbeddedLua* e = kEmbeddedLua; e->name; ++e)
    if (std::strcmp(e->name, name) == 0) {
      const std::string chunk = std::string("=[torte] ") + e->name;
      if (luaL_loadbufferx(L, e->source, std::strlen(e->source), chunk.c_str(), "t") != LUA_OK) return lua_error(L);
      lua_call(L, 0, 1);
      return 1;
    }
  return luaL_error(L, "module '%s' is not embedded", name);
}

// Whether msg starts with the location of a script file ("scene.lua:12: ..."), not of the embedded library
// ("[torte] minecraft.world:170: ..."), a string chunk ("[string \"...\"]:1: ...") or nothing.
bool located_in_file(const std::string& msg) {
  const size_t colon = msg.find(':');
  if (colon == std::string::npos || colon == 0 || msg[0] == '[') return false;
  size_t i = colon + 1;
  while (i < msg.size() && msg[i] >= '0' && msg[i] <= '9') ++i;
  return i > colon + 1 && i < msg.size() && msg[i] == ':';
}

// Message handler: the error as one line that names the script's file and line. Errors without a location
// (C stack overflow, errors from inside Lua's libraries or torte's embedded Lua, error values that are not
// strings) get the innermost frame of a script file in front.
int message_handler(lua_State* L) {
  ScriptLimits* limits = script_limits(L);
  std::string msg;
  try {
    if (lua_type(L, 1) == LUA_TSTRING || lua_type(L, 1) == LUA_TNUMBER) {
      msg = lua_tostring(L, 1);
    } else if (luaL_getmetafield(L, 1, "__tostring") != LUA_TNIL) {
      // Protected: a failing __tostring (or the hooks stopping it) must not turn this error into another one.
      lua_pushvalue(L, 1);
      if (lua_pcall(L, 1, 1, 0) == LUA_OK && lua_type(L, -1) == LUA_TSTRING)
        msg = lua_tostring(L, -1);
      else
        msg = "(error object is a " + type_name(L, 1) + " value whose __tostring failed)";
    } else {
      msg = "(error object is a " + type_name(L, 1) + " value)";
    }
    // A refusal by the Lua memory cap that a script caught and raised again says which limit it was.
    constexpr std::string_view kNoMemory = "not enough memory";
    if (limits && std::string_view(msg).ends_with(kNoMemory)) {
      const std::string what = limits->memory_error(false);
      if (!what.empty()) msg = msg.substr(0, msg.size() - kNoMemory.size()) + what;
    }
    if (!located_in_file(msg)) {
      const std::string where = script_location(L);
      if (!where.empty()) msg = where + " " + msg;
    }
  } catch (const std::exception&) {  // the C++ heap is exhausted too
    msg = "out of memory while reporting an error";
  }
  lua_pushstring(L, msg.c_str());
  return 1;
}

// One line: runs of line breaks, tabs and other control bytes (from multi-line Lua messages such as require's
// list of files tried, or from data files quoted in messages) become one space.
std::string one_line(const std::string& msg) {
  std::string out;
  bool in_control = false;
  for (const char c : msg) {
    const bool control = static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
    if (control) {
      if (!in_control && !out.empty()) out += ' ';
    } else {
      out += c;
    }
    in_control = control;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

int lua_panic(lua_State* L) {
  const char* msg = lua_tostring(L, -1);
  std::fprintf(stderr, "torte: error: unprotected Lua error: %s\n", msg ? one_line(msg).c_str() : "?");
  std::fflush(stderr);
  std::_Exit(kExitError);
}

// The script's directory, absolute (so paths a script builds from torte.script_dir do not depend on the working
// directory); "" without a script (tests and fuzz harnesses that run chunks).
std::string script_directory(const std::string& script) {
  if (script.empty()) return {};
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::absolute(script, ec);
  return (ec ? std::filesystem::path(script) : p).parent_path().lexically_normal().string();
}

int l_sandboxed(lua_State* L) {
  lua_pushvalue(L, lua_upvalueindex(1));
  return 1;
}

// Everything the protected part of run_script needs.
struct Run {
  const RunOptions* options;
  RunContext* ctx;
  ScriptLimits* limits;
  const FilePolicy* policy;
};

// The protected part of run_script: the libraries, the torte module, the prelude and the script itself.
// A glTF model given where a script goes.
bool is_model_file(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".gltf" || ext == ".glb";
}

int run_protected(lua_State* L) {
  const Run& run = *static_cast<const Run*>(lua_touserdata(L, 1));
  lua_settop(L, 0);
  set_run_context(L, run.ctx);
  set_file_policy(L, run.policy);
  run.limits->start(L);
  open_script_libraries(L, run.options->sandbox);
  open_torte_module(L, *run.options);
  lua_getglobal(L, "require");
  lua_pushstring(L, "torte.prelude");
  lua_call(L, 1, 0);
  make_api_strict(L);  // after the prelude, which adds torte.options and torte.save
  if (is_model_file(run.options->script)) {  // torte model.glb: the embedded viewer renders it (torte.view_model)
    lua_getglobal(L, "require");
    lua_pushstring(L, "torte.view_model");
    lua_call(L, 1, 1);
    std::error_code ec;
    const std::filesystem::path model = std::filesystem::absolute(run.options->script, ec);
    lua_pushstring(L, (ec ? std::filesystem::path(run.options->script) : model).string().c_str());
    lua_call(L, 1, 0);
    return 0;
  }
  if (load_text_file(L, run.options->script.c_str()) != LUA_OK) return lua_error(L);
  lua_getglobal(L, "torte");
  lua_getfield(L, -1, "args");
  lua_remove(L, -2);
  lua_call(L, 1, 0);  // the script gets its arguments as `...` too
  return 0;
}

}  // namespace

void open_torte_module(lua_State* L, const RunOptions& options) {
  lua_newtable(L);
  const int torte_index = lua_gettop(L);
  lua_pushstring(L, TORTE_VERSION);
  lua_setfield(L, torte_index, "version");
  lua_pushboolean(L, options.quiet);  // --quiet: Lua libraries print no progress either (lua/minecraft)
  lua_setfield(L, torte_index, "quiet");
  lua_pushboolean(L, options.sandbox);  // torte.sandboxed(): whether --sandbox restricts this run
  lua_pushcclosure(L, l_sandboxed, 1);
  lua_setfield(L, torte_index, "sandboxed");
  lua_newtable(L);
  for (const auto& [key, value] : options.args) {
    push_arg_value(L, value);
    lua_setfield(L, -2, key.c_str());
  }
  lua_setfield(L, torte_index, "args");
  // Under mpirun every rank runs the script: torte.rank (0 ...) and torte.ranks for what must differ.
  lua_pushinteger(L, dist::rank());
  lua_setfield(L, torte_index, "rank");
  lua_pushinteger(L, dist::ranks());
  lua_setfield(L, torte_index, "ranks");
  open_geometry(L, torte_index);
  open_materials(L, torte_index);
  open_lights(L, torte_index);
  open_cameras(L, torte_index);
  open_render(L, torte_index);
  open_images(L, torte_index);
  open_meshes(L, torte_index);
  open_gltf(L, torte_index);
  open_textures(L, torte_index);
  open_voxels(L, torte_index);
  open_bench(L, torte_index);
  open_data(L, torte_index);
  open_run(L, torte_index, script_directory(options.script), options.quick, options.list_args);
  // `torte` is a global and also what require "torte" returns.
  lua_pushvalue(L, torte_index);
  lua_setglobal(L, "torte");
  luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
  lua_pushvalue(L, torte_index);
  lua_setfield(L, -2, "torte");
  lua_pop(L, 1);
  // Embedded Lua modules load on require "torte.<name>"; torte.prelude runs now and extends the table.
  luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_PRELOAD_TABLE);
  for (const EmbeddedLua* e = kEmbeddedLua; e->name; ++e) {
    lua_pushcfunction(L, load_embedded);
    lua_setfield(L, -2, e->name);
  }
  lua_pop(L, 1);
  lua_settop(L, torte_index - 1);
}

void set_run_context(lua_State* L, RunContext* ctx) {
  lua_pushlightuserdata(L, ctx);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kContextKey);
}

RunContext& run_context(lua_State* L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kContextKey);
  auto* ctx = lua_islightuserdata(L, -1) ? static_cast<RunContext*>(lua_touserdata(L, -1)) : nullptr;
  lua_pop(L, 1);
  if (!ctx) luaL_error(L, "internal: this Lua state has no torte run context (set_run_context)");
  return *ctx;
}

void interrupt_running_script() noexcept { interrupt_scripts(); }

std::string resolve_script_path(lua_State* L, const std::string& path) {
  namespace fs = std::filesystem;
  if (path.empty() || fs::path(path).is_absolute()) return path;
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kContextKey);  // states without a run (tests) resolve as run from "."
  const auto* ctx = lua_islightuserdata(L, -1) ? static_cast<const RunContext*>(lua_touserdata(L, -1)) : nullptr;
  lua_pop(L, 1);
  if (!ctx || ctx->script_dir.empty()) return path;
  const fs::path beside = fs::path(ctx->script_dir) / path;
  std::error_code ec;
  if (!fs::exists(beside, ec) && fs::exists(path, ec)) return path;  // a command-line path, relative to the shell
  // Run from the script's own directory both readings agree: keep the spelling the script used (for messages).
  const fs::path here = fs::absolute(path, ec);
  if (!ec && here.lexically_normal() == beside.lexically_normal()) return path;
  return beside.lexically_normal().string();
}

// Prints the one line for a failed lua_pcall of the script and returns the exit code: 130 for a run ended by
// Ctrl-C ("torte: interrupted ..."), else 1 ("torte: error: ...").
int report_failure(lua_State* L, int status, const RunOptions& options, const ScriptLimits& limits) noexcept {
  try {
    std::string msg = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "unknown error";
    if (status == LUA_ERRMEM) {  // Lua calls no message handler for these
      const std::string what = limits.memory_error(true);
      msg = what.empty() ? options.script + ": " + msg : what;
    } else if (status == LUA_ERRERR) {
      msg = options.script + ": an error occurred while reporting an error (" + msg + ")";
    }
    if (!limits.interrupt_message().empty() && msg.find(limits.interrupt_message()) != std::string::npos) {
      std::string where = limits.interrupt_location();
      if (!where.empty() && where.back() == ':') where.pop_back();
      std::fprintf(stderr, "torte: %s%s\n", limits.interrupt_message().c_str(),
                   where.empty() ? "" : (" (" + where + ")").c_str());
      return kExitInterrupted;
    }
    std::fprintf(stderr, "torte: error: %s%s\n", options.error_prefix.c_str(), one_line(msg).c_str());
  } catch (const std::exception&) {  // no memory even for the message
    std::fputs("torte: error: out of memory while reporting an error\n", stderr);
  }
  return kExitError;
}

int run_script(const RunOptions& options) {
  ScriptLimitSettings settings;
  if (options.lua_instructions >= 0)
    settings.instructions = uint64_t(options.lua_instructions);
  else if (options.sandbox)
    settings.instructions = uint64_t(kSandboxInstructions);
  settings.memory = options.lua_memory > 0 ? options.lua_memory : memory_limit() / 2;
  ScriptLimits limits(settings);
  lua_State* L = limits.new_state();
  if (!L) {
    std::fprintf(stderr, "torte: error: cannot create a Lua state (out of memory)\n");
    return kExitError;
  }
  lua_atpanic(L, lua_panic);
  RunContext ctx;
  ctx.spp_override = options.spp_override;
  ctx.seed_override = options.seed_override;
  ctx.time_limit_override = options.time_limit_override;
  ctx.noise_threshold_override = options.noise_threshold_override;
  ctx.quiet = options.quiet;
  ctx.stats = options.stats;
  ctx.exposure_override = options.exposure_override;
  ctx.tonemap_override = options.tonemap_override;
  ctx.aovs = options.aovs;
  ctx.denoise = options.denoise;
  ctx.cancel = options.cancel;
  ctx.checkpoint = options.checkpoint;
  ctx.resume = options.resume;
  ctx.checkpoint_every = options.checkpoint_every;
  ctx.quick = options.quick;
  ctx.list_args = options.list_args;
  ctx.script_dir = script_directory(options.script);
  std::optional<FilePolicy> policy;
  if (options.sandbox) {
    try {
      policy.emplace(
          FilePolicySettings{options.script, options.allow_read, options.allow_write, output_arguments(options)});
    } catch (const std::exception& e) {
      std::fprintf(stderr, "torte: error: --sandbox: %s\n", one_line(e.what()).c_str());
      lua_close(L);
      return kExitError;
    }
  }
  Run run{&options, &ctx, &limits, policy ? &*policy : nullptr};
  guard_nested_reads(run.policy);

  int code = kExitOk;
  const auto start = std::chrono::steady_clock::now();
  lua_pushcfunction(L, message_handler);
  const int handler = lua_gettop(L);
  // Everything, including opening the libraries, runs protected so no Lua error escapes as a crash.
  lua_pushcfunction(L, run_protected);
  lua_pushlightuserdata(L, &run);
  const int status = lua_pcall(L, 1, 0, handler);
  if (status != LUA_OK) {
    // What the failed script held is garbage now; after a refusal of memory the report needs some.
    lua_gc(L, LUA_GCCOLLECT);
    code = ctx.args_listed ? kExitOk : report_failure(L, status, options, limits);
  }
  // --list-args stops the script at torte.options (the error above is its way out) or at its first render.
  if (options.list_args && !ctx.args_listed && code == kExitOk) {
    std::printf("this scene declares no arguments (torte.options)\n");
  }
  if ((ctx.interrupted || interrupt_requested()) && code == kExitOk) code = kExitInterrupted;
  lua_close(L);  // finalizers may run Lua code: the limits still apply
  limits.stop();
  guard_nested_reads(nullptr);
  // After an error, the error line is the last word: no summary.
  if (!options.quiet && ctx.renders > 0 && code != kExitError) {
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double script = std::max(0.0, total - ctx.build_seconds - ctx.render_seconds - ctx.write_seconds);
    std::fprintf(stderr,
                 "torte: %s in %s (scene build %s, render %s, image output %s, script %s); %d render%s, %.1f M rays, "
                 "%.2f Mrays/s; %llu NaN/Inf samples dropped\n",
                 code == kExitOk ? "finished" : "stopped", format_duration(total).c_str(),
                 format_duration(ctx.build_seconds).c_str(), format_duration(ctx.render_seconds).c_str(),
                 format_duration(ctx.write_seconds).c_str(), format_duration(script).c_str(), ctx.renders,
                 ctx.renders == 1 ? "" : "s", double(ctx.rays) * 1e-6,
                 ctx.render_seconds > 0 ? double(ctx.rays) / ctx.render_seconds * 1e-6 : 0.0,
                 static_cast<unsigned long long>(ctx.dropped_samples));
  }
  return code;
}

}  // namespace torte::lua
