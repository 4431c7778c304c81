// What an image file records about the render that made it (EXR header attributes, PNG text chunks), so a
// file found later says how to reproduce it.
#pragma once
#include <string>
#include <vector>

#include "camera/camera.h"
#include "film/image.h"
#include "render/render_settings.h"

namespace torte::lua {

/// The attributes of a finished render: `torte:spp`, `torte:integrator`, `torte:seed` (decimal text: 64 bits),
/// `torte:max_depth`, `torte:render_seconds`, `torte:camera` (a one-line description), `worldToCamera` (EXR's
/// standard camera matrix), `Software` (torte and its version), `torte:simd_target` (the SIMD target chosen by
/// --simd or torte.simd.use, e.g. "avx2"), `torte:highway_target` (the traversal kernels' Highway target, e.g.
/// "AVX2") and `torte:render_isa` (the render loop's copy), plus `torte:interrupted` when the render was cut short.
std::vector<ImageAttribute> render_attributes(const RenderSettings& s, const std::string& integrator,
                                              const CameraDesc& camera, const RenderStats& stats);

}  // namespace torte::lua
