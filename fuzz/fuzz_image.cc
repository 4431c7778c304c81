// Image loading through OpenImageIO as torte does it: read_image (src/film/image_io.h: environment maps) and
// image textures (src/texture/image_texture_oiio.h: open, then lookups at several points and footprints, which
// is when the texture cache reads and MIP-maps the pixels). The first input byte picks the file extension
// (kExtensions[byte % 8]), the second the texture options (wrap: bits 0-1, filter: bits 2-3 mod 3, colour space:
// bits 4-5 mod 3); the rest is the file, written to one fixed path in the scratch directory (the cache entry is
// invalidated after each input). Promise: pixels or a torte::Error naming the file.
#include <cmath>
#include <string>

#include "core/error.h"
#include "error_checks.h"
#include "film/image_io.h"
#include "fuzz_input.h"
#include "fuzz_support.h"
#include "harness.h"
#include "texture/image_texture_oiio.h"

namespace {

const char* const kExtensions[] = {"png", "jpg", "exr", "hdr", "ppm", "tga", "bmp", "tif"};

void check_named(const torte::Error& e, const std::string& path) {
  if (std::string_view(e.what()).find(path) == std::string_view::npos)
    torte::fuzz::broken_promise(std::string("image error does not name the file: ") + e.what());
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  torte::fuzz::init_process();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  torte::fuzz::FuzzInput in(data, size);
  const uint8_t extension = in.byte(), flags = in.byte();
  const std::string path = torte::fuzz::scratch_path(std::string("image.") + kExtensions[extension % 8]);
  torte::fuzz::write_file(path, in.rest());
  try {
    const torte::Image image = torte::read_image(path);
    if (image.width <= 0 || image.height <= 0 || image.pixels.size() != size_t(image.width) * size_t(image.height))
      torte::fuzz::broken_promise("read_image returned an image of inconsistent size");
  } catch (const torte::Error& e) {
    check_named(e, path);
  }
  torte::ImageTextureOptions options;
  options.wrap = torte::ImageTextureOptions::Wrap(flags & 3);
  options.filter = torte::ImageTextureOptions::Filter(((flags >> 2) & 3) % 3);
  options.color_space = torte::ImageTextureOptions::ColorSpace(((flags >> 4) & 3) % 3);
  try {
    const auto source = torte::open_image_texture(path, options);
    float sum = 0;
    for (float st : {0.0f, 0.37f, 1.0f, -2.5f, 1e9f, NAN})
      for (float width : {0.0f, 0.01f, 0.5f, 4.0f}) {
        const torte::Rgb c = source->lookup({st, 1 - st}, width);
        sum += c.r + c.g + c.b;
      }
    (void)source->description();
    (void)sum;
  } catch (const torte::Error& e) {
    check_named(e, path);
  }
  torte::invalidate_image_texture(path);
  return 0;
}
