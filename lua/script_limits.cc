#include "script_limits.h"

#include <lauxlib.h>

#include <cstdlib>
#include <cstring>

#include "core/interrupt.h"
#include "core/memory_budget.h"

namespace torte::lua {

namespace {

const char kLimitsKey = 0;  // its address keys the ScriptLimits in the Lua registry

// Instructions between two calls of the budget hook: the hook itself is cheap, what costs is that any count hook
// makes the VM check it on every instruction (about +45 % in tight loops), hence no hook without a budget.
constexpr int kHookPeriod = 10000;
// What the heap may grow past the cap after a refusal, so the error can still be raised and reported.
constexpr uint64_t kHeadroom = uint64_t(1) << 20;

// The script whose threads interrupt_scripts() arms; one script runs at a time.
std::atomic<ScriptLimits*> g_active{nullptr};

void hook(lua_State* L, lua_Debug* ar) {
  if (ScriptLimits* limits = script_limits(L)) {
    limits->on_hook(L, ar->event);
  } else {
    lua_sethook(L, nullptr, 0, 0);
  }
}

// Every event and every instruction: set when the script has to stop, so a pcall cannot swallow the stop and go
// on (the first instruction after the pcall raises again).
void arm_now(lua_State* L) { lua_sethook(L, hook, LUA_MASKCALL | LUA_MASKRET | LUA_MASKLINE | LUA_MASKCOUNT, 1); }

}  // namespace

ScriptLimits* script_limits(lua_State* L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kLimitsKey);
  auto* limits = lua_islightuserdata(L, -1) ? static_cast<ScriptLimits*>(lua_touserdata(L, -1)) : nullptr;
  lua_pop(L, 1);
  return limits;
}

std::string script_location(lua_State* L) {
  lua_Debug ar;
  for (int level = 0; lua_getstack(L, level, &ar); ++level) {
    if (!lua_getinfo(L, "Sl", &ar)) continue;
    if (ar.source && ar.source[0] == '@' && ar.currentline > 0)
      return std::string(ar.short_src) + ":" + std::to_string(ar.currentline) + ":";
  }
  return "";
}

// ---- memory -------------------------------------------------------------------------------------------------

void* ScriptLimits::allocate(void* ud, void* ptr, size_t osize, size_t nsize) noexcept {
  auto* self = static_cast<ScriptLimits*>(ud);
  const uint64_t old = ptr ? osize : 0;  // without ptr, osize tells the kind of object, not a size
  if (nsize == 0) {
    std::free(ptr);
    self->used_ -= old;
    if (self->over_ && self->used_ < self->settings_.memory) self->over_ = false;
    return nullptr;
  }
  const uint64_t cap = self->settings_.memory;
  if (cap > 0 && nsize > old && self->used_ - old + nsize > cap + (self->over_ ? kHeadroom : 0)) {
    self->refuse(nsize - old, true);
    return nullptr;  // Lua collects garbage and asks once more before it raises "not enough memory"
  }
  void* p = std::realloc(ptr, nsize);
  if (!p) {
    self->refuse(nsize - old, false);
    return nullptr;
  }
  self->used_ = self->used_ - old + nsize;
  if (self->used_ > self->peak_) self->peak_ = self->used_;
  return p;
}

void ScriptLimits::refuse(size_t more, bool by_cap) noexcept {
  over_ = true;
  refused_bytes_ = more;
  refused_by_cap_ = by_cap;
  refused_held_ = used_;
  // Where the script was: the stack is intact while the allocator runs, and reading it allocates nothing
  // (lua_getinfo "Sl"). The location string lives on the C++ heap; if even that fails, there is no location.
  lua_State* running = current.load() ? current.load() : main.load();
  try {
    refused_where_ = running ? script_location(running) : "";
  } catch (...) {
    refused_where_.clear();
  }
}

std::string ScriptLimits::memory_error(bool with_location) const {
  if (refused_bytes_ == 0) return "";
  std::string what;
  if (refused_by_cap_) {
    what = "Lua memory limit of " + format_bytes(settings_.memory) + " reached (the script held " +
           format_bytes(refused_held_) +
           " and asked for " + format_bytes(refused_bytes_) + " more; --lua-memory SIZE raises the limit)";
  } else {
    what = "out of memory: the system refused the script " + format_bytes(refused_bytes_) + " more";
  }
  return !with_location || refused_where_.empty() ? what : refused_where_ + " " + what;
}

lua_State* ScriptLimits::new_state() { return lua_newstate(allocate, this); }

void ScriptLimits::start(lua_State* L) {
  lua_pushlightuserdata(L, this);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kLimitsKey);
  main.store(L);
  g_active.store(this);
  arm(L);
}

void ScriptLimits::stop() {
  ScriptLimits* self = this;
  g_active.compare_exchange_strong(self, nullptr);
  main.store(nullptr);
  current.store(nullptr);
}

// ---- hooks --------------------------------------------------------------------------------------------------

void ScriptLimits::arm(lua_State* L) {
  // A budget needs the count hook; so does a pending Ctrl-C during the grace period (to see it run out).
  if (settings_.instructions > 0 || interrupt_requested())
    lua_sethook(L, hook, LUA_MASKCOUNT, kHookPeriod);
  else
    lua_sethook(L, nullptr, 0, 0);
}

