// Copyright 2026 The DCS Authors.
#include "learner/policy_export.h"

#include <filesystem>
#include <utility>

#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "common/enum_names.h"
#include "common/status_macros.h"
#include "dcs/proto_json.h"
#include "env/env_registry.h"

namespace dcs::learner {
namespace {

constexpr absl::string_view kStateInput = "state";
constexpr absl::string_view kContextInput = "context";

v1::ObservationLayout ObservationOf(const run::PolicySpec& policy) {
  v1::ObservationLayout observation;
  observation.set_state_size(policy.observation_size);
  if (policy.has_image()) {
    v1::ImageLayout& image = *observation.mutable_image();
    image.set_key(std::string(kSb3ImageKey));
    image.add_shape(policy.image_height);
    image.add_shape(policy.image_width);
    image.add_shape(policy.image_channels);
    image.set_dtype("uint8");
    image.set_preprocessing(
        "as float32, divided by 255, transposed to channel first [C, H, W] for NatureCNN");
    observation.add_input_order(std::string(kSb3ImageKey));
    if (policy.context_size > 0) observation.add_input_order(std::string(kSb3ContextKey));
  } else {
    observation.add_input_order(std::string(kStateInput));
    if (policy.context_size > 0) observation.add_input_order(std::string(kContextInput));
  }
  return observation;
}

v1::ContextLayout ContextOf(const TrainedPolicy& trained, const env::ContextSpace& space) {
  const run::RunSpec& spec = trained.run.spec;
  v1::ContextLayout context;
  context.set_observe_mode(std::string(NameOf(env::kObserveModeNames, spec.observe)));
  if (trained.policy.has_image() && trained.policy.context_size > 0) {
    context.set_key(std::string(kSb3ContextKey));
  }
  for (const int index : trained.plan.slot.observed_features) {
    const env::ContextFeature& feature = space.feature(index);
    v1::ObservedFeature& observed = *context.add_features();
    observed.set_name(feature.name);
    observed.set_normalization_lower(feature.normalization_lower);
    observed.set_normalization_upper(feature.normalization_upper);
    observed.set_default_value(feature.default_value);
  }
  context.set_normalization(
      "clip((x - mid) / half, -5, 5) as float32, mid = (normalization_lower + "
      "normalization_upper) / 2, half = (normalization_upper - normalization_lower) / 2");
  context.set_varied_feature(spec.feature);
  context.set_training_lower(spec.range_lo);
  context.set_training_upper(spec.range_hi);
  return context;
}

v1::ActionLayout ActionOf(const run::PolicySpec& policy) {
  v1::ActionLayout action;
  if (policy.discrete()) {
    action.set_type("discrete");
    action.set_n(policy.num_actions);
    action.set_deterministic("the argmax of action_net's logits");
  } else {
    action.set_type("box");
    action.mutable_low()->Add(policy.action_low.begin(), policy.action_low.end());
    action.mutable_high()->Add(policy.action_high.begin(), policy.action_high.end());
    action.set_deterministic(
        "action_net's output, the Gaussian's mean, unclipped (the environment clips it to "
        "[low, high])");
  }
  return action;
}

v1::NetworkLayout NetworkOf(const run::PolicySpec& policy, const run::PpoConfig& config) {
  v1::NetworkLayout network;
  network.mutable_pi_layers()->Add(config.pi_layers.begin(), config.pi_layers.end());
  network.mutable_vf_layers()->Add(config.vf_layers.begin(), config.vf_layers.end());
  if (policy.has_image()) {
    network.set_cnn_features(config.cnn_features);
    // The branch exists only where there is a context to take (learner/actor_critic.h).
    if (policy.context_size > 0) {
      network.mutable_context_layers()->Add(config.context_layers.begin(),
                                            config.context_layers.end());
    }
  }
  return network;
}

}  // namespace

absl::StatusOr<ExportedPolicy> ExportPolicy(const TrainedPolicy& trained) {
  DCS_ASSIGN_OR_RETURN(std::string state_dict, trained.learner->Sb3StateDict());
  ExportedPolicy exported{.state_dict = std::move(state_dict)};
  v1::PolicyLayout& layout = exported.layout;
  const run::RunSpec& spec = trained.run.spec;
  layout.set_env(spec.env);
  layout.set_sb3_policy(trained.policy.has_image() ? "MultiInputPolicy" : "MlpPolicy");
  layout.set_checkpoint_step(trained.step);
  *layout.mutable_observation() = ObservationOf(trained.policy);
  DCS_RETURN_IF_ERROR(env::VisitEnvironment(spec.env, [&]<typename Env>() {
    *layout.mutable_context() = ContextOf(trained, Env::Features());
    return absl::OkStatus();
  }));
  *layout.mutable_action() = ActionOf(trained.policy);
  *layout.mutable_network() = NetworkOf(trained.policy, spec.ppo);
  return exported;
}

absl::StatusOr<std::string> LayoutPathFor(const std::string& state_dict_path) {
  std::filesystem::path path(state_dict_path);
  if (path.extension() == ".json") {
    return absl::InvalidArgumentError(absl::StrCat(
        "--out ", state_dict_path, " ends in .json, where the observation layout goes"));
  }
  return path.replace_extension(".json").string();
}

absl::Status WriteExportedPolicy(const ExportedPolicy& exported,
                                 const std::string& state_dict_path) {
  DCS_ASSIGN_OR_RETURN(const std::string layout_path, LayoutPathFor(state_dict_path));
  DCS_RETURN_IF_ERROR(WriteFileAtomically(state_dict_path, exported.state_dict));
  return WriteFileAtomically(layout_path, ProtoToJson(exported.layout) + "\n");
}

}  // namespace dcs::learner
