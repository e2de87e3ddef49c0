// Copyright 2026 The DCS Authors.
#include "coordinator/store_schema.h"

#include <SQLiteCpp/Database.h>

#include <algorithm>
#include <iterator>

#include "absl/strings/str_cat.h"

namespace dcs::coordinator {
namespace {

// Times are microseconds since the Unix epoch, UTC.
constexpr const char* kMigrations[] = {
    // 0 -> 1: runs, their leases, their checkpoints.
    R"sql(
CREATE TABLE runs (
  number INTEGER PRIMARY KEY AUTOINCREMENT,
  request_id TEXT NOT NULL UNIQUE,
  config TEXT NOT NULL,
  seed INTEGER NOT NULL,
  env TEXT NOT NULL,
  n_envs INTEGER NOT NULL CHECK (n_envs >= 1),
  total_timesteps INTEGER NOT NULL,
  state TEXT NOT NULL
    CHECK (state IN ('queued', 'running', 'completed', 'failed', 'cancelled')),
  error TEXT NOT NULL DEFAULT '',
  learner_numerics TEXT NOT NULL DEFAULT '',
  actor_numerics TEXT NOT NULL DEFAULT '',
  timesteps INTEGER NOT NULL DEFAULT 0,
  policy_version INTEGER NOT NULL DEFAULT 0,
  steps_per_second REAL NOT NULL DEFAULT 0,
  recent_return REAL,
  avg_combined REAL,
  evaluation_step INTEGER,
  checkpoint TEXT NOT NULL DEFAULT '',
  created_at INTEGER NOT NULL,
  updated_at INTEGER NOT NULL
);
CREATE TABLE leases (
  run INTEGER NOT NULL REFERENCES runs(number),
  slot INTEGER NOT NULL,
  epoch INTEGER NOT NULL DEFAULT 0,
  holder TEXT NOT NULL DEFAULT '',
  address TEXT NOT NULL DEFAULT '',
  deadline INTEGER NOT NULL DEFAULT 0,
  PRIMARY KEY (run, slot)
);
CREATE TABLE checkpoints (
  run INTEGER NOT NULL REFERENCES runs(number),
  name TEXT NOT NULL,
  timesteps INTEGER NOT NULL,
  sha256 TEXT NOT NULL,
  created_at INTEGER NOT NULL,
  PRIMARY KEY (run, name)
);
)sql",
    // 1 -> 2: evaluations of runs' policies, as jobs for actors (one per context), and their
    // episodes' returns; indexes for the lease queries.
    R"sql(
CREATE TABLE evaluations (
  run INTEGER NOT NULL REFERENCES runs(number),
  policy_version INTEGER NOT NULL,
  step INTEGER NOT NULL,
  contexts INTEGER NOT NULL CHECK (contexts >= 1),
  episodes INTEGER NOT NULL CHECK (episodes >= 1),
  weights BLOB NOT NULL,
  created_at INTEGER NOT NULL,
  PRIMARY KEY (run, policy_version)
);
CREATE TABLE evaluation_jobs (
  run INTEGER NOT NULL,
  policy_version INTEGER NOT NULL,
  context INTEGER NOT NULL,
  epoch INTEGER NOT NULL DEFAULT 0,
  holder TEXT NOT NULL DEFAULT '',
  deadline INTEGER NOT NULL DEFAULT 0,
  done INTEGER NOT NULL DEFAULT 0,
  seconds REAL,
  PRIMARY KEY (run, policy_version, context),
  FOREIGN KEY (run, policy_version) REFERENCES evaluations(run, policy_version)
);
CREATE TABLE evaluation_returns (
  run INTEGER NOT NULL,
  policy_version INTEGER NOT NULL,
  context INTEGER NOT NULL,
  episode INTEGER NOT NULL,
  value REAL NOT NULL,
  PRIMARY KEY (run, policy_version, context, episode),
  FOREIGN KEY (run, policy_version, context)
    REFERENCES evaluation_jobs(run, policy_version, context)
);
-- What the lease queries scan (held leases, open jobs), not the whole history.
CREATE INDEX leases_held ON leases(deadline) WHERE holder != '';
CREATE INDEX evaluation_jobs_open ON evaluation_jobs(done, holder, deadline);
)sql",
    // 2 -> 3: sweeps, their trials (a condition in one observation mode, in the spec's order),
    // and which trial of which sweep a run trains (none for a run submitted alone).
    R"sql(
CREATE TABLE sweeps (
  number INTEGER PRIMARY KEY AUTOINCREMENT,
  request_id TEXT NOT NULL UNIQUE,
  name TEXT NOT NULL,
  spec TEXT NOT NULL,
  seeds INTEGER NOT NULL CHECK (seeds >= 1),
  cancelled INTEGER NOT NULL DEFAULT 0,
  created_at INTEGER NOT NULL,
  updated_at INTEGER NOT NULL
);
CREATE TABLE trials (
  sweep INTEGER NOT NULL REFERENCES sweeps(number),
  trial INTEGER NOT NULL,
  condition TEXT NOT NULL,
  family TEXT NOT NULL,
  observe TEXT NOT NULL,
  PRIMARY KEY (sweep, trial)
);
ALTER TABLE runs ADD COLUMN sweep INTEGER REFERENCES sweeps(number);
ALTER TABLE runs ADD COLUMN trial INTEGER;
-- Fair queueing counts each sweep's running runs; a sweep's view lists its runs.
CREATE INDEX runs_by_sweep ON runs(sweep, state);
)sql",
    // 3 -> 4: studies (a search space, a sampler, a pruner), their trials, each trial's
    // parameter values (internal representation), intermediate values and successive-halving
    // rungs.
    R"sql(
