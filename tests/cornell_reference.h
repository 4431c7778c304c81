// The path-traced reference of the Cornell-like box (cornell_like.h) that the bidirectional integrators' tests
// (test_bdpt, test_vcm, test_mlt, test_lt, test_igi) converge to, and what they measure against it.
#pragma once
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "cornell_like.h"
#include "scene_helpers.h"

namespace torte::test {

/// True in sanitizer builds (TORTE_TEST_REDUCED): heavy cases run with fewer samples and looser bounds.
inline bool reduced() {
  const char* v = std::getenv("TORTE_TEST_REDUCED");
  return v && std::string(v) != "0";
}

/// Root-mean-square difference of the pixels' channel averages (same-size images).
inline double rmse(const Image& a, const Image& b) {
  double sum = 0;
  for (size_t k = 0; k < a.pixels.size(); ++k) {
    const double d = a.pixels[k].average() - b.pixels[k].average();
    sum += d * d;
  }
  return std::sqrt(sum / double(a.pixels.size()));
}

/// Path tracing of the Cornell-like box, 64x64 at 4096 spp (16x16 tile means to about 0.1 %), seed 7; rendered
/// once per test binary: ctest runs every test case in a process of its own, and many of them compare with it, so
/// the first one keeps the pixels in the temporary directory under a name holding the test binary's modification
/// time (a rebuilt binary renders it again). A lock on that file makes processes that start together (ctest -j)
/// wait for the one rendering it instead of each rendering it again.
inline const Image& path_reference() {
  static const Image img = [] {
    namespace fs = std::filesystem;
    std::error_code ec;
    const auto built = fs::last_write_time("/proc/self/exe", ec).time_since_epoch().count();
    const fs::path cache = fs::temp_directory_path() / ("torte-test-path-reference-" + std::to_string(built) +
                                                        (reduced() ? "-reduced" : "") + ".bin");
    Image out;
    out.width = out.height = 64;
    out.pixels.resize(64 * 64);
    const size_t bytes = out.pixels.size() * sizeof(Rgb);
    // Held until this process has read or written the cache; released by close (also if rendering throws).
    const int lock = ec ? -1 : ::open((cache.string() + ".lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    struct Unlock {
      int fd;
      ~Unlock() {
        if (fd >= 0) ::close(fd);
      }
    } unlock{lock};
    if (lock >= 0) ::flock(lock, LOCK_EX);
    if (!ec) {
      std::ifstream in(cache, std::ios::binary);
      if (in.read(reinterpret_cast<char*>(out.pixels.data()), std::streamsize(bytes)) && in.gcount() == std::streamsize(bytes))
        return out;
    }
    RenderSettings p = integrator_settings(IntegratorKind::Path, 64, reduced() ? 512 : 4096);
    p.seed = 7;
    out = render_view(*cornell_like(), box_camera(), p).image;
    if (!ec) {
      const fs::path part = cache.string() + "." + std::to_string(::getpid());
      {
        std::ofstream f(part, std::ios::binary);
        f.write(reinterpret_cast<const char*>(out.pixels.data()), std::streamsize(bytes));
      }
      fs::rename(part, cache, ec);
    }
    return out;
  }();
  return img;
}

/// path_reference() at 32x32: each pixel the mean of its 2x2 block. With the default box filter a pixel's value is
/// the mean of the radiance over its square, so this is the same render at four times the samples per pixel
/// (16384; 2048 in sanitizer builds), and tests of 32x32 images share the suite's one cached reference.
inline const Image& path_reference_32() {
  static const Image img = [] {
    const Image& full = path_reference();
    Image out;
    out.width = out.height = 32;
    out.pixels.resize(32 * 32);
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x)
        out.pixels[size_t(y) * 32 + size_t(x)] = (full.at(2 * x, 2 * y) + full.at(2 * x + 1, 2 * y) +
                                                  full.at(2 * x, 2 * y + 1) + full.at(2 * x + 1, 2 * y + 1)) *
                                                 0.25f;
    return out;
  }();
  return img;
}

}  // namespace torte::test
