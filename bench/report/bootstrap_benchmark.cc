// Copyright 2026 The DCS Authors.
//
// The bootstrap intervals of one report cell of 10 seeds, 10,000 resamples at 95 % (what `dcs
// report` computes for each condition and mode), in time per cell (the figure that matters: a
// report of the paper's CartPole table has 42 IQM cells and 40 improvement cells):
//   BM_IqmInterval/next:0          BootstrapIqmInterval, a new seed each time (a report's first
//                                  cell, which draws the resamples)
//   BM_IqmInterval/next:1          the seed of the cell before, other scores (its next cells,
//                                  which reuse the draws)
//   BM_ImprovementInterval/next:N  BootstrapImprovementInterval of two such cells, alike
//   BM_PercentileInterval/ties:N   the interval's two quantiles of 10,000 estimates, without
//                                  ties (0) or with improvement-like ties (1: k / 200)
// Scores are uniform in [300, 500], 42 cells drawn once from a fixed seed.

#include <cstdint>
#include <vector>

#include "benchmark/benchmark.h"
#include "common/random.h"
#include "coordinator/iqm.h"
#include "report/probability_of_improvement.h"

namespace dcs::report {
namespace {

constexpr int kCells = 42;
constexpr int kSeeds = 10;
constexpr int kResamples = 10'000;
constexpr double kConfidence = 0.95;

std::vector<std::vector<double>> Cells() {
  Random random(7);
  std::vector<std::vector<double>> cells(kCells);
  for (std::vector<double>& cell : cells) {
    for (int i = 0; i < kSeeds; ++i) cell.push_back(random.Uniform(300, 500));
  }
  return cells;
}

// Range 0: 1 for a report's next cell (the seed of the cell before), 0 for its first (new seed).
uint64_t SeedOf(const benchmark::State& state, uint64_t cell) {
  return state.range(0) == 1 ? 0 : cell;
}

void BM_IqmInterval(benchmark::State& state) {
  const std::vector<std::vector<double>> cells = Cells();
  uint64_t cell = 0;
  for (auto _ : state) {
    const auto interval = coordinator::BootstrapIqmInterval({cells[cell % kCells]}, kConfidence,
                                                            kResamples, SeedOf(state, cell));
    benchmark::DoNotOptimize(interval);
    ++cell;
  }
}
BENCHMARK(BM_IqmInterval)->ArgName("next")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_ImprovementInterval(benchmark::State& state) {
  const std::vector<std::vector<double>> cells = Cells();
  uint64_t cell = 0;
  for (auto _ : state) {
    const auto interval =
        BootstrapImprovementInterval(cells[cell % kCells], cells[(cell + 1) % kCells], kConfidence,
                                     kResamples, SeedOf(state, cell));
    benchmark::DoNotOptimize(interval);
    ++cell;
  }
}
BENCHMARK(BM_ImprovementInterval)->ArgName("next")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_PercentileInterval(benchmark::State& state) {
  Random random(3);
  std::vector<double> estimates;
  for (int i = 0; i < kResamples; ++i) {
    estimates.push_back(state.range(0) == 1 ? static_cast<double>(random.Integers(0, 201)) / 200
                                            : random.Uniform(300, 500));
  }
  std::vector<double> work;
  for (auto _ : state) {
    work = estimates;  // PercentileInterval may reorder them
    benchmark::DoNotOptimize(coordinator::internal::PercentileInterval(work, kConfidence));
  }
}
BENCHMARK(BM_PercentileInterval)->ArgName("ties")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace dcs::report
