// Copyright 2026 The DCS Authors.
#include "actor/dense_forward.h"

namespace dcs::actor {

void Activate(Activation activation, Eigen::MatrixXf& outputs) {
  switch (activation) {
    case Activation::kNone:
      break;
    case Activation::kTanh:
      outputs = outputs.array().tanh();
      break;
    case Activation::kRelu:
      outputs = outputs.cwiseMax(0.0f);
      break;
  }
}

void ActivationGradient(Activation activation, const Eigen::MatrixXf& outputs,
                        Eigen::MatrixXf& d) {
  switch (activation) {
    case Activation::kNone:
      break;
    case Activation::kTanh:
      d.array() *= 1 - outputs.array().square();
      break;
    case Activation::kRelu:
      d.array() *= (outputs.array() > 0).cast<float>();
      break;
  }
}

}  // namespace dcs::actor
