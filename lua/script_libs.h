// The Lua standard libraries as a scene script gets them (docs/security.md):
// - always: text-only loaders (lua/text_chunks.h), coroutines that Ctrl-C reaches (lua/script_limits.h), and a
//   debug library without the functions that can corrupt the interpreter (debug.getregistry; changing the
//   metatable of a userdata; the upvalues of C functions; the locals of C frames and Lua's temporaries);
// - under --sandbox: no os.execute, io.popen, package.loadlib, C modules, os.exit, os.getenv, os.tmpname,
//   io.tmpfile or os.setlocale, no __gc metamethods (finalizers run without hooks); debug keeps only getinfo
//   and traceback; io.open, io.lines, io.input,
//   io.output, os.remove, os.rename, loadfile, dofile and require obey the file policy (lua/sandbox.h).
#pragma once
#include <lua.h>

namespace torte::lua {

/// Opens the standard libraries into L as described above. Runs Lua code: call it protected.
void open_script_libraries(lua_State* L, bool sandboxed);

}  // namespace torte::lua
