// Copyright 2026 The DCS Authors.
//
// A sweep spec submitted to the coordinator, checked and expanded into its runs (ExpandSweep:
// what SubmitSweep does before the store), the store and the runs' directories left out:
//   BM_ExpandTableSeeds40   the paper's biggest sweep, configs/paper/cartpole_table_seeds40.yaml
//                           (42 trials x 40 seeds = 1,680 runs)
//   BM_ExpandStudySearch    the paper's multi-stage search, a study sweep
//                           (configs/paper/cartpole_multistage_search.yaml: no runs until asked)

#include <string>

#include "benchmark/benchmark.h"
#include "common/atomic_file.h"
#include "coordinator/sweep_submission.h"

namespace dcs::coordinator {
namespace {

void Expand(benchmark::State& state, const std::string& path) {
  const absl::StatusOr<std::string> text = ReadFile(path);
  if (!text.ok()) {
    state.SkipWithError(std::string(text.status().message()).c_str());
    return;
  }
  for (auto _ : state) {
    absl::StatusOr<ExpandedSweep> sweep = ExpandSweep(*text, path, "sweep", "request");
    if (!sweep.ok()) {
      state.SkipWithError(std::string(sweep.status().message()).c_str());
      return;
    }
    benchmark::DoNotOptimize(sweep);
  }
}

void BM_ExpandTableSeeds40(benchmark::State& state) {
  Expand(state, DCS_SOURCE_DIR "/configs/paper/cartpole_table_seeds40.yaml");
}
void BM_ExpandStudySearch(benchmark::State& state) {
  Expand(state, DCS_SOURCE_DIR "/configs/paper/cartpole_multistage_search.yaml");
}

BENCHMARK(BM_ExpandTableSeeds40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ExpandStudySearch)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dcs::coordinator
