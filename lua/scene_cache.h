// The flattened scene of the last torte.render{}, reused by the next renders while the scene has not changed.
#pragma once
#include <memory>
#include <utility>
#include <vector>

#include "scene/builder.h"

namespace torte::lua {

/// One flattened scene and the fingerprint (SceneBuilder::fingerprint) of what it was built from. A render of an
/// unchanged scene reuses it, so a new camera, spp, size or integrator rebuilds nothing; any change (scene:add,
/// or an add to a group the scene places) rebuilds. It holds one scene at most and releases it before building
/// another, so a large scene is never in memory twice.
class SceneCache {
 public:
  struct Lookup {
    std::shared_ptr<const Scene> scene;
    bool reused = false;
  };

  /// The scene built from `builder`: the cached one when the fingerprints match, else the one `build()` returns
  /// (std::shared_ptr<Scene>), made after the cached one is released. When build() throws, the cache stays empty.
  template <class Build>
  Lookup get(const SceneBuilder& builder, Build&& build) {
    std::vector<uint64_t> fingerprint = builder.fingerprint();
    if (scene_ && fingerprint == fingerprint_) return {scene_, true};
    clear();
    std::shared_ptr<const Scene> built = std::forward<Build>(build)();
    scene_ = built;
    fingerprint_ = std::move(fingerprint);
    return {std::move(built), false};
  }

  void clear() {
    scene_.reset();
    fingerprint_.clear();
  }

 private:
  std::vector<uint64_t> fingerprint_;
  std::shared_ptr<const Scene> scene_;
};

}  // namespace torte::lua
