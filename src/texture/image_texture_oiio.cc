// ImageSource through OpenImageIO's TextureSystem.
#include "texture/image_texture_oiio.h"

#include <OpenImageIO/oiioversion.h>
#include <OpenImageIO/texture.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

#include "core/error.h"
#include "core/file_read.h"
#include "core/memory_budget.h"
#include "core/quiet_stderr.h"
#include "core/text.h"
#include "film/image_header_check.h"

namespace torte {

namespace {

namespace OIIO = OIIO_NAMESPACE;

// OpenImageIO 2.4 (Debian 12) has no colour transform in TextureOpt (no colortransformid), so sRGB is decoded
// after filtering (OiioImageSource::lookup). Revisit when the minimum version gains one.
static_assert(OIIO_VERSION >= OIIO_MAKE_VERSION(2, 4, 0), "torte needs OpenImageIO 2.4 or newer");

// One TextureSystem for the process, with its own ImageCache (not the shared one other code might configure).
// Never destroyed: image sources may outlive main()'s locals, and tearing the cache down at exit gains nothing.
OIIO::TextureSystem& texture_system() {
  static OIIO::TextureSystem* ts = [] {
    OIIO::TextureSystem* t = OIIO::TextureSystem::create(/*shared=*/false);
    t->attribute("automip", 1);      // MIP levels for untiled, un-MIPped files (PNG, JPEG, ...) built on load
    t->attribute("gray_to_rgb", 1);  // one-channel images read as grey RGB
    t->attribute("max_memory_MB", 1024.0f);
    return t;
  }();
  return *ts;
}

// The calling thread's Perthread record of the texture system (created on first use by each thread).
OIIO::TextureSystem::Perthread* perthread() {
  thread_local OIIO::TextureSystem::Perthread* pt = texture_system().get_perthread_info();
  return pt;
}

inline float srgb_to_linear(float v) {
  if (v <= 0.04045f) return v * (1 / 12.92f);
  return std::pow((v + 0.055f) * (1 / 1.055f), 2.4f);
}

// The image cache's message for a file it cannot read, without its boilerplate lines ('Error reading from
// "<file>" (subimg=0, ...)', 'PNG library error') when the reader said more, as one line.
std::string cache_error(const std::string& text) {
  std::string kept;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) eol = text.size();
    const std::string_view line(text.data() + pos, eol - pos);
    pos = eol + 1;
    if (line.starts_with("Error reading from \"") || line.starts_with("Invalid image file \"") ||
        line == "PNG library error")
      continue;
    kept.append(line).push_back('\n');
  }
  return one_line_message(kept.empty() ? text : kept, "");
}

class OiioImageSource final : public ImageSource {
 public:
  OiioImageSource(std::string path, OIIO::TextureSystem::TextureHandle* handle, const ImageTextureOptions& options,
                  bool decode_srgb, int width, int height)
      : path_(std::move(path)), handle_(handle), decode_srgb_(decode_srgb), first_channel_(options.first_channel),
        width_(width), height_(height) {
    switch (options.wrap) {
      case ImageTextureOptions::Wrap::Periodic: wrap_ = OIIO::TextureOpt::WrapPeriodic; break;
      case ImageTextureOptions::Wrap::Clamp: wrap_ = OIIO::TextureOpt::WrapClamp; break;
      case ImageTextureOptions::Wrap::Black: wrap_ = OIIO::TextureOpt::WrapBlack; break;
      case ImageTextureOptions::Wrap::Mirror: wrap_ = OIIO::TextureOpt::WrapMirror; break;
    }
    switch (options.filter) {
      case ImageTextureOptions::Filter::Closest:
        mip_ = OIIO::TextureOpt::MipModeNoMIP;
        interp_ = OIIO::TextureOpt::InterpClosest;
        break;
      case ImageTextureOptions::Filter::Bilinear:
        mip_ = OIIO::TextureOpt::MipModeOneLevel;
        interp_ = OIIO::TextureOpt::InterpBilinear;
        break;
      case ImageTextureOptions::Filter::Trilinear:
        mip_ = OIIO::TextureOpt::MipModeTrilinear;
        interp_ = OIIO::TextureOpt::InterpBilinear;
        break;
    }
  }

