// Where a script made an object, for messages about it that come later (at torte.render):
// "torte.light.point at scene.lua:12".
#pragma once
#include <string>

#include "binding.h"

namespace torte::lua {

/// `function` followed by " at <chunk>:<line>" of the Lua code calling the running binding (just `function`
/// when Lua does not know the line).
inline std::string made_at(lua_State* L, const std::string& function) {
  luaL_where(L, 1);
  std::string where = lua_tostring(L, -1);
  lua_pop(L, 1);
  while (!where.empty() && (where.back() == ' ' || where.back() == ':')) where.pop_back();
  return where.empty() ? function : function + " at " + where;
}

/// Upper bound of emitted quantities a script may give (intensity, radiance, irradiance, emission, per channel):
/// far above any physical light in any unit, and low enough that powers and sums stay finite in float.
constexpr float kMaxEmission = 1e20f;

}  // namespace torte::lua
