// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_ACTOR_CRITIC_H_
#define DCS_LEARNER_ACTOR_CRITIC_H_

// Stable-Baselines3's ActorCriticPolicy in libtorch (common/policies.py): separate policy and
// value MLPs with tanh (default [64, 64] each) on the features, a linear action head
// (categorical logits, or a Gaussian mean with a state-independent log-std) and a linear
// value head; orthogonal initialisation with SB3's gains (sqrt 2 for the feature extractor
// and the MLPs, 0.01 for the action head, 1 for the value head) and zero biases.
// Features: the flat observation and context as they are; or, for an image observation,
// SB3's CombinedExtractor: NatureCNN (256 features) on the image / 255, then the context
// appended, as it is or through its own MLP (`context_layers`, ReLU; the paper's CarRacing
// policy).
// Forward and backward passes are explicit (Forward, Backward), for PPO's update: the loss's
// gradient with respect to the heads' outputs (learner/ppo_loss.h) goes down the MLPs as Eigen
// matrix products on the parameters' own memory (actor/dense_forward.h: the layers actors
// compute), and down NatureCNN as im2col products (learner/nature_cnn.h); libtorch keeps the
// parameters (initialisation, Adam, checkpoints) and computes nothing of a pass. In a pass, a
// batch holds one sample per column ([values x samples], column-major): the memory of a
// row-major [samples x values] tensor.
//
// Internal to learner/: only learner translation units include libtorch headers.
// Confined to one thread (libtorch is pinned to one thread per run).

#include <torch/torch.h>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "absl/strings/string_view.h"
#include "actor/policy_weights.h"
#include "learner/nature_cnn.h"
#include "run/ppo_config.h"

namespace dcs::learner {

// A batch of B observations: `flat` [B, flat_input_size] float; `images` B channel-last
// images of image_size() bytes each, image after image (empty without an image), as rollouts
// carry them.
struct ObservationBatch {
  torch::Tensor flat;
  std::span<const uint8_t> images;
};

class ActorCriticImpl : public torch::nn::Module {
 public:
  // REQUIRES: spec and config valid. Initialises from torch's global generator (seed it first).
  ActorCriticImpl(const run::PolicySpec& spec, const run::PpoConfig& config);

  // One forward pass's inputs and outputs, kept for its backward pass, and the backward pass's
  // scratch. Buffers are reused by the next pass of the same batch size.
  struct Pass {
    NatureCnn::Pass cnn;             // image policies
    Eigen::MatrixXf image_features;  // NatureCNN's output, [cnn_features x B]
    torch::Tensor features;          // [B, F] contiguous, the MLPs' input
    torch::Tensor context_input;           // the context branch's input, [B, C] contiguous
    std::vector<Eigen::MatrixXf> context;  // each context layer's output, after ReLU
    std::vector<Eigen::MatrixXf> pi;  // each policy layer's output, after tanh: [width x B]
    std::vector<Eigen::MatrixXf> vf;  // each value layer's output, after tanh
    Eigen::MatrixXf head;             // [A x B]: logits, or the Gaussian mean
    Eigen::MatrixXf values;           // [1 x B]
    std::vector<Eigen::MatrixXf> d_context;
    std::vector<Eigen::MatrixXf> d_pi;
    std::vector<Eigen::MatrixXf> d_vf;
    Eigen::MatrixXf d_features;
    Eigen::MatrixXf d_context_output;  // the context branch's part of d_features
  };

  // The forward pass of `batch`. `for_backward`: `pass` keeps all NatureCNN's Backward needs
  // (image policies; otherwise their images go through in chunks, NatureCnn::kChunk).
  // `pass.features` shares the memory of `batch.flat` for policies without image.
  void Forward(const ObservationBatch& batch, bool for_backward, Pass& pass);

