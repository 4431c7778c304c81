// Image files through OpenImageIO: round trips per format, display encoding (exposure, sRGB, clamping, NaN),
// channel layouts on read, and the errors for bad paths and files.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/rng.h"
#include "film/image_io.h"
#include "test_support.h"

using namespace torte;
namespace fs = std::filesystem;

namespace {

struct ImageDir : test::TempDir {
  explicit ImageDir(const std::string& name) : test::TempDir("image_io", name) {}
};

// Random pixels with each channel drawn from [lo, hi).
Image random_image(int w, int h, float lo, float hi, uint64_t seed) {
  Image img(w, h);
  Pcg32 rng(seed);
  for (Rgb& p : img.pixels) {
    p.r = lo + (hi - lo) * rng.next_float();
    p.g = lo + (hi - lo) * rng.next_float();
    p.b = lo + (hi - lo) * rng.next_float();
  }
  return img;
}

float channel(const Rgb& p, int k) { return k == 0 ? p.r : (k == 1 ? p.g : p.b); }

}  // namespace

TEST_CASE("sRGB transfer functions", "[image_io]") {
  CHECK(linear_to_srgb(0) == 0);
  CHECK(linear_to_srgb(1) == 1);
  CHECK(linear_to_srgb(-0.5f) == 0);
  CHECK(linear_to_srgb(7) == 1);
  CHECK(linear_to_srgb(std::nanf("")) == 0);
  CHECK(linear_to_srgb(0.5f) == Approx(0.735357).epsilon(1e-5));
  CHECK(linear_to_srgb(0.002f) == Approx(0.002 * 12.92));
  CHECK(srgb_to_linear(0.735357f) == Approx(0.5).epsilon(1e-5));
  CHECK(srgb_to_linear(0.02f) == Approx(0.02 / 12.92));
  // Continuous at the breakpoint, and the two are inverses.
  CHECK(linear_to_srgb(0.0031308f * (1 + 1e-6f)) == Approx(linear_to_srgb(0.0031308f * (1 - 1e-6f))).epsilon(1e-4));
  for (float v = 0; v <= 1; v += 1.0f / 64) CHECK(srgb_to_linear(linear_to_srgb(v)) == Approx(v).margin(1e-6));
}

TEST_CASE("EXR round trip is exact in 32-bit float", "[image_io]") {
  ImageDir dir("exr");
  Image img = random_image(7, 5, -3, 1000, 1);
  img.at(0, 0) = Rgb(1e-20f, 3.0e30f, -0.0f);
  const std::string path = dir / "out.exr";
  write_image(img, path, {.exposure = 3});  // exposure applies to display formats only
  const Image back = read_image(path);
  REQUIRE(back.width == 7);
  REQUIRE(back.height == 5);
  for (size_t i = 0; i < img.pixels.size(); ++i) REQUIRE(back.pixels[i] == img.pixels[i]);
}

TEST_CASE("HDR round trip is within 1% of each pixel's largest channel", "[image_io]") {
  ImageDir dir("hdr");
  Image img(16, 8);
  Pcg32 rng(2);
  for (Rgb& p : img.pixels) {
    // Logarithmic spread over 1e-3 .. 1e2.
    p = Rgb(std::pow(10.0f, -3 + 5 * rng.next_float()), std::pow(10.0f, -3 + 5 * rng.next_float()),
            std::pow(10.0f, -3 + 5 * rng.next_float()));
  }
  img.at(0, 0) = Rgb(0.25f);
  img.at(1, 0) = Rgb(37.5f);
  img.at(2, 0) = Rgb(-1, std::nanf(""), 2);  // RGBE cannot store these: written as 0
  const std::string path = dir / "out.hdr";
  write_image(img, path);
  const Image back = read_image(path);
  REQUIRE(back.width == 16);
  REQUIRE(back.height == 8);
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    if (i == 2) continue;
    const Rgb a = img.pixels[i], b = back.pixels[i];
    for (int k = 0; k < 3; ++k) REQUIRE(std::fabs(channel(b, k) - channel(a, k)) < 0.01f * a.max_component());
  }
  for (int i : {0, 1})  // grey pixels: every channel is its pixel's largest
    for (int k = 0; k < 3; ++k) CHECK(channel(back.pixels[i], k) == Approx(channel(img.pixels[i], k)).epsilon(0.01));
  CHECK(back.at(2, 0).r == 0);
  CHECK(back.at(2, 0).g == 0);
  CHECK(back.at(2, 0).b == Approx(2).epsilon(0.01));
}

