// Copyright 2026 The DCS Authors.
#include "services/cli/torch_commands.h"

namespace dcs::services::cli {

int EvaluateInProcess(const EvalFlags& /*flags*/, const GlobalFlags& /*global*/) {
  return FailCommand(absl::UnimplementedError("dcs eval is being built"));
}

}  // namespace dcs::services::cli
