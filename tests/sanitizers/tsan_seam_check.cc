// Checks core/parallel.h's TSan annotations from both sides (tests/sanitizers/README.md): `clean` runs every
// seam primitive on data written before and read after the loops, and must pass without a report; `racy` adds
// an unsynchronised `+=` from every task of a loop, which TSan must still report (the annotations add fork and
// join edges only). Built and run by the TSan build only.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <thread>
#include <vector>

#include "core/parallel.h"

namespace {

int g_shared = 0;

int clean() {
  std::vector<long> v(100000, 1);
  torte::parallel_for(size_t(0), v.size(), [&](size_t i) { v[i] += long(i % 7); });
  torte::parallel_for_blocks(size_t(0), v.size(), 1000, [&](torte::IndexRange<size_t> r) {
    for (size_t i = r.begin(); i < r.end(); ++i) v[i] *= 2;
  }, torte::Split::each_block);
  const long sum = torte::parallel_reduce(size_t(0), v.size(), 512, 0L, [&](torte::IndexRange<size_t> r, long a) {
    for (size_t i = r.begin(); i < r.end(); ++i) a += v[i];
    return a;
  }, [](long a, const long& b) { return a + b; });
  std::vector<unsigned> keys(50000);
  for (unsigned i = 0; i < keys.size(); ++i) keys[i] = (i * 2654435761u) % 1000003u;
  torte::parallel_sort(keys.begin(), keys.end(), [](unsigned a, unsigned b) { return a < b; });
  int left = 0, right = 0;
  torte::parallel_invoke([&] { left = 1; }, [&] { right = 2; });
  torte::PerThread<std::vector<int>> per_thread;
  torte::parallel_for(0, 64, [&](int i) {  // nested, and slow enough that both threads take part
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    torte::parallel_for(0, 16, [&](int j) { per_thread.local().push_back(i * 16 + j); });
  });
  size_t items = 0;
  for (const auto& p : per_thread) items += p.size();
  long expect = 0;
  for (size_t i = 0; i < v.size(); ++i) expect += 2 * (1 + long(i % 7));
  for (size_t i = 1; i < keys.size(); ++i)
    if (keys[i - 1] > keys[i]) return std::puts("parallel_sort: not sorted"), 1;
  if (sum != expect || left != 1 || right != 2 || items != 64 * 16) return std::puts("wrong results"), 1;
  std::puts("clean: ok");
  return 0;
}

int racy() {
  torte::parallel_for(0, 64, [&](int i) {
    std::this_thread::sleep_for(std::chrono::microseconds(200));  // both threads take part
    g_shared += i;
  });
  std::printf("racy: %d (TSan should have stopped this process)\n", g_shared);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "clean") == 0) return clean();
  if (argc == 2 && std::strcmp(argv[1], "racy") == 0) return racy();
  std::fputs("usage: tsan_seam_check clean|racy\n", stderr);
  return 2;
}
