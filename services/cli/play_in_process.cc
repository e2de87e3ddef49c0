// Copyright 2026 The DCS Authors.
#include "services/cli/torch_commands.h"

namespace dcs::services::cli {

int PlayInProcess(const PlayFlags& /*flags*/, const GlobalFlags& /*global*/) {
  return FailCommand(absl::UnimplementedError("dcs play is being built"));
}

}  // namespace dcs::services::cli
