// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_FUZZ_SCRATCH_DIR_H_
#define DCS_TESTS_FUZZ_SCRATCH_DIR_H_

// A directory for a fuzz target's files (a checkpoint, a store), made once per process and
// removed when it exits. On tmpfs (/dev/shm) when there is one: every input writes and fsyncs
// files, which costs nothing there and would wear a disk. Thread-safe (a function-local static).

#include <stdlib.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace dcs::fuzz {

// The directory's path. Aborts if it cannot be made (the target could test nothing).
inline const std::string& ScratchDir() {
  // Never destroyed: the exit handler that removes the directory runs after static destructors.
  static const std::string* const dir = [] {
    std::error_code error;
    const std::filesystem::path parent = std::filesystem::is_directory("/dev/shm", error)
                                             ? std::filesystem::path("/dev/shm")
                                             : std::filesystem::temp_directory_path();
    std::string pattern = (parent / "dcs-fuzz-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) {
      std::perror("mkdtemp");
      std::abort();
    }
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(ScratchDir(), ignored);
    });
    return new std::string(pattern);
  }();
  return *dir;
}

}  // namespace dcs::fuzz

#endif  // DCS_TESTS_FUZZ_SCRATCH_DIR_H_