TEST_CASE("PNG round trip is 8-bit sRGB, rounded to nearest", "[image_io]") {
  ImageDir dir("png");
  Image img = random_image(19, 11, 0, 0.7f, 3);
  const std::string path = dir / "out.png";
  write_image(img, path);
  const Image back = read_image(path);
  REQUIRE(back.width == 19);
  REQUIRE(back.height == 11);
  for (size_t i = 0; i < img.pixels.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const float a = channel(img.pixels[i], k), b = channel(back.pixels[i], k);
      // Below linear 0.7 the sRGB decode's slope is under 2, so half a code value stays under 1/255 in linear.
      REQUIRE(std::fabs(b - a) < 1.0f / 255);
      // Round to nearest: within half a code value in the encoded domain.
      REQUIRE(std::fabs(linear_to_srgb(b) - linear_to_srgb(a)) <= 0.5f / 255 + 1e-5f);
    }
}

TEST_CASE("TIFF, BMP and JPEG are written and read back as sRGB", "[image_io]") {
  ImageDir dir("display");
  for (const char* file : {"out.tif", "out.bmp", "out.jpg"}) {
    INFO(file);
    const bool lossy = std::string(file) == "out.jpg";
    // JPEG is lossy; a constant colour survives its 8x8 DCT blocks almost exactly.
    Image img = lossy ? Image(16, 16) : random_image(13, 6, 0, 0.7f, 6);
    if (lossy)
      for (Rgb& p : img.pixels) p = Rgb(0.1f, 0.3f, 0.6f);
    write_image(img, dir / file);
    const Image back = read_image(dir / file);
    REQUIRE(back.width == img.width);
    REQUIRE(back.height == img.height);
    for (size_t i = 0; i < img.pixels.size(); ++i)
      for (int k = 0; k < 3; ++k)
        REQUIRE(std::fabs(linear_to_srgb(channel(back.pixels[i], k)) - linear_to_srgb(channel(img.pixels[i], k))) <=
                (lossy ? 3.0f : 0.5f) / 255 + 1e-5f);
  }
}

TEST_CASE("PNG exposure scales by 2^exposure before encoding and clamps", "[image_io]") {
  ImageDir dir("exposure");
  Image img = random_image(9, 4, 0, 0.35f, 4);
  img.at(0, 0) = Rgb(0.6f, 5, -1);  // over and under range after exposure
  const std::string path = dir / "exposed.png";
  write_image(img, path, {.exposure = 1});
  const Image back = read_image(path);
  for (size_t i = 1; i < img.pixels.size(); ++i)
    for (int k = 0; k < 3; ++k)
      REQUIRE(std::fabs(channel(back.pixels[i], k) - 2 * channel(img.pixels[i], k)) < 1.0f / 255);
  CHECK(back.at(0, 0) == Rgb(1, 1, 0));
}

TEST_CASE("Non-finite pixels are written black to display formats", "[image_io]") {
  ImageDir dir("nan");
  Image img(3, 1);
  img.at(0, 0) = Rgb(std::nanf(""), 0.5f, 0.5f);
  img.at(1, 0) = Rgb(0.5f, std::numeric_limits<float>::infinity(), 0.5f);
  img.at(2, 0) = Rgb(0.5f);
  const std::string path = dir / "nan.png";
  write_image(img, path);
  const Image back = read_image(path);
  CHECK(back.at(0, 0) == Rgb(0));
  CHECK(back.at(1, 0) == Rgb(0));
  CHECK(back.at(2, 0).r == Approx(0.5f).margin(1.0f / 255));
}