  // Sets the gradient (each parameter's .grad, allocated if undefined) of every parameter from
  // the gradient of the loss with respect to the outputs of `pass`, a Forward with
  // `for_backward` for image policies, the parameters unchanged since: `d_head` [A x B],
  // `d_values` [1 x B], `d_log_std` [action_size] (Gaussian policies; empty otherwise).
  void Backward(Pass& pass, const Eigen::MatrixXf& d_head, const Eigen::MatrixXf& d_values,
                std::span<const float> d_log_std);

  // The actor half, for Eigen inference (actor/policy_network.h).
  actor::PolicyWeights ExportActor() const;

  // Every parameter under its name in the state_dict of Stable-Baselines3's policy of the same
  // architecture (SB3's common/policies.py), as detached copies in SB3's order: MlpPolicy's; or,
  // for image policies, MultiInputPolicy's, whose Dict observation has the image under `image_key`
  // and the context under `context_key`. Its CombinedExtractor, shared by actor and critic, appears
  // under the three prefixes SB3's state_dict lists it by (features_extractor,
  // pi_features_extractor, vf_features_extractor), as the same tensors. The context branch, DCS's
  // addition, is extractors.<context_key> as a Sequential of Linear and ReLU.
  std::vector<std::pair<std::string, torch::Tensor>> Sb3Parameters(
      absl::string_view image_key, absl::string_view context_key) const;

  const torch::Tensor& log_std() const { return log_std_; }

 private:
  // Linear layers, each followed by `activation`.
  struct Mlp {
    using ConstView = Eigen::Map<const Eigen::MatrixXf>;
    std::vector<torch::nn::Linear> layers;
    actor::Activation activation = actor::Activation::kTanh;
    // Each layer's output into `outputs`.
    void Forward(ConstView input, std::vector<Eigen::MatrixXf>& outputs) const;
    // The last layer's output, or `input` without layers.
    ConstView Output(ConstView input, const std::vector<Eigen::MatrixXf>& outputs) const;
    // Gradients of the layers' parameters, given the forward pass's `input` and `outputs`, from
    // `d_above`: the gradient at the output of `above`, the linear layer the MLP's output feeds
    // (a head), or with `above` null the gradient at the MLP's output itself. If `d_input` is
    // not null, adds the gradient with respect to `input` to it.
    void Backward(ConstView input, const std::vector<Eigen::MatrixXf>& outputs,
                  const torch::nn::LinearImpl* above, const Eigen::MatrixXf& d_above,
                  std::vector<Eigen::MatrixXf>& d_outputs, Eigen::MatrixXf* d_input);
  };

  // `mlp` then the linear `head` on its output: each layer's output into `outputs`, the head's
  // into `head_output`; and the gradients of both from `d_head`, the gradient at the head's
  // output (adding the gradient at `input` to `d_input` if not null).
  static void Forward(const Mlp& mlp, const torch::nn::Linear& head, Mlp::ConstView input,
                      std::vector<Eigen::MatrixXf>& outputs, Eigen::MatrixXf& head_output);
  static void Backward(Mlp& mlp, torch::nn::Linear& head, Mlp::ConstView input,
                       const std::vector<Eigen::MatrixXf>& outputs, const Eigen::MatrixXf& d_head,
                       std::vector<Eigen::MatrixXf>& d_outputs, Eigen::MatrixXf* d_input);

  const run::PolicySpec spec_;
  // Image observations only: NatureCNN's passes, and its parameters as torch modules (their
  // names are the checkpoints').
  std::optional<NatureCnn> nature_cnn_;
  torch::nn::Sequential cnn_{nullptr};
  Mlp context_{.activation = actor::Activation::kRelu};  // image policies' context branch
  Mlp pi_;
  Mlp vf_;
  torch::nn::Linear action_net_{nullptr};
  torch::nn::Linear value_net_{nullptr};
  torch::Tensor log_std_;  // continuous actions only
};
TORCH_MODULE(ActorCritic);

}  // namespace dcs::learner

#endif  // DCS_LEARNER_ACTOR_CRITIC_H_
