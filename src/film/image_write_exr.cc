// EXR files through OpenEXR itself (Debian's libopenexr-dev), not OpenImageIO: writing is all torte asks of EXR
// on every render, and OpenImageIO's ~250 shared libraries added ~120 MB to the resident memory of every process
// that saved an image (bench/RESULTS.md, 2026-12-07). Reading still goes through OpenImageIO (image_io.cc).
#include "film/image_write_exr.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfMatrixAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>

#include <algorithm>
#include <exception>
#include <mutex>
#include <set>
#include <thread>
#include <variant>

#include "core/text.h"
#include "film/image_write_common.h"

namespace torte {

namespace {

// Large images are compressed on OpenEXR's own thread pool, one thread per core (as OpenImageIO set it up);
// small ones (previews, tests) on the calling thread, so most processes never start the pool.
int exr_threads(size_t pixels) {
  if (pixels < (size_t(1) << 20)) return 0;
  static std::once_flag once;
  static int threads = 1;
  std::call_once(once, [] {
    threads = int(std::max(1u, std::thread::hardware_concurrency()));
    Imf::setGlobalThreadCount(threads);
  });
  return threads;
}

void add_attribute(Imf::Header& header, const ImageAttribute& a) {
  if (const auto* s = std::get_if<std::string>(&a.value)) {
    header.insert(a.name, Imf::StringAttribute(*s));
  } else if (const auto* i = std::get_if<int>(&a.value)) {
    header.insert(a.name, Imf::IntAttribute(*i));
  } else if (const auto* f = std::get_if<float>(&a.value)) {
    header.insert(a.name, Imf::FloatAttribute(*f));
  } else if (const auto* m = std::get_if<std::array<float, 16>>(&a.value)) {
    const float* v = m->data();
    header.insert(a.name, Imf::M44fAttribute(Imath::M44f(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9],
                                                         v[10], v[11], v[12], v[13], v[14], v[15])));
  }
}

}  // namespace

void write_exr(const Image& image, const std::string& path) {
  check_image_to_write(image, path);
  check_layers_to_write(image, path);
  const int w = image.width, h = image.height;
  Imf::Header header(w, h);
  header.compression() = Imf::ZIP_COMPRESSION;
  Imf::FrameBuffer frame;
  std::set<std::string> names;
  // One slice per channel, straight from the image's arrays: RGB from the pixels, a layer's channels (named
  // <layer>.<channel>, as multi-layer EXR readers expect) from its interleaved values.
  const auto add = [&](const std::string& name, const float* first, size_t stride_floats) {
    if (!names.insert(name).second) write_error(path, "two channels are named '" + name + "'");
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    const size_t x_stride = stride_floats * sizeof(float);
    frame.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(first)), x_stride,
                                  x_stride * size_t(w)));
  };
  static_assert(sizeof(Rgb) == 3 * sizeof(float));
  const float* rgb = &image.pixels[0].r;
  add("R", rgb, 3);
  add("G", rgb + 1, 3);
  add("B", rgb + 2, 3);
  for (const ImageLayer& l : image.layers)
    for (size_t c = 0; c < l.channels.size(); ++c)
      add(l.name + "." + l.channels[c], l.values.data() + c, l.channels.size());
  create_parent_directories(path);
  try {
    // An attribute of a standard name and another type throws too.
    for (const ImageAttribute& a : image.attributes) add_attribute(header, a);
    Imf::OutputFile file(path.c_str(), header, exr_threads(image.pixels.size()));
    file.setFrameBuffer(frame);
    file.writePixels(h);
  } catch (const std::exception& e) {
    write_error(path, one_line_message(e.what(), "no message from OpenEXR"));
  }
}

}  // namespace torte
