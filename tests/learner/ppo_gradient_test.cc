// Copyright 2026 The DCS Authors.
//
// The learner's explicit backward pass (learner/ppo_loss.h, then ActorCriticImpl::Backward)
// against libtorch's autograd on SB3's loss written as tensor operations, as PPO computed it
// before the explicit pass: the same loss and every parameter's gradient, for categorical,
// Gaussian and image policies, with and without the entropy bonus and value clipping.

#include <torch/torch.h>

#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "gtest/gtest.h"
#include "learner/actor_critic.h"
#include "learner/ppo_loss.h"
#include "tests/learner/policy_specs.h"

namespace dcs::learner {
namespace {

std::vector<float> Floats(const torch::Tensor& tensor) {
  const torch::Tensor t = tensor.detach().contiguous();
  return std::vector<float>(t.data_ptr<float>(), t.data_ptr<float>() + t.numel());
}

// A pass's [rows x B] batch as a tensor [B, rows], copied.
torch::Tensor Tensor(const Eigen::MatrixXf& batch) {
  return torch::from_blob(const_cast<float*>(batch.data()), {batch.cols(), batch.rows()}).clone();
}

// One minibatch of made-up inputs to the loss.
struct Minibatch {
  std::vector<uint8_t> images;  // channel last
  ObservationBatch observations;
  torch::Tensor actions;  // [B, action_size]; a discrete action as its index
  torch::Tensor advantages;
  torch::Tensor returns;
  torch::Tensor old_log_probs;
  torch::Tensor old_values;
};

// SB3's forward pass and loss as tensor operations, recorded by autograd, on `network`'s
// parameters; returns the loss.
torch::Tensor AutogradLoss(ActorCritic& network, const run::PolicySpec& spec,
                           const run::PpoConfig& config, const Minibatch& m) {
  std::map<std::string, torch::Tensor> p;
  for (const auto& item : network->named_parameters()) p[item.key()] = item.value();
  // The layers `name`_0, `name`_1, ... on `x`, each followed by `activation`.
  const auto mlp = [&](const std::string& name, torch::Tensor x,
                       torch::Tensor (*activation)(const torch::Tensor&)) {
    for (int l = 0; p.count(name + "_" + std::to_string(l) + ".weight") > 0; ++l) {
      const std::string layer = name + "_" + std::to_string(l);
      x = activation(torch::nn::functional::linear(x, p[layer + ".weight"], p[layer + ".bias"]));
    }
    return x;
  };
  torch::Tensor features = m.observations.flat;
  if (spec.has_image()) {
    auto cnn = std::dynamic_pointer_cast<torch::nn::SequentialImpl>(
        network->named_children()["cnn"]);
    // As SB3 gives images to NatureCNN: channel first, floats in [0, 1].
    const torch::Tensor images =
        torch::from_blob(const_cast<uint8_t*>(m.images.data()),
                         {m.observations.flat.size(0), spec.image_height, spec.image_width,
                          spec.image_channels},
                         torch::kUInt8)
            .permute({0, 3, 1, 2})
            .to(torch::kFloat32)
            .div(255.0);
    features = torch::cat({cnn->forward(images), mlp("context", m.observations.flat, torch::relu)},
                          1);
  }
  const torch::Tensor head =
      torch::nn::functional::linear(mlp("pi", features, torch::tanh), p["action_net.weight"],
                                    p["action_net.bias"]);
  const torch::Tensor values =
      torch::nn::functional::linear(mlp("vf", features, torch::tanh), p["value_net.weight"],
                                    p["value_net.bias"])
          .squeeze(1);
  torch::Tensor log_probs;
  torch::Tensor entropy;
  if (spec.discrete()) {
    const torch::Tensor log_p = torch::log_softmax(head, 1);
    log_probs = log_p.gather(1, m.actions.to(torch::kLong)).squeeze(1);
    entropy = -(log_p.exp() * log_p).sum(1);
  } else {
    const double half_log_2pi = 0.5 * std::log(2 * std::numbers::pi);
    const torch::Tensor& log_std = p["log_std"];
    const torch::Tensor z = (m.actions - head) * torch::exp(-log_std);
    log_probs = (-0.5 * z * z - log_std - half_log_2pi).sum(1);
    entropy = (0.5 + half_log_2pi + log_std).sum().expand({head.size(0)});
  }
  const double clip = config.clip_range;
  const torch::Tensor ratio = torch::exp(log_probs - m.old_log_probs);
  const torch::Tensor policy_loss =
      -torch::min(m.advantages * ratio, m.advantages * torch::clamp(ratio, 1 - clip, 1 + clip))
           .mean();
  torch::Tensor predicted = values;
  if (config.clip_range_vf.has_value()) {
    predicted = m.old_values + torch::clamp(values - m.old_values, -*config.clip_range_vf,
                                            *config.clip_range_vf);
  }
  return policy_loss + config.vf_coef * torch::mse_loss(predicted, m.returns) -
         config.ent_coef * entropy.mean();
}

void ExpectExplicitGradientsMatchAutograd(const run::PolicySpec& spec,
                                          const run::PpoConfig& config, int b) {
  torch::manual_seed(11);
  ActorCritic network(spec, config);
  Minibatch m;
  m.observations.flat = torch::randn({b, spec.flat_input_size()});
  m.images = RandomImages(spec, b, 12);
  m.observations.images = m.images;
  ActorCriticImpl::Pass pass;
  network->Forward(m.observations, /*for_backward=*/true, pass);
  // Actions near the policy's and old log-probabilities and values off by enough that some
  // ratios and value changes fall outside their clips.
  m.actions = spec.discrete()
                  ? torch::randint(spec.num_actions, {b, 1}).to(torch::kFloat32)
                  : Tensor(pass.head) + 0.5 * torch::randn({b, spec.action_size});
  m.advantages = torch::randn({b});
  m.returns = torch::randn({b});
  m.old_values = Tensor(pass.values).squeeze(1) + 0.4 * torch::randn({b});
  std::vector<float> log_probs(b);
  const std::vector<float> head = Floats(Tensor(pass.head));
  const std::vector<float> actions = Floats(m.actions);
  const std::vector<float> log_std =
      spec.discrete() ? std::vector<float>() : Floats(network->log_std());
  ActionLogProbs(spec, head, log_std, actions, log_probs);
  m.old_log_probs = torch::tensor(log_probs) + 0.3 * torch::randn({b});

  const int head_size = spec.head_size();
  Eigen::MatrixXf d_head(head_size, b);
  Eigen::MatrixXf d_values(1, b);
  std::vector<float> d_log_std(spec.discrete() ? 0 : spec.action_size);
  const std::vector<float> values = Floats(Tensor(pass.values));
  const std::vector<float> advantages = Floats(m.advantages);
  const std::vector<float> returns = Floats(m.returns);
  const std::vector<float> old_log_probs = Floats(m.old_log_probs);
  const std::vector<float> old_values = Floats(m.old_values);
  const PpoLoss loss = ComputePpoLoss(
      spec, config,
      {.size = b, .head = head, .values = values, .log_std = log_std, .actions = actions,
       .advantages = advantages, .returns = returns, .old_log_probs = old_log_probs,
       .old_values = old_values},
      {.head = {d_head.data(), static_cast<size_t>(d_head.size())},
       .values = {d_values.data(), static_cast<size_t>(b)},
       .log_std = d_log_std});
  network->Backward(pass, d_head, d_values, d_log_std);
  std::map<std::string, torch::Tensor> explicit_gradients;
  for (auto& item : network->named_parameters()) {
    ASSERT_TRUE(item.value().grad().defined()) << item.key();
    explicit_gradients[item.key()] = item.value().grad().clone();
    item.value().mutable_grad().zero_();
  }

  const torch::Tensor reference = AutogradLoss(network, spec, config, m);
  reference.backward();
  EXPECT_NEAR(loss.total, reference.item<double>(), 1e-5 * (1 + std::abs(loss.total)));
  for (const auto& item : network->named_parameters()) {
    const torch::Tensor& expected = item.value().grad();
    const double scale = 1 + expected.abs().max().item<double>();
    const double error = (explicit_gradients[item.key()] - expected).abs().max().item<double>();
    EXPECT_LE(error, 1e-5 * scale) << item.key();
  }
}

TEST(PpoGradientTest, CategoricalWithSb3Defaults) {
  ExpectExplicitGradientsMatchAutograd(CartPoleSpec(), run::PpoConfig{}, 64);
}

TEST(PpoGradientTest, CategoricalWithEntropyBonusValueClippingAndOtherWidths) {
  run::PolicySpec spec = CartPoleSpec();
  spec.num_actions = 5;
  const run::PpoConfig config{.clip_range_vf = 0.2,
                              .ent_coef = 0.01,
                              .pi_layers = {32},
                              .vf_layers = {16, 8}};
  ExpectExplicitGradientsMatchAutograd(spec, config, 37);
}

TEST(PpoGradientTest, WithoutHiddenLayers) {
  ExpectExplicitGradientsMatchAutograd(CartPoleSpec(),
                                       run::PpoConfig{.pi_layers = {}, .vf_layers = {}}, 16);
}

TEST(PpoGradientTest, Gaussian) {
  ExpectExplicitGradientsMatchAutograd(WalkerSpec(), run::PpoConfig{.ent_coef = 0.01}, 64);
}

TEST(PpoGradientTest, ImagePolicyGradientsReachNatureCnn) {
  // 36 x 36: the smallest image NatureCNN takes.
  ExpectExplicitGradientsMatchAutograd(ImageSpec(36), run::PpoConfig{.ent_coef = 0.01}, 6);
}

TEST(PpoGradientTest, ImagePolicyGradientsReachNatureCnnOnCarRacingsImages) {
  // 96 x 96: the second convolution leaves its input's last row and column unread.
  ExpectExplicitGradientsMatchAutograd(ImageSpec(96), run::PpoConfig{}, 3);
}

TEST(PpoGradientTest, ImagePolicyGradientsReachTheContextBranch) {
  run::PolicySpec spec = ImageSpec(36);
  ASSERT_GT(spec.context_size, 0);
  ExpectExplicitGradientsMatchAutograd(
      spec, run::PpoConfig{.ent_coef = 0.01, .context_layers = {16, 8}}, 6);
}

}  // namespace
}  // namespace dcs::learner
