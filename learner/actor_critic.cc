// Copyright 2026 The DCS Authors.
#include "learner/actor_critic.h"

#include <cmath>
#include <numbers>
#include <tuple>

#include "absl/strings/str_cat.h"

namespace dcs::learner {
namespace {

// SB3's init_weights: orthogonal weights with `gain`, zero biases, for Linear and Conv2d.
void InitWeights(torch::nn::Module& module, double gain) {
  torch::NoGradGuard no_grad;
  for (auto& child : module.modules(/*include_self=*/true)) {
    if (auto* linear = child->as<torch::nn::Linear>()) {
      torch::nn::init::orthogonal_(linear->weight, gain);
      linear->bias.zero_();
    } else if (auto* conv = child->as<torch::nn::Conv2d>()) {
      torch::nn::init::orthogonal_(conv->weight, gain);
      conv->bias.zero_();
    }
  }
}

// A tensor's elements, row-major.
std::vector<float> Floats(const torch::Tensor& tensor) {
  const torch::Tensor t = tensor.detach().contiguous();
  return std::vector<float>(t.data_ptr<float>(), t.data_ptr<float>() + t.numel());
}

actor::DenseLayer ExportDense(const torch::nn::LinearImpl& linear, actor::Activation activation) {
  return {.inputs = static_cast<int>(linear.weight.size(1)),
          .outputs = static_cast<int>(linear.weight.size(0)),
          .weight = Floats(linear.weight),
          .bias = Floats(linear.bias),
          .activation = activation};
}

int OutputsOf(const std::vector<int>& widths, int inputs) {
  return widths.empty() ? inputs : widths.back();
}

}  // namespace

torch::Tensor ActorCriticImpl::TanhMlp::Forward(torch::Tensor x) {
  for (torch::nn::Linear& layer : layers) x = torch::tanh(layer->forward(x));
  return x;
}

ActorCriticImpl::ActorCriticImpl(const run::PolicySpec& spec, const run::PpoConfig& config)
    : spec_(spec) {
  const double sqrt2 = std::numbers::sqrt2;
  int features = spec.flat_input_size();
  if (spec.has_image()) {
    // NatureCNN: 8x8/4, 4x4/2, 3x3/1 convolutions with ReLU, then Linear -> ReLU.
    cnn_ = torch::nn::Sequential(
        torch::nn::Conv2d(torch::nn::Conv2dOptions(spec.image_channels, 32, 8).stride(4)),
        torch::nn::ReLU(),
        torch::nn::Conv2d(torch::nn::Conv2dOptions(32, 64, 4).stride(2)), torch::nn::ReLU(),
        torch::nn::Conv2d(torch::nn::Conv2dOptions(64, 64, 3).stride(1)), torch::nn::ReLU(),
        torch::nn::Flatten());
    torch::NoGradGuard no_grad;
    const int64_t flattened =
        cnn_->forward(torch::zeros({1, spec.image_channels, spec.image_height, spec.image_width}))
            .size(1);
    cnn_->push_back(torch::nn::Linear(flattened, config.cnn_features));
    cnn_->push_back(torch::nn::ReLU());
    register_module("cnn", cnn_);
    InitWeights(*cnn_, sqrt2);
    features = config.cnn_features + spec.context_size;
  }
  for (auto [mlp, widths, name] : {std::tuple{&pi_, &config.pi_layers, "pi"},
                                   std::tuple{&vf_, &config.vf_layers, "vf"}}) {
    int inputs = features;
    for (size_t i = 0; i < widths->size(); ++i) {
      mlp->layers.push_back(register_module(absl::StrCat(name, "_", i),
                                            torch::nn::Linear(inputs, (*widths)[i])));
      InitWeights(*mlp->layers.back(), sqrt2);
      inputs = (*widths)[i];
    }
  }
  const int action_outputs = spec.discrete() ? spec.num_actions : spec.action_size;
  action_net_ = register_module(
      "action_net", torch::nn::Linear(OutputsOf(config.pi_layers, features), action_outputs));
  value_net_ =
      register_module("value_net", torch::nn::Linear(OutputsOf(config.vf_layers, features), 1));
  InitWeights(*action_net_, 0.01);
  InitWeights(*value_net_, 1.0);
  if (!spec.discrete()) {
    log_std_ = register_parameter(
        "log_std", torch::full({spec.action_size}, config.log_std_init, torch::kFloat32));
  }
}

torch::Tensor ActorCriticImpl::Features(const ObservationBatch& batch) {
  if (!spec_.has_image()) return batch.flat;
  torch::Tensor image_features = cnn_->forward(batch.images);
  if (spec_.context_size == 0) return image_features;
  return torch::cat({image_features, batch.flat}, 1);
}

torch::Tensor ActorCriticImpl::ActionHead(const ObservationBatch& batch) {
  return action_net_->forward(pi_.Forward(Features(batch)));
}

torch::Tensor ActorCriticImpl::Value(const ObservationBatch& batch) {
  return value_net_->forward(vf_.Forward(Features(batch))).squeeze(1);
}

ActorCriticImpl::Evaluation ActorCriticImpl::EvaluateActions(const ObservationBatch& batch,
                                                             const torch::Tensor& actions,
                                                             bool entropy_gradient) {
  const torch::Tensor features = Features(batch);
  const torch::Tensor head = action_net_->forward(pi_.Forward(features));
  Evaluation evaluation;
  evaluation.values = value_net_->forward(vf_.Forward(features)).squeeze(1);
  if (spec_.discrete()) {
    // torch.distributions.Categorical(logits): normalised by logsumexp.
    const torch::Tensor log_p = torch::log_softmax(head, 1);
    evaluation.log_probs = log_p.gather(1, actions).squeeze(1);
    torch::AutoGradMode entropy_mode(entropy_gradient);
    evaluation.entropy = -(log_p.exp() * log_p).sum(1);
  } else {
    // A diagonal Gaussian, summed over action dimensions.
    static const double kHalfLog2Pi = 0.5 * std::log(2 * std::numbers::pi);
    const torch::Tensor z = (actions - head) * torch::exp(-log_std_);
    evaluation.log_probs = (-0.5 * z * z - log_std_ - kHalfLog2Pi).sum(1);
    torch::AutoGradMode entropy_mode(entropy_gradient);
    evaluation.entropy = (0.5 + kHalfLog2Pi + log_std_).sum().expand({head.size(0)});
  }
  return evaluation;
}

actor::PolicyWeights ActorCriticImpl::ExportActor() const {
  actor::PolicyWeights weights;
  weights.num_actions = spec_.num_actions;
  if (spec_.has_image()) {
    actor::ImageEncoderWeights& image = weights.image.emplace();
    image.height = spec_.image_height;
    image.width = spec_.image_width;
    image.channels = spec_.image_channels;
    for (const std::shared_ptr<torch::nn::Module>& child : cnn_->children()) {
      if (const auto* conv = child->as<torch::nn::Conv2d>()) {
        const torch::Tensor& w = conv->weight;
        image.convs.push_back({.in_channels = static_cast<int>(w.size(1)),
                               .out_channels = static_cast<int>(w.size(0)),
                               .kernel = static_cast<int>(w.size(2)),
                               .stride = static_cast<int>(conv->options.stride()->at(0)),
                               .weight = Floats(w),
                               .bias = Floats(conv->bias)});
      } else if (const auto* linear = child->as<torch::nn::Linear>()) {
        image.linear = ExportDense(*linear, actor::Activation::kRelu);
      }
    }
  }
  for (const torch::nn::Linear& layer : pi_.layers) {
    weights.layers.push_back(ExportDense(*layer, actor::Activation::kTanh));
  }
  weights.layers.push_back(ExportDense(*action_net_, actor::Activation::kNone));
  if (!spec_.discrete()) weights.log_std = Floats(log_std_);
  return weights;
}

}  // namespace dcs::learner
