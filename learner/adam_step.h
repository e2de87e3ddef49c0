// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_ADAM_STEP_H_
#define DCS_LEARNER_ADAM_STEP_H_

// torch.optim.Adam's step (libtorch 1.13's, without weight decay or AMSGrad) on one parameter
// tensor, computed in one pass over its elements instead of libtorch's eight (each with its own
// dispatch and temporaries), with the gradient scaled first, as a gradient-norm clip does:
//
//   g = scale * grad;  step += 1
//   m = beta1 * m + (1 - beta1) * g
//   v = beta2 * v + (1 - beta2) * g * g
//   p -= lr / (1 - beta1^step) * m / (sqrt(v) / sqrt(1 - beta2^step) + eps)
//
// in float32, each operation where and as libtorch's vectorised kernels do it, so that the result
// is theirs bit for bit (tested). The moments and the step count live in the optimiser's own
// state for the parameter, created as libtorch creates it, so the optimiser saves and loads as
// before.
//
// Internal to learner/. Confined to the thread that owns the optimiser.

#include <torch/torch.h>

namespace dcs::learner {

// REQUIRES: `parameter` is a contiguous float tensor of `optimizer` with a gradient of its shape;
// the optimiser has no weight decay and no AMSGrad.
void AdamStep(torch::optim::Adam& optimizer, torch::Tensor& parameter, float gradient_scale);

}  // namespace dcs::learner

#endif  // DCS_LEARNER_ADAM_STEP_H_
