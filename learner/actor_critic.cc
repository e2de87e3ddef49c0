// Copyright 2026 The DCS Authors.
#include "learner/actor_critic.h"

#include <ATen/CPUFunctions.h>

#include <cmath>
#include <numbers>
#include <tuple>

#include "absl/strings/str_cat.h"
#include "absl/synchronization/mutex.h"
#include "learner/torch_runtime.h"

namespace dcs::learner {
namespace {

// SB3's init_weights: orthogonal weights with `gain`, zero biases, for Linear and Conv2d.
void InitWeights(torch::nn::Module& module, double gain) {
  torch::NoGradGuard no_grad;
  absl::MutexLockMaybe blas(BlasMutex());  // orthogonal_ factorises with LAPACK
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

// `buffer`, (re)allocated if it does not have `sizes`.
torch::Tensor& Buffer(torch::Tensor& buffer, torch::IntArrayRef sizes) {
  if (!buffer.defined() || buffer.sizes() != sizes) buffer = torch::empty(sizes);
  return buffer;
}

// A parameter's gradient, allocated if it has none yet.
torch::Tensor& Gradient(torch::Tensor& parameter) {
  if (!parameter.grad().defined()) parameter.mutable_grad() = torch::zeros_like(parameter);
  return parameter.mutable_grad();
}

// out = a b, and out = c + a b (c broadcast): libtorch's matrix products, under BlasMutex.
void Product(torch::Tensor& out, const torch::Tensor& a, const torch::Tensor& b) {
  absl::MutexLockMaybe blas(BlasMutex());
  at::cpu::mm_out(out, a, b);
}
void ProductPlus(torch::Tensor& out, const torch::Tensor& c, const torch::Tensor& a,
                 const torch::Tensor& b) {
  absl::MutexLockMaybe blas(BlasMutex());
  at::cpu::addmm_out(out, c, a, b);
}

// out = input W^T + b, as torch::nn::Linear computes it.
void LinearForward(const torch::nn::LinearImpl& linear, const torch::Tensor& input,
                   torch::Tensor& out) {
  ProductPlus(Buffer(out, {input.size(0), linear.weight.size(0)}), linear.bias, input,
              linear.weight.t());
}

// The gradients of `linear`'s weight and bias from the gradient at its output.
void LinearGradients(torch::nn::LinearImpl& linear, const torch::Tensor& input,
                     const torch::Tensor& d_output) {
  Product(Gradient(linear.weight), d_output.t(), input);
  at::cpu::sum_out(Gradient(linear.bias), d_output, {0});
}

}  // namespace

const torch::Tensor& ActorCriticImpl::TanhMlp::Forward(const torch::Tensor& input,
                                                       std::vector<torch::Tensor>& outputs) {
  outputs.resize(layers.size());
  const torch::Tensor* x = &input;
  for (size_t l = 0; l < layers.size(); ++l) {
    LinearForward(*layers[l], *x, outputs[l]);
    at::cpu::tanh_out(outputs[l], outputs[l]);
    x = &outputs[l];
  }
  return *x;
}

void ActorCriticImpl::TanhMlp::Backward(torch::nn::Linear& head, const torch::Tensor& input,
                                        const std::vector<torch::Tensor>& outputs,
                                        const torch::Tensor& d_head,
                                        std::vector<torch::Tensor>& d_outputs,
                                        torch::Tensor* d_input) {
  d_outputs.resize(layers.size());
  LinearGradients(*head, outputs.empty() ? input : outputs.back(), d_head);
  // Down the layers: `d` is the gradient at the output of the linear layer `weight` belongs to.
  const torch::Tensor* d = &d_head;
  const torch::Tensor* weight = &head->weight;
  for (size_t l = layers.size(); l-- > 0;) {
    torch::Tensor& d_output = Buffer(d_outputs[l], outputs[l].sizes());
    Product(d_output, *d, *weight);
    at::cpu::tanh_backward_out(d_output, d_output, outputs[l]);
    LinearGradients(*layers[l], l == 0 ? input : outputs[l - 1], d_output);
    d = &d_output;
    weight = &layers[l]->weight;
  }
  if (d_input != nullptr) ProductPlus(*d_input, *d_input, *d, *weight);
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
    const int64_t flattened = [&] {
      torch::NoGradGuard no_grad;
      absl::MutexLockMaybe blas(BlasMutex());
      return cnn_
          ->forward(torch::zeros({1, spec.image_channels, spec.image_height, spec.image_width}))
          .size(1);
    }();
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
  action_net_ = register_module(
      "action_net", torch::nn::Linear(OutputsOf(config.pi_layers, features), spec.head_size()));
  value_net_ =
      register_module("value_net", torch::nn::Linear(OutputsOf(config.vf_layers, features), 1));
  InitWeights(*action_net_, 0.01);
  InitWeights(*value_net_, 1.0);
  if (!spec.discrete()) {
    log_std_ = register_parameter(
        "log_std", torch::full({spec.action_size}, config.log_std_init, torch::kFloat32));
  }
}

void ActorCriticImpl::Forward(const ObservationBatch& batch, bool record_image_graph,
                              Pass& pass) {
  // Not recorded: some of libtorch's kernels call dispatched operators (addmm copies the bias
  // into its output), which would otherwise chain autograd nodes on the reused buffers.
  torch::NoGradGuard no_grad;
  if (spec_.has_image()) {
    {
      absl::MutexLockMaybe blas(BlasMutex());
      torch::AutoGradMode graph(record_image_graph);
      pass.image_features = cnn_->forward(batch.images);
    }
    const torch::Tensor image_features = pass.image_features.detach();
    pass.features = spec_.context_size == 0 ? image_features
                                            : torch::cat({image_features, batch.flat}, 1);
  } else {
    pass.features = batch.flat;
  }
  LinearForward(*action_net_, pi_.Forward(pass.features, pass.pi), pass.head);
  LinearForward(*value_net_, vf_.Forward(pass.features, pass.vf), pass.values);
}

void ActorCriticImpl::Backward(Pass& pass, const torch::Tensor& d_head,
                               const torch::Tensor& d_values, const torch::Tensor& d_log_std) {
  torch::NoGradGuard no_grad;
  torch::Tensor* d_features = nullptr;
  if (spec_.has_image()) {
    Buffer(pass.d_features, pass.features.sizes()).zero_();
    d_features = &pass.d_features;
  }
  pi_.Backward(action_net_, pass.features, pass.pi, d_head, pass.d_pi, d_features);
  vf_.Backward(value_net_, pass.features, pass.vf, d_values, pass.d_vf, d_features);
  if (!spec_.discrete()) Gradient(log_std_).copy_(d_log_std);
  if (spec_.has_image()) {
    // NatureCNN's gradients through autograd, from the image features' part of d_features.
    for (torch::Tensor& parameter : cnn_->parameters()) Gradient(parameter).zero_();
    absl::MutexLockMaybe blas(BlasMutex());
    pass.image_features.backward(pass.d_features.narrow(1, 0, pass.image_features.size(1)));
  }
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
