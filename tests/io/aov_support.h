// Shared by the AOV tests (test_*_aov.cc): a render's layer as it reads back from the file.
#pragma once
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "film/image_io.h"
#include "test_support.h"

namespace torte::test {

/// Runs torte with `args` (which must succeed) and returns layer `name` of the image it wrote to `path`, after
/// checking that the layer has `channels` and a value per channel and pixel.
inline ImageLayer rendered_layer(const TempDir& dir, const std::vector<std::string>& args, const std::string& path,
                                 const std::string& name, const std::vector<std::string>& channels) {
  const Result r = run_torte(dir, args, 120);
  check_no_crash(r);
  INFO("stderr: " << r.err);
  REQUIRE(r.code == 0);
  const Image img = read_image(path);
  const ImageLayer* l = img.layer(name);
  REQUIRE(l);
  CHECK(l->channels == channels);
  REQUIRE(l->values.size() == channels.size() * img.pixels.size());
  return *l;
}

}  // namespace torte::test
