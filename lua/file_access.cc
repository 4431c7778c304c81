#include "file_access.h"

namespace torte::lua {

// Policy comes with the sandbox (lua/sandbox.cc); until a run sets one every path is allowed.
void check_read(lua_State*, const std::string&, const char*) {}
void check_write(lua_State*, const std::string&, const char*) {}

}  // namespace torte::lua
