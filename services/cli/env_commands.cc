// Copyright 2026 The DCS Authors.
#include "services/cli/env_commands.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <string>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "common/random.h"
#include "common/round_trip.h"
#include "common/status_macros.h"
#include "env/baseline_policies.h"
#include "env/cartpole.h"
#include "env/env_registry.h"
#include "env/raster.h"
#include "services/cli/context_flags.h"
#include "services/cli/png_file.h"
#include "services/command_line.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

struct TraceFlags {
  std::string env = "cartpole";
  std::vector<std::string> set;  // name=value
  std::string init;               // x,x_dot,theta,theta_dot
  uint64_t seed = 0;
  std::string actions;  // comma-separated
};

struct RolloutFlags {
  std::string env = "cartpole";
  std::string policy = "random";
  int episodes = 10;
  uint64_t seed = 0;
  std::vector<std::string> set;
};

struct RenderFlags {
  std::string env = "cartpole";
  std::string policy = "random";
  int steps = 200;
  uint64_t seed = 0;
  std::vector<std::string> set;
  std::string out;
  int scale = 0;  // 0: 4 for image observations, else 1
};

// A new Env (on the heap: Box2D environments are large) with the flags' context.
template <typename Env>
absl::StatusOr<std::unique_ptr<Env>> EnvFromFlags(const std::vector<std::string>& sets) {
  DCS_ASSIGN_OR_RETURN(const auto values, ParseAssignments(sets, "--set"));
  DCS_ASSIGN_OR_RETURN(
      const std::vector<double> context,
      ContextWithAssignments<Env>(Env::Features().Defaults(), values, "--set"));
  auto environment = std::make_unique<Env>();
  for (size_t i = 0; i < context.size(); ++i) {
    environment->SetFeature(static_cast<int>(i), context[i]);
  }
  return environment;
}

int RunTrace(const TraceFlags& flags, OutputFormat format) {
  if (flags.env != "cartpole") {
    return FailCommand(absl::InvalidArgumentError(
        absl::StrCat("unknown environment '", flags.env, "' (known: cartpole)")));
  }
  absl::StatusOr<std::unique_ptr<env::CartPole>> cartpole =
      EnvFromFlags<env::CartPole>(flags.set);
  if (!cartpole.ok()) return FailCommand(cartpole.status());
  absl::StatusOr<std::vector<double>> actions = ParseNumberList(flags.actions, "--actions");
  if (!actions.ok()) return FailCommand(actions.status());
  for (double action : *actions) {
    if (action != 0 && action != 1) {
      return FailCommand(absl::InvalidArgumentError(
          absl::StrCat("--actions: cartpole's actions are 0 (left) and 1 (right), got ",
                       action)));
    }
  }
  std::array<float, env::CartPole::kObservationSize> observation;
  if (flags.init.empty()) {
    Random random(flags.seed);  // Gymnasium's reset(seed=...)
    (*cartpole)->Reset(random, observation);
  } else {
    absl::StatusOr<std::vector<double>> init = ParseNumberList(flags.init, "--init");
    if (!init.ok()) return FailCommand(init.status());
    if (init->size() != 4) {
      return FailCommand(absl::InvalidArgumentError(
          absl::StrCat("--init: expected x,x_dot,theta,theta_dot, got ", init->size(),
                       " values")));
    }
    (*cartpole)->ResetTo({(*init)[0], (*init)[1], (*init)[2], (*init)[3]}, observation);
  }

  std::vector<std::vector<std::string>> rows = {
      {"t", "action", "x", "x_dot", "theta", "theta_dot", "reward", "terminated", "truncated"}};
  auto add_row = [&](int t, int action, const env::StepResult& result) {
    const env::CartPoleState& s = (*cartpole)->state();
    rows.push_back({absl::StrCat(t), absl::StrCat(action), RoundTrip(s.x), RoundTrip(s.x_dot),
                    RoundTrip(s.theta), RoundTrip(s.theta_dot), RoundTrip(result.reward),
                    absl::StrCat(int{result.terminated}), absl::StrCat(int{result.truncated})});
  };
  add_row(0, -1, {});
  for (size_t t = 0; t < actions->size(); ++t) {
    const std::array<int32_t, 1> action = {static_cast<int32_t>((*actions)[t])};
    add_row(static_cast<int>(t + 1), action[0], (*cartpole)->Step(action, observation));
  }
  std::cout << FormatRows(rows, format) << std::flush;
  return kExitOk;
}

