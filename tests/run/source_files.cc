// Copyright 2026 The DCS Authors.
#include "tests/run/source_files.h"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <sstream>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"

namespace dcs::run {
namespace {

const std::filesystem::path kSourceDir = DCS_SOURCE_DIR;

}  // namespace

std::vector<ConfigFile> ConfigFiles() {
  std::vector<ConfigFile> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(kSourceDir / "configs")) {
    const std::filesystem::path& path = entry.path();
    if (path.extension() != ".yaml" || path.filename() == "coordinator.yaml") continue;
    std::ifstream file(path);
    std::stringstream text;
    text << file.rdbuf();
    const YAML::Node root = YAML::Load(text.str());
    ConfigFile::Kind kind = ConfigFile::Kind::kRun;
    if (root.IsMap() && root["conditions"]) kind = ConfigFile::Kind::kSweep;
    files.push_back({.path = path, .text = text.str(), .kind = kind});
  }
  return files;
}

std::string HeaderExample(const std::string& header) {
  std::ifstream file(kSourceDir / header);
  std::string line;
  std::string example;
  while (std::getline(file, line)) {
    if (absl::StartsWith(line, "//   ")) {
      absl::StrAppend(&example, line.substr(5), "\n");
    } else if (!example.empty()) {
      break;
    }
  }
  return example;
}

}  // namespace dcs::run
