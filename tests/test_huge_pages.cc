// The huge-page allocator behind the BVH nodes and leaf triangles (core/huge_pages.h).
#include <catch2/catch.hpp>

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "accel/wide_bvh.h"
#include "core/huge_pages.h"

using namespace torte;

namespace {

// The kernel's THP mode, the bracketed word of /sys/kernel/mm/transparent_hugepage/enabled ("" when unknown).
std::string thp_mode() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string all;
  std::getline(f, all);
  const size_t open = all.find('['), close = all.find(']');
  return open == std::string::npos || close == std::string::npos ? "" : all.substr(open + 1, close - open - 1);
}

}  // namespace

TEST_CASE("Large blocks start on a huge page and are backed by huge pages", "[huge_pages]") {
  HugePageVector<float> big(3 * huge_pages::kHugePage / sizeof(float) + 5, 1.0f);
  CHECK(reinterpret_cast<uintptr_t>(big.data()) % huge_pages::kHugePage == 0);
  CHECK(big.front() == 1.0f);
  CHECK(big.back() == 1.0f);
  const std::string mode = thp_mode();
  if (mode != "always" && mode != "madvise") {
    WARN("transparent huge pages are '" << mode << "' here: only the alignment is checked");
    return;
  }
  // Every page was written by the vector's fill, so the kernel had the chance to back the aligned 2 MiB ranges.
  CHECK(huge_pages::backed_bytes(big.data()) >= huge_pages::kHugePage);
}

TEST_CASE("Small blocks keep their type's alignment and grow like any vector", "[huge_pages]") {
  HugePageVector<WideNode<8>> nodes(3);
  CHECK(reinterpret_cast<uintptr_t>(nodes.data()) % alignof(WideNode<8>) == 0);
  // Growing past the threshold moves the data to a mapping of its own, contents intact.
  for (uint32_t i = 0; nodes.size() * sizeof(WideNode<8>) < 3 * huge_pages::kHugePage; ++i) {
    nodes.emplace_back();
    nodes.back().child[0] = i;
  }
  CHECK(reinterpret_cast<uintptr_t>(nodes.data()) % huge_pages::kHugePage == 0);
  for (size_t i = 3; i < nodes.size(); ++i) REQUIRE(nodes[i].child[0] == uint32_t(i - 3));
}

TEST_CASE("fault_in makes a fresh block resident, zeros intact; make_huge_page_vector gives n zeros", "[huge_pages]") {
  // 40 MiB and a bit (not a whole number of huge pages): above fault_in's 32 MiB threshold. A fresh mapping, not
  // a block kept from an earlier test.
  huge_pages::release_cached();
  const size_t bytes = (size_t(40) << 20) + 12345;
  char* const p = static_cast<char*>(huge_pages::allocate(bytes, 64));
  const size_t page = size_t(sysconf(_SC_PAGESIZE));
  const size_t pages = (bytes + page - 1) / page;
  std::vector<unsigned char> resident(pages);
  REQUIRE(mincore(p, bytes, resident.data()) == 0);
  const auto count_resident = [&] { return size_t(std::count_if(resident.begin(), resident.end(),
                                                                [](unsigned char r) { return (r & 1) != 0; })); };
  INFO("resident before: " << count_resident() << " of " << pages);
  huge_pages::fault_in(p, bytes);
  REQUIRE(mincore(p, bytes, resident.data()) == 0);
  CHECK(count_resident() == pages);  // every page of the range, the partial last one included
  CHECK(std::all_of(p, p + bytes, [](char c) { return c == 0; }));
  huge_pages::deallocate(p, bytes, 64);

  for (const size_t n : {size_t(0), size_t(1000), (size_t(33) << 20) / sizeof(float) + 7}) {
    const HugePageVector<float> v = make_huge_page_vector<float>(n);
    CHECK(v.size() == n);
    CHECK(std::all_of(v.begin(), v.end(), [](float x) { return x == 0.0f; }));
  }
}

