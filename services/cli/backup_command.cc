// Copyright 2026 The DCS Authors.
#include "services/cli/backup_command.h"

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "services/cli/cluster_client.h"
#include "services/cli/run_client.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

int BackupCommand(const GlobalFlags& flags, const std::string& out) {
  absl::StatusOr<v1::BackupPiece> backup = BackupStore(CoordinatorAddress(flags), out,
                                                       flags.timeout);
  if (!backup.ok()) return FailCommand(backup.status());
  std::cout << out << ": " << backup->size() << " bytes, " << backup->runs() << " runs, "
            << backup->sweeps() << " sweeps, " << backup->studies() << " studies" << std::endl;
  return kExitOk;
}

}  // namespace

std::vector<CliCommand> AddBackupCommand(CLI::App& dcs, const GlobalFlags& flags) {
  auto out = std::make_shared<std::string>();
  CLI::App* backup = dcs.add_subcommand(
      "backup", "Copy the coordinator's store (runs, sweeps, studies, evaluations) as it is now "
                "into a file; the runs' checkpoints stay in its data directory");
  AddOutFile(*backup, out.get(), "the backup, a SQLite file (replaced if it exists)")->required();
  return {{backup, [&flags, out] { return BackupCommand(flags, *out); }}};
}

}  // namespace dcs::services::cli
