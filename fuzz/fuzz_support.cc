#include "fuzz_support.h"

#include <lauxlib.h>
#include <lualib.h>
#include <fcntl.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>
#include <tbb/global_control.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "core/memory_budget.h"
#include "runtime.h"

namespace torte::fuzz {

namespace {

std::string make_scratch_dir() {
  std::string base;
  if (const char* t = std::getenv("TMPDIR"); t && *t) base = t;
  else if (std::filesystem::is_directory("/dev/shm")) base = "/dev/shm";
  else base = "/tmp";
  std::string dir = base + "/torte-fuzz-" + std::to_string(getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::atexit([] { std::error_code ec; std::filesystem::remove_all(scratch_dir(), ec); });
  return dir;
}

// Lua lines run, hashed into counters libFuzzer reads as extra coverage (TORTE_LIBFUZZER builds only).
#ifdef TORTE_LIBFUZZER
__attribute__((used, section("__libfuzzer_extra_counters")))
#endif
uint8_t g_lua_lines[1 << 15];

}  // namespace

const std::string& scratch_dir() {
  // Never destroyed: the exit handler that removes the directory runs after static destructors would.
  static const std::string* dir = new std::string(make_scratch_dir());
  return *dir;
}

std::string scratch_path(std::string_view name) { return scratch_dir() + "/" + std::string(name); }

void write_file(const std::string& path, std::string_view bytes) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "wb"), std::fclose);
  if (!f || std::fwrite(bytes.data(), 1, bytes.size(), f.get()) != bytes.size())
    throw std::runtime_error("cannot write " + path);
}

bool verbose() {
  static const bool v = [] {
    const char* s = std::getenv("TORTE_FUZZ_VERBOSE");
    return s && *s == '1';
  }();
  return v;
}

// Weak: only sanitizer builds define it (the replay build may have none).
extern "C" void __sanitizer_set_report_fd(void* fd) __attribute__((weak));

int report_fd() {
  static const int fd = [] {
    const int copy = fcntl(2, F_DUPFD_CLOEXEC, 3);
    if (copy >= 0 && __sanitizer_set_report_fd) __sanitizer_set_report_fd(reinterpret_cast<void*>(intptr_t(copy)));
    return copy >= 0 ? copy : 2;
  }();
  return fd;
}

void init_process() {
  (void)report_fd();
  static tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  OIIO::attribute("threads", 1);
  OIIO::attribute("exr_threads", 1);
  set_memory_limit(uint64_t(1) << 30);
  (void)scratch_dir();
}

void* FuzzLua::alloc(void* ud, void* ptr, size_t osize, size_t nsize) {
  auto* self = static_cast<FuzzLua*>(ud);
  const size_t old = ptr ? osize : 0;
  if (nsize == 0) {
    std::free(ptr);
    self->used_ -= old;
    return nullptr;
  }
  if (nsize > old && self->used_ - old + nsize > self->cap_) return nullptr;  // Lua raises "not enough memory"
  void* p = std::realloc(ptr, nsize);
  if (!p) return nullptr;
  self->used_ = self->used_ - old + nsize;
  return p;
}

void FuzzLua::hook(lua_State* L, lua_Debug* ar) {
  if (ar->event == LUA_HOOKLINE) {
    if (lua_getinfo(L, "S", ar)) {
      const uint64_t h = (uint64_t(reinterpret_cast<uintptr_t>(ar->source)) ^ uint64_t(ar->currentline)) *
                         0x9E3779B97F4A7C15ull;
      ++g_lua_lines[h >> 49];
    }
    return;
  }
  FuzzLua* self = *static_cast<FuzzLua**>(lua_getextraspace(L));
  if (self->budget_ > 1000) {
    self->budget_ -= 1000;
    return;
  }
  self->budget_ = 0;
  luaL_error(L, "instruction budget exhausted");
}

FuzzLua::FuzzLua(size_t lua_memory_cap, bool line_coverage) : cap_(lua_memory_cap) {
  init_process();
  ctx_.quiet = true;
  L_ = lua_newstate(alloc, this);
  if (!L_) throw std::runtime_error("cannot create a Lua state");
  *static_cast<FuzzLua**>(lua_getextraspace(L_)) = this;
  lua::set_run_context(L_, &ctx_);
  std::string error;
  const bool ok = call(
      [](lua_State* L) -> int {
        luaL_openlibs(L);
        lua::RunOptions options;
        options.quiet = true;
        lua::open_torte_module(L, options);
        lua_getglobal(L, "require");
        lua_pushstring(L, "torte.prelude");
        lua_call(L, 1, 0);
        return 0;
      },
      nullptr, &error);
  if (!ok) throw std::runtime_error("setting up the Lua state failed: " + error);
#ifdef TORTE_LIBFUZZER
  lua_sethook(L_, hook, LUA_MASKCOUNT | (line_coverage ? LUA_MASKLINE : 0), 1000);
#else
  (void)line_coverage;
  lua_sethook(L_, hook, LUA_MASKCOUNT, 1000);
#endif
}

FuzzLua::~FuzzLua() { lua_close(L_); }

bool FuzzLua::call(lua_CFunction fn, void* ud, std::string* error) {
  lua_pushcfunction(L_, fn);
  lua_pushlightuserdata(L_, ud);
  if (lua_pcall(L_, 1, 0, 0) == LUA_OK) return true;
  const char* s = lua_tostring(L_, -1);
  if (error) *error = s ? s : "(error object is not a string)";
  if (verbose()) std::fprintf(stderr, "fuzz: error: %s\n", s ? s : "(not a string)");
  lua_pop(L_, 1);
  return false;
}

bool FuzzLua::run(std::string_view source, std::string* error) {
  if (luaL_loadbufferx(L_, source.data(), source.size(), "=fuzz", "t") != LUA_OK || lua_pcall(L_, 0, 1, 0) != LUA_OK) {
    if (error) {
      const char* s = lua_tostring(L_, -1);
      *error = s ? s : "(error object is not a string)";
    }
    lua_pop(L_, 1);
    return false;
  }
  return true;
}

}  // namespace torte::fuzz

// LeakSanitizer (libFuzzer builds): OpenImageIO 2.4 loses the strings ImageInput::geterror copies out of its
// per-thread error table; nothing torte holds.
extern "C" const char* __lsan_default_suppressions() { return "leak:OpenImageIO_v2_4::ImageInput::geterror\n"; }
