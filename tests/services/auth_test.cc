// Copyright 2026 The DCS Authors.
#include "services/auth.h"

#include <stdlib.h>

#include <string>

#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/testing/temp_dir.h"

namespace dcs::services {
namespace {

using ::testing::HasSubstr;

constexpr char kToken[] = "0123456789abcdef0123456789abcdef";  // 32 characters

class LoadTokenTest : public testing::TempDirTest {
 protected:
  void TearDown() override { ::unsetenv(kTokenEnvironmentVariable); }

  std::string File(const std::string& contents) {
    const std::string path = Path("token");
    EXPECT_TRUE(WriteFileAtomically(path, contents, 0600).ok());
    return path;
  }
};

TEST_F(LoadTokenTest, ReadsAFileWithoutItsSurroundingWhitespace) {
  EXPECT_EQ(LoadToken(File(absl::StrCat("  ", kToken, "\n"))).value_or("?"), kToken);
}

TEST_F(LoadTokenTest, FallsBackToTheEnvironmentThenToNone) {
  EXPECT_EQ(LoadToken("").value_or("?"), "");
  ::setenv(kTokenEnvironmentVariable, kToken, 1);
  EXPECT_EQ(LoadToken("").value_or("?"), kToken);
  // A file wins over the environment.
  const std::string other(40, 'x');
  EXPECT_EQ(LoadToken(File(other)).value_or("?"), other);
}

TEST_F(LoadTokenTest, RefusesWeakOrUnprintableTokensNamingTheSource) {
  const std::string path = File("secret");
  absl::StatusOr<std::string> weak = LoadToken(path);
  EXPECT_EQ(weak.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(weak.status().message(), HasSubstr(path));
  EXPECT_THAT(weak.status().message(), HasSubstr("too short"));

  EXPECT_THAT(LoadToken(File(absl::StrCat(kToken, " ", kToken))).status().message(),
              HasSubstr("not printable ASCII"));
  ::setenv(kTokenEnvironmentVariable, "short", 1);
  EXPECT_THAT(LoadToken("").status().message(), HasSubstr("$DCS_TOKEN"));
  EXPECT_THAT(LoadToken(Path("missing")).status().message(), HasSubstr("missing"));
}

TEST_F(LoadTokenTest, TlsFilesComeAllThreeAsPem) {
  EXPECT_TRUE(CheckTlsFiles({}).ok());
  const std::string pem = Path("cert.pem");
  ASSERT_TRUE(
      WriteFileAtomically(pem, "-----BEGIN CERTIFICATE-----\nMII\n-----END CERTIFICATE-----\n")
          .ok());
  const std::string key = Path("key.pem");
  ASSERT_TRUE(WriteFileAtomically(key, "-----BEGIN PRIVATE KEY-----\nMII\n").ok());
  EXPECT_TRUE(CheckTlsFiles({.certificate = pem, .key = key, .ca = pem}).ok());
  EXPECT_THAT(CheckTlsFiles({.certificate = pem, .key = key}).message(),
              HasSubstr("--tls-ca is missing"));
  EXPECT_THAT(CheckTlsFiles({.certificate = pem, .key = pem, .ca = pem}).message(),
              HasSubstr("--tls-key: " + pem + " holds no PEM"));
  EXPECT_THAT(CheckTlsFiles({.certificate = Path("none"), .key = key, .ca = pem}).message(),
              HasSubstr("--tls-cert: cannot read"));

  // A server name replaces the address a client checks, so it means nothing without TLS.
  EXPECT_TRUE(
      CheckTlsFiles({.certificate = pem, .key = key, .ca = pem, .server_name = "server.dcs"}).ok());
  const absl::Status alone = CheckTlsFiles({.server_name = "server.dcs"});
  EXPECT_EQ(alone.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(alone.message(), HasSubstr("--tls-server-name needs mutual TLS"));
}

class TlsFlagsTest : public ::testing::Test {
 protected:
  void SetUp() override { ::unsetenv("DCS_TLS_SERVER_NAME"); }
  void TearDown() override { ::unsetenv("DCS_TLS_SERVER_NAME"); }

  TlsFiles Parse(const std::string& command_line) {
    CLI::App app;
    TlsFiles files;
    AddTlsFlags(app, files);
    app.parse(command_line, /*program_name_included=*/false);
    return files;
  }
};

// Containers set DCS_TLS_SERVER_NAME; a flag wins over it.
TEST_F(TlsFlagsTest, ServerNameComesFromItsFlagOrTheEnvironment) {
  EXPECT_EQ(Parse("").server_name, "");
  EXPECT_EQ(Parse("--tls-server-name server.dcs").server_name, "server.dcs");
  ::setenv("DCS_TLS_SERVER_NAME", "env.dcs", 1);
  EXPECT_EQ(Parse("").server_name, "env.dcs");
  EXPECT_EQ(Parse("--tls-server-name=server.dcs").server_name, "server.dcs");
}

TEST(NewTokenTest, IsLongEnoughAndDiffersEachTime) {
  const std::string token = NewToken();
  EXPECT_EQ(token.size(), 64u);
  EXPECT_GE(token.size(), kMinTokenLength);
  EXPECT_NE(token, NewToken());
}

}  // namespace
}  // namespace dcs::services
