// Resource bounds of the core (issue 22): files read only when regular and within a size bound, sizes checked
// against the memory budget before the allocation they imply (subdivision, render film, BVH builds, voxel grids,
// environment maps), a failed image lookup failing the render, and bad text from files quoted with escapes.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "accel/bvh_build.h"
#include "core/error.h"
#include "core/file_read.h"
#include "core/memory_budget.h"
#include "error_helpers.h"
#include "core/quiet_stderr.h"
#include "core/text.h"
#include "film/image.h"
#include "geometry/mesh_io.h"
#include "geometry/obj.h"
#include "geometry/ply.h"
#include "geometry/subdivide.h"
#include "light/environment.h"
#include "scene_helpers.h"
#include "texture/texture.h"
#include "voxel/voxel_grid.h"

using namespace torte;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

using test::error_of;
using test::ScopedMemoryLimit;

struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& name)
      : path(fs::temp_directory_path() / ("torte_limits_" + std::to_string(getpid()) + "_" + name)) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(*this / name, std::ios::binary) << bytes;
    return *this / name;
  }
};

// A string literal with its NUL bytes.
template <size_t N>
std::string bytes(const char (&s)[N]) {
  return std::string(s, N - 1);
}

bool has_control_bytes(const std::string& s) {
  for (unsigned char c : s)
    if (c < 0x20 || c == 0x7f) return true;
  return false;
}

}  // namespace

TEST_CASE("limits: read_file_bytes reads regular files exactly and refuses everything else", "[limits]") {
  TempDir dir("read");
  const std::string content = bytes("a\0b\r\nc");
  CHECK(read_file_bytes(dir.write("a.bin", content)) == content);
  CHECK(read_file_bytes(dir.write("empty.bin", "")).empty());

  CHECK_THAT(error_of([&] { read_file_bytes(dir / "missing.ply"); }),
             Contains("cannot open '" + dir / "missing.ply" + "' (No such file or directory)"));
  fs::create_directories(dir / "sub.ply");
  CHECK_THAT(error_of([&] { read_file_bytes(dir / "sub.ply"); }), Contains("it is a directory, not a regular file"));
  CHECK_THAT(error_of([&] { read_file_bytes("/dev/zero"); }),
             Contains("'/dev/zero' (it is a character device, not a regular file)"));
  // A symlink is followed: what it points at is checked.
  fs::create_symlink("/dev/zero", dir / "zero.ply");
  CHECK_THAT(error_of([&] { read_file_bytes(dir / "zero.ply"); }), Contains("character device"));
  fs::create_symlink(dir / "a.bin", dir / "link.bin");
  CHECK(read_file_bytes(dir / "link.bin") == content);
  // A FIFO without a writer: refused at once (opening it blocking would wait for a writer forever).
  REQUIRE(mkfifo((dir / "fifo").c_str(), 0600) == 0);
  CHECK_THAT(error_of([&] { read_file_bytes(dir / "fifo"); }), Contains("a FIFO (named pipe), not a regular file"));
  // A file the kernel reports as 0 bytes (procfs) is read to its end.
  CHECK_THAT(read_file_bytes("/proc/self/status"), Contains("Name:"));
}

TEST_CASE("limits: read_file_bytes stops at its size bound, which follows the memory limit", "[limits]") {
  TempDir dir("bound");
  const std::string path = dir.write("big.obj", std::string(100000, '#'));
  CHECK(read_file_bytes(path, 100000).size() == 100000);
  CHECK_THAT(error_of([&] { read_file_bytes(path, 99999); }),
             Contains("it holds 97.7 KB, over the limit of 97.7 KB for a file read whole"));
  CHECK_THAT(error_of([&] { read_file_bytes("/proc/self/status", 16); }), Contains("over the limit of 16 B"));
  {
    ScopedMemoryLimit limit(uint64_t(256) << 10);  // a quarter: 64 KB
    CHECK(max_file_bytes() == uint64_t(64) << 10);
    CHECK_THAT(error_of([&] { load_mesh(path); }), Contains("over the limit of 64.0 KB") && Contains("--max-memory"));
  }
  CHECK(max_file_bytes() == memory_limit() / 4);
  CHECK(check_regular_file(path) == 100000);
  CHECK(regular_file_problem("/dev/null") == "it is a character device, not a regular file");
}

TEST_CASE("limits: quote_text escapes control bytes and invalid UTF-8 and caps the length", "[limits]") {
  CHECK(quote_text(std::string("a\0b", 3)) == "'a\\x00b'");
  CHECK(quote_text("tab\there\x1b[31m") == "'tab\\there\\x1b[31m'");
  CHECK(quote_text("it's \\") == "'it\\'s \\\\'");
  CHECK(quote_text("caf\xc3\xa9 \xff") == "'caf\xc3\xa9 \\xff'");  // valid UTF-8 passes, a stray byte does not
  CHECK(quote_text(std::string(100, 'x'), 10) == "'xxxxxxxxxx'... (100 bytes)");
  CHECK(escape_text("dir/\nname.ply") == "dir/\\nname.ply");
  CHECK(one_line_message("Read error\nPNG read error: x\nRead error\n") == "Read error; PNG read error: x");
  CHECK(one_line_message("  \n", "fallback") == "fallback");
  CHECK(one_line_message(std::string(500, 'y'), "", 20) == std::string(20, 'y') + "...");
}

