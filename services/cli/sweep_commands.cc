// Copyright 2026 The DCS Authors.
#include "services/cli/sweep_commands.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "common/text_table.h"
#include "coordinator/sweep_submission.h"
#include "services/cli/cluster_client.h"
#include "services/cli/command_output.h"
#include "services/cli/detach.h"
#include "services/cli/run_client.h"
#include "services/cli/sweep_view.h"
#include "services/coordinator/record_proto.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

// Follows the sweep until it ends: on a terminal, the progress view redrawn in place whenever
// it changes; otherwise its headline (with -o json, the GetSweepResponse) whenever a run starts
// or ends. Ctrl-C detaches (the sweep goes on). Exit: 0 completed, 1 failed or cancelled, 130
// detached.
int WatchSweepCommand(const GlobalFlags& flags, const std::string& sweep_id) {
  const bool json = flags.output == OutputFormat::kJson;
  const bool terminal = !json && isatty(STDOUT_FILENO) == 1;
  const DetachOnInterrupt detach;
  std::string shown;
  int shown_lines = 0;
  auto show = [&](const v1::GetSweepResponse& sweep) {
    const std::string view = json       ? CommandJson(sweep)
                             : terminal ? SweepProgressView(sweep)
                                        : SweepHeadline(sweep);
    // A terminal's view is redrawn whenever it changes; plain lines only when a run moved.
    const v1::Sweep& counts = sweep.sweep();
    const std::string key =
        terminal ? view
                 : absl::StrCat(counts.state(), " ", counts.completed(), " ", counts.running(),
                                " ", counts.queued(), " ", counts.failed(), " ",
                                counts.cancelled());
    if (key == shown) return;
    // Back over the previous view and clear it, then draw the new one.
    if (terminal && shown_lines > 0) std::cout << "\x1b[" << shown_lines << "F\x1b[J";
    std::cout << view << (view.ends_with('\n') ? "" : "\n") << std::flush;
    shown = key;
    shown_lines = static_cast<int>(std::count(view.begin(), view.end(), '\n')) +
                  (view.ends_with('\n') ? 0 : 1);
  };
  absl::StatusOr<v1::GetSweepResponse> last =
      WatchSweep(CoordinatorAddress(flags), sweep_id,
                 {.on_update = show,
                  .interrupted = [&detach] { return detach.requested(); },
                  .on_lost =
                      [&](const absl::Status& status) {
                        std::cout << std::flush;
                        std::cerr << WatchLostMessage(status) << std::endl;
                        // The view is drawn again below the message once the watch is back.
                        shown.clear();
                        shown_lines = 0;
                      }});
  if (absl::IsCancelled(last.status())) {
    std::cerr << "dcs: detached from " << sweep_id << " (it goes on); follow it with: dcs watch "
              << sweep_id << std::endl;
    return kExitInterrupted;
  }
  if (!last.ok()) return FailCommand(last.status());
  if (last->sweep().state() != v1::SWEEP_STATE_COMPLETED) {
    std::cerr << "dcs: " << sweep_id << " " << EnumWordOf(last->sweep().state())
              << (last->sweep().failed() > 0 ? "; `dcs retry " + sweep_id + "` reruns its "
                                                "failed runs"
                                              : "")
              << std::endl;
    return kExitFailure;
  }
  return kExitOk;
}

// What `submit --dry-run` shows: the sweep `spec` would be, read and expanded as the
// coordinator does (coordinator/sweep_submission.h), without one.
absl::StatusOr<v1::Sweep> PreviewSweep(const std::string& spec, const std::string& spec_name,
                                       const std::string& name) {
  DCS_ASSIGN_OR_RETURN(const coordinator::ExpandedSweep sweep,
                       coordinator::ExpandSweep(spec, spec_name, name, /*request_id=*/""));
  return SweepToProto(coordinator::SweepPreview(sweep));
}

struct SubmitFlags {
  std::string spec;
  bool watch = false;
  bool dry_run = false;
};

