// Copyright 2026 The DCS Authors.
#include "services/cli/torch_commands.h"

namespace dcs::services::cli {

int ExportInProcess(const ExportFlags& /*flags*/, const GlobalFlags& /*global*/) {
  return FailCommand(absl::UnimplementedError("dcs export is being built"));
}

}  // namespace dcs::services::cli
