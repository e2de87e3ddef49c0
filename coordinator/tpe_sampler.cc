// Copyright 2026 The DCS Authors.
#include "coordinator/tpe_sampler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/str_cat.h"

namespace dcs::coordinator {
namespace {

bool IsFinished(const StudyTrial& trial) {
  return trial.state == TrialState::kComplete || trial.state == TrialState::kPruned;
}

// Each trial's values by the parameter's position in the space, NaN where it has none: read
// once per suggestion rather than by name for every parameter.
using ValueTable = absl::flat_hash_map<const StudyTrial*, std::vector<double>>;

ValueTable Tabulate(const run::SearchSpace& space, const std::vector<const StudyTrial*>& trials) {
  ValueTable table;
  for (const StudyTrial* trial : trials) {
    std::vector<double>& row = table[trial];
    row.assign(space.parameters.size(), std::numeric_limits<double>::quiet_NaN());
    for (size_t p = 0; p < space.parameters.size(); ++p) {
      const auto value = trial->values.find(space.parameters[p].name);
      if (value != trial->values.end()) row[p] = value->second;
    }
  }
  return table;
}

// The values at `positions` of the trials that have them all, in trial order: one column per
// position.
std::vector<std::vector<double>> Observations(const std::vector<const StudyTrial*>& trials,
                                              const std::vector<size_t>& positions,
                                              const ValueTable& table) {
  std::vector<std::vector<double>> columns(positions.size());
  for (const StudyTrial* trial : trials) {
    const std::vector<double>& values = table.at(trial);
    if (std::any_of(positions.begin(), positions.end(),
                    [&](size_t p) { return std::isnan(values[p]); })) {
      continue;
    }
    for (size_t i = 0; i < positions.size(); ++i) columns[i].push_back(values[positions[i]]);
  }
  return columns;
}

// The position of parameter `name` in the space. REQUIRES: the space has it.
size_t Position(const run::SearchSpace& space, const std::string& name) {
  return run::FindParameter(space, name) - space.parameters.data();
}

class TpeSampler : public Sampler {
 public:
  TpeSampler(uint64_t seed, Direction direction, const TpeOptions& options)
      : seed_(seed), direction_(direction), options_(options) {}

  run::ParameterValues Sample(const run::SearchSpace& space, const std::vector<StudyTrial>& trials,
                              int64_t number) const override {
    Random random(StreamSeed(seed_, "trial", {static_cast<uint64_t>(number)}));
    std::vector<const StudyTrial*> history;
    std::vector<const StudyTrial*> finished;
    for (const StudyTrial& trial : trials) {
      if (trial.number == number) continue;
      if (IsFinished(trial)) finished.push_back(&trial);
      if (IsFinished(trial) || (options_.constant_liar && trial.state == TrialState::kRunning)) {
        history.push_back(&trial);
      }
    }
    const auto by_number = [](const StudyTrial* a, const StudyTrial* b) {
      return a->number < b->number;
    };
    std::sort(history.begin(), history.end(), by_number);
    std::sort(finished.begin(), finished.end(), by_number);

    if (static_cast<int>(finished.size()) < options_.startup_trials) {
      return RandomValues(space, random);
    }
    const Split split = SplitTrials(history, Gamma(static_cast<int>(finished.size())), direction_);
    const ValueTable table = Tabulate(space, history);

    run::ParameterValues values;
    run::ParameterValues joint;
    if (options_.parzen.multivariate) {
      for (const std::vector<std::string>& names : JointGroups(space, finished)) {
        std::vector<size_t> group;
        for (const std::string& name : names) group.push_back(Position(space, name));
        const std::vector<double> drawn = SampleJointly(space, group, split, table, random);
        for (size_t i = 0; i < group.size(); ++i) joint[names[i]] = drawn[i];
      }
    }
    for (size_t p = 0; p < space.parameters.size(); ++p) {
      const run::SearchParameter& parameter = space.parameters[p];
      if (!run::IsActive(parameter, space, values)) continue;
      const auto drawn = joint.find(parameter.name);
      values[parameter.name] = drawn != joint.end() ? drawn->second
                               : run::IsSingleValued(parameter.distribution)
                                   ? RandomValue(parameter.distribution, random)
                                   : SampleJointly(space, {p}, split, table, random)[0];
    }
    return values;
  }

 private:
  // The parameters sampled jointly: those every finished trial has, or the groups of those that
  // occur together; single-valued ones left out.
  std::vector<std::vector<std::string>> JointGroups(
      const run::SearchSpace& space, const std::vector<const StudyTrial*>& finished) const {
    std::vector<std::vector<std::string>> groups;
    if (options_.group) {
      groups = GroupParameters(space, finished);
    } else {
      std::vector<std::string>& everywhere = groups.emplace_back();
      for (const run::SearchParameter& p : space.parameters) {
        if (std::all_of(finished.begin(), finished.end(),
                        [&](const StudyTrial* t) { return t->values.contains(p.name); })) {
          everywhere.push_back(p.name);
        }
      }
    }
    for (std::vector<std::string>& group : groups) {
      std::erase_if(group, [&](const std::string& name) {
        return run::IsSingleValued(space.parameters[Position(space, name)].distribution);
      });
    }
    std::erase_if(groups, [](const std::vector<std::string>& group) { return group.empty(); });
    return groups;
  }

