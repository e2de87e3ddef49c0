// Copyright 2026 The DCS Authors.
#include "learner/adam_step.h"

#include <cmath>
#include <string>
#include <tuple>

namespace dcs::learner {
namespace {

// The parameter's state, created as libtorch's Adam::step creates it on the first step.
torch::optim::AdamParamState& StateOf(torch::optim::Adam& optimizer,
                                      const torch::Tensor& parameter) {
  // libtorch keys an optimiser's state by the address of the parameter's TensorImpl.
  const std::string key = c10::guts::to_string(parameter.unsafeGetTensorImpl());
  std::unique_ptr<torch::optim::OptimizerParamState>& state = optimizer.state()[key];
  if (state == nullptr) {
    auto created = std::make_unique<torch::optim::AdamParamState>();
    created->step(0);
    created->exp_avg(torch::zeros_like(parameter, torch::MemoryFormat::Preserve));
    created->exp_avg_sq(torch::zeros_like(parameter, torch::MemoryFormat::Preserve));
    state = std::move(created);
  }
  return static_cast<torch::optim::AdamParamState&>(*state);
}

}  // namespace

void AdamStep(torch::optim::Adam& optimizer, torch::Tensor& parameter, float gradient_scale) {
  const auto& options =
      static_cast<const torch::optim::AdamOptions&>(optimizer.param_groups().front().options());
  torch::optim::AdamParamState& state = StateOf(optimizer, parameter);
  state.step(state.step() + 1);
  const auto [beta1, beta2] = options.betas();
  // libtorch computes these in double and hands them to its float kernels as float.
  const double bias_correction1 = 1 - std::pow(beta1, state.step());
  const double bias_correction2 = 1 - std::pow(beta2, state.step());
  const auto beta1_f = static_cast<float>(beta1);
  const auto beta2_f = static_cast<float>(beta2);
  const auto one_minus_beta1 = static_cast<float>(1 - beta1);
  const auto one_minus_beta2 = static_cast<float>(1 - beta2);
  const auto bias_correction2_sqrt = static_cast<float>(std::sqrt(bias_correction2));
  const auto eps = static_cast<float>(options.eps());
  const auto step_size = static_cast<float>(-(options.lr() / bias_correction1));

  float* p = parameter.data_ptr<float>();
  const float* grad = parameter.grad().data_ptr<float>();
  float* m = state.exp_avg().data_ptr<float>();
  float* v = state.exp_avg_sq().data_ptr<float>();
  const int64_t n = parameter.numel();
  for (int64_t i = 0; i < n; ++i) {
    const float g = grad[i] * gradient_scale;  // grad.mul_(scale)
    // exp_avg.mul_(beta1).add_(grad, 1 - beta1): add's kernel is fmadd(grad, alpha, self).
    m[i] = std::fma(g, one_minus_beta1, m[i] * beta1_f);
    // exp_avg_sq.mul_(beta2).addcmul_(grad, grad, 1 - beta2): self + value * t1 * t2, whose
    // last product and sum libtorch's build fuses.
    v[i] = std::fma(one_minus_beta2 * g, g, v[i] * beta2_f);
    // (exp_avg_sq.sqrt() / sqrt(bias_correction2)).add_(eps), then
    // p.addcdiv_(exp_avg, denom, -step_size): self + value * t1 / t2.
    const float denom = std::sqrt(v[i]) / bias_correction2_sqrt + eps;
    p[i] = p[i] + step_size * m[i] / denom;
  }
}

}  // namespace dcs::learner
