// Copyright 2026 The DCS Authors.
#include "coordinator/parzen_estimator.h"

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "coordinator/truncated_normal.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::coordinator {
namespace {

using google::protobuf::ListValue;
using google::protobuf::Struct;
using google::protobuf::Value;

// tests/coordinator/data/parzen_vectors.json: Optuna 4.9.0's Parzen
// estimators, fitted to below and above observations, and their densities at 24 candidates.
Struct LoadVectors() {
  std::ifstream file(DCS_TEST_DATA_DIR "/parzen_vectors.json");
  std::stringstream text;
  text << file.rdbuf();
  Struct vectors;
  EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(text.str(), &vectors).ok());
  return vectors;
}

std::vector<double> Numbers(const Value& list) {
  std::vector<double> numbers;
  for (const Value& v : list.list_value().values()) numbers.push_back(v.number_value());
  return numbers;
}

run::SearchParameter Parameter(const std::string& name, const Struct& spec) {
  const auto& f = spec.fields();
  run::SearchParameter parameter{.name = name};
  const std::string type = f.at("type").string_value();
  if (type == "categorical") {
    const int n = static_cast<int>(f.at("n_choices").number_value());
    run::CategoricalDistribution choices;
    for (int i = 0; i < n; ++i) choices.choices.push_back(std::to_string(i));
    parameter.distribution = choices;
  } else if (type == "int") {
    parameter.distribution =
        run::IntDistribution{.low = static_cast<int64_t>(f.at("low").number_value()),
                             .high = static_cast<int64_t>(f.at("high").number_value()),
                             .log = f.at("log").bool_value(),
                             .step = static_cast<int64_t>(f.at("step").number_value())};
  } else {
    run::FloatDistribution d{.low = f.at("low").number_value(),
                             .high = f.at("high").number_value(),
                             .log = f.at("log").bool_value()};
    if (f.at("step").has_number_value()) d.step = f.at("step").number_value();
    parameter.distribution = d;
  }
  return parameter;
}

// Rows of the named parameters' values from {name: [values]}.
std::vector<std::vector<double>> Rows(const Struct& columns,
                                      const std::vector<std::string>& names) {
  std::vector<std::vector<double>> rows;
  for (size_t p = 0; p < names.size(); ++p) {
    const std::vector<double> column = Numbers(columns.fields().at(names[p]));
    rows.resize(column.size(), std::vector<double>(names.size()));
    for (size_t i = 0; i < column.size(); ++i) rows[i][p] = column[i];
  }
  return rows;
}

// The columns of the named parameters' values from {name: [values]}.
std::vector<std::vector<double>> Columns(const Struct& columns,
                                         const std::vector<std::string>& names) {
  std::vector<std::vector<double>> result;
  for (const std::string& name : names) result.push_back(Numbers(columns.fields().at(name)));
  return result;
}

void ExpectNear(const std::vector<double>& actual, const std::vector<double>& expected,
                double relative, const std::string& what) {
  ASSERT_EQ(actual.size(), expected.size()) << what;
  for (size_t i = 0; i < actual.size(); ++i) {
    EXPECT_NEAR(actual[i], expected[i], relative * std::max(1.0, std::abs(expected[i])))
        << what << "[" << i << "]";
  }
}

// Kernels as (centre, bandwidth) pairs in centre order. Which of several equal centres gets which
// bandwidth is a tie: Optuna breaks it by numpy's argsort, which is not stable, DCS by trial order;
// the pairs are the same either way.
std::vector<std::pair<double, double>> Kernels(const std::vector<double>& mu,
                                               const std::vector<double>& sigma) {
  std::vector<std::pair<double, double>> kernels;
  for (size_t k = 0; k < mu.size(); ++k) kernels.emplace_back(mu[k], sigma[k]);
  std::sort(kernels.begin(), kernels.end());
  return kernels;
}

void ExpectMixture(const ParzenEstimator& estimator, const Struct& mixture,
                   const std::vector<std::string>& names, const std::string& what) {
  ExpectNear(estimator.weights(), Numbers(mixture.fields().at("weights")), 1e-12,
             what + " weights");
  for (size_t p = 0; p < names.size(); ++p) {
    const Struct& dim =
        mixture.fields().at("dims").struct_value().fields().at(names[p]).struct_value();
    const ParzenDimension& d = estimator.dimensions()[p];
    if (dim.fields().contains("prob_rows")) {
      const auto& rows = dim.fields().at("prob_rows").list_value().values();
      ASSERT_EQ(d.probabilities.size(), static_cast<size_t>(rows.size())) << what;
      for (int k = 0; k < rows.size(); ++k) {
        ExpectNear(d.probabilities[k], Numbers(rows[k]), 1e-12, what + " " + names[p] + " row");
      }
      continue;
    }
    const auto actual = Kernels(d.mu, d.sigma);
    const auto expected =
        Kernels(Numbers(dim.fields().at("mu_transformed")), Numbers(dim.fields().at("sigma")));
    ASSERT_EQ(actual.size(), expected.size()) << what;
    for (size_t k = 0; k < actual.size(); ++k) {
      EXPECT_NEAR(actual[k].first, expected[k].first, 1e-12) << what << " " << names[p];
      EXPECT_NEAR(actual[k].second, expected[k].second, 1e-12) << what << " " << names[p];
    }
  }
}

