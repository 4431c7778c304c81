#include "runtime.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <cstring>

#include "progress.h"
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

int load_embedded(lua_State* L) {
  const char* name = lua_tostring(L, 1);
  for (const EmbeddedLua* e = kEmbeddedLua; e->name; ++e)
    if (std::strcmp(e->name, name) == 0) {
      const std::string chunk = std::string("=[torte] ") + e->name;
      if (luaL_loadbuffer(L, e->source, std::strlen(e->source), chunk.c_str()) != LUA_OK) return lua_error(L);
      lua_call(L, 0, 1);
      return 1;
    }
  return luaL_error(L, "module '%s' is not embedded", name);
}

// Message handler: keep the error one line (no traceback), and make non-string errors printable.
int message_handler(lua_State* L) {
  luaL_tolstring(L, 1, nullptr);
  return 1;
}

}  // namespace

void open_torte_module(lua_State* L, const RunOptions& options) {
  lua_newtable(L);
  const int torte_index = lua_gettop(L);
  lua_pushstring(L, TORTE_VERSION);
  lua_setfield(L, torte_index, "version");
  lua_pushboolean(L, options.quiet);  // --quiet: Lua libraries print no progress either (lua/minecraft)
  lua_setfield(L, torte_index, "quiet");
  lua_newtable(L);
  for (const auto& [key, value] : options.args) {
    push_arg_value(L, value);
    lua_setfield(L, -2, key.c_str());
  }
  lua_setfield(L, torte_index, "args");
  open_geometry(L, torte_index);
  open_materials(L, torte_index);
  open_lights(L, torte_index);
  open_cameras(L, torte_index);
  open_render(L, torte_index);
  open_meshes(L, torte_index);
  open_textures(L, torte_index);
  open_voxels(L, torte_index);
  open_data(L, torte_index);
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
  auto* ctx = static_cast<RunContext*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return *ctx;
}

int run_script(const RunOptions& options) {
  lua_State* L = luaL_newstate();
  if (!L) {
    std::fprintf(stderr, "torte: error: cannot create a Lua state (out of memory)\n");
    return kExitError;
  }
  RunContext ctx;
  ctx.spp_override = options.spp_override;
  ctx.seed_override = options.seed_override;
  ctx.quiet = options.quiet;
  ctx.cancel = options.cancel;
  set_run_context(L, &ctx);

  int code = kExitOk;
  const auto start = std::chrono::steady_clock::now();
  lua_pushcfunction(L, message_handler);
  const int handler = lua_gettop(L);
  // Everything, including opening the libraries, runs protected so no Lua error escapes as a crash.
  lua_pushcfunction(L, [](lua_State* L2) -> int {
    const auto* opts = static_cast<const RunOptions*>(lua_touserdata(L2, 1));
    luaL_openlibs(L2);
    open_torte_module(L2, *opts);
    lua_getglobal(L2, "require");
    lua_pushstring(L2, "torte.prelude");
    lua_call(L2, 1, 0);
    if (luaL_loadfile(L2, opts->script.c_str()) != LUA_OK) return lua_error(L2);
    lua_getglobal(L2, "torte");
    lua_getfield(L2, -1, "args");
    lua_remove(L2, -2);
    lua_call(L2, 1, 0);  // the script gets its arguments as `...` too
    return 0;
  });
  lua_pushlightuserdata(L, const_cast<RunOptions*>(&options));
  if (lua_pcall(L, 1, 0, handler) != LUA_OK) {
    std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "unknown error";
    // One line: Lua syntax errors may quote a line break.
    for (char& c : msg)
      if (c == '\n') c = ' ';
    std::fprintf(stderr, "torte: error: %s\n", msg.c_str());
    code = kExitError;
  }
  if (ctx.interrupted && code == kExitOk) code = kExitInterrupted;
  lua_close(L);
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
