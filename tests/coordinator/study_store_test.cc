// Copyright 2026 The DCS Authors.
//
// The store's studies (coordinator/study_table.h) on a real SQLite file.

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <SQLiteCpp/Database.h>

#include "absl/status/status.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/time/time.h"
#include "coordinator/store.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/testing/temp_dir.h"

namespace dcs::coordinator {
namespace {

using ::testing::Each;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Pair;

const absl::Time kStart = absl::FromUnixSeconds(1'800'000'000);

constexpr char kSpace[] = R"(
parameters:
  - {name: x, type: float, low: 0, high: 1}
  - {name: mode, type: categorical, choices: [a, b]}
  - {name: k, type: int, low: 1, high: 9, when: {mode: b}}
)";

StudySubmission Study(std::string request_id, SamplerKind sampler = SamplerKind::kTpe) {
  return {.request_id = std::move(request_id),
          .name = "toy",
          .space = kSpace,
          .sampler = sampler,
          .seed = 4,
          .direction = Direction::kMinimize,
          .tpe = {.startup_trials = 3}};
}

// A request id no other ask of the test uses.
std::string NextAsk() {
  static int asks = 0;
  return absl::StrCat("ask-", ++asks);
}

int64_t CountIn(const StudyRecord& study, TrialState wanted) {
  for (const auto& [state, trials] : study.trials_by_state) {
    if (state == wanted) return trials;
  }
  return -1;
}

class StudyStoreTest : public testing::TempDirTest {
 protected:
  std::unique_ptr<Store> Open(const std::string& file = "coordinator.db") {
    absl::StatusOr<std::unique_ptr<Store>> store = Store::Open(Path(file), StoreOptions{}, kStart);
    EXPECT_TRUE(store.ok()) << store.status();
    return std::move(*store);
  }
};

// Asks `count` trials, telling each x² (x its parameter); returns their values.
std::vector<run::ParameterValues> AskAndTell(Store& store, const std::string& study, int count) {
  std::vector<run::ParameterValues> asked;
  for (int i = 0; i < count; ++i) {
    absl::StatusOr<StudyTrial> trial = store.studies().AskTrial(study, NextAsk(), kStart);
    EXPECT_TRUE(trial.ok()) << trial.status();
    asked.push_back(trial->values);
    const double x = trial->values.at("x");
    EXPECT_TRUE(
        store.studies().TellTrial(study, trial->number, TrialState::kComplete, x * x, kStart).ok());
  }
  return asked;
}

TEST_F(StudyStoreTest, AskTellAndBestAsOptunas) {
  std::unique_ptr<Store> store = Open();
  absl::StatusOr<StudyRecord> study = store->studies().CreateStudy(Study("r1"), kStart);
  ASSERT_TRUE(study.ok()) << study.status();
  EXPECT_EQ(study->id, "study-1");
  EXPECT_FALSE(study->best.has_value());
  AskAndTell(*store, study->id, 12);

  study = store->studies().GetStudy(study->id);
  EXPECT_EQ(CountIn(*study, TrialState::kComplete), 12);
  ASSERT_TRUE(study->best.has_value());
  const absl::StatusOr<std::vector<StudyTrial>> trials =
      store->studies().ListStudyTrials(study->id);
  ASSERT_EQ(trials->size(), 12u);
  for (size_t i = 0; i < trials->size(); ++i) {
    const StudyTrial& trial = (*trials)[i];
    EXPECT_EQ(trial.number, static_cast<int64_t>(i));
    EXPECT_EQ(trial.values.contains("k"), trial.values.at("mode") == 1);
    EXPECT_LE(study->best->value, trial.value);
  }
  // A repeated request returns the study it made.
  EXPECT_EQ(store->studies().CreateStudy(Study("r1"), kStart)->id, "study-1");
  EXPECT_EQ(store->studies().CreateStudy(Study("r2"), kStart)->id, "study-2");
}

// The sampler keeps nothing between trials: a store reopened (a coordinator restarted) asks the
// same trials as one that never closed.
TEST_F(StudyStoreTest, AReopenedStoreAsksWhatTheFirstWouldHave) {
  std::vector<run::ParameterValues> uninterrupted;
  {
    std::unique_ptr<Store> store = Open();
    const std::string study = store->studies().CreateStudy(Study("same"), kStart)->id;
    uninterrupted = AskAndTell(*store, study, 15);
  }
  std::vector<run::ParameterValues> reopened;
  {
    std::unique_ptr<Store> store = Open("reopened.db");
    const std::string study = store->studies().CreateStudy(Study("same"), kStart)->id;
    reopened = AskAndTell(*store, study, 8);
  }
  std::unique_ptr<Store> store = Open("reopened.db");
  const std::vector<run::ParameterValues> rest = AskAndTell(*store, "study-1", 7);
  reopened.insert(reopened.end(), rest.begin(), rest.end());
  EXPECT_EQ(reopened, uninterrupted);
}

// A retried ask (its response lost) gets the trial the first made, not a second one.
TEST_F(StudyStoreTest, ARepeatedAskReturnsTheTrialItMade) {
  std::unique_ptr<Store> store = Open();
  const std::string study = store->studies().CreateStudy(Study("r"), kStart)->id;
  const absl::StatusOr<StudyTrial> first = store->studies().AskTrial(study, "same", kStart);
  const absl::StatusOr<StudyTrial> again = store->studies().AskTrial(study, "same", kStart);
  ASSERT_TRUE(first.ok() && again.ok());
  EXPECT_EQ(again->number, first->number);
  EXPECT_EQ(again->values, first->values);
  EXPECT_EQ(store->studies().ListStudyTrials(study)->size(), 1u);
  EXPECT_EQ(store->studies().AskTrial(study, "", kStart).status().code(),
            absl::StatusCode::kInvalidArgument);
}

TEST_F(StudyStoreTest, TellRefusesFinishedTrialsAndFailsNaN) {
  std::unique_ptr<Store> store = Open();
  const std::string study = store->studies().CreateStudy(Study("r"), kStart)->id;
  const int64_t first = store->studies().AskTrial(study, NextAsk(), kStart)->number;
  const int64_t second = store->studies().AskTrial(study, NextAsk(), kStart)->number;
  EXPECT_EQ(second, first + 1);

  const absl::StatusOr<StudyTrial> nan = store->studies().TellTrial(
      study, first, TrialState::kComplete, std::numeric_limits<double>::quiet_NaN(), kStart);
  ASSERT_TRUE(nan.ok()) << nan.status();
  EXPECT_EQ(nan->state, TrialState::kFailed);

  const absl::StatusOr<StudyTrial> again =
      store->studies().TellTrial(study, first, TrialState::kComplete, 1.0, kStart);
  EXPECT_EQ(again.status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(again.status().message(), HasSubstr("it is failed"));
  // The same tell again (a retry) is answered as the first was.
  const absl::StatusOr<StudyTrial> retried = store->studies().TellTrial(
      study, first, TrialState::kComplete, std::numeric_limits<double>::quiet_NaN(), kStart);
  ASSERT_TRUE(retried.ok()) << retried.status();
  EXPECT_EQ(retried->state, TrialState::kFailed);
  EXPECT_EQ(
      store->studies().TellTrial(study, 99, TrialState::kComplete, 1.0, kStart).status().code(),
      absl::StatusCode::kNotFound);
  EXPECT_EQ(
      store->studies().TellTrial(study, second, TrialState::kRunning, 1.0, kStart).status().code(),
      absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(store->studies().AskTrial("study-7", NextAsk(), kStart).status().code(),
            absl::StatusCode::kNotFound);

  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(store->studies().TellTrial(study, second, TrialState::kComplete, inf, kStart)->value,
            inf);
  EXPECT_EQ(store->studies().GetStudy(study)->best->value, inf);  // ±inf is a value
}

TEST_F(StudyStoreTest, PrunedTrialsKeepTheirReportsAndLastValue) {
  std::unique_ptr<Store> store = Open();
  const std::string study = store->studies().CreateStudy(Study("r"), kStart)->id;
  const int64_t trial = store->studies().AskTrial(study, NextAsk(), kStart)->number;
  ASSERT_TRUE(store->studies().ReportTrial(study, trial, 1, 5.0).ok());
  ASSERT_TRUE(store->studies().ReportTrial(study, trial, 3, 4.0).ok());
  ASSERT_TRUE(
      store->studies().ReportTrial(study, trial, 3, 9.0).ok());  // a repeated step keeps the first
  const absl::StatusOr<StudyTrial> pruned =
      store->studies().TellTrial(study, trial, TrialState::kPruned, 0.0, kStart);
  ASSERT_TRUE(pruned.ok()) << pruned.status();
  EXPECT_EQ(pruned->value, 4.0);
  EXPECT_THAT(pruned->reported, ElementsAre(Pair(1, 5.0), Pair(3, 4.0)));
  EXPECT_EQ(store->studies().ReportTrial(study, trial, 4, 1.0).status().code(),
            absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT((*store->studies().ListStudyTrials(study))[0].reported,
              ElementsAre(Pair(1, 5.0), Pair(3, 4.0)));
}

// A study with the median pruner: once enough trials completed, a trial whose report is worse
// than theirs at the same step is to be stopped; without a pruner none is.
TEST_F(StudyStoreTest, TheStudysPrunerAnswersEachReport) {
  std::unique_ptr<Store> store = Open();
  StudySubmission with_pruner = Study("pruned");
  with_pruner.pruner = {.kind = PrunerKind::kMedian, .median = {.startup_trials = 2}};
  const std::string study = store->studies().CreateStudy(with_pruner, kStart)->id;
  const std::string plain = store->studies().CreateStudy(Study("plain"), kStart)->id;
  for (const std::string& id : {study, plain}) {
    for (const double value : {1.0, 2.0, 3.0}) {
      const int64_t trial = store->studies().AskTrial(id, NextAsk(), kStart)->number;
      ASSERT_TRUE(store->studies().ReportTrial(id, trial, 10, value).ok());
      ASSERT_TRUE(store->studies().TellTrial(id, trial, TrialState::kComplete, value, kStart).ok());
    }
  }
  EXPECT_EQ(store->studies().GetStudy(study)->submission.pruner.kind, PrunerKind::kMedian);
  const int64_t poor = store->studies().AskTrial(study, NextAsk(), kStart)->number;
  EXPECT_TRUE(*store->studies().ReportTrial(study, poor, 10, 2.5));  // worse than the median, 2
  const int64_t good = store->studies().AskTrial(study, NextAsk(), kStart)->number;
  EXPECT_FALSE(*store->studies().ReportTrial(study, good, 10, 1.5));
  const int64_t unpruned = store->studies().AskTrial(plain, NextAsk(), kStart)->number;
  EXPECT_FALSE(*store->studies().ReportTrial(plain, unpruned, 10, 9.0));
}

// Successive halving keeps each trial's rungs in the store: the second trial to reach rung 0
// with a worse value is stopped.
TEST_F(StudyStoreTest, SuccessiveHalvingRemembersTheRungs) {
  std::unique_ptr<Store> store = Open();
  StudySubmission halving = Study("halving");
  halving.pruner = {.kind = PrunerKind::kSuccessiveHalving,
                    .halving = {.min_resource = 1, .reduction_factor = 2}};
  const std::string study = store->studies().CreateStudy(halving, kStart)->id;
  const int64_t first = store->studies().AskTrial(study, NextAsk(), kStart)->number;
  EXPECT_FALSE(*store->studies().ReportTrial(study, first, 1, 1.0));
  const int64_t second = store->studies().AskTrial(study, NextAsk(), kStart)->number;
  EXPECT_TRUE(*store->studies().ReportTrial(study, second, 1, 2.0));
}

TEST_F(StudyStoreTest, BadStudiesAreRefusedAndStoreNothing) {
  std::unique_ptr<Store> store = Open();
  StudySubmission bad_space = Study("a");
  bad_space.space = "parameters: [{name: x, type: float, low: 2, high: 1}]";
  EXPECT_THAT(store->studies().CreateStudy(bad_space, kStart).status().message(),
              HasSubstr("parameter 'x': low 2 is above high 1"));
  StudySubmission bad_group = Study("b");
  bad_group.tpe.group = true;
  EXPECT_EQ(store->studies().CreateStudy(bad_group, kStart).status().code(),
            absl::StatusCode::kInvalidArgument);
  StudySubmission bad_pruner = Study("c");
  bad_pruner.pruner = {.kind = PrunerKind::kSuccessiveHalving, .halving = {.reduction_factor = 1}};
  EXPECT_THAT(store->studies().CreateStudy(bad_pruner, kStart).status().message(),
              HasSubstr("reduction_factor >= 2"));
  EXPECT_EQ(store->studies().CreateStudy(Study(""), kStart).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_TRUE(store->studies().ListStudies()->empty());
}

// Issue 14 (found by tests/fuzz/run_store_fuzzer): a study row damaged in the file (a space that
// no longer parses, a name outside its table, a value of a trial the study lacks) was read as
// INVALID_ARGUMENT (the caller's fault), dereferenced as an absent name, or threw out of the
// store (std::out_of_range, ending the coordinator). Each is DATA_LOSS naming the file.
class DamagedStudyTest : public StudyStoreTest {
 protected:
  // A store with study-1 and one told trial, changed by `sql` behind the store's back (with the
  // schema's checks off, as a damaged file escapes them); then every reader of the study.
  std::vector<absl::Status> ReadAfter(const std::string& sql) {
    const std::string file = absl::StrCat("damaged-", ++stores_, ".db");
    {
      std::unique_ptr<Store> store = Open(file);
      const std::string study = store->studies().CreateStudy(Study("r"), kStart)->id;
      AskAndTell(*store, study, 1);
    }
    {
      SQLite::Database db(Path(file), SQLite::OPEN_READWRITE);
      db.exec("PRAGMA ignore_check_constraints = ON");
      db.exec(sql);
    }
    std::unique_ptr<Store> store = Open(file);
    return {store->studies().GetStudy("study-1").status(), store->studies().ListStudies().status(),
            store->studies().ListStudyTrials("study-1").status()};
  }

 private:
  int stores_ = 0;
};

MATCHER_P(IsDataLossNaming, text, "") {
  return arg.code() == absl::StatusCode::kDataLoss &&
         absl::StrContains(arg.message(), ".db is corrupt") &&
         absl::StrContains(arg.message(), text);
}

TEST_F(DamagedStudyTest, ASpaceThatNoLongerParsesIsDataLoss) {
  EXPECT_THAT(ReadAfter("UPDATE studies SET space = 'parameters: [{name: x'"),
              Each(IsDataLossNaming("the search space of study-1 does not parse")));
}

TEST_F(DamagedStudyTest, ANameOutsideItsTableIsDataLoss) {
  EXPECT_THAT(ReadAfter("UPDATE studies SET sampler = 'tpx'"),
              Each(IsDataLossNaming("the sampler of study-1 is 'tpx'")));
  EXPECT_THAT(ReadAfter("UPDATE studies SET direction = 'up'"),
              Each(IsDataLossNaming("the direction of study-1 is 'up'")));
  EXPECT_THAT(ReadAfter("UPDATE studies SET pruner = 'hyper'"),
              Each(IsDataLossNaming("the pruner of study-1 is 'hyper'")));
  EXPECT_THAT(ReadAfter("UPDATE study_trials SET state = 'lost'"),
              Each(IsDataLossNaming("the state of trial 0 of study-1 is 'lost'")));
}

TEST_F(DamagedStudyTest, AValueOfATrialTheStudyLacksIsDataLoss) {
  EXPECT_THAT(ReadAfter("UPDATE study_trial_values SET trial = 7"),
              Each(IsDataLossNaming("study-1 has values of trial 7")));
}

}  // namespace
}  // namespace dcs::coordinator
