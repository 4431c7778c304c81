#include "film/checkpoint.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/error.h"

namespace torte {

namespace {

// The last byte is the format's version (2: the film's luminance moments follow its splat sums).
constexpr char kMagic[8] = {'T', 'O', 'R', 'T', 'E', 'C', 'K', '2'};

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

class Writer {
 public:
  Writer(std::FILE* f, const std::string& path) : f_(f), path_(path) {}
  void bytes(const void* p, size_t n) {
    if (n > 0 && std::fwrite(p, 1, n, f_) != n)
      throw Error("checkpoint " + path_ + ": cannot write (" + std::strerror(errno) + ")");
  }
  template <class T>
  void value(const T& v) { bytes(&v, sizeof v); }

 private:
  std::FILE* f_;
  const std::string& path_;
};

class Reader {
 public:
  Reader(std::FILE* f, const std::string& path) : f_(f), path_(path) {}
  void bytes(void* p, size_t n) {
    if (n > 0 && std::fread(p, 1, n, f_) != n) throw Error("checkpoint " + path_ + ": file is cut short");
  }
  template <class T>
  T value() {
    T v;
    bytes(&v, sizeof v);
    return v;
  }
  // A count of items of `size` bytes that the rest of the file could hold (a corrupt count fails here, not in
  // an allocation).
  uint64_t count(uint64_t size) {
    const uint64_t n = value<uint64_t>();
    const long at = std::ftell(f_);
    std::fseek(f_, 0, SEEK_END);
    const long end = std::ftell(f_);
    std::fseek(f_, at, SEEK_SET);
    if (size > 0 && n > uint64_t(end - at) / size) throw Error("checkpoint " + path_ + ": file is cut short");
    return n;
  }

 private:
  std::FILE* f_;
  const std::string& path_;
};

// "name=value" fields of a key.
std::vector<std::string> fields(const std::string& key) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= key.size()) {
    const size_t end = std::min(key.find(';', start), key.size());
    out.push_back(key.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

std::string mismatch(const std::string& saved, const std::string& expected) {
  const std::vector<std::string> a = fields(saved), b = fields(expected);
  for (size_t i = 0; i < std::max(a.size(), b.size()); ++i) {
    const std::string x = i < a.size() ? a[i] : "(none)", y = i < b.size() ? b[i] : "(none)";
    if (x != y) return "checkpoint has " + x + ", this render " + y;
  }
  return "keys differ";
}

}  // namespace

void write_checkpoint(const std::string& path, const Checkpoint& c) {
  const std::string tmp = path + ".tmp";
  {
    File f(std::fopen(tmp.c_str(), "wb"));
    if (!f) throw Error("checkpoint " + tmp + ": cannot create (" + std::strerror(errno) + ")");
    Writer w(f.get(), tmp);
    w.bytes(kMagic, sizeof kMagic);
    w.value(uint64_t(c.key.size()));
    w.bytes(c.key.data(), c.key.size());
    w.value(uint32_t(c.film.width()));
    w.value(uint32_t(c.film.height()));
    w.value(c.pass);
    w.value(uint64_t(c.tile_done.size()));
    w.bytes(c.tile_done.data(), c.tile_done.size());
    w.bytes(c.counters, sizeof c.counters);
    w.bytes(c.film.sums().data(), c.film.sums().size_bytes());
    w.value(uint64_t(c.film.splat_sums().size()));
    w.bytes(c.film.splat_sums().data(), c.film.splat_sums().size_bytes());
    w.value(uint64_t(c.film.moments().size()));
    w.bytes(c.film.moments().data(), c.film.moments().size_bytes());
    w.value(uint64_t(c.pending.size()));
    for (const auto& [tile, buffer] : c.pending) {
      w.value(tile);
      w.value(uint64_t(buffer.size()));
      w.bytes(buffer.splats().data(), buffer.splats().size_bytes());
    }
    if (std::fflush(f.get()) != 0 || fsync(fileno(f.get())) != 0)
      throw Error("checkpoint " + tmp + ": cannot write (" + std::strerror(errno) + ")");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw Error("checkpoint " + path + ": cannot rename " + tmp + " to it (" + std::strerror(errno) + ")");
}

Checkpoint read_checkpoint(const std::string& path, const std::string& expected_key) {
  File f(std::fopen(path.c_str(), "rb"));
  if (!f) throw Error("--resume " + path + ": cannot open (" + std::strerror(errno) + ")");
  Reader r(f.get(), path);
  char magic[sizeof kMagic];
  if (std::fread(magic, 1, sizeof magic, f.get()) != sizeof magic || std::memcmp(magic, kMagic, sizeof magic - 1) != 0)
    throw Error("--resume " + path + ": not a torte checkpoint");
  if (magic[sizeof magic - 1] != kMagic[sizeof kMagic - 1])
    throw Error("--resume " + path + ": a checkpoint of another torte version (format " +
                std::string(1, magic[sizeof magic - 1]) + ", this one reads " + kMagic[sizeof kMagic - 1] + ")");
  Checkpoint c;
  c.key.resize(r.count(1));
  r.bytes(c.key.data(), c.key.size());
  if (c.key != expected_key)
    throw Error("--resume " + path + ": the checkpoint is of another render (" + mismatch(c.key, expected_key) + ")");
  const uint32_t width = r.value<uint32_t>(), height = r.value<uint32_t>();
  c.pass = r.value<uint32_t>();
  c.tile_done.resize(r.count(1));
  r.bytes(c.tile_done.data(), c.tile_done.size());
  r.bytes(c.counters, sizeof c.counters);
  c.film = Film(int(width), int(height));  // the key fixes the size: it matched
  r.bytes(c.film.sums().data(), c.film.sums().size_bytes());
  std::vector<Rgb> splats(r.count(sizeof(Rgb)));
  if (!splats.empty() && splats.size() != c.film.pixel_count()) throw Error("checkpoint " + path + ": corrupt");
  r.bytes(splats.data(), splats.size() * sizeof(Rgb));
  c.film.set_splat_sums(std::move(splats));
  std::vector<float> moments(r.count(sizeof(float)));
  if (!moments.empty() && moments.size() != c.film.pixel_count()) throw Error("checkpoint " + path + ": corrupt");
  r.bytes(moments.data(), moments.size() * sizeof(float));
  c.film.set_moments(std::move(moments));
  c.pending.resize(r.count(4));
  for (auto& [tile, buffer] : c.pending) {
    tile = r.value<uint32_t>();
    const uint64_t n = r.count(sizeof(SplatBuffer::Splat));
    for (uint64_t i = 0; i < n; ++i) {
      const auto s = r.value<SplatBuffer::Splat>();
      if (s.pixel >= c.film.pixel_count()) throw Error("checkpoint " + path + ": corrupt");
      buffer.append(s);
    }
    if (tile >= c.tile_done.size()) throw Error("checkpoint " + path + ": corrupt");
  }
  return c;
}

}  // namespace torte