  Rgb lookup(Vec2f st, float filter_width) const override {
    OIIO::TextureOpt opt;
    opt.swrap = opt.twrap = wrap_;
    opt.mipmode = mip_;
    opt.interpmode = interp_;
    opt.firstchannel = first_channel_;
    // An isotropic footprint: the screen-space derivatives stand in for the st-space filter width. OIIO's t
    // grows downwards (row 0 is the top), uv's v upwards, hence 1 - t.
    const float w = std::isfinite(filter_width) && filter_width > 0 ? filter_width : 0.0f;
    float rgb[3] = {0, 0, 0};
    if (!texture_system().texture(handle_, perthread(), opt, st.x, 1.0f - st.y, w, 0, 0, w, 3, rgb)) {
      record_failure(texture_system().geterror());
      return Rgb(0);
    }
    if (decode_srgb_) return {srgb_to_linear(rgb[0]), srgb_to_linear(rgb[1]), srgb_to_linear(rgb[2])};
    return {rgb[0], rgb[1], rgb[2]};
  }

  std::string description() const override {
    return path_ + " (" + std::to_string(width_) + "x" + std::to_string(height_) + (decode_srgb_ ? ", sRGB)" : ", linear)");
  }

  std::string failure() const override {
    if (!failed_.load(std::memory_order_acquire)) return {};
    std::lock_guard lock(failure_mutex_);
    return failure_;
  }

 private:
  // OpenImageIO reports a tile it cannot read once and then serves it black, so the first message is kept.
  void record_failure(const std::string& message) const {
    std::lock_guard lock(failure_mutex_);
    if (failed_.load(std::memory_order_relaxed)) return;
    const std::string why = cache_error(message);
    failure_ = "cannot read image texture '" + escape_text(path_) + "' while rendering: " +
               (why.empty() ? "the pixel data is truncated or corrupt" : why);
    failed_.store(true, std::memory_order_release);
  }

  std::string path_;
  OIIO::TextureSystem::TextureHandle* handle_;
  OIIO::TextureOpt::Wrap wrap_ = OIIO::TextureOpt::WrapPeriodic;
  OIIO::TextureOpt::MipMode mip_ = OIIO::TextureOpt::MipModeTrilinear;
  OIIO::TextureOpt::InterpMode interp_ = OIIO::TextureOpt::InterpBilinear;
  bool decode_srgb_;
  int first_channel_;
  int width_, height_;
  mutable std::mutex failure_mutex_;
  mutable std::atomic<bool> failed_{false};
  mutable std::string failure_;
};

// Checks a texture's header before its pixels are read: the image cache reads an untiled file (PNG, JPEG, PPM,
// HDR, ...) as one tile holding the whole image, MIP levels add a third, and a failed allocation there leaves
// other threads waiting for the tile forever. So the size is checked against the memory budget first.
void check_texture_size(const std::string& path, const OIIO::ImageSpec& spec) {
  const std::string what = "image texture '" + escape_text(path) + "' (" + std::to_string(spec.width) + "x" +
                           std::to_string(spec.height) + ", " + std::to_string(spec.nchannels) + " channels)";
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw Error("cannot read " + what + ": the header declares no pixels");
  if (spec.depth > 1) throw Error("cannot read " + what + ": volume images (depth " + std::to_string(spec.depth) +
                                  ") are not supported");
  // A tiled file's cache unit is a tile, and a header may declare tiles far larger than the image; the cache's
  // MIP levels of an untiled file follow the display window (OpenEXR's displayWindow), which may dwarf the pixels.
  const auto area = [&](int w, int h) { return checked_bytes(uint64_t(std::max(w, 0)), uint64_t(std::max(h, 0)), what); };
  const uint64_t texels = std::max({area(spec.width, spec.height), area(spec.tile_width, spec.tile_height),
                                    area(spec.full_width, spec.full_height)});
  // Per texel: the cached tile, the reader's buffer of the same size and a float copy when it converts (OpenImageIO
  // 2.4 was seen past 13 bytes per 8-bit RGB texel; 4/3 of the file's own size let a 19791880x8 BMP reach 2 GB).
  const uint64_t per_texel = 2 * uint64_t(spec.nchannels) * spec.format.size() + 4 * uint64_t(spec.nchannels);
  const uint64_t bytes = checked_bytes(texels, per_texel, what);
  reserve_memory(bytes > UINT64_MAX / 2 ? UINT64_MAX : bytes + bytes / 3, what);
}

