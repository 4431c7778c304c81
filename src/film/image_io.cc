#include "film/image_io.h"

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include <algorithm>
#include <cmath>
#include <variant>
#include <vector>

#include "core/error.h"
#include "core/file_read.h"
#include "core/memory_budget.h"
#include "core/quiet_stderr.h"
#include "core/text.h"
#include "film/image_header_check.h"
#include "film/image_write_common.h"

namespace torte {

namespace {

[[noreturn]] void read_error(const std::string& path, const std::string& reason) {
  throw Error("cannot read image '" + escape_text(path) + "': " + reason);
}

// OIIO's messages can span lines, repeat a line and end in a newline; keep ours one line.
std::string one_line(const std::string& s) { return one_line_message(s, "no message from OpenImageIO"); }

}  // namespace

void write_image(const Image& image, const std::string& path, const WriteOptions& options) {
  check_image_to_write(image, path);
  const std::string ext = lower_extension(path);
  // EXR and PNG go to the writing module (image_io_loader.cc); every other format through OpenImageIO.
  if (ext == ".exr" || ext == ".png") write_error(path, "internal: EXR and PNG are the writing module's");
  if (ext.empty()) write_error(path, "no file extension to choose the format from");
  // Ask OpenImageIO for a writer before touching the file system, so an unknown extension creates no directories.
  auto out = OIIO::ImageOutput::create(path);
  if (!out) write_error(path, one_line(OIIO::geterror()));
  create_parent_directories(path);

  const int w = image.width, h = image.height;
  const size_t n = image.pixels.size();
  OIIO::ImageSpec spec;
  std::vector<float> linear_data;
  std::vector<uint8_t> display_data;
  const void* data = nullptr;
  OIIO::TypeDesc data_type;
  const bool linear = ext == ".hdr";
  if (linear) {
    spec = OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT);
    spec.attribute("oiio:ColorSpace", "Linear");
    // RGBE has no sign and no NaN/inf: such values would come back as garbage, so they are written as 0.
    linear_data.resize(3 * n);
    for (size_t i = 0; i < n; ++i) {
      const Rgb& p = image.pixels[i];
      const float c[3] = {p.r, p.g, p.b};
      for (int k = 0; k < 3; ++k) linear_data[3 * i + size_t(k)] = c[k] > 0 && std::isfinite(c[k]) ? c[k] : 0.0f;
    }
    data = linear_data.data();
    data_type = OIIO::TypeDesc::FLOAT;
  } else {
    spec = OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    display_data = display_bytes(image, options);
    data = display_data.data();
    data_type = OIIO::TypeDesc::UINT8;
  }
  for (const ImageAttribute& a : image.attributes) {
    if (const auto* v = std::get_if<std::string>(&a.value)) {
      spec.attribute(a.name, *v);
    } else if (!linear) {
      continue;  // JPEG, TIFF and the like get text only, as PNG
    } else if (const auto* i = std::get_if<int>(&a.value)) {
      spec.attribute(a.name, *i);
    } else if (const auto* f = std::get_if<float>(&a.value)) {
      spec.attribute(a.name, *f);
    } else if (const auto* m = std::get_if<std::array<float, 16>>(&a.value)) {
      spec.attribute(a.name, OIIO::TypeMatrix44, m->data());
    }
  }

  if (!out->open(path, spec)) write_error(path, one_line(out->geterror()));
  if (!out->write_image(data_type, data)) {
    const std::string reason = one_line(out->geterror());
    out->close();
    write_error(path, reason);
  }
  if (!out->close()) write_error(path, one_line(out->geterror()));
}

Image read_image(const std::string& path) {
  if (const std::string problem = regular_file_problem(path); !problem.empty()) read_error(path, problem);
  // OpenEXR allocates from header values before reading pixels (a string attribute's declared size, a block's
  // decoding buffers): checked here, since OpenImageIO gives no hook before that.
  const ImageHeaderCheck header = check_image_header(path);
  if (!header.problem.empty()) read_error(path, header.problem);
  reserve_memory(header.decode_bytes, "image '" + escape_text(path) + "' (OpenEXR decoding buffers)");
  std::unique_ptr<OIIO::ImageInput> in;
  {
    QuietStderr quiet;  // libpng prints its own line for a broken file; OIIO's error string has the message
    in = OIIO::ImageInput::open(path);
  }
  if (!in) read_error(path, one_line(OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  const int w = spec.width, h = spec.height, nc = spec.nchannels;
  if (w <= 0 || h <= 0 || nc <= 0) read_error(path, "the file holds no pixels");
  // Sizes come from the header: checked before anything is allocated, naming the file and the size.
  const std::string what = "image '" + escape_text(path) + "' (" + std::to_string(w) + "x" + std::to_string(h) + ", " +
                           std::to_string(nc) + " channels)";
  const uint64_t pixels = checked_bytes(uint64_t(w), uint64_t(h), what);
  const uint64_t decoded = checked_bytes(pixels, uint64_t(nc) * sizeof(float), what);
  reserve_memory(checked_bytes(pixels, sizeof(Rgb), what) + decoded, what);
  std::vector<float> buf(size_t(pixels) * size_t(nc));
  bool ok;
  {
    QuietStderr quiet;
    ok = in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, buf.data());
  }
  // Some readers (PPM) report a short file without a message.
  if (!ok) {
    const std::string why = one_line_message(in->geterror(), "");
    read_error(path, "the pixel data is truncated or corrupt" + (why.empty() ? std::string() : " (" + why + ")"));
  }

  // 8-bit PNG and JPEG are sRGB whatever they are tagged; other 8-bit files (BMP, TGA, ...) carry no colour
  // space and are display-referred by convention, as write_image makes them.
  const std::string format = in->format_name(), space = spec.get_string_attribute("oiio:ColorSpace");
  const bool srgb = OIIO::Strutil::iequals(space, "sRGB") ||
                    (spec.format == OIIO::TypeDesc::UINT8 && (space.empty() || format == "png" || format == "jpeg"));
  const auto decode = [srgb](float v) { return srgb ? srgb_to_linear(v) : v; };
  // Grey (and grey + alpha) images are replicated to RGB; other channels past the third (alpha, ...) are dropped.
  const int cg = nc >= 3 ? 1 : 0, cb = nc >= 3 ? 2 : 0;
  Image image(w, h);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const float* p = &buf[i * nc];
    image.pixels[i] = Rgb(decode(p[0]), decode(p[cg]), decode(p[cb]));
  }
  // Multi-layer EXR (what write_image makes of an image's layers): channels named <layer>.<channel> past the
  // first three come back as layers, in file order.
  for (int c = 3; c < nc;) {
    const std::string& name = spec.channel_name(c);
    const size_t dot = name.rfind('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == name.size()) {  // not <layer>.<channel>: dropped
      ++c;
      continue;
    }
    ImageLayer layer{name.substr(0, dot), {}, {}};
    const int first = c;
    const auto same_layer = [&](const std::string& other) {
      return other.size() > dot + 1 && other.compare(0, dot + 1, name, 0, dot + 1) == 0 &&
             other.find('.', dot + 1) == std::string::npos;
    };
    while (c < nc && same_layer(spec.channel_name(c))) layer.channels.push_back(spec.channel_name(c++).substr(dot + 1));
    const size_t k = layer.channels.size();
    layer.values.resize(image.pixels.size() * k);
    for (size_t i = 0; i < image.pixels.size(); ++i)
      for (size_t j = 0; j < k; ++j) layer.values[i * k + j] = buf[i * size_t(nc) + size_t(first) + j];
    image.layers.push_back(std::move(layer));
  }
  return image;
}

}  // namespace torte