// The reference's own mixture, kernel by kernel, laid out as `fitted`.
ParzenEstimator ReferenceMixture(const ParzenEstimator& fitted, const Struct& mixture,
                                 const std::vector<std::string>& names) {
  std::vector<ParzenDimension> dimensions = fitted.dimensions();
  for (size_t p = 0; p < names.size(); ++p) {
    const Struct& dim =
        mixture.fields().at("dims").struct_value().fields().at(names[p]).struct_value();
    if (dim.fields().contains("prob_rows")) continue;
    dimensions[p].mu = Numbers(dim.fields().at("mu_transformed"));
    dimensions[p].sigma = Numbers(dim.fields().at("sigma"));
  }
  return ParzenEstimator::FromKernels(Numbers(mixture.fields().at("weights")),
                                      std::move(dimensions));
}

// Whether some equal observations carry different weights (25 or more observations, so the oldest
// are ramped down): then the tie above changes the mixture.
bool TiesChangeWeights(const std::vector<std::vector<double>>& rows) {
  if (rows.size() < 25) return false;
  std::vector<std::vector<double>> sorted = rows;
  std::sort(sorted.begin(), sorted.end());
  return std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
}

TEST(ParzenEstimatorTest, MatchesOptunasMixturesAndDensitiesOnTheReferenceVectors) {
  const Struct vectors = LoadVectors();
  const auto& cases = vectors.fields().at("cases").list_value().values();
  ASSERT_EQ(cases.size(), 10);
  for (const Value& entry : cases) {
    const auto& c = entry.struct_value().fields();
    const std::string name = c.at("name").string_value();
    SCOPED_TRACE(name);
    std::vector<std::string> names;
    std::vector<run::SearchParameter> parameters;
    for (const auto& [key, spec] : c.at("space").struct_value().fields()) {
      names.push_back(key);
      parameters.push_back(Parameter(key, spec.struct_value()));
    }
    std::vector<const run::SearchParameter*> space;
    for (const run::SearchParameter& p : parameters) space.push_back(&p);
    const ParzenOptions options{.multivariate = c.at("multivariate").bool_value()};
    const auto below_rows = Rows(c.at("below_obs").struct_value(), names);
    const auto above_rows = Rows(c.at("above_obs").struct_value(), names);
    const ParzenEstimator below(space, Columns(c.at("below_obs").struct_value(), names), options);
    const ParzenEstimator above(space, Columns(c.at("above_obs").struct_value(), names), options);
    ExpectMixture(below, c.at("l_mixture").struct_value(), names, "l");
    ExpectMixture(above, c.at("g_mixture").struct_value(), names, "g");

    const std::vector<std::vector<double>> candidates =
        Rows(c.at("candidates").struct_value(), names);
    const std::vector<double> log_l = below.LogPdf(candidates);
    const std::vector<double> log_g = above.LogPdf(candidates);
    // Densities to the spec's 1e-9: of the reference's kernels always, and of the fitted ones
    // wherever the tie above leaves the mixture alone (everywhere but the integer and grid cases,
    // whose 27 "above" observations repeat values under ramped weights).
    const std::vector<double> expected_l = Numbers(c.at("log_l"));
    const std::vector<double> expected_g = Numbers(c.at("log_g"));
    const auto l_mixture = c.at("l_mixture").struct_value();
    const auto g_mixture = c.at("g_mixture").struct_value();
    ExpectNear(ReferenceMixture(below, l_mixture, names).LogPdf(candidates), expected_l, 1e-9,
               "log_l of the reference kernels");
    ExpectNear(ReferenceMixture(above, g_mixture, names).LogPdf(candidates), expected_g, 1e-9,
               "log_g of the reference kernels");
    if (!TiesChangeWeights(below_rows)) ExpectNear(log_l, expected_l, 1e-9, "log_l");
    if (!TiesChangeWeights(above_rows)) ExpectNear(log_g, expected_g, 1e-9, "log_g");
    if (TiesChangeWeights(below_rows) || TiesChangeWeights(above_rows)) continue;
    std::vector<double> score(log_l.size());
    for (size_t i = 0; i < score.size(); ++i) score[i] = log_l[i] - log_g[i];
    EXPECT_EQ(std::max_element(score.begin(), score.end()) - score.begin(),
              static_cast<long>(c.at("argmax").number_value()));
  }
}

TEST(DefaultWeightsTest, RampsTheOldestBeyondTwentyFive) {
  EXPECT_THAT(DefaultWeights(0), ::testing::IsEmpty());
  EXPECT_THAT(DefaultWeights(3), ::testing::ElementsAre(1.0, 1.0, 1.0));
  const std::vector<double> w = DefaultWeights(28);
  ASSERT_EQ(w.size(), 28u);
  EXPECT_DOUBLE_EQ(w[0], 1.0 / 28);
  EXPECT_DOUBLE_EQ(w[1], 1.0 / 28 + (1 - 1.0 / 28) / 2);
  EXPECT_DOUBLE_EQ(w[2], 1.0);
  EXPECT_DOUBLE_EQ(w[27], 1.0);
}

