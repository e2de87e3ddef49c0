// Copyright 2026 The DCS Authors.
#include "services/cli_command.h"

#include "services/command_line.h"
#include "services/exit_codes.h"

namespace dcs::services {

int FailCommand(const absl::Status& status) {
  PrintError("dcs", status.ToString());
  return ExitCodeFor(status);
}

}  // namespace dcs::services
