// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_COVERAGE_REPORT_H_
#define DCS_COORDINATOR_COVERAGE_REPORT_H_

// The coverage part of a sweep's report (dcs/v1/report.proto, CoverageSection): for each state
// projection the runs counted (run/coverage.h), each condition's and mode's coverage per run and
// per window, and per mode whether conditions differ in coverage (one-way ANOVA, as the paper's
// §4.4) and whether coverage goes with score (Pearson's r, its Appendix). Thread-safe (pure
// function).

#include "absl/status/status.h"
#include "dcs/v1/report.pb.h"
#include "dcs/v1/sweep.pb.h"

namespace dcs::report {

// Adds the coverage sections of `results` to `report`, which BuildSweepReport made from them
// (its cells' scores are those of the trials' runs, in order). Runs without coverage are left
// out; no section if no run counted any. INVALID_ARGUMENT naming the run whose projection has a
// number of cells other runs' do not.
absl::Status AddCoverageSections(const v1::SweepResults& results, v1::SweepReport& report);

}  // namespace dcs::report

#endif  // DCS_COORDINATOR_COVERAGE_REPORT_H_