CREATE TABLE studies (
  number INTEGER PRIMARY KEY AUTOINCREMENT,
  request_id TEXT NOT NULL UNIQUE,
  name TEXT NOT NULL,
  space TEXT NOT NULL,
  sampler TEXT NOT NULL,
  seed INTEGER NOT NULL,
  direction TEXT NOT NULL CHECK (direction IN ('minimize', 'maximize')),
  startup_trials INTEGER NOT NULL CHECK (startup_trials >= 0),
  ei_candidates INTEGER NOT NULL CHECK (ei_candidates >= 1),
  multivariate INTEGER NOT NULL,
  grouped INTEGER NOT NULL,
  constant_liar INTEGER NOT NULL,
  pruner TEXT NOT NULL CHECK (pruner IN ('none', 'median', 'successive_halving')),
  median_percentile REAL NOT NULL,
  median_startup_trials INTEGER NOT NULL,
  median_warmup_steps INTEGER NOT NULL,
  median_interval_steps INTEGER NOT NULL,
  median_min_trials INTEGER NOT NULL,
  halving_min_resource INTEGER,
  halving_reduction_factor INTEGER NOT NULL,
  halving_min_early_stopping_rate INTEGER NOT NULL,
  halving_bootstrap_count INTEGER NOT NULL,
  created_at INTEGER NOT NULL
);
CREATE TABLE study_trials (
  study INTEGER NOT NULL REFERENCES studies(number),
  number INTEGER NOT NULL,
  request_id TEXT NOT NULL,
  state TEXT NOT NULL CHECK (state IN ('running', 'complete', 'pruned', 'failed')),
  value REAL,
  created_at INTEGER NOT NULL,
  finished_at INTEGER,
  PRIMARY KEY (study, number),
  UNIQUE (study, request_id)
);
CREATE TABLE study_trial_values (
  study INTEGER NOT NULL,
  trial INTEGER NOT NULL,
  name TEXT NOT NULL,
  value REAL NOT NULL,
  PRIMARY KEY (study, trial, name),
  FOREIGN KEY (study, trial) REFERENCES study_trials(study, number)
);
CREATE TABLE study_trial_rungs (
  study INTEGER NOT NULL,
  trial INTEGER NOT NULL,
  rung INTEGER NOT NULL,
  value REAL NOT NULL,
  PRIMARY KEY (study, trial, rung),
  FOREIGN KEY (study, trial) REFERENCES study_trials(study, number)
);
CREATE TABLE study_trial_reports (
  study INTEGER NOT NULL,
  trial INTEGER NOT NULL,
  step INTEGER NOT NULL,
  value REAL,
  PRIMARY KEY (study, trial, step),
  FOREIGN KEY (study, trial) REFERENCES study_trials(study, number)
);
)sql",
    // 4 -> 5: study sweeps. A sweep may drive a study (its trials are the study's, added as the
    // study asks for them, and its best ones again with more seeds): `open` while it will add
    // trials; each trial names the study trial it trains and whether it is a retrain.
    R"sql(