  // Values for the parameters at `positions` by TPE: the first candidate from l(x) that
  // maximises l/g.
  std::vector<double> SampleJointly(const run::SearchSpace& space,
                                    const std::vector<size_t>& positions, const Split& split,
                                    const ValueTable& table, Random& random) const {
    std::vector<const run::SearchParameter*> parameters;
    for (const size_t p : positions) parameters.push_back(&space.parameters[p]);
    const ParzenEstimator below(parameters, Observations(split.below, positions, table),
                                options_.parzen);
    const ParzenEstimator above(parameters, Observations(split.above, positions, table),
                                options_.parzen);
    std::vector<std::vector<double>> candidates = below.Sample(random, options_.ei_candidates);
    const std::vector<double> log_l = below.LogPdf(candidates);
    const std::vector<double> log_g = above.LogPdf(candidates);
    size_t best = 0;
    for (size_t i = 1; i < candidates.size(); ++i) {
      if (log_l[i] - log_g[i] > log_l[best] - log_g[best]) best = i;
    }
    return std::move(candidates[best]);
  }

  uint64_t seed_;
  Direction direction_;
  TpeOptions options_;
};

}  // namespace

int Gamma(int n) { return std::min(static_cast<int>(std::ceil(0.1 * n)), 25); }

Split SplitTrials(const std::vector<const StudyTrial*>& history, int below, Direction direction) {
  const double sign = direction == Direction::kMinimize ? 1.0 : -1.0;
  std::vector<const StudyTrial*> complete;
  std::vector<const StudyTrial*> pruned;
  Split split;
  for (const StudyTrial* trial : history) {
    if (trial->state == TrialState::kComplete) complete.push_back(trial);
    if (trial->state == TrialState::kPruned) pruned.push_back(trial);
    if (trial->state == TrialState::kRunning) split.above.push_back(trial);
  }
  std::stable_sort(complete.begin(), complete.end(), [&](const StudyTrial* a, const StudyTrial* b) {
    return sign * a->value < sign * b->value;
  });
  // Deeper-pruned first, then better last value; none reported ranks last.
  const auto key = [&](const StudyTrial* t) {
    if (t->reported.empty()) return std::make_pair(int64_t{1}, 0.0);
    const auto& [step, value] = *t->reported.rbegin();
    return std::make_pair(
        -step, std::isnan(value) ? std::numeric_limits<double>::infinity() : sign * value);
  };
  std::stable_sort(pruned.begin(), pruned.end(),
                   [&](const StudyTrial* a, const StudyTrial* b) { return key(a) < key(b); });
  size_t places = static_cast<size_t>(std::max(below, 0));
  for (const std::vector<const StudyTrial*>* ranked : {&complete, &pruned}) {
    for (const StudyTrial* trial : *ranked) {
      if (places > 0) {
        split.below.push_back(trial);
        --places;
      } else {
        split.above.push_back(trial);
      }
    }
  }
  const auto by_number = [](const StudyTrial* a, const StudyTrial* b) {
    return a->number < b->number;
  };
  std::sort(split.below.begin(), split.below.end(), by_number);
  std::sort(split.above.begin(), split.above.end(), by_number);
  return split;
}

std::vector<std::vector<std::string>> GroupParameters(
    const run::SearchSpace& space, const std::vector<const StudyTrial*>& finished) {
  std::vector<std::set<std::string>> groups;
  for (const StudyTrial* trial : finished) {
    std::set<std::string> keys;
    for (const auto& [name, value] : trial->values) keys.insert(name);
    std::vector<std::set<std::string>> next;
    for (const std::set<std::string>& group : groups) {
      std::set<std::string> inside;
      std::set<std::string> outside;
      for (const std::string& name : group) (keys.contains(name) ? inside : outside).insert(name);
      for (const std::string& name : inside) keys.erase(name);
      if (!inside.empty()) next.push_back(std::move(inside));
      if (!outside.empty()) next.push_back(std::move(outside));
    }
    if (!keys.empty()) next.push_back(std::move(keys));
    groups = std::move(next);
  }
  std::vector<std::vector<std::string>> ordered;
  for (const std::set<std::string>& group : groups) {
    std::vector<std::string>& names = ordered.emplace_back();
    for (const run::SearchParameter& p : space.parameters) {
      if (group.contains(p.name)) names.push_back(p.name);
    }
  }
  std::erase_if(ordered, [](const std::vector<std::string>& names) { return names.empty(); });
  std::sort(ordered.begin(), ordered.end(), [&](const auto& a, const auto& b) {
    return Position(space, a.front()) < Position(space, b.front());
  });
  return ordered;
}

absl::Status ValidateTpeOptions(const TpeOptions& options) {
  if (options.startup_trials < 0 || options.ei_candidates < 1) {
    return absl::InvalidArgumentError(
        absl::StrCat("TPE needs startup_trials >= 0 and ei_candidates >= 1, got ",
                     options.startup_trials, " and ", options.ei_candidates));
  }
  if (options.group && !options.parzen.multivariate) {
    return absl::InvalidArgumentError("TPE's group option needs multivariate");
  }
  return absl::OkStatus();
}

std::unique_ptr<Sampler> MakeTpeSampler(uint64_t seed, Direction direction,
                                        const TpeOptions& options) {
  return std::make_unique<TpeSampler>(seed, direction, options);
}

}  // namespace dcs::coordinator
