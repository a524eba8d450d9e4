// Minimal checking helpers shared by the kernel unit tests.
#ifndef caoTestUtilities_h
#define caoTestUtilities_h
#include <cstdio>

#define CAO_CHECK(cond, ...)                                                                       \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond);               \
      std::fprintf(stderr, __VA_ARGS__);                                                           \
      std::fprintf(stderr, "\n");                                                                  \
      return 1;                                                                                    \
    }                                                                                              \
  } while (0)
#endif
