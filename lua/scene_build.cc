// Building the scene a script describes: the run's scene cache, a progress display while a build runs, and the
// keys that choose the triangles' layout.
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "core/interrupt.h"
#include "core/memory_budget.h"
#include "progress.h"
#include "runtime.h"
#include "types.h"

namespace torte::lua {

// Unless quiet, a thread shows the build's progress on stderr (ConsoleProgress: a bar on a terminal, a line per
// 10 % otherwise, nothing for builds under a second), polling the builders' counter ten times a second; a
// 28 M-triangle scene takes several seconds.
std::shared_ptr<Scene> build_scene(const SceneBuilder& scene, bool quiet, const AccelOptions& options) {
  if (quiet) return scene.flatten(nullptr, &options);
  ProgressCounter counter;
  ConsoleProgress console("scene build", "Mtris/s");
  std::mutex mutex;
  std::condition_variable wake;
  bool finished = false;
  const auto t0 = std::chrono::steady_clock::now();
  std::thread monitor([&] {
    std::unique_lock lock(mutex);
    while (!wake.wait_for(lock, std::chrono::milliseconds(100), [&] { return finished; })) {
      const uint64_t total = counter.total.load(), done = std::min(counter.done.load(), total);
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (total > 0 && done < total)
        console.update(done, total, done / GeometrySet::kProgressPerTriangle, elapsed);  // rate: triangles/s
    }
  });
  const auto stop = [&] {
    {
      std::lock_guard lock(mutex);
      finished = true;
    }
    wake.notify_one();
    monitor.join();
    console.finish();
  };
  try {
    std::shared_ptr<Scene> flat = scene.flatten(&counter, &options);
    stop();
    return flat;
  } catch (...) {
    stop();
    throw;
  }
}

AccelOptions read_accel_options(KwArgs& kw, AccelOptions base) {
  lua_State* L = kw.state();
  kw.push("bvh_layout");
  if (!lua_isnil(L, -1)) {
    const std::string got = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : type_name(L, -1);
    lua_pop(L, 1);
    try {
      base.layout = parse_bvh_layout(got);
    } catch (const Error& e) {
      kw.fail("bvh_layout", e.what());
    }
  } else {
    lua_pop(L, 1);
  }
  kw.push("memory_budget");
  const int type = lua_type(L, -1);
  if (type == LUA_TSTRING) {
    const std::string text = lua_tostring(L, -1);
    lua_pop(L, 1);
    uint64_t bytes = 0;
    try {
      bytes = parse_byte_size(text);
    } catch (const Error& e) {
      kw.fail("memory_budget", std::string("must be a size such as \"1.5GB\": ") + e.what());
    }
    if (bytes == 0) kw.fail("memory_budget", "must be more than 0 bytes, got \"" + text + "\"");
    base.memory_budget = bytes;
  } else if (type == LUA_TNUMBER) {
    const double bytes = lua_tonumber(L, -1);
    lua_pop(L, 1);
    if (!(bytes >= 1 && bytes < 0x1p63)) kw.fail("memory_budget", "must be a positive number of bytes");
    base.memory_budget = uint64_t(bytes);
  } else {
    const std::string got = type_name(L, -1);
    lua_pop(L, 1);
    if (type != LUA_TNIL) kw.fail("memory_budget", "must be a size such as \"1.5GB\" or a number of bytes, got " + got);
  }
  return base;
}

SceneCache::Lookup cached_scene(lua_State* L, const SceneBuilder& scene, const char* caller,
                                const AccelOptions* options) {
  RunContext& ctx = run_context(L);
  const AccelOptions o = options ? *options : scene.accel_options();
  try {
    return ctx.scene_cache.get(scene, o, [&] { return build_scene(scene, ctx.quiet, o); });
  } catch (const Interrupted&) {
    throw;
  } catch (const Error& e) {
    throw Error(std::string(caller) + ": " + e.what());  // the shape, light or group named comes after
  }
}

}  // namespace torte::lua
