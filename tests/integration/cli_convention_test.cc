// Copyright 2026 The DCS Authors.
//
// The convention every `dcs` command follows: each command that prints data prints it as JSON
// Lines with -o json, and refuses a format it cannot print; each exit code of README's table
// (services/exit_codes.h) comes from the failures it names.

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <signal.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/cli/child_process.h"
#include "services/cli/local_cluster.h"
#include "services/exit_codes.h"
#include "tests/integration/cluster_processes.h"
#include "tests/integration/test_util.h"
#include "tests/testing/net.h"
#include "tests/testing/slowdown.h"
#include "tests/testing/temp_dir.h"

namespace dcs::integration {
namespace {

using ::testing::HasSubstr;

// `dcs args...` with its stdout alone: what a script reads.
RunResult DcsStdout(const std::vector<std::string>& args) {
  std::vector<std::string> shell = {"-c", "exec \"$0\" \"$@\" 2>/dev/null", BinaryPath("dcs")};
  shell.insert(shell.end(), args.begin(), args.end());
  return RunProgram("/bin/sh", shell, absl::Minutes(5));
}

// Every command line JsonLines ran.
std::vector<std::vector<std::string>>& JsonInvocations() {
  static auto* invocations = new std::vector<std::vector<std::string>>;
  return *invocations;
}

// Runs `args` with -o json and expects each line of its stdout, and at least one, to be a JSON
// value; returns them.
std::vector<google::protobuf::Value> JsonLines(std::vector<std::string> args) {
  JsonInvocations().push_back(args);
  args.insert(args.end(), {"-o", "json"});
  const RunResult result = DcsStdout(args);
  const std::string command = absl::StrJoin(args, " ");
  EXPECT_EQ(result.exit_code, 0) << command << ": " << result.output;
  std::vector<google::protobuf::Value> values;
  for (const std::string& line : Lines(result.output)) {
    google::protobuf::Value& value = values.emplace_back();
    EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(line, &value).ok())
        << command << ": not JSON: " << line;
  }
  EXPECT_FALSE(values.empty()) << command << " printed nothing";
  return values;
}

// The help of `dcs command...` and of each command under it, depth first, by command path.
void CollectHelp(const std::vector<std::string>& command,
                 std::map<std::string, std::string>& help) {
  // dcs's commands nest two deep (`dcs studies ask`): deeper, the walk misreads the help.
  ASSERT_LE(command.size(), 2u) << absl::StrJoin(command, " ");
  std::vector<std::string> args = command;
  args.push_back("--help");
  const RunResult result = DcsStdout(args);
  ASSERT_EQ(result.exit_code, 0) << absl::StrJoin(args, " ") << ": " << result.output;
  help[absl::StrJoin(command, " ")] = result.output;
  bool in_subcommands = false;
  for (const std::string& line : Lines(result.output)) {
    if (line == "Subcommands:") {
      in_subcommands = true;
    } else if (in_subcommands && absl::StartsWith(line, "  ") && line[2] != ' ') {
      std::vector<std::string> subcommand = command;
      // "  studies, study   Ask-and-tell ...": a command, its aliases, its description.
      subcommand.push_back(line.substr(2, line.find_first_of(", ", 2) - 2));
      CollectHelp(subcommand, help);
    } else if (!absl::StartsWith(line, "  ")) {
      in_subcommands = false;
    }
  }
}

// The commands whose help says they print JSON (services/cli/dcs_main.cc), by command path.
std::set<std::string> JsonCommands(const std::map<std::string, std::string>& help) {
  std::set<std::string> commands;
  for (const auto& [command, text] : help) {
    if (absl::StrContains(text, "Prints its data as -o") && absl::StrContains(text, "json")) {
      commands.insert(command);
    }
  }
  return commands;
}

// The command path `args` starts with: the longest prefix of it that `help` knows.
std::string CommandPathOf(const std::vector<std::string>& args,
                          const std::map<std::string, std::string>& help) {
  std::string path;
  for (size_t n = 1; n <= args.size(); ++n) {
    const std::string prefix = absl::StrJoin(args.begin(), args.begin() + n, " ");
    if (help.contains(prefix)) path = prefix;
  }
  return path;
}

// A cluster that ran a small sweep, and a study in a store: every command that prints data is
// run with -o json against them.
TEST(CliConventionTest, EveryDataCommandPrintsJsonLines) {
  const std::string dir = testing::MakeTempDir();
  const std::string spec = dir + "/small.yaml";
  ASSERT_TRUE(WriteFileAtomically(spec, EightRunSweepSpec("small", 512, 256)).ok());
  ClusterProcesses cluster(absl::Seconds(1));
  StartCoordinatorLearnerAndActors(cluster);
  const std::string addr = "--addr=" + cluster.coordinator_address();
  const std::vector<google::protobuf::Value> submitted =
      JsonLines({"submit", spec, "--watch", addr});
  ASSERT_FALSE(submitted.empty());
  EXPECT_EQ(JsonField(submitted[0], "sweep_id").string_value(), "sweep-1");

  JsonLines({"submit", spec, "--dry-run", addr});
  const std::vector<google::protobuf::Value> status = JsonLines({"status", addr});
  ASSERT_FALSE(status.empty());
  EXPECT_EQ(JsonField(status[0], "workers").list_value().values_size(), 3);
  const std::vector<google::protobuf::Value> runs = JsonLines({"runs", addr});
  ASSERT_FALSE(runs.empty());
  ASSERT_EQ(JsonField(runs[0], "runs").list_value().values_size(), 8);
  for (const google::protobuf::Value& run : JsonField(runs[0], "runs").list_value().values()) {
    EXPECT_EQ(JsonField(run, "state").string_value(), "completed");
    EXPECT_TRUE(JsonField(run, "seed").has_number_value()) << "a 64-bit integer as a number";
  }
  // One sweep's runs: all 8 here, the cluster's only sweep (an unknown sweep is NOT_FOUND,
  // EachExitCodeOfTheTableComesFromWhatItNames).
  const std::vector<google::protobuf::Value> sweep_runs =
      JsonLines({"runs", "--sweep", "sweep-1", addr});
  ASSERT_FALSE(sweep_runs.empty());
  EXPECT_EQ(JsonField(sweep_runs[0], "runs").list_value().values_size(), 8);
  const std::vector<google::protobuf::Value> sweeps = JsonLines({"sweeps", addr});
  ASSERT_FALSE(sweeps.empty());
  EXPECT_EQ(
      JsonField(JsonField(sweeps[0], "sweeps").list_value().values(0), "state").string_value(),
      "completed");
  JsonLines({"report", "sweep-1", addr});
  // A sweep's verbs as a run's are spelt, and their first spelling.
  for (const std::vector<std::string>& watch : std::vector<std::vector<std::string>>{
           {"sweeps", "watch", "sweep-1", addr}, {"watch", "sweep-1", addr}}) {
    const std::vector<google::protobuf::Value> watched = JsonLines(watch);
    ASSERT_FALSE(watched.empty()) << watch[0];
    EXPECT_EQ(JsonField(JsonField(watched.back(), "sweep"), "state").string_value(), "completed")
        << watch[0];
  }
  const std::string run_dir = dir + "/run-1";
  JsonLines({"runs", "watch", "run-1", "--out", run_dir, addr});
  JsonLines({"summarize", run_dir});
  JsonLines({"eval", run_dir, "--grid", "length=0.3:1.2:2", "--episodes", "1"});

  JsonLines({"env", "trace", "--actions", "0,1"});
  JsonLines({"env", "rollout", "--episodes", "1"});

  const std::string store = dir + "/studies.db";
  ASSERT_TRUE(WriteFileAtomically(dir + "/space.yaml",
                                  "parameters:\n  - {name: x, type: float, low: 0, high: 1}\n")
                  .ok());
  ASSERT_EQ(DcsStdout({"studies", "create", dir + "/space.yaml", "--store", store}).exit_code, 0);
  JsonLines({"studies", "ask", "study-1", "--store", store});
  ASSERT_EQ(DcsStdout({"studies", "tell", "study-1", "0", "0.5", "--store", store}).exit_code, 0);
  JsonLines({"studies", "trials", "study-1", "--store", store});
  JsonLines({"studies", "best", "study-1", "--store", store});
  // The studies listed as runs and sweeps are, and by a verb of their own.
  for (const std::vector<std::string>& list : std::vector<std::vector<std::string>>{
           {"studies", "--store", store}, {"studies", "list", "--store", store}}) {
    const std::vector<google::protobuf::Value> studies = JsonLines(list);
    ASSERT_FALSE(studies.empty());
    ASSERT_EQ(JsonField(studies[0], "studies").list_value().values_size(), 1);
    EXPECT_EQ(
        JsonField(JsonField(JsonField(studies[0], "studies").list_value().values(0), "best"),
                  "value")
            .number_value(),
        0.5);
  }
  JsonLines({"studies", addr});
  JsonLines({"train", DCS_SOURCE_DIR "/configs/cartpole_length_pool7_static_blind.yaml", "--out",
             dir + "/trained"});

  // Cancels: of a run, then of the rest of its sweep, then of another sweep by the first
  // spelling of the verb.
  const std::string long_spec = dir + "/long.yaml";
  ASSERT_TRUE(WriteFileAtomically(long_spec, EightRunSweepSpec("long", 10'000'000, 512)).ok());
  for (const char* sweep : {"sweep-2", "sweep-3"}) {
    ASSERT_EQ(DcsStdout({"submit", long_spec, addr}).output, absl::StrCat(sweep, "\n"));
  }
  JsonLines({"runs", "cancel", "run-9", addr});
  JsonLines({"sweeps", "cancel", "sweep-2", addr});
  JsonLines({"cancel", "sweep-3", addr});

  // Removals: a run alone, then two ended sweeps with their runs, each printed as it was.
  const std::string tiny = dir + "/tiny.yaml";
  ASSERT_TRUE(WriteFileAtomically(tiny, "env: cartpole\ntotal_timesteps: 512\n"
                                        "evaluation: {freq: 256, episodes: 2, "
                                        "contexts: {id: [0.5]}}\n"
                                        "ppo: {n_steps: 256, batch_size: 64, n_epochs: 2}\n")
                  .ok());
  ASSERT_EQ(DcsStdout({"train", "--cluster", tiny, "--out", dir + "/alone", addr}).exit_code, 0);
  const std::vector<google::protobuf::Value> removed_run =
      JsonLines({"runs", "rm", "run-25", addr});
  ASSERT_FALSE(removed_run.empty());
  EXPECT_EQ(
      JsonField(JsonField(removed_run[0], "runs").list_value().values(0), "state").string_value(),
      "completed");
  const std::vector<google::protobuf::Value> removed =
      JsonLines({"sweeps", "rm", "sweep-1", "sweep-2", addr});
  ASSERT_FALSE(removed.empty());
  ASSERT_EQ(JsonField(removed[0], "sweeps").list_value().values_size(), 2);
  EXPECT_EQ(
      JsonField(JsonField(removed[0], "sweeps").list_value().values(0), "state").string_value(),
      "completed");
  EXPECT_EQ(JsonField(removed[0], "runs").list_value().values_size(), 16);
  const std::vector<google::protobuf::Value> left = JsonLines({"runs", addr});
  ASSERT_FALSE(left.empty());
  ASSERT_EQ(JsonField(left[0], "runs").list_value().values_size(), 8);
  for (const google::protobuf::Value& run : JsonField(left[0], "runs").list_value().values()) {
    EXPECT_EQ(JsonField(run, "sweep_id").string_value(), "sweep-3");
  }

  // Every command that says it prints JSON ran above, but retry: it needs a failed run, which
  // no command can make, and prints what is left as cancel does (sweep_commands.cc).
  std::map<std::string, std::string> help;
  CollectHelp({}, help);
  std::set<std::string> untested = JsonCommands(help);
  ASSERT_THAT(untested, ::testing::Contains("runs")) << "the commands' help says what they print";
  for (const std::vector<std::string>& args : JsonInvocations()) {
    untested.erase(CommandPathOf(args, help));
  }
  EXPECT_THAT(untested, ::testing::UnorderedElementsAre("retry", "sweeps retry"));
}

// A format a command cannot print is a usage error naming what it prints, before it runs.
TEST(CliConventionTest, AFormatACommandCannotPrintIsRefused) {
  const std::string dir = testing::MakeTempDir();
  const RunResult up = RunProgram(BinaryPath("dcs"), {"up", "--data-dir", dir, "-o", "json"});
  EXPECT_EQ(up.exit_code, services::kExitUsage) << up.output;
  EXPECT_THAT(up.output, HasSubstr("-o json: `dcs up` prints table"));
  const RunResult submit =
      RunProgram(BinaryPath("dcs"), {"submit", dir + "/none.yaml", "-o", "csv"});
  EXPECT_EQ(submit.exit_code, services::kExitUsage) << submit.output;
  EXPECT_THAT(submit.output, HasSubstr("-o csv: `dcs submit` prints table or json"));
  const RunResult trace =
      RunProgram(BinaryPath("dcs"), {"env", "trace", "--actions", "0,1", "-o", "csv"});
  EXPECT_EQ(trace.exit_code, 0) << trace.output;
  EXPECT_THAT(trace.output, HasSubstr("t,action,x,x_dot,theta,theta_dot,reward,"));
}

// What a command writes is a directory or a file, and its help says which: `--out DIR` or
// `--out FILE` (services/cli/cli_command.h), in every command of the tree.
TEST(CliConventionTest, EveryOutSaysWhetherItIsADirectoryOrAFile) {
  std::map<std::string, std::string> help;
  CollectHelp({}, help);
  EXPECT_TRUE(help.contains("studies plot")) << "the walk reaches nested commands";
  int outs = 0;
  for (const auto& [command, text] : help) {
    for (const std::string& line : Lines(text)) {
      const std::vector<std::string> words = absl::StrSplit(line, ' ', absl::SkipEmpty());
      if (words.empty() || words[0] != "--out") continue;
      ++outs;
      const std::string kind = words.size() > 1 ? words[1].substr(0, words[1].find('=')) : "";
      EXPECT_THAT(kind, ::testing::AnyOf("DIR", "FILE"))
          << "dcs " << command << ": " << line;
    }
  }
  EXPECT_GE(outs, 10) << "commands with --out found";
}

// `dcs args...` exits with `code`, printing one line that holds `message`.
void ExpectExit(int code, const std::vector<std::string>& args, const std::string& message) {
  const RunResult result = RunProgram(BinaryPath("dcs"), args);
  const std::string command = absl::StrJoin(args, " ");
  EXPECT_EQ(result.exit_code, code) << command << ": " << result.output;
  EXPECT_THAT(result.output, HasSubstr(message)) << command;
}

// Starts `dcs args...`, waits until its output holds `text`, then sends it SIGINT; returns its
// exit code.
int InterruptedExit(const std::vector<std::string>& args, const std::string& text) {
  const std::string output = testing::MakeTempDir() + "/output";
  absl::StatusOr<services::cli::ChildProcess> dcs = services::cli::ChildProcess::Start(
      {.path = BinaryPath("dcs"), .args = args, .output_path = output});
  EXPECT_TRUE(dcs.ok()) << dcs.status();
  if (!dcs.ok()) return -1;
  const absl::Time deadline = absl::Now() + testing::Patient(absl::Minutes(1));
  while (ReadFile(output).value_or("").find(text) == std::string::npos && absl::Now() < deadline) {
    absl::SleepFor(absl::Milliseconds(50));
  }
  ::kill(dcs->pid(), SIGINT);
  const std::optional<int> status = dcs->Wait(testing::Patient(absl::Seconds(30)));
  EXPECT_TRUE(status.has_value()) << ReadFile(output).value_or("");
  return status.has_value() && WIFEXITED(*status) ? WEXITSTATUS(*status) : -1;
}

// README's table of exit codes, each from a command that should give it.
TEST(CliConventionTest, EachExitCodeOfTheTableComesFromWhatItNames) {
  const std::string dir = testing::MakeTempDir();
  const std::string data_dir = dir + "/cluster";
  const std::string local = "--data-dir=" + data_dir;
  ASSERT_EQ(RunProgram(BinaryPath("dcs"), {"up", "--detach", "--actors=1", local}).exit_code, 0);
  const absl::StatusOr<services::cli::ClusterState> cluster =
      services::cli::ReadClusterState(data_dir);
  ASSERT_TRUE(cluster.ok()) << cluster.status();
  const std::string long_spec = dir + "/long.yaml";
  ASSERT_TRUE(WriteFileAtomically(long_spec, EightRunSweepSpec("long", 10'000'000, 512)).ok());
  const std::string bad_spec = dir + "/bad.yaml";
  ASSERT_TRUE(WriteFileAtomically(bad_spec, "seeds: 2\nenv: cartpole\nconditions: []\n").ok());
  const std::string bad_config = dir + "/coordinator.yaml";
  ASSERT_TRUE(WriteFileAtomically(bad_config, "lissten: 127.0.0.1:0\n").ok());

  ExpectExit(services::kExitOk, {"submit", long_spec, local}, "sweep-1");
  ExpectExit(services::kExitFailure, {"up", "--detach", local}, "already runs");
  ExpectExit(services::kExitUsage, {"train"}, "a run config is required");
  ExpectExit(services::kExitUsage, {"status", "--adr", "x"},
             "unknown flag --adr for `dcs status`; did you mean --addr?");
  ExpectExit(services::kExitUsage, {"runs", "cancle", "run-1"},
             "unknown command 'cancle' for `dcs runs`; did you mean cancel?");
  ExpectExit(services::kExitUsage, {"sweeps", "-o", "yaml"}, "'yaml' is not one of");
  ExpectExit(services::kExitDataError, {"submit", bad_spec, "--dry-run", local}, "bad.yaml");
  ExpectExit(services::kExitNoInput, {"submit", dir + "/missing.yaml", local}, "missing.yaml");
  ExpectExit(services::kExitNoInput, {"runs", "get", "run-99", local}, "run-99");
  ExpectExit(services::kExitNoInput, {"runs", "--sweep", "sweep-99", local}, "sweep-99");
  ExpectExit(services::kExitNoInput, {"sweeps", "cancel", "sweep-99", local}, "sweep-99");
  ExpectExit(services::kExitNoInput, {"retry", "sweep-99", local}, "sweep-99");
  ExpectExit(services::kExitNoInput, {"sweeps", "rm", "sweep-99", local}, "sweep-99");
  ExpectExit(services::kExitNoInput, {"runs", "rm", "run-99", local}, "run-99");
  // Removing what still runs: the state forbids it, as cancelling a finished sweep.
  ExpectExit(services::kExitFailure, {"sweeps", "rm", "sweep-1", local},
             "stop it first with `dcs sweeps cancel sweep-1`");
  ExpectExit(services::kExitFailure, {"runs", "rm", "run-1", local},
             "remove the sweep with `dcs sweeps rm sweep-1`");
  ExpectExit(services::kExitUsage, {"rm", "sweep-1", local}, "unknown command 'rm' for `dcs`");
  const std::string nobody = absl::StrCat("127.0.0.1:", testing::PickFreePort());
  ExpectExit(services::kExitUnavailable, {"health", "--addr", nobody, "--timeout=2s"},
             "UNAVAILABLE");
  // Another directory: the cluster's token is not used.
  ExpectExit(services::kExitNoPermission,
             {"status", "--addr", cluster->coordinator_address, "--data-dir", dir},
             "requires a token");
  const RunResult config =
      RunProgram(BinaryPath("dcs-coordinator"), {"--config", bad_config});
  EXPECT_EQ(config.exit_code, services::kExitConfig) << config.output;
  EXPECT_THAT(config.output, HasSubstr("unknown key 'lissten'"));
  EXPECT_EQ(InterruptedExit({"runs", "watch", "run-1", local}, "eval@"),
            services::kExitInterrupted);

  ExpectExit(services::kExitOk, {"down", local}, "cluster stopped");
}

}  // namespace
}  // namespace dcs::integration
