// ImageSource through OpenImageIO's TextureSystem.
#include "texture/image_texture_oiio.h"

#include <OpenImageIO/oiioversion.h>
#include <OpenImageIO/texture.h>

#include <cmath>
#include <filesystem>

#include "core/error.h"

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

class OiioImageSource final : public ImageSource {
 public:
  OiioImageSource(std::string path, OIIO::TextureSystem::TextureHandle* handle, const ImageTextureOptions& options,
                  bool decode_srgb, int width, int height)
      : path_(std::move(path)), handle_(handle), decode_srgb_(decode_srgb), width_(width), height_(height) {
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
    // An isotropic footprint: the screen-space derivatives stand in for the st-space filter width. OIIO's t
    // grows downwards (row 0 is the top), uv's v upwards, hence 1 - t.
    const float w = std::isfinite(filter_width) && filter_width > 0 ? filter_width : 0.0f;
    float rgb[3] = {0, 0, 0};
    if (!texture_system().texture(handle_, perthread(), opt, st.x, 1.0f - st.y, w, 0, 0, w, 3, rgb)) {
      (void)texture_system().geterror();  // clear the message; the file was checked when opened
      return Rgb(0);
    }
    if (decode_srgb_) return {srgb_to_linear(rgb[0]), srgb_to_linear(rgb[1]), srgb_to_linear(rgb[2])};
    return {rgb[0], rgb[1], rgb[2]};
  }

  std::string description() const override {
    return path_ + " (" + std::to_string(width_) + "x" + std::to_string(height_) + (decode_srgb_ ? ", sRGB)" : ", linear)");
  }

 private:
  std::string path_;
  OIIO::TextureSystem::TextureHandle* handle_;
  OIIO::TextureOpt::Wrap wrap_ = OIIO::TextureOpt::WrapPeriodic;
  OIIO::TextureOpt::MipMode mip_ = OIIO::TextureOpt::MipModeTrilinear;
  OIIO::TextureOpt::InterpMode interp_ = OIIO::TextureOpt::InterpBilinear;
  bool decode_srgb_;
  int width_, height_;
};

}  // namespace

std::shared_ptr<const ImageSource> open_image_texture(const std::string& path, const ImageTextureOptions& options) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error("cannot open image texture '" + path + "': no such file");
  OIIO::TextureSystem& ts = texture_system();
  OIIO::TextureSystem::TextureHandle* handle = ts.get_texture_handle(OIIO::ustring(path), perthread());
  OIIO::ImageSpec spec;
  if (!handle || !ts.good(handle) || !ts.get_imagespec(handle, perthread(), 0, spec)) {
    std::string why = ts.geterror();
    while (!why.empty() && (why.back() == '\n' || why.back() == ' ')) why.pop_back();
    for (char& c : why)
      if (c == '\n') c = ' ';
    throw Error("cannot read image texture '" + path + "'" + (why.empty() ? std::string() : ": " + why));
  }
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

}  // namespace torte