// One episode of `policy` in `environment` from the reset of Random(seed), calling
// `on_step(observation)` after the reset and after every step; returns the return.
template <typename Env, typename OnStep>
double RunEpisode(Env& environment, env::BaselinePolicy<Env>& policy, uint64_t seed,
                  int max_steps, OnStep on_step) {
  std::vector<typename Env::Observation> observation(Env::kObservationSize);
  std::vector<typename Env::ActionElement> action(Env::kActionSize);
  const std::span<typename Env::Observation, Env::kObservationSize> obs(observation.data(),
                                                                        Env::kObservationSize);
  Random random(seed);  // as Gymnasium's reset(seed=...)
  environment.Reset(random, obs);
  policy.Reset(environment);
  on_step(obs);
  double total = 0;
  for (int step = 0; step < max_steps; ++step) {
    policy.Act(environment, obs, std::span<typename Env::ActionElement, Env::kActionSize>(
                                     action.data(), Env::kActionSize));
    const env::StepResult result = environment.Step(
        std::span<const typename Env::ActionElement, Env::kActionSize>(action.data(),
                                                                       Env::kActionSize),
        obs);
    total += result.reward;
    on_step(obs);
    if (result.done()) break;
  }
  return total;
}

template <typename Env>
absl::Status Rollout(const RolloutFlags& flags, OutputFormat format) {
  DCS_ASSIGN_OR_RETURN(std::unique_ptr<Env> environment, EnvFromFlags<Env>(flags.set));
  DCS_ASSIGN_OR_RETURN(std::unique_ptr<env::BaselinePolicy<Env>> policy,
                       env::MakeBaselinePolicy<Env>(flags.policy, flags.seed));
  std::vector<double> returns;
  for (int episode = 0; episode < flags.episodes; ++episode) {
    // Episode i resets with seed + i, as Gymnasium evaluations seed consecutive episodes.
    returns.push_back(RunEpisode(*environment, *policy, flags.seed + episode,
                                 std::numeric_limits<int>::max(), [](auto) {}));
  }
  double mean = 0;
  for (double r : returns) mean += r / static_cast<double>(returns.size());
  double variance = 0;
  for (double r : returns) variance += (r - mean) * (r - mean) / static_cast<double>(returns.size());
  const auto [min, max] = std::minmax_element(returns.begin(), returns.end());
  std::cout << FormatRows({{"ENV", "POLICY", "EPISODES", "MEAN", "STD", "MIN", "MAX"},
                           {flags.env, flags.policy, absl::StrCat(returns.size()),
                            absl::StrFormat("%.2f", mean),
                            absl::StrFormat("%.2f", std::sqrt(variance)),
                            absl::StrFormat("%.2f", *min), absl::StrFormat("%.2f", *max)}},
                          format)
            << std::flush;
  return absl::OkStatus();
}

template <typename Env>
absl::Status Render(const RenderFlags& flags) {
  DCS_ASSIGN_OR_RETURN(std::unique_ptr<Env> environment, EnvFromFlags<Env>(flags.set));
  DCS_ASSIGN_OR_RETURN(std::unique_ptr<env::BaselinePolicy<Env>> policy,
                       env::MakeBaselinePolicy<Env>(flags.policy, flags.seed));
  std::error_code error;
  std::filesystem::create_directories(flags.out, error);
  if (error) {
    return absl::PermissionDeniedError(absl::StrCat("cannot create ", flags.out, ": ",
                                                    error.message()));
  }
  int frames = 0;
  absl::Status status = absl::OkStatus();
  auto write_frame = [&](std::span<const typename Env::Observation> observation) {
    if (!status.ok()) return;
    const std::string path = absl::StrFormat("%s/frame_%05d.png", flags.out, frames++);
    if constexpr (requires { Env::kImageWidth; }) {
      // An image observation: exactly what the policy sees.
      status = WritePng(path, observation, Env::kImageWidth, Env::kImageHeight,
                        flags.scale > 0 ? flags.scale : 4);
    } else {
      env::Canvas canvas(Env::kRenderWidth, Env::kRenderHeight);
      environment->Render(canvas);
      status = WritePng(path, canvas.pixels(), canvas.width(), canvas.height(),
                        flags.scale > 0 ? flags.scale : 1);
    }
  };
  const double total = RunEpisode(*environment, *policy, flags.seed, flags.steps, write_frame);
  DCS_RETURN_IF_ERROR(status);
  std::cerr << "wrote " << frames << " frames to " << flags.out << " (return "
            << absl::StrFormat("%.2f", total) << ")" << std::endl;
  return absl::OkStatus();
}

}  // namespace

