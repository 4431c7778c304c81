#include "render_metadata.h"

#include <array>
#include <cstdio>

#include "render/render_isa.h"
#include "simd/simd_target.h"
#include "traverse.h"

namespace torte::lua {

namespace {

std::string describe_camera(const CameraDesc& c) {
  const Vec3f eye = c.camera_to_world.apply_point({0, 0, 0});
  const Vec3f forward = normalize(c.camera_to_world.apply_vector({0, 0, 1}));
  const char* axis = c.fov_axis == FovAxis::Vertical ? "vertical" : c.fov_axis == FovAxis::Horizontal ? "horizontal"
                                                                                                       : "diagonal";
  char buf[320];
  if (c.kind == CameraKind::Perspective)
    std::snprintf(buf, sizeof buf, "perspective fov %g (%s)", double(c.fov_degrees), axis);
  else
    std::snprintf(buf, sizeof buf, "orthographic extent %g (%s)", double(c.extent), axis);
  std::string s = buf;
  std::snprintf(buf, sizeof buf, ", eye (%g, %g, %g), forward (%g, %g, %g), aperture radius %g, focus distance %g",
                double(eye.x), double(eye.y), double(eye.z), double(forward.x), double(forward.y), double(forward.z),
                double(c.aperture_radius), double(c.focus_distance));
  return s + buf;
}

}  // namespace

std::vector<ImageAttribute> render_attributes(const RenderSettings& s, const std::string& integrator,
                                              const CameraDesc& camera, const RenderStats& stats) {
  std::vector<ImageAttribute> a;
  a.push_back({"Software", std::string("torte ") + TORTE_VERSION});
  a.push_back({"torte:integrator", integrator});
  // Samples per pixel the render was asked for and what it reached (fewer after a time limit or an interruption;
  // with adaptive sampling the most any pixel took, the image's "samples" layer holding each pixel's count).
  a.push_back({"torte:spp", s.spp});
  a.push_back({"torte:spp_reached", stats.spp_reached});
  if (s.noise_threshold > 0) a.push_back({"torte:noise_threshold", s.noise_threshold});
  if (stats.time_limited) a.push_back({"torte:time_limit", float(s.time_limit)});
  a.push_back({"torte:max_depth", s.max_depth});
  a.push_back({"torte:seed", std::to_string(s.seed)});
  a.push_back({"torte:render_seconds", float(stats.render_seconds)});
  a.push_back({"torte:camera", describe_camera(camera)});
  // The target chosen by --simd or torte.simd.use (the best the CPU runs by default), what Highway dispatched the
  // traversal kernels to, and the render loop's copy (render/render_isa.h).
  a.push_back({"torte:simd_target", simd::current_target()});
  a.push_back({"torte:highway_target", std::string(traversal_target_name())});
  a.push_back({"torte:render_isa", std::string(render_isa::selected_name())});
  if (stats.interrupted) a.push_back({"torte:interrupted", std::string("partial image: the render was interrupted")});
  // EXR's worldToCamera: row vectors (p' = p M), so the transpose of torte's column-vector world-to-camera.
  const Mat4& w2c = camera.camera_to_world.inverse_matrix();
  std::array<float, 16> m{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m[size_t(4 * r + c)] = w2c.m[c][r];
  a.push_back({"worldToCamera", m});
  return a;
}

}  // namespace torte::lua