// Draws follow the mixture LogPdf describes: the share of 40,000 draws in each of 10 cells of a
// log-uniform range, against the mixture's integral over the cell.
TEST(ParzenEstimatorTest, DrawsFollowTheMixtureTheyScore) {
  const run::SearchParameter period{
      .name = "period",
      .distribution = run::FloatDistribution{.low = 10, .high = 500, .log = true}};
  const ParzenEstimator estimator({&period}, {{20.0, 25.0, 300.0}}, ParzenOptions{});
  Random random(7);
  const auto draws = estimator.Sample(random, 40000);
  const double low = std::log(10.0);
  const double width = (std::log(500.0) - low) / 10;
  std::vector<double> share(10, 0.0);
  for (const auto& draw : draws) {
    ASSERT_GE(draw[0], 10.0);
    ASSERT_LE(draw[0], 500.0);
    share[std::min(9, static_cast<int>((std::log(draw[0]) - low) / width))] += 1.0 / draws.size();
  }
  for (int cell = 0; cell < 10; ++cell) {
    // The density is in ln(period): integrate it over the cell by the midpoint rule.
    double mass = 0;
    constexpr int kPoints = 200;
    for (int i = 0; i < kPoints; ++i) {
      const double x = low + width * (cell + (i + 0.5) / kPoints);
      mass += std::exp(estimator.LogPdf({{std::exp(x)}})[0]) * width / kPoints;
    }
    EXPECT_NEAR(share[cell], mass, 0.01) << "cell " << cell;
  }
}

TEST(ParzenEstimatorTest, DiscreteDrawsLandOnTheGridInsideTheBounds) {
  const run::SearchParameter steps{
      .name = "s", .distribution = run::FloatDistribution{.low = 0, .high = 5, .step = 0.5}};
  const run::SearchParameter count{
      .name = "j", .distribution = run::IntDistribution{.low = 1, .high = 1000, .log = true}};
  const ParzenEstimator estimator({&steps, &count}, {{0.0, 5.0, 2.5}, {1.0, 1000.0, 30.0}},
                                  ParzenOptions{.multivariate = true});
  Random random(3);
  for (const auto& draw : estimator.Sample(random, 2000)) {
    EXPECT_TRUE(run::Contains(steps.distribution, draw[0])) << draw[0];
    EXPECT_TRUE(run::Contains(count.distribution, draw[1])) << draw[1];
  }
}

TEST(TruncatedNormalTest, LogCdfIsAccurateInBothTails) {
  EXPECT_NEAR(LogNormalCdf(0), std::log(0.5), 1e-15);
  // ln Φ(-30) and ln Φ(-40) (mpmath): where Φ itself is 4.9e-198 and 3.6e-350 (underflow).
  EXPECT_NEAR(LogNormalCdf(-30), -454.3212439563432, 1e-9);
  EXPECT_NEAR(LogNormalCdf(-40), -804.6084420137538, 1e-9);
  EXPECT_NEAR(LogNormalCdf(8), -6.220960574271784e-16, 1e-28);
}

// Interval masses against mpmath at 60 digits: narrow ones (summed as a Hermite series), wide
// ones (from the normal CDFs), in the middle and far in both tails.
TEST(TruncatedNormalTest, MassesOfNarrowAndWideIntervalsAreAccurate) {
  const struct {
    double a, b, log_mass;
  } cases[] = {
      {0.1, 0.3, -2.5499754246125898808},   {-2, -1.9, -5.1216068777570823534},
      {3, 3.01, -10.039087761156880471},    {-30, -29.99, -455.37037945483563641},
      {0.5, 2.5, -1.1962431770139122147},   {-1, 1, -0.38171514630212607227},
      {-0.2, 1.8, -0.61003953094415684545}, {-40, -39.9, -800.62947416012146008},
      {12, 12.5, -75.412776310697438372},   {-3, -2.999999, -19.234447591028960336},
  };
  for (const auto& c : cases) {
    EXPECT_NEAR(LogNormalMass(c.a, c.b), c.log_mass, 2e-15 * std::max(1.0, std::abs(c.log_mass)))
        << "[" << c.a << ", " << c.b << "]";
  }
}

TEST(TruncatedNormalTest, QuantilesInvertTheCdfInsideTheInterval) {
  for (const auto& [a, b] :
       std::vector<std::pair<double, double>>{{-1, 1}, {2, 3}, {-40, -35}, {35, 40}, {-0.5, 30}}) {
    const double mass = LogNormalMass(a, b);
    for (const double q : {0.001, 0.25, 0.5, 0.9, 0.999}) {
      const double x = TruncatedNormalQuantile(q, a, b);
      ASSERT_GE(x, a);
      ASSERT_LE(x, b);
      // The mass of [a, x] is q of the mass of [a, b].
      EXPECT_NEAR(std::exp(LogNormalMass(a, x) - mass), q, 1e-9) << a << " " << b << " " << q;
    }
  }
}

}  // namespace
}  // namespace dcs::coordinator
