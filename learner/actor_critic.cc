// Copyright 2026 The DCS Authors.
#include "learner/actor_critic.h"

#include <cmath>
#include <numbers>
#include <tuple>

#include "absl/strings/str_cat.h"
#include "absl/synchronization/mutex.h"
#include "actor/dense_forward.h"
#include "actor/eigen_blocking.h"
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

// A parameter's gradient, allocated if it has none yet.
torch::Tensor& Gradient(torch::Tensor& parameter) {
  if (!parameter.grad().defined()) parameter.mutable_grad() = torch::zeros_like(parameter);
  return parameter.mutable_grad();
}

// NatureCNN's parameters, or their gradients, as its passes take them from `tensors`: each
// layer's weight, then its bias, layer after layer (the order of cnn_->parameters()).
template <typename T>
NatureCnn::Tensors<T> CnnLayers(const std::vector<torch::Tensor>& tensors) {
  NatureCnn::Tensors<T> layers;
  int layer = 0;
  for (const torch::Tensor& t : tensors) {
    auto& slot = t.dim() == 1 ? layers.biases[layer++] : layers.weights[layer];
    slot = {t.data_ptr<float>(), static_cast<size_t>(t.numel())};
  }
  return layers;
}

using ConstView = Eigen::Map<const Eigen::MatrixXf>;

// A Linear's weight, [outputs x inputs] row-major as torch stores it, and its bias.
Eigen::Map<const actor::RowMajorMatrix> WeightOf(const torch::nn::LinearImpl& linear) {
  return {linear.weight.data_ptr<float>(), linear.weight.size(0), linear.weight.size(1)};
}
Eigen::Map<const Eigen::VectorXf> BiasOf(const torch::nn::LinearImpl& linear) {
  return {linear.bias.data_ptr<float>(), linear.bias.size(0)};
}

ConstView View(const Eigen::MatrixXf& matrix) {
  return {matrix.data(), matrix.rows(), matrix.cols()};
}

// `tensor` [B, F] (contiguous) as a batch of B columns.
ConstView BatchView(const torch::Tensor& tensor) {
  return {tensor.data_ptr<float>(), tensor.size(1), tensor.size(0)};
}

// The gradients of `linear`'s weight and bias from the gradient at its output.
void LinearGradients(torch::nn::LinearImpl& linear, ConstView input,
                     const Eigen::MatrixXf& d_output) {
  torch::Tensor& d_weight = Gradient(linear.weight);
  Eigen::Map<actor::RowMajorMatrix>(d_weight.data_ptr<float>(), d_weight.size(0),
                                    d_weight.size(1))
      .noalias() = d_output * input.transpose();
  Eigen::Map<Eigen::VectorXf>(Gradient(linear.bias).data_ptr<float>(), d_output.rows()) =
      d_output.rowwise().sum();
}

// outputs = activation(W input + b) for the whole batch at once: one matrix-matrix product
// (the learner's batches have fixed shapes, so it needs no per-sample bits as actors do).
void LinearForward(const torch::nn::LinearImpl& linear, actor::Activation activation,
                   ConstView input, Eigen::MatrixXf& outputs) {
  outputs.resize(linear.weight.size(0), input.cols());
  outputs.colwise() = BiasOf(linear);  // the product is added to the bias
  outputs.noalias() += WeightOf(linear) * input;
  actor::Activate(activation, outputs);
}

}  // namespace

void ActorCriticImpl::Mlp::Forward(ConstView input, std::vector<Eigen::MatrixXf>& outputs) const {
  outputs.resize(layers.size());
  for (size_t l = 0; l < layers.size(); ++l) {
    LinearForward(*layers[l], activation, l == 0 ? input : View(outputs[l - 1]), outputs[l]);
  }
}

ActorCriticImpl::Mlp::ConstView ActorCriticImpl::Mlp::Output(
    ConstView input, const std::vector<Eigen::MatrixXf>& outputs) const {
  return layers.empty() ? input : View(outputs.back());
}

void ActorCriticImpl::Mlp::Backward(ConstView input, const std::vector<Eigen::MatrixXf>& outputs,
                                    const torch::nn::LinearImpl* above,
                                    const Eigen::MatrixXf& d_above,
                                    std::vector<Eigen::MatrixXf>& d_outputs,
                                    Eigen::MatrixXf* d_input) {
  d_outputs.resize(layers.size());
  const auto input_of = [&](size_t l) { return l == 0 ? input : View(outputs[l - 1]); };
  // Down the layers: `d` is the gradient at the output of `linear` (the layer above the one
  // whose gradient is made), or at the MLP's output where there is no such layer.
  const Eigen::MatrixXf* d = &d_above;
  const torch::nn::LinearImpl* linear = above;
  for (size_t l = layers.size(); l-- > 0;) {
    Eigen::MatrixXf& d_output = d_outputs[l];
    if (linear != nullptr) {
      d_output.noalias() = WeightOf(*linear).transpose() * *d;
    } else {
      d_output = *d;
    }
    actor::ActivationGradient(activation, outputs[l], d_output);
    LinearGradients(*layers[l], input_of(l), d_output);
    d = &d_output;
    linear = layers[l].get();
  }
  if (d_input == nullptr) return;
  if (linear != nullptr) {
    d_input->noalias() += WeightOf(*linear).transpose() * *d;
  } else {
    *d_input += *d;
  }
}

