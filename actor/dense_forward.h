// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_DENSE_FORWARD_H_
#define DCS_ACTOR_DENSE_FORWARD_H_

// Dense layers on batches, in Eigen: actors' inference (actor/policy_network.h) computes them
// with DenseForward; the learner's passes (learner/actor_critic.h) with matrix-matrix products
// of their own, and the same Activate. A batch holds one sample per column ([features x
// samples], column-major), so a sample's values are contiguous, as in a row-major [samples x
// features] array (a torch tensor of a batch). tanh is Eigen's vectorised rational
// approximation (within a few units in the last place of std::tanh), the same in both.
// Thread-safe (free functions on their arguments).

#include <Eigen/Core>

#include "actor/policy_weights.h"

namespace dcs::actor {

using RowMajorMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// outputs = activation(weight * inputs + bias), `bias` added to every column; `outputs` is
// resized to [weight.rows() x inputs.cols()] (its memory is reused when it has that size).
// `weight` is a matrix of either storage order (Eigen's matrix-vector kernel for a tall matrix
// is faster by columns, for a short one by rows).
// A sample's outputs are a function of its own inputs alone, bit for bit, whatever else the
// batch holds: an episode acts the same whichever episodes share its batch, and a slot the same
// on whichever actor. For that, each column is its own matrix-vector product (Eigen's
// matrix-matrix kernels give a column inside a block of four other bits than a column left
// over, and take the matrix-vector kernel for a lone column); the bias and the activation go
// element by element, and Eigen computes an element alike in a vector register or alone (on
// x86-64-v3 its scalar code fuses multiply-adds as its vector code does).
// REQUIRES: weight.cols() == inputs.rows(), bias.size() == weight.rows().
template <typename Weight>
void DenseForward(const Eigen::MatrixBase<Weight>& weight,
                  const Eigen::Ref<const Eigen::VectorXf>& bias, Activation activation,
                  const Eigen::Ref<const Eigen::MatrixXf>& inputs, Eigen::MatrixXf& outputs);

// Applies `activation` to every element of `outputs`, in place.
void Activate(Activation activation, Eigen::MatrixXf& outputs);

// The backward pass of Activate: multiplies `d`, the gradient at its outputs, by the
// activation's derivative, written from `outputs` (tanh' = 1 - tanh^2; ReLU passes the gradient
// where its output is positive, as torch's threshold_backward), in place.
// REQUIRES: d has the shape of outputs.
void ActivationGradient(Activation activation, const Eigen::MatrixXf& outputs,
                        Eigen::MatrixXf& d);

// Implementation details.

template <typename Weight>
void DenseForward(const Eigen::MatrixBase<Weight>& weight,
                  const Eigen::Ref<const Eigen::VectorXf>& bias, Activation activation,
                  const Eigen::Ref<const Eigen::MatrixXf>& inputs, Eigen::MatrixXf& outputs) {
  // The bias first, the product added to it: Eigen's kernels add a product to what is there,
  // so this spares two passes over the batch and gives the same bits as bias after product.
  outputs.resize(weight.rows(), inputs.cols());
  outputs.colwise() = bias;
  for (Eigen::Index sample = 0; sample < inputs.cols(); ++sample) {
    outputs.col(sample).noalias() += weight * inputs.col(sample);
  }
  Activate(activation, outputs);
}

}  // namespace dcs::actor

#endif  // DCS_ACTOR_DENSE_FORWARD_H_
