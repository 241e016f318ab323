// CHECK for the consumer programs: a failed condition prints where and returns 1 from main (the
// programs use only the installed package, not gtest).
#pragma once
#include <cstdio>

#define CHECK(cond)                                                                 \
  do {                                                                              \
    if (!(cond)) {                                                                  \
      std::fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
      return 1;                                                                     \
    }                                                                               \
  } while (0)