void ActorCriticImpl::Forward(const Mlp& mlp, const torch::nn::Linear& head, Mlp::ConstView input,
                              std::vector<Eigen::MatrixXf>& outputs,
                              Eigen::MatrixXf& head_output) {
  mlp.Forward(input, outputs);
  LinearForward(*head, actor::Activation::kNone, mlp.Output(input, outputs), head_output);
}

void ActorCriticImpl::Backward(Mlp& mlp, torch::nn::Linear& head, Mlp::ConstView input,
                               const std::vector<Eigen::MatrixXf>& outputs,
                               const Eigen::MatrixXf& d_head,
                               std::vector<Eigen::MatrixXf>& d_outputs, Eigen::MatrixXf* d_input) {
  LinearGradients(*head, mlp.Output(input, outputs), d_head);
  mlp.Backward(input, outputs, head.get(), d_head, d_outputs, d_input);
}

ActorCriticImpl::ActorCriticImpl(const run::PolicySpec& spec, const run::PpoConfig& config)
    : spec_(spec) {
  const double sqrt2 = std::numbers::sqrt2;
  int features = spec.flat_input_size();
  if (spec.has_image()) {
    // As SB3's NatureCNN module: each convolution and ReLU, Flatten, then Linear and ReLU.
    nature_cnn_.emplace(spec.image_height, spec.image_width, spec.image_channels,
                        config.cnn_features);
    cnn_ = torch::nn::Sequential();
    for (const ConvShape& conv : nature_cnn_->convs()) {
      cnn_->push_back(torch::nn::Conv2d(
          torch::nn::Conv2dOptions(conv.in_channels, conv.out_channels, conv.kernel)
              .stride(conv.stride)));
      cnn_->push_back(torch::nn::ReLU());
    }
    cnn_->push_back(torch::nn::Flatten());
    cnn_->push_back(torch::nn::Linear(nature_cnn_->flattened_size(), config.cnn_features));
    cnn_->push_back(torch::nn::ReLU());
    register_module("cnn", cnn_);
    InitWeights(*cnn_, sqrt2);
    features = config.cnn_features +
               (spec.context_size > 0 ? OutputsOf(config.context_layers, spec.context_size) : 0);
  }
  // The context branch exists for image policies that observe a context and ask for it.
  const std::vector<int> no_layers;
  const std::vector<int>& context_widths =
      spec.has_image() && spec.context_size > 0 ? config.context_layers : no_layers;
  for (auto [mlp, widths, name, inputs] :
       {std::tuple{&context_, &context_widths, "context", spec.context_size},
        std::tuple{&pi_, &config.pi_layers, "pi", features},
        std::tuple{&vf_, &config.vf_layers, "vf", features}}) {
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

void ActorCriticImpl::Forward(const ObservationBatch& batch, bool for_backward, Pass& pass) {
  torch::NoGradGuard no_grad;
  actor::PinEigenBlocking();
  if (spec_.has_image()) {
    const auto count = static_cast<int>(batch.flat.size(0));
    nature_cnn_->Forward(CnnLayers<const float>(cnn_->parameters()), batch.images, count,
                         for_backward, pass.cnn, pass.image_features);
    // The MLPs' input: the image's features, then the context, as it is or through its branch.
    const Eigen::Index image_rows = pass.image_features.rows();
    Eigen::Index rows = image_rows;
    if (!context_.layers.empty()) {
      pass.context_input = batch.flat.contiguous();
      context_.Forward(BatchView(pass.context_input), pass.context);
      rows += pass.context.back().rows();
    } else {
      rows += spec_.context_size;
    }
    pass.features = torch::empty({count, rows});
    Eigen::Map<Eigen::MatrixXf> features(pass.features.data_ptr<float>(), rows, count);
    features.topRows(image_rows) = pass.image_features;
    if (!context_.layers.empty()) {
      features.bottomRows(rows - image_rows) = pass.context.back();
    } else if (spec_.context_size > 0) {
      features.bottomRows(rows - image_rows) = BatchView(batch.flat.contiguous());
    }
  } else {
    pass.features = batch.flat.contiguous();
  }
  const ConstView features = BatchView(pass.features);
  Forward(pi_, action_net_, features, pass.pi, pass.head);
  Forward(vf_, value_net_, features, pass.vf, pass.values);
}

void ActorCriticImpl::Backward(Pass& pass, const Eigen::MatrixXf& d_head,
                               const Eigen::MatrixXf& d_values,
                               std::span<const float> d_log_std) {
  torch::NoGradGuard no_grad;
  actor::PinEigenBlocking();
  const ConstView features = BatchView(pass.features);
  Eigen::MatrixXf* d_features = nullptr;
  if (spec_.has_image()) {
    pass.d_features.setZero(features.rows(), features.cols());
    d_features = &pass.d_features;
  }
  Backward(pi_, action_net_, features, pass.pi, d_head, pass.d_pi, d_features);
  Backward(vf_, value_net_, features, pass.vf, d_values, pass.d_vf, d_features);
  if (!spec_.discrete()) {
    std::copy(d_log_std.begin(), d_log_std.end(), Gradient(log_std_).data_ptr<float>());
  }
  if (!context_.layers.empty()) {
    // The branch's gradients from its part of d_features, the rows after the image's features.
    pass.d_context_output = pass.d_features.bottomRows(pass.context.back().rows());
    context_.Backward(BatchView(pass.context_input), pass.context, nullptr, pass.d_context_output,
                      pass.d_context, nullptr);
  }
  if (spec_.has_image()) {
    // NatureCNN's gradients from the image features' part of d_features.
    std::vector<torch::Tensor> parameters = cnn_->parameters();
    std::vector<torch::Tensor> gradients;
    for (torch::Tensor& parameter : parameters) gradients.push_back(Gradient(parameter));
    nature_cnn_->Backward(CnnLayers<const float>(parameters),
                          pass.d_features.topRows(pass.image_features.rows()), pass.cnn,
                          CnnLayers<float>(gradients));
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
  for (const torch::nn::Linear& layer : context_.layers) {
    weights.context_layers.push_back(ExportDense(*layer, actor::Activation::kRelu));
  }
  for (const torch::nn::Linear& layer : pi_.layers) {
    weights.layers.push_back(ExportDense(*layer, actor::Activation::kTanh));
  }
  weights.layers.push_back(ExportDense(*action_net_, actor::Activation::kNone));
  if (!spec_.discrete()) weights.log_std = Floats(log_std_);
  return weights;
}

std::vector<std::pair<std::string, torch::Tensor>> ActorCriticImpl::Sb3Parameters(
    absl::string_view image_key, absl::string_view context_key) const {
  using Named = std::vector<std::pair<std::string, torch::Tensor>>;
  const auto add = [](Named& named, const std::string& prefix, const torch::Tensor& weight,
                      const torch::Tensor& bias) {
    named.emplace_back(prefix + ".weight", weight.detach().clone());
    named.emplace_back(prefix + ".bias", bias.detach().clone());
  };
  Named named;
  // A module's own parameters come before its children's in a state_dict.
  if (!spec_.discrete()) named.emplace_back("log_std", log_std_.detach().clone());
  if (spec_.has_image()) {
    // NatureCNN is two Sequentials in SB3: `cnn` (convolutions and ReLUs, then Flatten) and
    // `linear` (Linear, ReLU); cnn_ is their concatenation, so its Linear is linear.0.
    const std::string image = absl::StrCat("extractors.", image_key);
    Named extractor;
    const std::vector<std::shared_ptr<torch::nn::Module>> cnn = cnn_->children();
    for (size_t i = 0; i < cnn.size(); ++i) {
      if (const auto* conv = cnn[i]->as<torch::nn::Conv2d>()) {
        add(extractor, absl::StrCat(image, ".cnn.", i), conv->weight, conv->bias);
      } else if (const auto* linear = cnn[i]->as<torch::nn::Linear>()) {
        add(extractor, image + ".linear.0", linear->weight, linear->bias);
      }
    }
    for (size_t i = 0; i < context_.layers.size(); ++i) {
      const torch::nn::LinearImpl& layer = *context_.layers[i];
      add(extractor, absl::StrCat("extractors.", context_key, ".", 2 * i), layer.weight,
          layer.bias);
    }
    for (const char* owner :
         {"features_extractor", "pi_features_extractor", "vf_features_extractor"}) {
      for (const auto& [name, tensor] : extractor) {
        named.emplace_back(absl::StrCat(owner, ".", name), tensor);
      }
    }
  }
  // MlpExtractor's Sequentials: Linear at even indices, Tanh at odd ones.
  for (auto [mlp, prefix] : {std::pair{&pi_, "mlp_extractor.policy_net."},
                             std::pair{&vf_, "mlp_extractor.value_net."}}) {
    for (size_t i = 0; i < mlp->layers.size(); ++i) {
      add(named, absl::StrCat(prefix, 2 * i), mlp->layers[i]->weight, mlp->layers[i]->bias);
    }
  }
  add(named, "action_net", action_net_->weight, action_net_->bias);
  add(named, "value_net", value_net_->weight, value_net_->bias);
  return named;
}

}  // namespace dcs::learner
