// Copyright 2026 The DCS Authors.
//
// One TPE suggestion (Sampler::Sample: the split, the Parzen estimators of every parameter the
// trial has, 24 candidates each) after N finished trials, the sampler alone (no store):
//   BM_SuggestFourStages/N           the paper's 4-stage schedule search (the space of
//                                    configs/paper/cartpole_multistage_search.yaml: a mode per
//                                    stage, the mode's parameters)
//   BM_SuggestFourStagesGrouped/N    the same with multivariate TPE by groups
//   BM_SuggestHartmann6/N            6 floats, for comparison with Optuna 4.9's 6.9 ms per trial
//                                    at trials 91-100 (bench/study/ask_tell.py)
// The N trials are TPE's own, told a synthetic objective, so the history is what a study has.

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "benchmark/benchmark.h"
#include "absl/strings/match.h"
#include "coordinator/study_sweep_spec.h"
#include "coordinator/tpe_sampler.h"
#include "run/search_space_yaml.h"

namespace dcs::coordinator {
namespace {

// The search space of `path`: a space file, or a study sweep spec's.
run::SearchSpace LoadSpace(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  if (absl::StrContains(text.str(), "\nstudy:")) return ParseStudySweepYaml(text.str(), path)->space;
  return *run::ParseSearchSpaceYaml(text.str(), path);
}

// A value that prefers sinusoidal early stages and cosine annealing late ones, or for floats a
// smooth bowl: enough structure that TPE's below set means something.
double Objective(const run::ParameterValues& values) {
  double value = 0;
  for (const auto& [name, v] : values) value += std::sin(3 * v + static_cast<double>(name.size()));
  return value;
}

std::vector<StudyTrial> History(const Sampler& sampler, const run::SearchSpace& space, int n) {
  std::vector<StudyTrial> history;
  for (int number = 0; number < n; ++number) {
    StudyTrial trial{.number = number, .state = TrialState::kComplete};
    trial.values = sampler.Sample(space, history, number);
    trial.value = Objective(trial.values);
    history.push_back(std::move(trial));
  }
  return history;
}

void Suggest(benchmark::State& state, const std::string& space_file, const TpeOptions& options) {
  const run::SearchSpace space = LoadSpace(space_file);
  const auto sampler = MakeTpeSampler(0, Direction::kMaximize, options);
  const int n = static_cast<int>(state.range(0));
  const std::vector<StudyTrial> history = History(*sampler, space, n);
  for (auto _ : state) {
    benchmark::DoNotOptimize(sampler->Sample(space, history, n));
  }
}

void BM_SuggestFourStages(benchmark::State& state) {
  Suggest(state, DCS_SOURCE_DIR "/configs/paper/cartpole_multistage_search.yaml", TpeOptions{});
}
void BM_SuggestFourStagesGrouped(benchmark::State& state) {
  Suggest(state, DCS_SOURCE_DIR "/configs/paper/cartpole_multistage_search.yaml",
          TpeOptions{.parzen = {.multivariate = true}, .group = true});
}
void BM_SuggestHartmann6(benchmark::State& state) {
  Suggest(state, DCS_SOURCE_DIR "/bench/study/hartmann6.yaml", TpeOptions{});
}

BENCHMARK(BM_SuggestFourStages)
    ->Arg(10)
    ->Arg(50)
    ->Arg(100)
    ->Arg(240)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SuggestFourStagesGrouped)->Arg(100)->Arg(240)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SuggestHartmann6)->Arg(100)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace dcs::coordinator