void ScriptLimits::on_hook(lua_State* L, int event) {
  if (event == LUA_HOOKCOUNT) instructions_ += uint64_t(lua_gethookcount(L));
  if (interrupt_requested()) {
    if (!render_interrupted_) raise_interrupt(L, "interrupted while running the script");
    if (std::chrono::steady_clock::now() - render_interrupted_at_ > kInterruptGrace)
      raise_interrupt(L, "interrupted: the script was still running " + std::to_string(kInterruptGrace.count()) +
                             " s after Ctrl-C stopped its render");
  }
  if (settings_.instructions > 0 && instructions_ > settings_.instructions) {
    arm_now(L);
    const std::string where = script_location(L);
    const std::string message = (where.empty() ? "" : where + " ") + "the script ran " +
                                std::to_string(settings_.instructions) +
                                " Lua instructions, its limit (--lua-instructions N raises it, 0 removes it)";
    lua_pushstring(L, message.c_str());
    lua_error(L);
  }
  arm(L);
}

void ScriptLimits::note_render_interrupted() {
  if (render_interrupted_) return;
  render_interrupted_ = true;
  render_interrupted_at_ = std::chrono::steady_clock::now();
}

void ScriptLimits::raise_interrupt(lua_State* L, const std::string& what) {
  arm_now(L);
  interrupt_location_ = script_location(L);
  interrupt_message_ = what;
  const std::string message = (interrupt_location_.empty() ? "" : interrupt_location_ + " ") + what;
  lua_pushstring(L, message.c_str());
  lua_error(L);
  std::abort();  // lua_error does not return
}

void interrupt_scripts() noexcept {
  ScriptLimits* limits = g_active.load();
  if (!limits) return;
  // lua_sethook only stores a few fields: Lua documents it as safe to call from a signal handler.
  if (lua_State* L = limits->main.load()) arm_now(L);
  if (lua_State* L = limits->current.load()) arm_now(L);
}

void raise_interrupted(lua_State* L, const std::string& what) {
  if (ScriptLimits* limits = script_limits(L)) limits->raise_interrupt(L, what);
  const std::string where = script_location(L);
  const std::string message = (where.empty() ? "" : where + " ") + what;
  lua_pushstring(L, message.c_str());
  lua_error(L);
  std::abort();
}

void note_render_interrupted(lua_State* L) {
  if (ScriptLimits* limits = script_limits(L)) limits->note_render_interrupted();
}

// ---- coroutines ---------------------------------------------------------------------------------------------

namespace {

// While a coroutine runs, `current` names it (the previous one comes back when it yields or ends, also by an
// error), and a pending Ctrl-C is armed in it before it runs.
class Resuming {
 public:
  Resuming(ScriptLimits* limits, lua_State* co) : limits_(limits) {
    if (!limits_ || !co) return;
    previous_ = limits_->current.exchange(co);
    if (interrupt_requested()) arm_now(co);
  }
  ~Resuming() {
    if (limits_) limits_->current.store(previous_);
  }
  Resuming(const Resuming&) = delete;
  Resuming& operator=(const Resuming&) = delete;

 private:
  ScriptLimits* limits_ = nullptr;
  lua_State* previous_ = nullptr;
};

// coroutine.resume(co, ...) through the library's own (upvalue 1).
int tracked_resume(lua_State* L) {
  Resuming scope(script_limits(L), lua_tothread(L, 1));
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

// coroutine.wrap on top of the tracked resume, raising errors as the library's wrap does (string errors get the
// caller's position; the coroutine is closed so its to-be-closed variables are).
const char kWrapSource[] = R"(
local create, resume, close, pack, unpack, type, error = ...
return function(f)
  local co = create(f)
  return function(...)
    local r = pack(resume(co, ...))
    if r[1] then return unpack(r, 2, r.n) end
    close(co)
    if type(r[2]) == "string" then error(r[2], 2) end
    error(r[2], 0)
  end
end
)";

}  // namespace

void track_coroutines(lua_State* L) {
  if (lua_getglobal(L, "coroutine") != LUA_TTABLE) {
    lua_pop(L, 1);
    return;
  }
  const int co = lua_gettop(L);
  lua_getfield(L, co, "resume");
  lua_pushcclosure(L, tracked_resume, 1);
  lua_setfield(L, co, "resume");
  if (luaL_loadbufferx(L, kWrapSource, sizeof kWrapSource - 1, "=[torte] coroutine.wrap", "t") != LUA_OK)
    lua_error(L);
  lua_getfield(L, co, "create");
  lua_getfield(L, co, "resume");
  lua_getfield(L, co, "close");
  lua_getglobal(L, "table");
  lua_getfield(L, -1, "pack");
  lua_getfield(L, -2, "unpack");
  lua_remove(L, -3);
  lua_getglobal(L, "type");
  lua_getglobal(L, "error");
  lua_call(L, 7, 1);
  lua_setfield(L, co, "wrap");
  lua_pop(L, 1);
}

}  // namespace torte::lua
