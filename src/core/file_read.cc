#include "core/file_read.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <algorithm>
#include <cstring>

#include "core/error.h"
#include "core/memory_budget.h"
#include "core/text.h"

namespace torte {

namespace {

// What a non-regular file is, for the message.
const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw Error("cannot read '" + escape_text(path) + "': " + why);
}

[[noreturn]] void cannot_open(const std::string& path, const std::string& why) {
  throw Error("cannot open '" + escape_text(path) + "' (" + why + ")");
}

void check_mode(const std::string& path, const struct stat& st) {
  if (!S_ISREG(st.st_mode)) cannot_open(path, std::string("it is ") + kind_of(st.st_mode) + ", not a regular file");
}

void check_size(const std::string& path, uint64_t size, uint64_t max_bytes) {
  if (size > max_bytes)
    refuse(path, "it holds " + format_bytes(size) + ", over the limit of " + format_bytes(max_bytes) +
                     " for a file read whole (a quarter of the memory limit, set with --max-memory)");
}

struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

uint64_t max_file_bytes() { return memory_limit() / 4; }

std::string read_file_bytes(const std::string& path, uint64_t max_bytes) {
  if (max_bytes == 0) max_bytes = max_file_bytes();
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer. It changes nothing for regular files.
  Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
  if (f.fd < 0) cannot_open(path, std::strerror(errno));
  struct stat st;
  if (::fstat(f.fd, &st) != 0) refuse(path, std::strerror(errno));
  check_mode(path, st);
  const uint64_t size = uint64_t(st.st_size);
  check_size(path, size, max_bytes);
  reserve_memory(size, "reading '" + escape_text(path) + "'");
  std::string bytes;
  bytes.resize(size_t(size));
  size_t got = 0;
  for (;;) {
    if (got == bytes.size()) {
      // At the size seen at open time: done, unless the kernel reported 0 (procfs), whose files are read to EOF.
      if (size > 0) break;
      if (bytes.size() >= max_bytes) check_size(path, bytes.size() + 1, max_bytes);
      bytes.resize(std::min<uint64_t>(max_bytes, std::max<size_t>(4096, 2 * bytes.size())));
    }
    const ssize_t n = ::read(f.fd, bytes.data() + got, bytes.size() - got);
    if (n < 0) {
      if (errno == EINTR) continue;
      refuse(path, std::string("read error (") + std::strerror(errno) + ")");
    }
    if (n == 0) break;
    got += size_t(n);
  }
  if (size > 0 && got != size)
    refuse(path, "read " + std::to_string(got) + " of " + std::to_string(size) +
                     " bytes (the file shrank while it was read)");
  bytes.resize(got);
  return bytes;
}

FileBytes::FileBytes(const std::string& path, uint64_t max_bytes) {
  if (max_bytes == 0) max_bytes = max_file_bytes();
  Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
  if (f.fd < 0) cannot_open(path, std::strerror(errno));
  struct stat st;
  if (::fstat(f.fd, &st) != 0) refuse(path, std::strerror(errno));
  check_mode(path, st);
  const uint64_t size = uint64_t(st.st_size);
  if (size == 0) {  // procfs and the like report 0: read to the end the usual way
    small_ = read_file_bytes(path, max_bytes);
    data_ = small_.data(), size_ = small_.size();
    return;
  }
  check_size(path, size, max_bytes);
  reserve_memory(size, "reading '" + escape_text(path) + "'");
  void* m = ::mmap(nullptr, size_t(size), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (m == MAP_FAILED) refuse(path, std::string("cannot allocate ") + format_bytes(size) + " (" + std::strerror(errno) + ")");
  data_ = static_cast<char*>(m), mapped_ = size_t(size);
  size_t got = 0;
  while (got < mapped_) {
    const ssize_t n = ::read(f.fd, data_ + got, mapped_ - got);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string why = std::string("read error (") + std::strerror(errno) + ")";
      ::munmap(data_, mapped_);
      refuse(path, why);
    }
    if (n == 0) break;
    got += size_t(n);
  }
  if (got != mapped_) {
    ::munmap(data_, mapped_);
    refuse(path, "read " + std::to_string(got) + " of " + std::to_string(size) +
                     " bytes (the file shrank while it was read)");
  }
  size_ = got;
}

FileBytes::~FileBytes() {
  if (mapped_) ::munmap(data_, mapped_);
}

void FileBytes::release_before(const char* p) {
  if (!mapped_ || p < data_ || p > data_ + size_) return;
  const size_t page = size_t(::sysconf(_SC_PAGESIZE));
  const size_t end = (size_t(p - data_) / page) * page;
  if (end <= released_) return;
  ::madvise(data_ + released_, end - released_, MADV_DONTNEED);  // anonymous pages: freed, not written back
  released_ = end;
}

std::string regular_file_problem(const std::string& path, uint64_t* size) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) return std::strerror(errno);
  if (!S_ISREG(st.st_mode)) return std::string("it is ") + kind_of(st.st_mode) + ", not a regular file";
  if (size) *size = uint64_t(st.st_size);
  return {};
}

uint64_t check_regular_file(const std::string& path) {
  uint64_t size = 0;
  const std::string problem = regular_file_problem(path, &size);
  if (!problem.empty()) cannot_open(path, problem);
  return size;
}

}  // namespace torte
