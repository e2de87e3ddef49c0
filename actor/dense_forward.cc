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

}  // namespace dcs::actor
