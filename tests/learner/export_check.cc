// Copyright 2026 The DCS Authors.
#include "tests/learner/export_check.h"

#include <stdio.h>
#include <sys/wait.h>

#include "absl/strings/str_cat.h"
#include "actor/policy_network.h"
#include "common/atomic_file.h"
#include "gtest/gtest.h"

namespace dcs::learner {
namespace {

constexpr int kObservations = 1000;

// `values`' bytes, as numpy's fromfile reads them (x86-64: little endian).
template <typename T>
void WriteArray(const std::string& path, const std::vector<T>& values) {
  const absl::Status written = WriteFileAtomically(
      path, absl::string_view(reinterpret_cast<const char*>(values.data()),
                              values.size() * sizeof(T)));
  EXPECT_TRUE(written.ok()) << written;
}

}  // namespace

Observations RandomObservations(const run::PolicySpec& spec, int count, Random& random) {
  Observations observations;
  observations.inputs.resize(static_cast<size_t>(count) * spec.flat_input_size());
  for (float& x : observations.inputs) x = static_cast<float>(random.Uniform(-2, 2));
  observations.images.resize(count * spec.image_size());
  for (uint8_t& pixel : observations.images) pixel = static_cast<uint8_t>(random.Integers(0, 256));
  return observations;
}

ExportCheck CheckExport(const TrainedPolicy& trained, const std::string& policy_path,
                        const std::string& dir) {
  Random random(29);
  const run::PolicySpec& spec = trained.policy;
  const Observations observations = RandomObservations(spec, kObservations, random);
  absl::StatusOr<actor::PolicyNetwork> network =
      actor::PolicyNetwork::Create(trained.learner->ActorWeights());
  EXPECT_TRUE(network.ok()) << network.status();
  if (!network.ok()) return {};
  std::vector<float> actions(static_cast<size_t>(kObservations) * spec.action_size);
  std::vector<Random> unused(kObservations, Random(0));  // deterministic: no draws
  network->Act(kObservations, observations.inputs, observations.images,
               /*deterministic=*/true, unused, actions);
  WriteArray(dir + "/inputs.f32", observations.inputs);
  WriteArray(dir + "/images.u8", observations.images);
  WriteArray(dir + "/actions.f32", actions);
  WriteArray(dir + "/values.f32",
             trained.learner->Values(observations.inputs, observations.images, kObservations));

  const std::string command = absl::StrCat("/usr/bin/python3 ", DCS_CHECK_EXPORT_SCRIPT, " ",
                                           policy_path, " ", dir, " 2>&1");
  ExportCheck check;
  FILE* pipe = popen(command.c_str(), "r");
  EXPECT_NE(pipe, nullptr) << command;
  if (pipe == nullptr) return check;
  char buffer[4096];
  for (size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) check.output.append(buffer, n);
  const int status = pclose(pipe);
  check.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return check;
}

}  // namespace dcs::learner
