#pragma once
// FUZZ_CHECK(cond): the invariant check of the libFuzzer targets. A violated invariant traps, so
// that libFuzzer records the input as a crash.

#define FUZZ_CHECK(cond)           \
  do {                             \
    if (!(cond)) __builtin_trap(); \
  } while (0)