std::vector<CliCommand> AddEnvCommands(CLI::App& dcs, const GlobalFlags& flags) {
  CLI::App* env_group = dcs.add_subcommand("env", "Environments: debugging tools");
  env_group->require_subcommand(1);
  auto trace_flags = std::make_shared<TraceFlags>();
  CLI::App* trace = env_group->add_subcommand(
      "trace", "Print an environment's state after every step of an action sequence (numbers "
               "with round-trip precision)");
  trace->add_option("--env", trace_flags->env, "the environment")->capture_default_str();
  trace->add_option("--set", trace_flags->set,
                    "a context feature's value, name=value (repeatable), e.g. length=1.3");
  trace->add_option("--init", trace_flags->init,
                    "the initial state x,x_dot,theta,theta_dot (default: a seeded reset)");
  trace->add_option("--seed", trace_flags->seed, "the reset's seed, as Gymnasium's reset(seed)")
      ->capture_default_str();
  trace->add_option("--actions", trace_flags->actions, "the actions, e.g. 0,1,1,0")->required();

  auto rollout_flags = std::make_shared<RolloutFlags>();
  CLI::App* rollout = env_group->add_subcommand(
      "rollout", "Run a baseline policy for some episodes; print the return's mean, std, min, max");
  rollout->add_option("--env", rollout_flags->env, "the environment")->capture_default_str();
  rollout->add_option("--policy", rollout_flags->policy,
                      "random (any environment), heuristic (bipedal_walker) or centerline "
                      "(car_racing)")
      ->capture_default_str();
  rollout->add_option("--episodes", rollout_flags->episodes, "episodes to run")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  rollout->add_option("--seed", rollout_flags->seed, "episode i resets with seed + i")
      ->capture_default_str();
  rollout->add_option("--set", rollout_flags->set,
                      "a context feature's value, name=value (repeatable), e.g. COM_X=0.4");

  auto render_flags = std::make_shared<RenderFlags>();
  CLI::App* render = env_group->add_subcommand(
      "render", "Write PNG frames of one episode: what the policy sees, or the scene");
  render->add_option("--env", render_flags->env, "the environment")->capture_default_str();
  render->add_option("--policy", render_flags->policy, "as for rollout")->capture_default_str();
  render->add_option("--steps", render_flags->steps, "the most steps to render")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  render->add_option("--seed", render_flags->seed, "the reset's seed")->capture_default_str();
  render->add_option("--set", render_flags->set, "a context feature's value, name=value");
  AddOutDirectory(*render, &render_flags->out, "the directory for frame_NNNNN.png")
      ->required();
  render->add_option("--scale", render_flags->scale,
                     "pixel repetition (default: 4 for image observations, else 1)")
      ->check(CLI::Range(0, 16));

  auto visit = [](const std::string& name, auto run) {
    const absl::Status status = env::VisitEnvironment(name, run);
    return status.ok() ? kExitOk : FailCommand(status);
  };
  return {
      {trace, [trace_flags, &flags] { return RunTrace(*trace_flags, flags.output); },
       kEveryFormat},
      {rollout,
       [rollout_flags, visit, &flags] {
         return visit(rollout_flags->env, [&]<typename Env>() {
           return Rollout<Env>(*rollout_flags, flags.output);
         });
       },
       kEveryFormat},
      {render,
       [render_flags, visit] {
         return visit(render_flags->env,
                      [&]<typename Env>() { return Render<Env>(*render_flags); });
       }},
  };
}

}  // namespace dcs::services::cli