// Reads the finest level's texel at the image centre now, on the calling thread: for an untiled file that reads
// the whole image, so a truncated or corrupt file fails here with its name rather than rendering black (the cache
// reports a bad tile to the first lookup only). libpng's own stderr lines are kept out of the one-line error.
void preload(OIIO::TextureSystem& ts, OIIO::TextureSystem::TextureHandle* handle, const std::string& path) {
  OIIO::TextureOpt opt;
  opt.mipmode = OIIO::TextureOpt::MipModeNoMIP;
  opt.interpmode = OIIO::TextureOpt::InterpClosest;
  float rgb[3];
  bool ok;
  {
    QuietStderr quiet;
    ok = ts.texture(handle, perthread(), opt, 0.5f, 0.5f, 0, 0, 0, 0, 3, rgb);
  }
  if (ok) return;
  const std::string why = cache_error(ts.geterror());
  ts.invalidate(OIIO::ustring(path), true);  // so a later attempt reads the file again rather than a black tile
  throw Error("cannot read image texture '" + escape_text(path) + "': the pixel data is truncated or corrupt" +
              (why.empty() ? std::string() : " (" + why + ")"));
}

}  // namespace

std::shared_ptr<const ImageSource> open_image_texture(const std::string& path, const ImageTextureOptions& options) {
  const std::string problem = regular_file_problem(path);
  if (!problem.empty()) throw Error("cannot open image texture '" + escape_text(path) + "': " + problem);
  const ImageHeaderCheck header = check_image_header(path);
  if (!header.problem.empty()) throw Error("cannot read image texture '" + escape_text(path) + "': " + header.problem);
  reserve_memory(header.decode_bytes, "image texture '" + escape_text(path) + "' (OpenEXR decoding buffers)");
  OIIO::TextureSystem& ts = texture_system();
  OIIO::ImageSpec spec;
  OIIO::TextureSystem::TextureHandle* handle = nullptr;
  bool ok;
  {
    QuietStderr quiet;
    handle = ts.get_texture_handle(OIIO::ustring(path), perthread());
    ok = handle && ts.good(handle) && ts.get_imagespec(handle, perthread(), 0, spec);
  }
  if (!ok) {
    const std::string why = cache_error(ts.geterror());
    ts.invalidate(OIIO::ustring(path), true);
    throw Error("cannot read image texture '" + escape_text(path) + "'" + (why.empty() ? std::string() : ": " + why));
  }
  check_texture_size(path, spec);
  if (options.first_channel < 0 || options.first_channel >= spec.nchannels)
    throw Error("image texture '" + escape_text(path) + "' has " + std::to_string(spec.nchannels) +
                " channels; channel " + std::to_string(options.first_channel) + " was asked for");
  preload(ts, handle, path);
  bool srgb = false;
  switch (options.color_space) {
    case ImageTextureOptions::ColorSpace::Srgb: srgb = true; break;
    case ImageTextureOptions::ColorSpace::Linear: srgb = false; break;
    case ImageTextureOptions::ColorSpace::Auto: {
      const std::string cs = spec.get_string_attribute("oiio:ColorSpace");
      const bool linear_file = OIIO::Strutil::iequals(cs, "linear") || OIIO::Strutil::iequals(cs, "scene_linear") ||
                               OIIO::Strutil::iequals(cs, "lin_srgb");
      srgb = spec.format.basetype == OIIO::TypeDesc::UINT8 && !linear_file;
      break;
    }
  }
  return std::make_shared<OiioImageSource>(path, handle, options, srgb, spec.width, spec.height);
}

void invalidate_image_texture(const std::string& path) { texture_system().invalidate(OIIO::ustring(path), true); }

}  // namespace torte
