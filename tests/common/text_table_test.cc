// Copyright 2026 The DCS Authors.
#include "common/text_table.h"

#include <string>
#include <vector>

#include "gtest/gtest.h"

namespace dcs {
namespace {

TEST(RenderTableTest, AlignsColumnsTwoSpacesApart) {
  const std::string table = RenderTable({{"ROLE", "ID", "ADDRESS"},
                                         {"learner", "learner-1", "127.0.0.1:5"},
                                         {"actor", "actor-10", "10.0.0.1:50051"}});
  EXPECT_EQ(table,
            "ROLE     ID         ADDRESS\n"
            "learner  learner-1  127.0.0.1:5\n"
            "actor    actor-10   10.0.0.1:50051\n");
}

TEST(RenderTableTest, NoTrailingSpacesAfterLastColumn) {
  const std::string table = RenderTable({{"A", "LONG HEADER"}, {"xyz", "b"}});
  EXPECT_EQ(table,
            "A    LONG HEADER\n"
            "xyz  b\n");
}

TEST(RenderTableTest, ShortRowsAndEmptyCells) {
  const std::string table = RenderTable({{"A", "B", "C"}, {"", "bb"}, {"a"}});
  EXPECT_EQ(table,
            "A  B   C\n"
            "   bb\n"
            "a\n");
}

TEST(RenderTableTest, EmptyTableIsEmpty) { EXPECT_EQ(RenderTable({}), ""); }

TEST(RenderTableTest, PadsLeftAndRightAlignedColumns) {
  EXPECT_EQ(RenderTable({{"NAME", "N", "NOTE"}, {"long name", "1", "a"}, {"x", "123", ""}},
                               {false, true, false}),
            "NAME         N  NOTE\n"
            "long name    1  a\n"
            "x          123\n");
}

TEST(RenderTableTest, ShortRowsAndMissingAlignmentsAreLeftAligned) {
  EXPECT_EQ(RenderTable({{"A", "B"}, {"ccc"}}, {}), "A    B\nccc\n");
  EXPECT_EQ(RenderTable({}, {}), "");
}

}  // namespace
}  // namespace dcs
