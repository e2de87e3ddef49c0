// Copyright 2026 The DCS Authors.
#include "services/port_file.h"

#include <unistd.h>

#include <optional>
#include <string>

#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/testing/temp_dir.h"

namespace dcs::services {
namespace {

using ::testing::HasSubstr;

using PortFileTest = dcs::testing::TempDirTest;

TEST_F(PortFileTest, RoundTrips) {
  const std::string path = Path("coordinator.ports");
  ASSERT_TRUE(WritePortFile(path, {.grpc = 41234, .metrics = 38811}).ok());
  const std::optional<BoundPorts> ports = ReadPortFile(path);
  ASSERT_TRUE(ports.has_value());
  EXPECT_EQ(ports->grpc, 41234);
  EXPECT_EQ(ports->metrics, 38811);
}

TEST_F(PortFileTest, RecordsThePid) {
  const std::string path = Path("coordinator.ports");
  ASSERT_TRUE(WritePortFile(path, {.grpc = 1, .metrics = 2}).ok());
  EXPECT_THAT(dcs::ReadFile(path).value_or(""),
              HasSubstr("pid: " + std::to_string(::getpid()) + "\n"));
}

TEST_F(PortFileTest, OverwritesPreviousPorts) {
  const std::string path = Path("coordinator.ports");
  ASSERT_TRUE(WritePortFile(path, {.grpc = 1000, .metrics = 2000}).ok());
  ASSERT_TRUE(WritePortFile(path, {.grpc = 3000, .metrics = 4000}).ok());
  const std::optional<BoundPorts> ports = ReadPortFile(path);
  ASSERT_TRUE(ports.has_value());
  EXPECT_EQ(ports->grpc, 3000);
  EXPECT_EQ(ports->metrics, 4000);
}

TEST_F(PortFileTest, MissingFileIsNullopt) {
  EXPECT_EQ(ReadPortFile(Path("absent.ports")), std::nullopt);
}

TEST_F(PortFileTest, WriteIntoMissingDirectoryFails) {
  EXPECT_EQ(WritePortFile(Path("no/such/dir.ports"), {.grpc = 1, .metrics = 2}).code(),
            absl::StatusCode::kNotFound);
}

TEST_F(PortFileTest, GarbageIsNullopt) {
  const struct {
    const char* name;
    const char* contents;
  } kCases[] = {
      {"empty", ""},
      {"scalar", "garbage"},
      {"broken_yaml", "grpc_port: [1, 2\n"},
      {"list", "- 1\n- 2\n"},
      {"missing_metrics", "grpc_port: 41234\n"},
      {"not_a_number", "grpc_port: many\nmetrics_port: 2\n"},
      {"binary", "\x01\x02\xff\xfe"},
  };
  for (const auto& [name, contents] : kCases) {
    WritePlain(name, contents);
    EXPECT_EQ(ReadPortFile(Path(name)), std::nullopt) << name;
  }
}

}  // namespace
}  // namespace dcs::services