TEST_CASE("Writing creates missing parent directories", "[image_io]") {
  ImageDir dir("parents");
  const std::string path = dir / "a/b/c/out.exr";
  write_image(Image(2, 2), path);
  CHECK(fs::is_regular_file(path));
  CHECK(read_image(path).width == 2);
}

TEST_CASE("Writing fails with torte::Error naming the file", "[image_io]") {
  ImageDir dir("write_errors");
  const Image img(2, 2);
  SECTION("unknown extension") {
    const std::string path = dir / "new_dir/out.notaformat";
    CHECK_THROWS_WITH(write_image(img, path), Catch::Contains("cannot write image '" + path + "'"));
    CHECK_FALSE(fs::exists(dir / "new_dir"));  // nothing created for a format we cannot write
  }
  SECTION("no extension") {
    const std::string path = dir / "out";
    CHECK_THROWS_WITH(write_image(img, path), Catch::Contains("cannot write image '" + path + "'"));
  }
  SECTION("parent is a regular file") {
    std::ofstream(dir / "blocker") << "x";
    for (const std::string& path : {dir / "blocker/out.png", dir / "blocker/sub/out.exr"})
      CHECK_THROWS_WITH(write_image(img, path), Catch::Contains("cannot write image '" + path + "'"));
  }
  SECTION("path is a directory") {
    fs::create_directories(dir / "taken.png");
    CHECK_THROWS_AS(write_image(img, dir / "taken.png"), Error);
  }
  SECTION("empty image") {
    CHECK_THROWS_AS(write_image(Image(), dir / "empty.png"), Error);
  }
}

TEST_CASE("Reading fails with torte::Error naming the file", "[image_io]") {
  ImageDir dir("read_errors");
  const std::string missing = dir / "missing.exr";
  CHECK_THROWS_AS(read_image(missing), Error);
  CHECK_THROWS_WITH(read_image(missing), Catch::Contains(missing));
  const std::string corrupt = dir / "corrupt.png";
  std::ofstream(corrupt) << "this is not a PNG file";
  CHECK_THROWS_AS(read_image(corrupt), Error);
  CHECK_THROWS_WITH(read_image(corrupt), Catch::Contains(corrupt));
  // A valid header followed by truncated data must not come back as an image either.
  const std::string good = dir / "good.exr", truncated = dir / "truncated.exr";
  write_image(random_image(64, 64, 0, 1, 5), good);
  const auto size = fs::file_size(good);
  fs::copy_file(good, truncated);
  fs::resize_file(truncated, size / 2);
  CHECK_THROWS_WITH(read_image(truncated), Catch::Contains(truncated));
}

TEST_CASE("Reading replicates grey channels and drops alpha", "[image_io]") {
  ImageDir dir("channels");
  const auto write_raw = [](const std::string& path, int channels, OIIO::TypeDesc type, const void* data) {
    auto out = OIIO::ImageOutput::create(path);
    REQUIRE(out);
    REQUIRE(out->open(path, OIIO::ImageSpec(2, 1, channels, type)));
    REQUIRE(out->write_image(type, data));
    REQUIRE(out->close());
  };
  SECTION("grey + alpha 8-bit PNG is decoded from sRGB") {
    const unsigned char ga[4] = {188, 255, 0, 128};  // sRGB 188/255 ~ linear 0.5
    write_raw(dir / "ga.png", 2, OIIO::TypeDesc::UINT8, ga);
    const Image back = read_image(dir / "ga.png");
    CHECK(back.at(0, 0).r == Approx(srgb_to_linear(188.0f / 255)));
    CHECK(back.at(0, 0).r == back.at(0, 0).g);
    CHECK(back.at(0, 0).r == back.at(0, 0).b);
    CHECK(back.at(1, 0) == Rgb(0));
  }
  SECTION("RGBA float EXR stays linear") {
    const float rgba[8] = {0.25f, 2, 3, 0.5f, 4, 5, 6, 0};
    write_raw(dir / "rgba.exr", 4, OIIO::TypeDesc::FLOAT, rgba);
    const Image back = read_image(dir / "rgba.exr");
    CHECK(back.at(0, 0) == Rgb(0.25f, 2, 3));
    CHECK(back.at(1, 0) == Rgb(4, 5, 6));
  }
}
