// PNG files through libpng itself, not OpenImageIO, for the reason image_write_exr.cc gives: every render writes
// one (the preview beside its EXR). libpng reports errors by longjmp, so the frame between its setjmp and the end
// holds no C++ object that would need a destructor, and the message is copied into a plain buffer.
#include "film/image_write_png.h"

#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <variant>
#include <vector>

#include "core/text.h"
#include "film/image_write_common.h"

namespace torte {

namespace {

struct PngError {
  char message[256] = {};
};

void on_error(png_structp png, png_const_charp message) {
  auto* e = static_cast<PngError*>(png_get_error_ptr(png));
  std::snprintf(e->message, sizeof e->message, "%s", message ? message : "libpng error");
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}  // nothing of ours can be wrong in a way a warning reports

// Writes the header, the text chunks and the rows; false with `error` set on failure.
bool write_rows(std::FILE* file, int w, int h, const uint8_t* rgb, png_text* text, int text_count, PngError* error) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, error, on_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    std::snprintf(error->message, sizeof error->message, "out of memory");
    png_destroy_write_struct(&png, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, png_uint_32(w), png_uint_32(h), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);  // the view transforms encode sRGB
  if (text_count > 0) png_set_text(png, info, text, text_count);
  png_write_info(png, info);
  for (int y = 0; y < h; ++y) png_write_row(png, rgb + size_t(y) * size_t(w) * 3);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

void write_png(const Image& image, const std::string& path, const WriteOptions& options) {
  check_image_to_write(image, path);
  const std::vector<uint8_t> rgb = display_bytes(image, options);
  // Text attributes only (tEXt keywords have 1 to 79 characters); numbers and matrices stay in the EXR.
  std::vector<png_text> text;
  for (const ImageAttribute& a : image.attributes) {
    const auto* s = std::get_if<std::string>(&a.value);
    if (!s || a.name.empty() || a.name.size() > 79) continue;
    png_text t{};
    t.compression = PNG_TEXT_COMPRESSION_NONE;
    t.key = const_cast<char*>(a.name.c_str());
    t.text = const_cast<char*>(s->c_str());
    t.text_length = s->size();
    text.push_back(t);
  }
  create_parent_directories(path);
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) write_error(path, std::strerror(errno));
  PngError error;
  const bool ok = write_rows(file, image.width, image.height, rgb.data(), text.data(), int(text.size()), &error);
  const bool closed = std::fclose(file) == 0;
  if (!ok) write_error(path, one_line_message(error.message, "libpng error"));
  if (!closed) write_error(path, std::strerror(errno));
}

}  // namespace torte