TEST_CASE("limits: QuietStderr keeps a library's own lines off stderr and restores it, also when nested", "[limits]") {
  TempDir dir("stderr");
  const std::string log = dir / "stderr.txt";
  std::fflush(stderr);
  const int saved = dup(2);
  const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  REQUIRE((saved >= 0 && fd >= 0));
  dup2(fd, 2);
  close(fd);
  std::fputs("before\n", stderr);
  {
    QuietStderr quiet;
    std::fputs("libpng error: IDAT: Read error\n", stderr);
    { QuietStderr nested; }
    std::fputs("still quiet\n", stderr);
  }
  std::fputs("after\n", stderr);
  std::fflush(stderr);
  dup2(saved, 2);
  close(saved);
  CHECK(read_file_bytes(log) == "before\nafter\n");
}

TEST_CASE("limits: OBJ, MTL and PLY errors quote bad text with escapes, on one line", "[limits]") {
  TempDir dir("text");
  // A NUL inside a token used to cut the message short; control bytes reached the terminal.
  std::string e = error_of([&] { parse_obj(bytes("v 1 2a\0\x01z 3\n"), "m.obj", ""); });
  CHECK(e == "m.obj: line 1: '2a\\x00\\x01z' is not a number");
  e = error_of([&] { parse_obj("\x1b[2Jboom 1 2\n", "m.obj", ""); });
  CHECK(e == "m.obj: line 1: unknown statement '\\x1b[2Jboom'");
  e = error_of([&] { parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 " + std::string(300, '\x7f') + "\n", "m.obj", ""); });
  CHECK_THAT(e, Contains("m.obj: line 4: bad vertex index '\\x7f\\x7f") && Contains("... (300 bytes)"));
  CHECK(e.size() < 300);
  dir.write("bad.mtl", std::string("newmtl a\nKd 1 \x02\x03 1\n"));
  const std::string obj = dir.write("m.obj", "mtllib bad.mtl\nv 0 0 0\n");
  e = error_of([&] { read_obj(obj); });
  CHECK_THAT(e, Contains("bad.mtl: line 2: '\\x02\\x03' is not a number"));
  e = error_of([&] { parse_ply(bytes("ply\nformat ascii 1.0\nelem\0ent vertex 3\n"), "p.ply"); });
  CHECK(e == "p.ply: header line 3: unknown keyword 'elem\\x00ent'");
  e = error_of([&] {
    parse_ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
              "end_header\n0 \x05 0\n",
              "p.ply");
  });
  CHECK(e == "p.ply: vertex 0 of 1 (line 8): '\\x05' is not a valid number");
  for (const std::string& m : {e}) CHECK_FALSE(has_control_bytes(m));
}

TEST_CASE("limits: a PLY count the file cannot hold fails at the end of the data, saying so", "[limits]") {
  const std::string head = "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
                           "property float y\nproperty float z\nend_header\n";
  std::string e = error_of([&] { parse_ply(head + std::string(24, '\0'), "huge.ply"); });
  CHECK(e == "huge.ply: vertex 2 of 4000000000: file ends early (the header declares 4000000000, which need "
             "at least 12 bytes each; 24 bytes follow the header)");
  e = error_of([&] {
    parse_ply("ply\nformat ascii 1.0\nelement vertex 5000000000\nproperty float x\nend_header\n", "v.ply");
  });
  CHECK(e == "v.ply: the header declares 5000000000 vertices, more than the limit of 4294967295 (2^32 - 1)");
  // A face count far past the file reserves nothing for it (the reservation follows the file's size).
  ScopedMemoryLimit limit(uint64_t(1) << 30);
  const std::string faces = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 900000000000\nproperty list uchar int vertex_indices\n"
                            "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  CHECK_THAT(error_of([&] { parse_ply(faces, "f.ply"); }), Contains("face 1 of 900000000000: file ends early"));
}

TEST_CASE("limits: subdivide checks the whole result before the first level", "[limits]") {
  const TriangleMesh cube = make_cube();  // 12 triangles
  // 12 x 4^14 = 3.2e9 > 2^31: refused by the count, naming both.
  CHECK(error_of([&] { subdivide(cube, 14); }) ==
        "subdivide: 14 levels of 12 triangles would give 3.22e+09 triangles, more than the limit of 2^31 "
        "(2147483648)");
  const SubdivisionSize s = subdivision_size(cube, 3, false);
  CHECK(s.triangles == 12 * 64);
  CHECK(s.vertices >= subdivide(cube, 3).vertex_count());
  // 12 x 4^10 = 12.6 M triangles, a few hundred MB: over a 64 MB budget, refused at once with the size asked.
  ScopedMemoryLimit limit(uint64_t(64) << 20);
  const std::string e = error_of([&] { subdivide(cube, 10); });
  CHECK_THAT(e, Contains("subdivide: 10 levels of 12 triangles (12582912 triangles) needs ~") &&
                    Contains("over the memory limit of 64.0 MB"));
}

TEST_CASE("limits: render sizes are bounded and the film is checked against the budget", "[limits]") {
  SceneBuilder b;
  b.add_shape(test::sphere_shape(1, Transform(), test::matte(0.5f)));
  auto scene = b.flatten();
  const CameraDesc cam = test::camera_at({0, 0, -4}, {0, 0, 0}, 40);
  RenderSettings s;
  s.width = 1 << 15, s.height = 1 << 14;
  CHECK(error_of([&] { test::render_view(*scene, cam, s); }) ==
        "'width' x 'height' = 32768x16384 = 536870912 pixels, more than the limit of 268435456 (2^28)");
  s.width = s.height = 8, s.spp = kMaxSpp + 1;
  CHECK(error_of([&] { test::render_view(*scene, cam, s); }) == "'spp' must be in [1, 16777216], got 16777217");
  s.spp = 1;
  // A camera made for another size would leave part of the image unseen (or look outside it).
  CHECK(error_of([&] { render(*scene, Camera(cam, 16, 8), s); }) ==
        "the camera was made for a 16x8 image, the settings ask for 8x8");
  s.width = s.height = 8192;  // 64 M pixels: 1.7 GB of film and image
  CHECK(render_memory_bytes(s) == uint64_t(8192) * 8192 * 28);
  ScopedMemoryLimit limit(uint64_t(256) << 20);
  CHECK_THAT(error_of([&] { test::render_view(*scene, cam, s); }),
             Contains("the 8192x8192 image's film needs ~1.8 GB") && Contains("over the memory limit of 256 MB"));
}

namespace {

// An image source whose lookups fail, as OpenImageIO's do for a tile it cannot read.
struct BrokenImage : ImageSource {
  Rgb lookup(Vec2f, float) const override {
    failed = true;
    return Rgb(0);
  }
  std::string failure() const override { return failed ? "cannot read image texture 'cut.exr' while rendering" : ""; }
  mutable std::atomic<bool> failed{false};
};

}  // namespace

TEST_CASE("limits: an image lookup that fails makes the render fail naming the file", "[limits]") {
  auto image = std::make_shared<BrokenImage>();
  auto material = test::matte(0.5f);
  material->color.texture = texture::image(image);
  SceneBuilder b;
  b.add_shape(test::sphere_shape(1, Transform(), material));
  Light point;
  point.kind = LightKind::Point;
  point.position = {0, 0, -4};
  point.radiance = Rgb(10);
  b.add_light(point);
  auto scene = b.flatten();
  const CameraDesc cam = test::camera_at({0, 0, -4}, {0, 0, 0}, 40);
  RenderSettings s;
  s.width = s.height = 16, s.spp = 4;
  CHECK(error_of([&] { test::render_view(*scene, cam, s); }) == "cannot read image texture 'cut.exr' while rendering");
  CHECK(image->failed);
}

TEST_CASE("limits: BVH builds, environment maps and voxel grids check the budget first", "[limits]") {
  std::vector<Bounds3f> prims(1 << 20);
  for (size_t i = 0; i < prims.size(); ++i) {
    const float f = float(i);
    prims[i] = Bounds3f{Vec3f(f, f, f), Vec3f(f + 1, f + 1, f + 1)};
  }
  {
    ScopedMemoryLimit limit(uint64_t(96) << 20);
    CHECK_THAT(error_of([&] { build_binary_bvh(prims, BvhBuildOptions{}); }),
               Contains("BVH build of 1048576 primitives needs ~68.0 MB") && Contains("over the memory limit"));
  }
  Image sky(2048, 1024);
  for (Rgb& p : sky.pixels) p = Rgb(1);
  {
    ScopedMemoryLimit limit(uint64_t(48) << 20);
    CHECK_THAT(error_of([&] { make_environment_map(sky, Transform(), Rgb(1)); }),
               Contains("environment map of 2048x1024 pixels needs ~") && Contains("over the memory limit"));
  }
  CHECK(make_environment_map(sky, Transform(), Rgb(1))->width == 2048);

  VoxelGrid grid;
  CHECK(error_of([&] { grid.set(1 << 24, 0, 0, 1); }) ==
        "voxel grid: chunk (1048576, 0, 0) is out of range (chunk coordinates lie in [-2^20, 2^20), voxel "
        "coordinates in [-2^24, 2^24))");
  ScopedMemoryLimit limit(resident_memory() + (uint64_t(64) << 20));
  const std::string e = error_of([&] {
    for (int c = 0; c < 1 << 16; ++c) grid.set(16 * (c & 255), 16 * (c >> 8), 0, 1);  // 8 KB per chunk
  });
  CHECK_THAT(e, Contains("voxel grid: ") && Contains("chunks and more needs ~") && Contains("over the memory limit"));
  CHECK(grid.chunk_count() < (1u << 16));
}
