// Copyright 2026 The DCS Authors.
#include "services/did_you_mean.h"

#include <optional>
#include <string>
#include <vector>

#include "gtest/gtest.h"

namespace dcs::services {
namespace {

TEST(EditDistanceTest, CountsInsertionsDeletionsReplacementsAndSwaps) {
  EXPECT_EQ(EditDistance("status", "status"), 0);
  EXPECT_EQ(EditDistance("statsu", "status"), 1);  // a swap
  EXPECT_EQ(EditDistance("--adr", "--addr"), 1);
  EXPECT_EQ(EditDistance("lenght", "length"), 1);
  EXPECT_EQ(EditDistance("cancle", "cancel"), 1);
  EXPECT_EQ(EditDistance("", "abc"), 3);
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3);
}

TEST(ClosestNameTest, SuggestsOnlyASlip) {
  const std::vector<std::string> commands = {"status", "sweeps", "submit"};
  EXPECT_EQ(ClosestName("statsu", commands), "status");
  EXPECT_EQ(ClosestName("sweep", commands), "sweeps");
  EXPECT_EQ(ClosestName("xyzzy", commands), std::nullopt);
  EXPECT_EQ(ClosestName("st", commands), std::nullopt);  // 4 edits from each
  EXPECT_EQ(ClosestName("up", {"ui", "un"}), std::nullopt);  // half of a short word
}

// A program as `dcs` is built: a global flag, commands, one with its own subcommands, one with
// an argument.
class UnknownNameErrorTest : public ::testing::Test {
 protected:
  UnknownNameErrorTest() {
    program_.add_option("--addr", addr_);
    program_.fallthrough();
    CLI::App* runs = program_.add_subcommand("runs");
    runs->add_subcommand("cancel")->add_option("run", value_);
    CLI::App* tell = program_.add_subcommand("tell");
    tell->add_option("value", value_);
    tell->add_flag("--quiet");
  }

  CLI::App program_{"test", "dcs"};
  std::string addr_;
  std::string value_;
};

TEST_F(UnknownNameErrorTest, NamesTheUnknownFlagOrCommandAndTheClosestKnownOne) {
  EXPECT_EQ(UnknownNameError(program_, {"runs", "cancle", "run-1"}),
            "unknown command 'cancle' for `dcs runs`; did you mean cancel?");
  EXPECT_EQ(UnknownNameError(program_, {"tell", "1", "--adr", "x"}),
            "unknown flag --adr for `dcs tell`; did you mean --addr?");
  EXPECT_EQ(UnknownNameError(program_, {"--addr", "x", "tell", "--quiet", "--nothing"}),
            "unknown flag --nothing for `dcs tell`");
}

TEST_F(UnknownNameErrorTest, KnowsValuesArgumentsAndNegativeNumbers) {
  // "runs" is --addr's value, not a command; "-0.5" is tell's argument.
  EXPECT_EQ(UnknownNameError(program_, {"--addr", "runs", "tell", "-0.5", "--quiet"}),
            std::nullopt);
  EXPECT_EQ(UnknownNameError(program_, {"--addr=x", "runs", "cancel", "run-1"}), std::nullopt);
}

}  // namespace
}  // namespace dcs::services
