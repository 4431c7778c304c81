// The traversal kernels' -inl headers in the order they need each other, for the dispatch files
// (traverse_packet*.cc, traverse_compact_*.cc) to include after foreach_target. No include guard of its own: it is
// included once per Highway target, and each header it names has its per-target guard.
#include "traverse-inl.h"
#include "packet-inl.h"
#include "traverse_single-inl.h"
#include "packet_tests-inl.h"
#include "packet_trace-inl.h"
