// The flattened scene of the last torte.render{}, reused by the next renders while the scene has not changed.
#pragma once
#include <memory>
#include <utility>
#include <vector>

#include "scene/builder.h"

namespace torte::lua {

/// One flattened scene, the fingerprint (SceneBuilder::fingerprint) of what it was built from and the layout
/// options it was built with. A render of an unchanged scene with the same options reuses it, so a new camera, spp, size or integrator rebuilds nothing; any change (scene:add,
/// or an add to a group the scene places) rebuilds. It holds one scene at most and releases it before building
/// another, so a large scene is never in memory twice.
class SceneCache {
 public:
  struct Lookup {
    std::shared_ptr<const Scene> scene;
    bool reused = false;
  };

  /// The scene built from `builder` with `options`: the cached one when the fingerprints and options match, else
  /// the one `build()` returns (std::shared_ptr<Scene>), made after the cached one is released. When build()
  /// throws, the cache stays empty.
  template <class Build>
  Lookup get(const SceneBuilder& builder, const AccelOptions& options, Build&& build) {
    std::vector<uint64_t> fingerprint = builder.fingerprint();
    if (scene_ && fingerprint == fingerprint_ && options == options_) return {scene_, true};
    clear();
    std::shared_ptr<const Scene> built = std::forward<Build>(build)();
    scene_ = built;
    fingerprint_ = std::move(fingerprint);
    options_ = options;
    return {std::move(built), false};
  }

  /// The same with the builder's own options.
  template <class Build>
  Lookup get(const SceneBuilder& builder, Build&& build) {
    return get(builder, builder.accel_options(), std::forward<Build>(build));
  }

  void clear() {
    scene_.reset();
    fingerprint_.clear();
  }

 private:
  std::vector<uint64_t> fingerprint_;
  AccelOptions options_;
  std::shared_ptr<const Scene> scene_;
};

}  // namespace torte::lua
