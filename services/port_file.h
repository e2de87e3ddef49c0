// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_PORT_FILE_H_
#define DCS_SERVICES_PORT_FILE_H_

// The port file a DCS service writes once it serves (--port-file), so that whoever started it
// with port 0 learns the ports it got:
//   grpc_port: 41234
//   metrics_port: 38811
//   pid: 5120
// Written atomically: a reader sees the whole file or none. Thread-safe.

#include <optional>
#include <string>

#include "absl/status/status.h"

namespace dcs::services {

struct BoundPorts {
  int grpc = 0;
  int metrics = 0;
};

absl::Status WritePortFile(const std::string& path, const BoundPorts& ports);

// The ports, or nullopt while the file does not exist (or is not a port file).
std::optional<BoundPorts> ReadPortFile(const std::string& path);

}  // namespace dcs::services

#endif  // DCS_SERVICES_PORT_FILE_H_