int SubmitCommand(const GlobalFlags& flags, const SubmitFlags& submit) {
  absl::StatusOr<std::string> text = ReadFile(submit.spec);
  if (!text.ok()) return FailCommand(text.status());
  const std::string stem = std::filesystem::path(submit.spec).stem().string();
  // A dry run checks and expands the spec here, as the coordinator would: no cluster needed.
  absl::StatusOr<v1::Sweep> sweep =
      submit.dry_run ? PreviewSweep(*text, submit.spec, stem)
                     : SubmitSweep(CoordinatorAddress(flags), *text, submit.spec, stem,
                                   flags.timeout);
  if (!sweep.ok()) return FailCommand(sweep.status());
  if (flags.output == OutputFormat::kJson) {
    std::cout << CommandJson(*sweep) << std::endl;
  } else if (submit.dry_run) {
    std::vector<std::vector<std::string>> rows = {{"CONDITION", "FAMILY", "MODE"}};
    for (const v1::Trial& trial : sweep->trials()) {
      rows.push_back({trial.condition(), trial.family(), trial.observe()});
    }
    std::cout << RenderTable(rows) << sweep->name() << ": " << sweep->trials_size()
              << " trials x " << sweep->seeds() << " seeds = " << sweep->runs() << " runs"
              << std::endl;
  } else {
    std::cout << sweep->sweep_id() << std::endl;
  }
  if (submit.dry_run) return kExitOk;
  std::cerr << "dcs: submitted " << sweep->sweep_id() << " (" << sweep->name() << ", ";
  if (sweep->study_id().empty()) {
    std::cerr << sweep->runs() << " runs";
  } else {  // its runs come as its study asks for trials
    std::cerr << "a search: " << sweep->study_id() << " asks for its trials";
  }
  std::cerr << "); follow it with: dcs watch " << sweep->sweep_id() << std::endl;
  return submit.watch ? WatchSweepCommand(flags, sweep->sweep_id()) : kExitOk;
}

int ListSweepsCommand(const GlobalFlags& flags) {
  absl::StatusOr<std::vector<v1::Sweep>> sweeps =
      ListSweeps(CoordinatorAddress(flags), flags.timeout);
  if (!sweeps.ok()) return FailCommand(sweeps.status());
  if (flags.output == OutputFormat::kJson) {
    v1::ListSweepsResponse response;
    for (const v1::Sweep& sweep : *sweeps) *response.add_sweeps() = sweep;
    std::cout << CommandJson(response) << std::endl;
    return kExitOk;
  }
  std::vector<std::vector<std::string>> rows = {
      {"SWEEP", "NAME", "STATE", "TRIALS", "SEEDS", "DONE", "RUNNING", "QUEUED", "FAILED"}};
  for (const v1::Sweep& sweep : *sweeps) {
    rows.push_back({sweep.sweep_id(), sweep.name(), EnumWordOf(sweep.state()),
                    absl::StrCat(sweep.trials_size()), absl::StrCat(sweep.seeds()),
                    absl::StrCat(sweep.completed(), "/", sweep.runs()),
                    absl::StrCat(sweep.running()), absl::StrCat(sweep.queued()),
                    absl::StrCat(sweep.failed())});
  }
  std::cout << FormatRows(rows, flags.output) << std::flush;
  return kExitOk;
}

// Prints the sweep a cancel or retry left, as JSON or as "<id> <state>".
int PrintSweepState(const GlobalFlags& flags, const v1::Sweep& sweep) {
  if (flags.output == OutputFormat::kJson) {
    std::cout << CommandJson(sweep) << std::endl;
  } else {
    std::cout << sweep.sweep_id() << " " << EnumWordOf(sweep.state()) << std::endl;
  }
  return kExitOk;
}

int CancelSweepCommand(const GlobalFlags& flags, const std::string& sweep_id) {
  absl::StatusOr<v1::Sweep> sweep = CancelSweep(CoordinatorAddress(flags), sweep_id,
                                                flags.timeout);
  if (!sweep.ok()) return FailCommand(sweep.status());
  return PrintSweepState(flags, *sweep);
}

int RetrySweepCommand(const GlobalFlags& flags, const std::string& sweep_id) {
  absl::StatusOr<v1::RetrySweepResponse> retried =
      RetrySweep(CoordinatorAddress(flags), sweep_id, flags.timeout);
  if (!retried.ok()) return FailCommand(retried.status());
  std::cerr << "dcs: " << retried->retried() << " failed run(s) of " << sweep_id
            << " queued again" << std::endl;
  return PrintSweepState(flags, retried->sweep());
}

int RemoveSweepsCommand(const GlobalFlags& flags, const std::vector<std::string>& sweep_ids) {
  absl::StatusOr<v1::DeleteSweepsResponse> removed =
      DeleteSweeps(CoordinatorAddress(flags), sweep_ids, flags.timeout);
  if (!removed.ok()) return FailCommand(removed.status());
  if (flags.output == OutputFormat::kJson) {
    std::cout << CommandJson(*removed) << std::endl;
    return kExitOk;
  }
  for (const v1::Sweep& sweep : removed->sweeps()) {
    std::cout << sweep.sweep_id() << " removed: " << sweep.runs() << " runs"
              << (sweep.study_id().empty() ? "" : " and " + sweep.study_id()) << std::endl;
  }
  return kExitOk;
}

