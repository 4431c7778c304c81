// Errors of the bindings that once said too little or nothing: each names the function and the key, and values
// out of range are refused where they are given.
#include <catch2/catch.hpp>
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>

#include <string>

#include "runtime.h"
#include "types.h"

namespace torte {
namespace {

std::string error_of(const std::string& code) {
  lua_State* L = luaL_newstate();
  luaL_openlibs(L);
  lua::RunContext ctx;
  ctx.quiet = true;
  lua::set_run_context(L, &ctx);
  lua::open_torte_module(L, lua::RunOptions{});
  std::string msg = "no error";
  if (luaL_dostring(L, code.c_str()) != LUA_OK) msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "?";
  lua_close(L);
  return msg;
}

TEST_CASE("binding errors: name the function and the key, and refuse values out of range", "[lua]") {
  CHECK_THAT(error_of("torte.voxel.grid{size = 3}"), Catch::Contains("torte.voxel.grid takes no keys (got 'size')"));
  CHECK(error_of("torte.voxel.grid{}; torte.voxel.grid()") == "no error");
  CHECK_THAT(error_of("torte.filter.box{radius = -1}"), Catch::Contains("torte.filter.box: box filter radius"));
  CHECK_THAT(error_of("torte.filter.mitchell{radius = 0}"), Catch::Contains("torte.filter.mitchell:"));
  CHECK_THAT(error_of("torte.voxel.grid():define{id = 1, emission = 1e30}"),
             Catch::Contains("grid:define: 'emission' must be at most 1e20"));
  CHECK_THAT(error_of("torte.render{scene = torte.scene(), camera = torte.camera.perspective{}, rr_depth = -1}"),
             Catch::Contains("torte.render: 'rr_depth' must be a non-negative"));
}

}  // namespace
}  // namespace torte
