// The process's memory budget: input that asks for more memory than the machine can give fails with one
// clear error ("<what> needs ~24 GB; the limit is 18 GB (--max-memory)") before anything is allocated, instead
// of a std::bad_alloc tens of seconds later or the kernel's OOM killer. Sizes read from files (image headers,
// mesh element counts, decompressed lengths) and sizes a script asks for (subdivision levels, render sizes,
// voxel grids) are checked here before the allocation they imply.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

namespace torte {

/// The limit in bytes: set_memory_limit's value, else 3/4 of the memory this process may use (physical memory,
/// or the cgroup's memory.max when lower).
uint64_t memory_limit();
/// Sets the limit (--max-memory); 0 restores the default.
void set_memory_limit(uint64_t bytes);
/// Physical memory (or the cgroup limit when lower), in bytes.
uint64_t available_memory();
/// The process's resident set now, in bytes (from /proc/self/statm; 0 when unknown).
uint64_t resident_memory();

/// The process's peak resident set so far (VmHWM in /proc/self/status), in bytes; 0 when unknown.
uint64_t peak_resident_memory();

/// Throws torte::Error naming `what`, the bytes asked for and the limit when allocating `bytes` more would take
/// the process past memory_limit(). Requests below 16 MiB are not checked (the check reads /proc).
void reserve_memory(uint64_t bytes, std::string_view what);

/// count * size in bytes, or an Error naming `what` when the product does not fit in 64 bits.
uint64_t checked_bytes(uint64_t count, uint64_t size, std::string_view what);

/// "1.5 GB", "812 MB", "96 KB", "17 B" (powers of 1024, one decimal above KB).
std::string format_bytes(uint64_t bytes);
/// Parses "1.5GB", "800MB", "2G", "64k", "1073741824" (binary units, case-insensitive, optional 'B' and
/// space); throws torte::Error quoting `text` otherwise.
uint64_t parse_byte_size(std::string_view text);

}  // namespace torte