ALTER TABLE sweeps ADD COLUMN open INTEGER NOT NULL DEFAULT 0;
ALTER TABLE studies ADD COLUMN sweep INTEGER REFERENCES sweeps(number);
CREATE UNIQUE INDEX studies_by_sweep ON studies(sweep) WHERE sweep IS NOT NULL;
ALTER TABLE trials ADD COLUMN study_trial INTEGER;
ALTER TABLE trials ADD COLUMN retrain INTEGER NOT NULL DEFAULT 0;
CREATE UNIQUE INDEX trials_by_study_trial ON trials(sweep, study_trial, retrain)
  WHERE study_trial IS NOT NULL;
)sql",
    // 5 -> 6: grid evaluations (`dcs eval --on-actors`): a client's policy of a run over a grid
    // of contexts. Each is an evaluation of the run whose contexts are the grid's cells, under a
    // negative policy version of its own (a learner's are never negative), so that its jobs are
    // leased, reported and read as any evaluation's; this row says what makes it a grid: the
    // request that made it and the grid (axes and seed, serialised by the caller).
    R"sql(
CREATE TABLE grid_evaluations (
  run INTEGER NOT NULL,
  policy_version INTEGER NOT NULL CHECK (policy_version < 0),
  request_id TEXT NOT NULL UNIQUE,
  grid BLOB NOT NULL,
  PRIMARY KEY (run, policy_version),
  FOREIGN KEY (run, policy_version) REFERENCES evaluations(run, policy_version)
);
)sql",
    // 6 -> 7: what metrics read at each scrape (coordinator/store_counts.h): each run's latest
    // evaluation (its step, avg_combined and split means) and its best (highest avg_combined)
    // as its checkpoints brought them, when its lease was granted, and runs by state.
    R"sql(
ALTER TABLE runs ADD COLUMN latest_evaluation_step INTEGER;
ALTER TABLE runs ADD COLUMN latest_avg_combined REAL;
ALTER TABLE runs ADD COLUMN latest_id_return REAL;
ALTER TABLE runs ADD COLUMN latest_ood_low_return REAL;
ALTER TABLE runs ADD COLUMN latest_ood_high_return REAL;
ALTER TABLE runs ADD COLUMN best_evaluation_step INTEGER;
ALTER TABLE runs ADD COLUMN best_avg_combined REAL;
ALTER TABLE leases ADD COLUMN granted_at INTEGER NOT NULL DEFAULT 0;
CREATE INDEX runs_by_state ON runs(state);
)sql",
};

int UserVersion(SQLite::Database& db) {
  return db.execAndGet("PRAGMA user_version").getInt();
}

}  // namespace

int CurrentSchemaVersion() { return static_cast<int>(std::size(kMigrations)); }

absl::Status MigrateSchema(SQLite::Database& db, int target) {
  const int found = UserVersion(db);
  if (found < 0) {
    return absl::DataLossError(absl::StrCat(db.getFilename(), " is corrupt: schema version ",
                                            found, " (no DCS writes a negative one)"));
  }
  if (found > CurrentSchemaVersion()) {
    return absl::FailedPreconditionError(absl::StrCat(
        db.getFilename(), " has schema version ", found, "; this DCS knows versions up to ",
        CurrentSchemaVersion(), " (the database was written by a newer DCS)"));
  }
  for (int version = found; version < std::min(target, CurrentSchemaVersion()); ++version) {
    db.exec("BEGIN IMMEDIATE");
    try {
      db.exec(kMigrations[version]);
      db.exec(absl::StrCat("PRAGMA user_version = ", version + 1));
      db.exec("COMMIT");
    } catch (...) {
      db.exec("ROLLBACK");
      throw;
    }
  }
  return absl::OkStatus();
}

}  // namespace dcs::coordinator
