// Copyright 2026 The DCS Authors.
//
// The cluster's bearer token and mutual TLS (services/auth.h) with real processes on loopback.
//
// Token: a local cluster started with a token comes up (its workers register, so the token
// holds between services); every method every process serves (as its /metrics lists them, so
// a method or service added later is called too) refuses a call without the token and one with
// a wrong token, UNAUTHENTICATED, and counts it; health stays open; the `dcs` client is refused
// without the token and served with it.
//
// Mutual TLS: a cluster with certificates comes up; plaintext and a certificate of another CA
// are refused; certificates renewed in place are taken up without a restart.
//
// Server name: with scripts/make-certs' certificate, which names only DNS:server.dcs as in
// containers, a cluster comes up and runs a sweep (every process dialling 127.0.0.1 and
// checking the name instead); a client dialling 127.0.0.1 is refused without the name.

#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>
#include <google/protobuf/descriptor.h>

#include <stdlib.h>

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "absl/cleanup/cleanup.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/time/clock.h"
#include "common/atomic_file.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "dcs/v1/learner_service.grpc.pb.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/auth.h"
#include "services/cli/cluster_client.h"
#include "services/cli/local_cluster.h"
#include "services/exit_codes.h"
#include "tests/integration/test_util.h"
#include "tests/testing/net.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/slowdown.h"

