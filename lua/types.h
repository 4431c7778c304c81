// The C++ types that Lua scripts hold as userdata, and their metatable names (also used in error messages).
#pragma once
#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "binding.h"
#include "film/filter.h"
#include "film/image.h"
#include "film/view_transform.h"
#include "render/aov_pass.h"
#include "render/render.h"
#include "scene/builder.h"
#include "scene_cache.h"

namespace torte::lua {

// A rendered image as the script sees it: pixels plus how they were made.
struct RenderedImage {
  Image image;
  RenderStats stats;
  double build_seconds = 0;   // flattening the scene and building its BVHs for this render
  bool scene_reused = false;  // the scene of an earlier render was unchanged and served again (SceneCache)
  double aov_seconds = 0;     // the AOV pass and the denoiser, after the render
  std::vector<uint32_t> pixel_spp;  // samples each pixel took, with adaptive sampling; else empty
  std::vector<float> variance;      // each pixel's mean-luminance variance (denoise or the "variance" AOV); else empty
};

template <> struct LuaName<MaterialDesc> { static constexpr const char* value = "torte.material"; };
template <> struct LuaName<ShapeDesc> { static constexpr const char* value = "torte.shape"; };
template <> struct LuaName<Light> { static constexpr const char* value = "torte.light"; };
template <> struct LuaName<CameraDesc> { static constexpr const char* value = "torte.camera"; };
template <> struct LuaName<SceneBuilder> { static constexpr const char* value = "torte.scene"; };
template <> struct LuaName<InstanceDesc> { static constexpr const char* value = "torte.instance"; };
template <> struct LuaName<Filter> { static constexpr const char* value = "torte.filter"; };
template <> struct LuaName<RenderedImage> { static constexpr const char* value = "torte.image"; };
template <> struct LuaName<TriangleMesh> { static constexpr const char* value = "torte.mesh"; };

// What torte.render{} asked for besides light (lua/bind_image.cc).
struct AovRequest {
  std::vector<Aov> aovs;  // aovs = {...} (and --aovs)
  int samples = 16;       // aov_samples: camera samples per pixel of the AOV pass
  bool denoise = false;   // denoise = true (and --denoise): also albedo, normal, depth, then film/denoise.h
};
/// Reads aovs, aov_samples and denoise from torte.render{}'s table (spp: the render's, for the default).
AovRequest read_aov_request(KwArgs& kw, int spp);
/// The AOV names of `names` (errors start with `where`), each once.
std::vector<Aov> parse_aov_names(const std::vector<std::string>& names, const std::string& where);
/// Renders the layers `request` asks for into img.image (and denoises it when asked); the "samples" layer comes
/// from img.pixel_spp and img.stats, which must be set first.
void add_aovs(RenderedImage& img, const Scene& scene, const Camera& camera, const RenderSettings& s,
              AovRequest request, const std::atomic<bool>* cancel);

// Settings of the whole run that bindings consult (from the command line).
struct RunContext {
  int spp_override = -1;        // --spp
  int64_t seed_override = -1;   // --seed
  std::optional<double> time_limit_override;       // --time-limit
  std::optional<float> noise_threshold_override;   // --noise-threshold
  bool quiet = false;           // --quiet
  bool stats = false;           // --stats: every render collects and prints its per-stage profile
  std::optional<float> exposure_override;           // --exposure
  std::optional<ViewTransform> tonemap_override;    // --tonemap
  std::vector<Aov> aovs;                            // --aovs: added to every render's
  bool denoise = false;                             // --denoise: every render is denoised
  const std::atomic<bool>* cancel = nullptr;  // set by Ctrl-C
  std::string checkpoint, resume;              // --checkpoint, --resume (render/render_control.h)
  double checkpoint_every = 60;                // --checkpoint-every
  bool quick = false;           // --quick (runtime.h: kQuickDivisor, kQuickSpp)
  bool list_args = false;       // --list-args: torte.options prints the arguments and stops the script
  bool args_listed = false;     // ... and did: the error that stopped the script is a clean exit
  std::string script_dir;       // the script's directory, absolute (torte.script_dir, resolve_script_path)
  bool interrupted = false;     // a render was cut short: later renders are refused
  // Totals over the run, for the closing summary.
  double build_seconds = 0, render_seconds = 0, write_seconds = 0;
  uint64_t rays = 0, dropped_samples = 0;
  int renders = 0;
  SceneCache scene_cache;  // the last render's flattened scene, for the next renders of the same scene
};
RunContext& run_context(lua_State* L);

void open_geometry(lua_State* L, int torte_index);  // torte.shape.*, transforms
void open_materials(lua_State* L, int torte_index);  // torte.material.*
void open_lights(lua_State* L, int torte_index);     // torte.light.*
void open_cameras(lua_State* L, int torte_index);    // torte.camera.*
void open_render(lua_State* L, int torte_index);     // torte.scene, torte.render, torte.filter.*
void open_images(lua_State* L, int torte_index);     // images' fields and methods, torte.denoise (lua/bind_image.cc)
void open_meshes(lua_State* L, int torte_index);     // torte.mesh.*, torte.clock
void open_gltf(lua_State* L, int torte_index);       // torte.gltf.load (lua/bind_gltf.cc)
void open_textures(lua_State* L, int torte_index);   // torte.texture.* (lua/bind_texture.cc)
void open_voxels(lua_State* L, int torte_index);     // torte.voxel.*, torte.shape.voxels (lua/bind_voxel.cc)
void open_bench(lua_State* L, int torte_index);      // torte.bench (lua/bind_bench.cc)
void open_data(lua_State* L, int torte_index);       // torte.data.*: files, zlib/gzip, NBT, bit fields (lua/bind_data.cc)
// torte.simd.*, torte.script_dir, torte.quick, under --list-args torte._list_args (lua/bind_run.cc).
/// The scene flattened and built for rendering, with a progress display on stderr unless `quiet`
/// (lua/scene_build.cc).
/// bvh_layout and memory_budget (accel/accel_options.h) read from `kw` over `base`: the keys of torte.scene{...}
/// and torte.render{...}; a bad value fails naming its key (lua/scene_build.cc).
AccelOptions read_accel_options(KwArgs& kw, AccelOptions base);
/// `options`: the triangles' layout options (the scene's own unless torte.render gave others).
std::shared_ptr<Scene> build_scene(const SceneBuilder& scene, bool quiet, const AccelOptions& options);
/// `scene` through the run's scene cache (built with build_scene when it or the options changed); a build error
/// becomes "<caller>: <message>" (torte.render and scene:stats). `options`: as build_scene's (nullptr: the
/// scene's accel_options()).
SceneCache::Lookup cached_scene(lua_State* L, const SceneBuilder& scene, const char* caller,
                                const AccelOptions* options = nullptr);
void open_run(lua_State* L, int torte_index, const std::string& script_dir, bool quick, bool list_args);
/// After the prelude: indexing a missing name of torte or of its tables of functions (torte.material, ...) is
/// an error "torte.material has no 'plastik' (known: ...)" instead of a nil that fails later (lua/bind_run.cc).
void make_api_strict(lua_State* L);
/// --list-args: prints the scene's arguments (the defaults table at `index`: name, default, type) on stdout,
/// marks the run as listed and stops the script with an error run_script turns into exit code 0.
[[noreturn]] void list_arguments(lua_State* L, int index);
void set_data_lz4_functions(lua_State* L);  // lz4_block, lz4_compress, xxhash32 into the table on top of the stack
// unpack_bits into the table on top of the stack, and the torte.data.longs metatable (lua/bind_data_longs.cc).
void set_data_longs_functions(lua_State* L);
/// Pushes a new torte.data.longs of `n` entries and returns its `n` values for the caller to fill.
int64_t* new_longs(lua_State* L, size_t n);
// Output bound of torte.data's decompressors when the script gives none: generous for a Minecraft chunk (a few
// MB at most), small enough that a compression bomb fails at once.
constexpr uint64_t kDefaultDecompressLimit = uint64_t(256) << 20;
// The optional output limit argument at `idx` of decompressor `fn`: kDefaultDecompressLimit when nil.
uint64_t decompress_limit(lua_State* L, int idx, const char* fn);
/// Pushes a torte transform (userdata with `*`, :inverse() and :point()).
void push_transform(lua_State* L, const Transform& t);
// torte.shape.mesh's mesh=<torte.mesh> or file="path" (loaded now); nullptr when neither key is given.
std::shared_ptr<const TriangleMesh> mesh_argument(KwArgs& kw);

}  // namespace torte::lua