TEST_CASE("Freed large blocks are handed out again until release_cached", "[huge_pages]") {
  huge_pages::release_cached();
  REQUIRE(huge_pages::cached_bytes() == 0);
  const size_t mib = size_t(1) << 20;
  // A freed 16 MiB block serves a 4 MiB request from its head and a 12 MiB one from its tail.
  char* const big = static_cast<char*>(huge_pages::allocate(16 * mib, 64));
  std::fill(big, big + 16 * mib, char(7));
  huge_pages::deallocate(big, 16 * mib, 64);
  CHECK(huge_pages::cached_bytes() == 16 * mib);
  char* const head = static_cast<char*>(huge_pages::allocate(4 * mib, 64));
  CHECK(head == big);
  CHECK(huge_pages::cached_bytes() == 12 * mib);
  char* const tail = static_cast<char*>(huge_pages::allocate(12 * mib - 100, 64));  // rounds up to 12 MiB
  CHECK(tail == big + 4 * mib);
  CHECK(huge_pages::cached_bytes() == 0);
  CHECK(reinterpret_cast<uintptr_t>(tail) % huge_pages::kHugePage == 0);
  // The pages came back as they were (not zeroed, not unmapped): no first touch is paid again.
  CHECK(std::all_of(head, head + 4 * mib, [](char c) { return c == 7; }));
  huge_pages::deallocate(head, 4 * mib, 64);
  huge_pages::deallocate(tail, 12 * mib - 100, 64);
  CHECK(huge_pages::cached_bytes() == 16 * mib);
  huge_pages::release_cached();
  CHECK(huge_pages::cached_bytes() == 0);

  // Only resident pages are kept: a block is cut after its last touched huge page, an untouched one not kept.
  char* const part = static_cast<char*>(huge_pages::allocate(16 * mib, 64));
  std::fill(part, part + 3 * mib, char(1));
  huge_pages::deallocate(part, 16 * mib, 64);
  CHECK(huge_pages::cached_bytes() == 4 * mib);
  char* const bigger = static_cast<char*>(huge_pages::allocate(32 * mib, 64));  // a fresh range ...
  CHECK(huge_pages::cached_bytes() == 0);  // ... into which the kept block was moved
  CHECK(std::all_of(bigger, bigger + 3 * mib, [](char c) { return c == 1; }));
  huge_pages::deallocate(bigger, 32 * mib, 64);
  huge_pages::release_cached();
  void* const untouched = huge_pages::allocate(8 * mib, 64);
  huge_pages::deallocate(untouched, 8 * mib, 64);
  CHECK(huge_pages::cached_bytes() == 0);
}

TEST_CASE("A request larger than every kept block grows one, aligned, its pages kept", "[huge_pages]") {
  huge_pages::release_cached();
  const size_t mib = size_t(1) << 20;
  // Something mapped right after the freed block would stop it growing in place; either way (grown in place or
  // moved) the result starts on a huge page and holds the old pages first.
  char* const a = static_cast<char*>(huge_pages::allocate(6 * mib, 64));
  std::fill(a, a + 6 * mib, char(3));
  huge_pages::deallocate(a, 6 * mib, 64);
  char* const grown = static_cast<char*>(huge_pages::allocate(20 * mib, 64));
  CHECK(huge_pages::cached_bytes() == 0);
  CHECK(reinterpret_cast<uintptr_t>(grown) % huge_pages::kHugePage == 0);
  CHECK(std::all_of(grown, grown + 6 * mib, [](char c) { return c == 3; }));
  CHECK(std::all_of(grown + 6 * mib, grown + 20 * mib, [](char c) { return c == 0; }));  // fresh pages
  std::fill(grown, grown + 20 * mib, char(1));  // all of it writable
  huge_pages::deallocate(grown, 20 * mib, 64);
  huge_pages::release_cached();

  // make_huge_page_vector on a reused, dirty block still gives zeros.
  {
    HugePageVector<float> dirty((size_t(40) << 20) / sizeof(float), 5.0f);
  }
  CHECK(huge_pages::cached_bytes() >= (size_t(40) << 20));
  const HugePageVector<float> v = make_huge_page_vector<float>((size_t(36) << 20) / sizeof(float));
  CHECK(std::all_of(v.begin(), v.end(), [](float x) { return x == 0.0f; }));
  huge_pages::release_cached();
}
