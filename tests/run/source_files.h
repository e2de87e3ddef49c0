// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_RUN_SOURCE_FILES_H_
#define DCS_TESTS_RUN_SOURCE_FILES_H_

// The project's own files that the config tests read: the YAML files of configs/ and the
// examples in the headers that document the formats. Paths are relative to the source tree
// (DCS_SOURCE_DIR, defined by the test target). Thread-compatible.

#include <filesystem>
#include <string>
#include <vector>

namespace dcs::run {

// A YAML file of configs/ (subfolders included), but the coordinator's settings file.
struct ConfigFile {
  enum class Kind {
    kRun,          // a run config
    kSweep,        // a sweep spec: a mapping with `conditions` (a study sweep's too)
  };
  std::filesystem::path path;
  std::string text;
  Kind kind = Kind::kRun;
};
std::vector<ConfigFile> ConfigFiles();

// The first block of "//   " lines of `header` (e.g. "run/run_spec_yaml.h"), without the
// comment marks: the format's example.
std::string HeaderExample(const std::string& header);

}  // namespace dcs::run

#endif  // DCS_TESTS_RUN_SOURCE_FILES_H_
