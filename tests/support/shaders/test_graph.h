#ifndef AOR_TEST_GRAPH_H
#define AOR_TEST_GRAPH_H
// Push constants of the test-only techniques that exercise the graph's mip levels and buffers
// (tests/runtime/graph_capacity_test.cpp).
#include "../../../shaders/common/shared_begin.h"

struct TestGraphConstants {
  ivec2 size;  // of the image the dispatch writes (one invocation per texel)
  int level;   // the mip level written (minify) or read up to (use)
};

#include "../../../shaders/common/shared_end.h"
#endif
