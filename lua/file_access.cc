#include "file_access.h"

#include "sandbox.h"

namespace torte::lua {

// Without --sandbox there is no policy and every path is allowed (lua/sandbox.h has the rule).
void check_read(lua_State* L, const std::string& path, const char* function) {
  if (const FilePolicy* policy = file_policy(L)) policy->check_read(path, function);
}

void check_write(lua_State* L, const std::string& path, const char* function) {
  if (const FilePolicy* policy = file_policy(L)) policy->check_write(path, function);
}

}  // namespace torte::lua
