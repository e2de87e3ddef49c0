// Copyright 2026 The DCS Authors.
#include "services/port_file.h"

#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"

namespace dcs::services {

absl::Status WritePortFile(const std::string& path, const BoundPorts& ports) {
  return WriteFileAtomically(path, absl::StrCat("grpc_port: ", ports.grpc, "\nmetrics_port: ",
                                                ports.metrics, "\npid: ", ::getpid(), "\n"));
}

std::optional<BoundPorts> ReadPortFile(const std::string& path) {
  if (!std::filesystem::exists(path)) return std::nullopt;
  try {
    const YAML::Node node = YAML::LoadFile(path);
    return BoundPorts{node["grpc_port"].as<int>(), node["metrics_port"].as<int>()};
  } catch (const YAML::Exception&) {
    return std::nullopt;
  }
}

}  // namespace dcs::services
