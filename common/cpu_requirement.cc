// Copyright 2026 The DCS Authors.
//
// Every DCS program is compiled for x86-64-v3 (AVX2 and FMA; CMakeLists.txt). On an older CPU
// its first such instruction would end it with SIGILL and no word of why; this check runs before
// any other code of the program (the first constructor, itself compiled for plain x86-64) and
// exits with a message instead. Every program links it: dcs_common makes the linker take it
// (common/CMakeLists.txt), as nothing calls it.

#include <unistd.h>

#include <cstdlib>

extern "C" __attribute__((constructor(101), target("arch=x86-64"))) void DcsCpuRequirement() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return;
  static constexpr char kMessage[] =
      "DCS needs an x86-64 CPU with AVX2 and FMA (x86-64-v3: Intel since 2013, AMD since "
      "2015); this one lacks them\n";
  // Nothing else has run yet: write(2) and _exit, not stdio and exit.
  [[maybe_unused]] const ssize_t written = write(STDERR_FILENO, kMessage, sizeof(kMessage) - 1);
  _exit(EXIT_FAILURE);
}