// A verb of one sweep, as the table runs it: on the one id its command line takes.
template <int (*Run)(const GlobalFlags&, const std::string&)>
int OnOneSweep(const GlobalFlags& flags, const std::vector<std::string>& sweep_ids) {
  return Run(flags, sweep_ids.front());
}

// A command on sweeps named by their ids.
struct SweepVerb {
  const char* name;
  const char* help;
  int (*run)(const GlobalFlags& flags, const std::vector<std::string>& sweep_ids);
  bool several;  // takes SWEEP..., not one SWEEP
  // Also spelt `dcs VERB`, the first verbs' first spelling; not a verb added since, so that the
  // top level does not fill with one noun's verbs (`dcs rm` would not say what it removes).
  bool top_level;
};
constexpr SweepVerb kSweepVerbs[] = {
    {"watch",
     "Follow a sweep live (Ctrl-C detaches): runs by state per trial, steps/s, ETA, the best "
     "trial so far; exit 0 once it completed, 1 if it failed",
     OnOneSweep<WatchSweepCommand>, false, true},
    {"cancel", "Stop a sweep's queued and running runs", OnOneSweep<CancelSweepCommand>, false,
     true},
    {"retry", "Queue a sweep's failed runs again (each resumes from its last checkpoint)",
     OnOneSweep<RetrySweepCommand>, false, true},
    {"rm",
     "Remove ended sweeps for good with their runs (records and files on the coordinator) and a "
     "search's study, every one named or none",
     RemoveSweepsCommand, true, false},
};

}  // namespace

std::vector<CliCommand> AddSweepCommands(CLI::App& dcs, const GlobalFlags& flags) {
  auto submit_flags = std::make_shared<SubmitFlags>();
  auto sweep_ids = std::make_shared<std::vector<std::string>>();

  CLI::App* submit = dcs.add_subcommand(
      "submit", "Submit a sweep (a grid of conditions x observation modes x seeds; see "
                "configs/quickstart.yaml), or a search with a study block (see "
                "configs/paper/cartpole_multistage_search.yaml), and print its id");
  submit->add_option("spec", submit_flags->spec, "the sweep spec (YAML)")->required();
  submit->add_flag("--watch", submit_flags->watch,
                   "then follow it to its end, as `dcs watch`, and exit with its outcome");
  submit->add_flag("--dry-run", submit_flags->dry_run,
                   "check and expand the spec here, as the coordinator would, and list its trials; "
                   "needs no cluster, queues nothing");

  CLI::App* sweeps = dcs.add_subcommand(
      "sweeps", "The cluster's sweeps: list them with progress (no subcommand), watch, cancel or "
                "retry one, remove ended ones");

  std::vector<CliCommand> commands;
  // The verbs on sweeps, as `dcs sweeps VERB`, beside `dcs runs VERB`; and at the top level,
  // the first verbs' first spelling, kept.
  for (const SweepVerb& verb : kSweepVerbs) {
    for (CLI::App* parent : {sweeps, &dcs}) {
      if (parent == &dcs && !verb.top_level) continue;
      CLI::App* command = parent->add_subcommand(
          verb.name, parent == sweeps
                         ? std::string(verb.help)
                         : absl::StrCat(verb.help, " (as `dcs sweeps ", verb.name, "`)"));
      CLI::Option* sweep =
          command->add_option("sweep", *sweep_ids,
                              verb.several ? "the sweeps' ids, e.g. sweep-1 sweep-2"
                                           : "the sweep's id, e.g. sweep-1")
              ->required();
      if (!verb.several) sweep->expected(1);
      commands.push_back({command,
                          [&flags, sweep_ids, run = verb.run] { return run(flags, *sweep_ids); },
                          kTableOrJson});
    }
  }
  // After its verbs: the first command parsed is the one run.
  commands.push_back({sweeps, [&flags] { return ListSweepsCommand(flags); }, kEveryFormat});
  commands.push_back({submit,
                      [&flags, submit_flags] { return SubmitCommand(flags, *submit_flags); },
                      kTableOrJson});
  return commands;
}

}  // namespace dcs::services::cli
