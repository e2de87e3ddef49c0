// Copyright 2026 The DCS Authors.
#include <iostream>

#include "absl/strings/str_cat.h"
#include "common/status_macros.h"
#include "learner/policy_export.h"
#include "learner/trained_policy.h"
#include "services/cli/torch_commands.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

// Writes the export of `flags.run`'s checkpoint and returns the line that says what it wrote.
absl::StatusOr<std::string> Export(const ExportFlags& flags, const GlobalFlags& global) {
  // Refused before anything is loaded: the layout's path must differ from the state dict's.
  DCS_ASSIGN_OR_RETURN(const std::string layout_path, learner::LayoutPathFor(flags.out));
  DCS_ASSIGN_OR_RETURN(const LocalRun run, LocalRun::Find(flags.run, global));
  DCS_ASSIGN_OR_RETURN(const learner::TrainedPolicy trained,
                       learner::LoadTrainedPolicy(run.dir(), flags.checkpoint));
  DCS_ASSIGN_OR_RETURN(const learner::ExportedPolicy exported, learner::ExportPolicy(trained));
  DCS_RETURN_IF_ERROR(learner::WriteExportedPolicy(exported, flags.out));
  return absl::StrCat("wrote ", flags.out, " (", exported.layout.sb3_policy(),
                      " state dict) and ", layout_path, " (observation layout) of ", flags.run,
                      " at step ", trained.step);
}

}  // namespace

int ExportInProcess(const ExportFlags& flags, const GlobalFlags& global) {
  const absl::StatusOr<std::string> written = Export(flags, global);
  if (!written.ok()) return FailCommand(written.status());
  std::cout << *written << std::endl;
  return kExitOk;
}

}  // namespace dcs::services::cli