namespace dcs::integration {
namespace {

using ::testing::HasSubstr;

// Calls `method` ("/dcs.v1.CoordinatorService/GetRun") with one empty request message, as any
// kind of RPC looks on the wire, presenting `authorization` if given; returns how it ended.
grpc::Status CallWithEmptyRequest(const std::string& address, const std::string& method,
                                  const std::optional<std::string>& authorization) {
  grpc::GenericStub stub(grpc::CreateChannel(address, grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(5));
  if (authorization.has_value()) context.AddMetadata("authorization", *authorization);
  grpc::CompletionQueue queue;
  std::unique_ptr<grpc::GenericClientAsyncReaderWriter> call =
      stub.PrepareCall(&context, method, &queue);
  void* tag = nullptr;
  bool ok = false;
  call->StartCall(nullptr);
  queue.Next(&tag, &ok);
  grpc::Slice empty("");
  call->Write(grpc::ByteBuffer(&empty, 1), nullptr);
  queue.Next(&tag, &ok);
  call->WritesDone(nullptr);
  queue.Next(&tag, &ok);
  grpc::ByteBuffer reply;  // read to the end, or the status never comes
  do {
    call->Read(&reply, nullptr);
    queue.Next(&tag, &ok);
  } while (ok);
  grpc::Status status;
  call->Finish(&status, nullptr);
  queue.Next(&tag, &ok);
  queue.Shutdown();
  while (queue.Next(&tag, &ok)) {
  }
  return status;
}

// The value of `label` in a series line of an exposition (`name{a="1",b="2"} 0`).
std::string LabelValue(absl::string_view line, absl::string_view label) {
  const std::string key = absl::StrCat(label, "=\"");
  const size_t start = line.find(key);
  if (start == absl::string_view::npos) return "";
  const size_t begin = start + key.size();
  return std::string(line.substr(begin, line.find('"', begin) - begin));
}

// The path of every method a process serves but health and reflection, which stay open: each
// served method has a grpc_server_started_total series from the start (services/server.h).
std::vector<std::string> ServedMethodPaths(const std::string& exposition) {
  std::set<std::string> paths;
  for (absl::string_view line : absl::StrSplit(exposition, '\n')) {
    if (!absl::StartsWith(line, "grpc_server_started_total{")) continue;
    const std::string service = LabelValue(line, "grpc_service");
    if (service == "grpc.health.v1.Health" || absl::StartsWith(service, "grpc.reflection.")) {
      continue;
    }
    paths.insert(absl::StrCat("/", service, "/", LabelValue(line, "grpc_method")));
  }
  return {paths.begin(), paths.end()};
}

// Every method's path of `service`.
std::vector<std::string> MethodPaths(const google::protobuf::ServiceDescriptor& service) {
  std::vector<std::string> paths;
  for (int i = 0; i < service.method_count(); ++i) {
    paths.push_back(absl::StrCat("/", service.full_name(), "/", service.method(i)->name()));
  }
  return paths;
}

// The sum of grpc_server_handled_total's UNAUTHENTICATED series in a /metrics exposition.
double UnauthenticatedCalls(const std::string& exposition) {
  double sum = 0;
  for (absl::string_view line : absl::StrSplit(exposition, '\n')) {
    if (!absl::StartsWith(line, "grpc_server_handled_total{") ||
        !absl::StrContains(line, "grpc_code=\"UNAUTHENTICATED\"")) {
      continue;
    }
    double value = 0;
    EXPECT_TRUE(absl::SimpleAtod(line.substr(line.rfind(' ') + 1), &value)) << line;
    sum += value;
  }
  return sum;
}

TEST(AuthTest, EveryServiceRefusesCallsWithoutTheClustersTokenAndCountsThem) {
  const std::string data_dir = testing::MakeTempDir();
  const std::string token = services::NewToken();
  // Up means every worker registered with the coordinator: with the token, between services.
  absl::StatusOr<std::unique_ptr<services::cli::LocalCluster>> cluster =
      services::cli::LocalCluster::Start(
          {.data_dir = data_dir, .bin_dir = BinDir(), .actors = 1, .token = token});
  ASSERT_TRUE(cluster.ok()) << cluster.status();
  const auto& processes = (*cluster)->state().processes;
  ASSERT_EQ(processes.size(), 3u);
  const services::cli::ClusterProcess& coordinator = processes[0];  // then the learner

  // What the processes serve, as their /metrics say; the DCS services at least.
  std::vector<std::vector<std::string>> served;
  for (const services::cli::ClusterProcess& process : processes) {
    absl::StatusOr<std::string> metrics =
        testing::HttpGet(absl::StrCat("http://", process.metrics_address, "/metrics"));
    ASSERT_TRUE(metrics.ok()) << process.name << ": " << metrics.status();
    served.push_back(ServedMethodPaths(*metrics));
  }
  const google::protobuf::ServiceDescriptor* coordinator_service =
      v1::GetRunRequest::descriptor()->file()->FindServiceByName("CoordinatorService");
  const google::protobuf::ServiceDescriptor* learner_service =
      v1::GetSlotWorkRequest::descriptor()->file()->FindServiceByName("LearnerService");
  ASSERT_NE(coordinator_service, nullptr);
  ASSERT_NE(learner_service, nullptr);
  EXPECT_THAT(served[0], ::testing::IsSupersetOf(MethodPaths(*coordinator_service)));
  EXPECT_THAT(served[1], ::testing::IsSupersetOf(MethodPaths(*learner_service)));

  int refused = 0;
  for (size_t i = 0; i < processes.size(); ++i) {
    const services::cli::ClusterProcess& process = processes[i];
    for (const std::string& method : served[i]) {
      const grpc::Status without = CallWithEmptyRequest(process.grpc_address, method, std::nullopt);
      EXPECT_EQ(without.error_code(), grpc::StatusCode::UNAUTHENTICATED) << method;
      EXPECT_THAT(without.error_message(), HasSubstr("has none")) << method;
      const grpc::Status wrong =
          CallWithEmptyRequest(process.grpc_address, method, "Bearer " + services::NewToken());
      EXPECT_EQ(wrong.error_code(), grpc::StatusCode::UNAUTHENTICATED) << method;
      EXPECT_THAT(wrong.error_message(), HasSubstr("not this cluster's")) << method;
      const grpc::Status bare = CallWithEmptyRequest(process.grpc_address, method, token);
      EXPECT_EQ(bare.error_code(), grpc::StatusCode::UNAUTHENTICATED) << method << ": no scheme";
      // With the token the call gets past authentication (the empty request may be refused
      // for what it is).
      const grpc::Status with =
          CallWithEmptyRequest(process.grpc_address, method, "Bearer " + token);
      EXPECT_NE(with.error_code(), grpc::StatusCode::UNAUTHENTICATED)
          << method << ": " << with.error_message();
      refused += 3;
    }
    // Counted where the operator looks.
    absl::StatusOr<std::string> metrics =
        testing::HttpGet(absl::StrCat("http://", process.metrics_address, "/metrics"));
    ASSERT_TRUE(metrics.ok()) << metrics.status();
    EXPECT_EQ(UnauthenticatedCalls(*metrics), 3.0 * static_cast<double>(served[i].size()))
        << process.name;
  }
  EXPECT_GT(refused, 0);

  // Health stays open for probes, of every process.
  for (const services::cli::ClusterProcess& process : processes) {
    absl::StatusOr<bool> serving =
        services::cli::IsServing(process.grpc_address, "", absl::Seconds(5));
    ASSERT_TRUE(serving.ok()) << process.name << ": " << serving.status();
    EXPECT_TRUE(*serving) << process.name;
  }

  // The client: refused without the token, served with it from a file or the environment.
  const RunResult anonymous = DcsAt({"status"}, coordinator.grpc_address);
  EXPECT_EQ(anonymous.exit_code, services::kExitNoPermission) << anonymous.output;
  EXPECT_THAT(anonymous.output, HasSubstr("requires a token"));
  const RunResult with_file = DcsAt({"status", "--token-file", services::cli::TokenPath(data_dir)},
                                    coordinator.grpc_address);
  EXPECT_EQ(with_file.exit_code, 0) << with_file.output;
  const std::string short_token = absl::StrCat(testing::MakeTempDir(), "/short");
  ASSERT_TRUE(WriteFileAtomically(short_token, "secret\n").ok());
  const RunResult weak = DcsAt({"status", "--token-file", short_token}, coordinator.grpc_address);
  EXPECT_EQ(weak.exit_code, services::kExitDataError) << weak.output;
  EXPECT_THAT(weak.output, HasSubstr("too short"));
}

// A CA and a certificate it signs for 127.0.0.1 (server and client use), in `dir`:
// ca.pem, node.pem, node.key. EC keys, so that it takes milliseconds.
services::TlsFiles MakeCertificates(const std::string& dir) {
  const RunResult made = RunProgram(
      "/bin/sh",
      {"-ec",
       absl::StrCat("cd ", dir, "\n",
                    "openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes "
                    "-keyout ca.key -out ca.pem -days 2 -subj /CN=dcs-test-ca 2>/dev/null\n",
                    "openssl req -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes "
                    "-keyout node.key -out node.csr -subj /CN=dcs-node 2>/dev/null\n",
                    "printf 'subjectAltName=IP:127.0.0.1,DNS:localhost\\n"
                    "extendedKeyUsage=serverAuth,clientAuth\\n' > node.ext\n",
                    "openssl x509 -req -in node.csr -CA ca.pem -CAkey ca.key -CAcreateserial "
                    "-out node.pem -days 2 -extfile node.ext 2>/dev/null\n")});
  EXPECT_EQ(made.exit_code, 0) << made.output;
  return {.certificate = absl::StrCat(dir, "/node.pem"),
          .key = absl::StrCat(dir, "/node.key"),
          .ca = absl::StrCat(dir, "/ca.pem")};
}

// One CartPole run, a few seconds long.
constexpr char kOneRunSweep[] = R"(name: tiny
seeds: 1
env: cartpole
total_timesteps: 512
feature: length
training_range: [0.35, 0.75]
pool: {size: 3}
evaluation: {freq: 256, episodes: 2, contexts: {id: [0.5]}}
ppo: {n_steps: 256, batch_size: 64, n_epochs: 2}
conditions:
  - name: static
)";

std::vector<std::string> TlsFlags(const services::TlsFiles& files) {
  return {"--tls-cert", files.certificate, "--tls-key", files.key, "--tls-ca", files.ca};
}

TEST(AuthTest, MutualTlsRefusesPlaintextAndStrangersAndRereadsRenewedCertificates) {
  const std::string data_dir = testing::MakeTempDir();
  // The cluster's files are copies, so that they can be renewed in place.
  const std::string live = testing::MakeTempDir();
  const services::TlsFiles first = MakeCertificates(testing::MakeTempDir());
  const services::TlsFiles cluster_files{.certificate = absl::StrCat(live, "/node.pem"),
                                         .key = absl::StrCat(live, "/node.key"),
                                         .ca = absl::StrCat(live, "/ca.pem")};
  auto install = [&](const services::TlsFiles& files) {
    for (const auto& [from, to] :
         {std::pair(files.certificate, cluster_files.certificate),
          std::pair(files.key, cluster_files.key), std::pair(files.ca, cluster_files.ca)}) {
      ASSERT_TRUE(WriteFileAtomically(to, ReadFile(from).value_or("")).ok());
    }
  };
  install(first);
  const std::string token = services::NewToken();
  // This process dials the cluster as `dcs up` does, with the cluster's files.
  services::SetClusterTls(cluster_files);
  absl::Cleanup plaintext_again = [] { services::SetClusterTls({}); };
  // Up means every worker registered with the coordinator: over mutual TLS, with the token.
  absl::StatusOr<std::unique_ptr<services::cli::LocalCluster>> cluster =
      services::cli::LocalCluster::Start({.data_dir = data_dir,
                                          .bin_dir = BinDir(),
                                          .actors = 1,
                                          .token = token,
                                          .tls = cluster_files});
  ASSERT_TRUE(cluster.ok()) << cluster.status();
  const std::string coordinator = (*cluster)->state().coordinator_address;
  const std::string token_file = services::cli::TokenPath(data_dir);

  // Plaintext is refused at the connection, with or without the token.
  const grpc::Status plaintext =
      CallWithEmptyRequest(coordinator, "/dcs.v1.CoordinatorService/ListSweeps", "Bearer " + token);
  EXPECT_EQ(plaintext.error_code(), grpc::StatusCode::UNAVAILABLE) << plaintext.error_message();
  const RunResult no_tls =
      DcsAt({"status", "--token-file", token_file, "--timeout=2s"}, coordinator);
  EXPECT_EQ(no_tls.exit_code, services::kExitUnavailable) << no_tls.output;

  // A certificate from another CA is refused too.
  const services::TlsFiles stranger = MakeCertificates(testing::MakeTempDir());
  std::vector<std::string> args = {"status", "--token-file", token_file, "--timeout=2s"};
  for (const std::string& flag : TlsFlags(stranger)) args.push_back(flag);
  const RunResult strange = DcsAt(args, coordinator);
  EXPECT_EQ(strange.exit_code, services::kExitUnavailable) << strange.output;

  // The cluster's certificate and token are served; its certificate without the token is not.
  args = {"status", "--token-file", token_file};
  for (const std::string& flag : TlsFlags(first)) args.push_back(flag);
  const RunResult served = DcsAt(args, coordinator);
  EXPECT_EQ(served.exit_code, 0) << served.output;
  std::vector<std::string> tokenless = {"status"};
  for (const std::string& flag : TlsFlags(first)) tokenless.push_back(flag);
  EXPECT_EQ(DcsAt(tokenless, coordinator).exit_code, services::kExitNoPermission);

  // Renewed in place under a new CA: taken up without a restart, the old CA then refused.
  const services::TlsFiles renewed = MakeCertificates(testing::MakeTempDir());
  install(renewed);
  std::vector<std::string> with_renewed = {"status", "--token-file", token_file, "--timeout=2s"};
  for (const std::string& flag : TlsFlags(renewed)) with_renewed.push_back(flag);
  const absl::Time deadline = absl::Now() + testing::Patient(absl::Seconds(30));
  int exit_code = -1;
  while ((exit_code = DcsAt(with_renewed, coordinator).exit_code) != 0 && absl::Now() < deadline) {
    absl::SleepFor(absl::Milliseconds(500));
  }
  EXPECT_EQ(exit_code, 0) << "the renewed certificates were not taken up";
  args.push_back("--timeout=2s");
  EXPECT_EQ(DcsAt(args, coordinator).exit_code, services::kExitUnavailable);
}

// Sets the DCS_TLS_* variables to `files`, as the containers do (docker-compose.tls.yml,
// deploy/kubernetes/overlays/cluster); empty files unset them.
void SetTlsEnvironment(const services::TlsFiles& files) {
  for (const auto& [variable, value] :
       {std::pair("DCS_TLS_CERT", files.certificate), std::pair("DCS_TLS_KEY", files.key),
        std::pair("DCS_TLS_CA", files.ca), std::pair("DCS_TLS_SERVER_NAME", files.server_name)}) {
    if (value.empty()) {
      ::unsetenv(variable);
    } else {
      ::setenv(variable, value.c_str(), 1);
    }
  }
}

// The certificate every server of a cluster in containers holds (scripts/make-certs): it names
// server.dcs and nothing else, so dialling 127.0.0.1 passes only with that name given.
TEST(AuthTest, ClientsCheckTheServerNameInsteadOfTheAddressDialled) {
  const std::string certificates = testing::MakeTempDir();
  const RunResult made =
      RunProgram(absl::StrCat(DCS_SOURCE_DIR, "/scripts/make-certs"), {certificates});
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const services::TlsFiles files{.certificate = absl::StrCat(certificates, "/node.pem"),
                                 .key = absl::StrCat(certificates, "/node.key"),
                                 .ca = absl::StrCat(certificates, "/ca.pem"),
                                 .server_name = "server.dcs"};
  // This process waits for the cluster as `dcs up` does, which hands the name to the children.
  services::SetClusterTls(files);
  absl::Cleanup plaintext_again = [] {
    services::SetClusterTls({});
    SetTlsEnvironment({});
  };
  const std::string data_dir = testing::MakeTempDir();
  absl::StatusOr<std::unique_ptr<services::cli::LocalCluster>> cluster =
      services::cli::LocalCluster::Start({.data_dir = data_dir,
                                          .bin_dir = BinDir(),
                                          .actors = 1,
                                          .token = services::NewToken(),
                                          .tls = files});
  // Up means the workers registered: each dialled the coordinator at 127.0.0.1.
  ASSERT_TRUE(cluster.ok()) << cluster.status();
  const std::string coordinator = (*cluster)->state().coordinator_address;
  // The containers' probes: `dcs health` with nothing but the variables.
  SetTlsEnvironment(files);
  for (const services::cli::ClusterProcess& process : (*cluster)->state().processes) {
    const RunResult probe = DcsAt({"--timeout=2s", "health"}, process.grpc_address);
    EXPECT_EQ(probe.exit_code, 0) << process.name << ": " << probe.output;
  }
  SetTlsEnvironment({});

  std::vector<std::string> args = {"--token-file", services::cli::TokenPath(data_dir)};
  for (const std::string& flag : TlsFlags(files)) args.push_back(flag);
  std::vector<std::string> status = {"status", "--timeout=2s"};
  status.insert(status.end(), args.begin(), args.end());
  const RunResult unnamed = DcsAt(status, coordinator);
  EXPECT_EQ(unnamed.exit_code, services::kExitUnavailable) << unnamed.output;
  status.insert(status.end(), {"--tls-server-name", "server.dcs"});
  const RunResult named = DcsAt(status, coordinator);
  EXPECT_EQ(named.exit_code, 0) << named.output;

  // A sweep completes: the actor dials the learner, at the address it registered.
  const std::string spec = absl::StrCat(testing::MakeTempDir(), "/tiny.yaml");
  ASSERT_TRUE(WriteFileAtomically(spec, kOneRunSweep).ok());
  std::vector<std::string> submit = {"submit", spec, "--watch", "--tls-server-name", "server.dcs"};
  submit.insert(submit.end(), args.begin(), args.end());
  const RunResult swept = DcsAt(submit, coordinator, absl::Minutes(3));
  EXPECT_EQ(swept.exit_code, 0) << swept.output;
  EXPECT_THAT(swept.output, HasSubstr("completed, 1/1 runs done"));
}

}  // namespace
}  // namespace dcs::integration
