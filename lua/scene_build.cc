// Building the scene a script describes: the run's scene cache, and a progress display while a build runs.
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "core/interrupt.h"
#include "progress.h"
#include "runtime.h"
#include "types.h"

namespace torte::lua {

// Unless quiet, a thread shows the build's progress on stderr (ConsoleProgress: a bar on a terminal, a line per
// 10 % otherwise, nothing for builds under a second), polling the builders' counter ten times a second; a
// 28 M-triangle scene takes several seconds.
std::shared_ptr<Scene> build_scene(const SceneBuilder& scene, bool quiet) {
  if (quiet) return scene.flatten();
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
    std::shared_ptr<Scene> flat = scene.flatten(&counter);
    stop();
    return flat;
  } catch (...) {
    stop();
    throw;
  }
}

SceneCache::Lookup cached_scene(lua_State* L, const SceneBuilder& scene, const char* caller) {
  RunContext& ctx = run_context(L);
  try {
    return ctx.scene_cache.get(scene, [&] { return build_scene(scene, ctx.quiet); });
  } catch (const Interrupted&) {
    throw;
  } catch (const Error& e) {
    throw Error(std::string(caller) + ": " + e.what());  // the shape, light or group named comes after
  }
}

}  // namespace torte::lua
