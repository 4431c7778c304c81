// The image torte.render{} returns: its fields (size, statistics, the stage profile, layers) and methods
// (write, pixel, mean, layer), the AOV requests of torte.render{} (aovs, aov_samples, denoise; render/aov_pass.h),
// and torte.denoise (film/denoise.h).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "distributed/session.h"
#include "file_access.h"
#include "film/denoise.h"
#include "film/image_io.h"
#include "render/aov_pass.h"
#include "render/stage_stats.h"
#include "runtime.h"
#include "types.h"

namespace torte::lua {

std::vector<Aov> parse_aov_names(const std::vector<std::string>& names, const std::string& where) {
  std::vector<Aov> out;
  for (const std::string& n : names) {
    Aov a;
    if (!parse_aov(n, a)) throw Error(where + ": unknown AOV '" + n + "' (known: " + kAovChoices + ")");
    if (std::find(out.begin(), out.end(), a) == out.end()) out.push_back(a);
  }
  return out;
}

AovRequest read_aov_request(KwArgs& kw, int spp) {
  AovRequest r;
  lua_State* L = kw.state();
  kw.push("aovs");
  if (!lua_isnil(L, -1)) {
    if (!lua_istable(L, -1)) {
      lua_pop(L, 1);
      kw.fail("aovs", std::string("must be a list of names (") + kAovChoices + ")");
    }
    std::vector<std::string> names;
    const lua_Integer n = luaL_len(L, -1);
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_geti(L, -1, i);
      if (lua_type(L, -1) != LUA_TSTRING) {
        lua_pop(L, 2);
        kw.fail("aovs", "entry " + std::to_string(i) + " is not a name");
      }
      names.push_back(lua_tostring(L, -1));
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
    try {
      r.aovs = parse_aov_names(names, "aovs");
    } catch (const Error& e) {
      kw.fail("aovs", std::string(e.what()).substr(6));
    }
  } else {
    lua_pop(L, 1);
  }
  r.denoise = kw.boolean("denoise", false);
  // AOVs need far fewer samples than light: they only average over the pixel footprint and lens.
  r.samples = kw.integer("aov_samples", std::min(spp, 16));
  if (r.samples < 1 || r.samples > 4096) kw.fail("aov_samples", "must be in [1, 4096], got " + std::to_string(r.samples));
  return r;
}

void add_aovs(RenderedImage& img, const Scene& scene, const Camera& camera, const RenderSettings& s,
              AovRequest request, const std::atomic<bool>* cancel) {
  std::vector<Aov> aovs = request.aovs;
  if (request.denoise)
    for (Aov a : {Aov::Albedo, Aov::Normal, Aov::Depth, Aov::Emission, Aov::Glossiness})
      if (std::find(aovs.begin(), aovs.end(), a) == aovs.end()) aovs.push_back(a);
  // "samples" and "variance" come from the render itself, not from the AOV pass's rays.
  const auto take = [&](Aov a) {
    const auto it = std::find(aovs.begin(), aovs.end(), a);
    if (it == aovs.end()) return false;
    aovs.erase(it);
    return true;
  };
  const bool samples = take(Aov::Samples), variance = take(Aov::Variance);
  if (!aovs.empty()) img.image.layers = render_aovs(scene, camera, s, aovs, request.samples, cancel);
  if (samples)
    img.image.layers.push_back(samples_layer(s.width, s.height, img.pixel_spp, img.stats.spp_reached));
  if ((variance || request.denoise) && !img.variance.empty())
    img.image.layers.push_back({"variance", {"Y"}, img.variance});
  if (request.denoise) img.image = denoise(img.image);
}

namespace {

std::shared_ptr<RenderedImage> self_image(lua_State* L, const char* method) {
  auto img = to_object<RenderedImage>(L, 1);
  if (!img) throw Error(std::string("image:") + method + " must be called with ':' on an image");
  return img;
}

// image:write(path [, {exposure = stops, tonemap = "standard" | "filmic" | "agx"}]); --exposure and --tonemap
// on the command line win over the script's values.
int image_write(lua_State* L) {
  auto img = self_image(L, "write");
  if (lua_type(L, 2) != LUA_TSTRING) throw Error("image:write expects a file name");
  const std::string path = lua_tostring(L, 2);
  check_write(L, path, "image:write");
  WriteOptions options;
  if (!lua_isnoneornil(L, 3)) {
    KwArgs kw(L, 3, "image:write");
    options.exposure = float(kw.number("exposure", 0));
    const std::string view = kw.string("tonemap", "standard");
    if (!parse_view_transform(view, options.view))
      kw.fail("tonemap", std::string("must be ") + kViewTransformChoices + ", got \"" + view + "\"");
    kw.finish();
  }
  const RunContext& ctx = run_context(L);
  if (dist::rank() != 0) {  // a distributed render's image is rank 0's; the other ranks write nothing
    lua_settop(L, 1);
    return 1;
  }
  if (ctx.exposure_override) options.exposure = *ctx.exposure_override;
  if (ctx.tonemap_override) options.view = *ctx.tonemap_override;
  const auto t0 = std::chrono::steady_clock::now();
  write_image(img->image, path, options);
  run_context(L).write_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!run_context(L).quiet) std::fprintf(stderr, "wrote %s\n", path.c_str());
  lua_settop(L, 1);
  return 1;
}

// image:pixel(x, y) -> r, g, b (0-based, (0,0) top left)
int image_pixel(lua_State* L) {
  auto img = self_image(L, "pixel");
  const lua_Integer x = luaL_checkinteger(L, 2), y = luaL_checkinteger(L, 3);
  if (x < 0 || y < 0 || x >= img->image.width || y >= img->image.height)
    throw Error("image:pixel: (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the image");
  const Rgb c = img->image.at(int(x), int(y));
  lua_pushnumber(L, c.r);
  lua_pushnumber(L, c.g);
  lua_pushnumber(L, c.b);
  return 3;
}

// image:mean() -> r, g, b over all pixels
int image_mean(lua_State* L) {
  auto img = self_image(L, "mean");
  double r = 0, g = 0, b = 0;
  for (const Rgb& c : img->image.pixels) r += c.r, g += c.g, b += c.b;
  const double n = double(img->image.pixels.size());
  lua_pushnumber(L, r / n);
  lua_pushnumber(L, g / n);
  lua_pushnumber(L, b / n);
  return 3;
}

// image.stages: nil unless the render collected its profile, else {threads = n, <stage> = {seconds, calls,
// items}, ..., shade = {<material type> = {...}}} (render/stage_stats.h; shade lists the types that were hit;
// shadows also has blocked and tested where next-event estimation's shadow rays were counted).
void push_stages(lua_State* L, const StageStats& st) {
  if (!st.enabled) {
    lua_pushnil(L);
    return;
  }
  auto push_time = [&](const StageTime& t) {
    lua_createtable(L, 0, 3);
    lua_pushnumber(L, t.seconds);
    lua_setfield(L, -2, "seconds");
    lua_pushinteger(L, lua_Integer(t.calls));
    lua_setfield(L, -2, "calls");
    lua_pushinteger(L, lua_Integer(t.items));
    lua_setfield(L, -2, "items");
    if (t.tested > 0) {
      lua_pushinteger(L, lua_Integer(t.blocked));
      lua_setfield(L, -2, "blocked");
      lua_pushinteger(L, lua_Integer(t.tested));
      lua_setfield(L, -2, "tested");
    }
  };
  lua_createtable(L, 0, kStageCount + 2);
  lua_pushinteger(L, st.threads);
  lua_setfield(L, -2, "threads");
  for (int i = 0; i < kStageCount; ++i) {
    push_time(st.stage[i]);
    lua_setfield(L, -2, stage_name(Stage(i)));
  }
  lua_newtable(L);
  for (int t = 0; t < kShadedMaterialTypeCount; ++t)
    if (st.shade[t].calls != 0) {
      push_time(st.shade[t]);
      lua_setfield(L, -2, shade_stage_name(MaterialType(t)));
    }
  lua_setfield(L, -2, "shade");
}

int image_index(lua_State* L) {
  auto img = to_object<RenderedImage>(L, 1);
  if (!img) throw Error("image fields need an image");
  const std::string key = luaL_checkstring(L, 2);
  if (key == "width") {
    lua_pushinteger(L, img->image.width);
  } else if (key == "height") {
    lua_pushinteger(L, img->image.height);
  } else if (key == "rays") {
    lua_pushinteger(L, lua_Integer(img->stats.rays()));
  } else if (key == "dropped_samples") {
    lua_pushinteger(L, lua_Integer(img->stats.dropped_samples));
  } else if (key == "render_seconds") {
    lua_pushnumber(L, img->stats.render_seconds);
  } else if (key == "build_seconds") {
    lua_pushnumber(L, img->build_seconds);
  } else if (key == "scene_reused") {
    lua_pushboolean(L, img->scene_reused);
  } else if (key == "interrupted") {
    lua_pushboolean(L, img->stats.interrupted);
  } else if (key == "time_limited") {
    lua_pushboolean(L, img->stats.time_limited);
  } else if (key == "spp") {  // reached: the most any pixel took (fewer than asked after a time limit)
    lua_pushinteger(L, img->stats.spp_reached);
  } else if (key == "samples") {  // camera samples taken in all (adaptive sampling takes fewer)
    lua_pushinteger(L, lua_Integer(img->stats.samples_done));
  } else if (key == "stages") {
    push_stages(L, img->stats.stages);
  } else if (key == "layers") {
    lua_createtable(L, int(img->image.layers.size()), 0);
    for (size_t i = 0; i < img->image.layers.size(); ++i) {
      lua_pushstring(L, img->image.layers[i].name.c_str());
      lua_seti(L, -2, lua_Integer(i + 1));
    }
  } else if (push_method(L, 1, key)) {
  } else {
    throw Error("image has no field '" + key + "'");
  }
  return 1;
}

// image:layer(name) -> an image of that layer: three channels as R, G, B; one channel as grey.
int image_layer(lua_State* L) {
  auto img = self_image(L, "layer");
  const std::string name = luaL_checkstring(L, 2);
  const ImageLayer* layer = img->image.layer(name);
  if (!layer) {
    std::string known;
    for (const ImageLayer& l : img->image.layers) known += (known.empty() ? "" : ", ") + l.name;
    throw Error("image:layer: the image has no layer '" + name + "' (it has: " + (known.empty() ? "none" : known) +
                ")");
  }
  auto out = std::make_shared<RenderedImage>();
  out->image = Image(img->image.width, img->image.height);
  out->image.attributes = img->image.attributes;
  const size_t k = layer->channels.size();
  for (size_t i = 0; i < out->image.pixels.size(); ++i) {
    const float* v = layer->at(i);
    out->image.pixels[i] = k >= 3 ? Rgb(v[0], v[1], v[2]) : Rgb(v[0]);
  }
  out->stats = img->stats;
  push_object(L, std::move(out));
  return 1;
}

// torte.denoise(image [, {strength = 1, iterations = 5}]) -> a new image (film/denoise.h).
int l_denoise(lua_State* L) {
  auto img = to_object<RenderedImage>(L, 1);
  if (!img) throw Error("torte.denoise expects an image, got " + type_name(L, 1));
  DenoiseOptions o;
  if (!lua_isnoneornil(L, 2)) {
    KwArgs kw(L, 2, "torte.denoise");
    o.strength = float(kw.number("strength", o.strength));
    o.iterations = kw.integer("iterations", o.iterations);
    kw.finish();
  }
  auto out = std::make_shared<RenderedImage>(*img);
  out->image = denoise(img->image, o);
  push_object(L, std::move(out));
  return 1;
}

}  // namespace

void open_images(lua_State* L, int torte_index) {
  // Metatables get their methods once; push_object creates them on first use, so make one now.
  push_object(L, std::make_shared<RenderedImage>());
  lua_getmetatable(L, -1);
  lua_pushcfunction(L, guarded<image_index>);
  lua_setfield(L, -2, "__index");
  const luaL_Reg image_methods[] = {{"write", guarded<image_write>}, {"pixel", guarded<image_pixel>},
                                    {"mean", guarded<image_mean>}, {"layer", guarded<image_layer>},
                                    {nullptr, nullptr}};
  set_methods(L, image_methods);
  lua_pop(L, 2);
  const luaL_Reg fns[] = {{"denoise", guarded<l_denoise>}, {nullptr, nullptr}};
  lua_pushvalue(L, torte_index);
  set_functions(L, fns);
  lua_pop(L, 1);
}

}  // namespace torte::lua
