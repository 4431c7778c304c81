// Reading files a scene names: regular files only (a FIFO, a device such as /dev/zero, a directory or a socket is
// refused, symlinks are followed), never more than a size bound, and with the count of bytes read checked. Every
// reader of script-named files goes through here: the mesh readers, torte.data.read_file, and (through
// check_regular_file) the image readers, whose files OpenImageIO opens itself.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

namespace torte {

/// The largest file read_file_bytes reads by default: a quarter of memory_limit() (--max-memory), so that a
/// file and what is parsed from it fit the budget together.
uint64_t max_file_bytes();

/// The whole file as bytes. Opens without blocking (a FIFO cannot stall the run), then checks the opened file:
/// throws torte::Error("cannot open|read '<path>': ...") when it cannot be opened, is not a regular file, is
/// larger than `max_bytes` (0: max_file_bytes()) or changes size while it is read. Files whose size the kernel
/// reports as 0 (/proc) are read to their end, within the same bound.
std::string read_file_bytes(const std::string& path, uint64_t max_bytes = 0);

/// A file read whole, as read_file_bytes reads it (same checks and bound), into memory whose front a parser can
/// hand back as it goes (release_before), so a reader building a mesh of the file's size does not hold both at
/// their full size. Anonymous pages, not a file mapping: a file truncated while it is parsed cannot SIGBUS.
class FileBytes {
 public:
  explicit FileBytes(const std::string& path, uint64_t max_bytes = 0);
  ~FileBytes();
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  std::string_view bytes() const { return {data_, size_}; }
  /// Returns the whole pages before `p` (a pointer into bytes()) to the system; they must not be read again.
  void release_before(const char* p);

 private:
  char* data_ = nullptr;
  size_t size_ = 0, mapped_ = 0, released_ = 0;
  std::string small_;  // files whose size the kernel reports as 0 (procfs): read_file_bytes
};

/// Throws torte::Error("cannot open '<path>' ...") unless `path` names an existing regular file (after
/// symlinks), for files a library opens by name. Returns the file's size in bytes.
uint64_t check_regular_file(const std::string& path);
/// The same check without the throw: "" for a regular file (its size in *size when given), else why not
/// ("No such file or directory", "it is a directory, not a regular file", ...).
std::string regular_file_problem(const std::string& path, uint64_t* size = nullptr);

}  // namespace torte
