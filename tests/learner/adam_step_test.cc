// Copyright 2026 The DCS Authors.
//
// AdamStep (learner/adam_step.h) against libtorch's own Adam: the same parameters and moments
// bit for bit, step after step, with a gradient scale below one (a clipped gradient) and at
// one; and its state is the optimiser's, saved and loaded by libtorch's serialisation.

#include "learner/adam_step.h"

#include <torch/torch.h>

#include <bit>
#include <cstdint>
#include <sstream>
#include <vector>

#include "gtest/gtest.h"

namespace dcs::learner {
namespace {

// 9,159 values: no multiple of a vector register's 8 floats, as CartPole's network's 9,155 is
// not, so a vectorised kernel's remainder is compared too.
constexpr int64_t kSize = 9159;

torch::optim::AdamOptions Options() { return torch::optim::AdamOptions(3e-4).eps(1e-5); }

// The elements of two float tensors that differ in any bit.
int64_t DifferingBits(const torch::Tensor& a, const torch::Tensor& b) {
  const torch::Tensor x = a.contiguous();
  const torch::Tensor y = b.contiguous();
  int64_t differing = 0;
  for (int64_t i = 0; i < x.numel(); ++i) {
    differing += std::bit_cast<uint32_t>(x.data_ptr<float>()[i]) !=
                 std::bit_cast<uint32_t>(y.data_ptr<float>()[i]);
  }
  return differing;
}

torch::optim::AdamParamState& StateOf(torch::optim::Adam& adam, const torch::Tensor& p) {
  return static_cast<torch::optim::AdamParamState&>(
      *adam.state().at(c10::guts::to_string(p.unsafeGetTensorImpl())));
}

TEST(AdamStepTest, IsLibtorchsAdamBitForBit) {
  torch::manual_seed(3);
  torch::Tensor ours = torch::randn({kSize});
  torch::Tensor theirs = ours.clone();
  ours.mutable_grad() = torch::zeros({kSize});
  theirs.mutable_grad() = torch::zeros({kSize});
  torch::optim::Adam our_adam({ours}, Options());
  torch::optim::Adam their_adam({theirs}, Options());
  for (int step = 0; step < 60; ++step) {
    const torch::Tensor gradient = torch::randn({kSize}) * (step % 7 + 1);
    // A clipped gradient every other step, as PPO's gradient-norm clip scales it.
    const float scale = step % 2 == 0 ? 0.37f : 1.0f;
    ours.mutable_grad().copy_(gradient);
    theirs.mutable_grad().copy_(gradient);
    AdamStep(our_adam, ours, scale);
    {
      torch::NoGradGuard no_grad;
      if (scale < 1.0f) theirs.mutable_grad().mul_(scale);
      their_adam.step();
    }
    ASSERT_EQ(DifferingBits(ours, theirs), 0) << "parameters after step " << step;
    ASSERT_EQ(DifferingBits(StateOf(our_adam, ours).exp_avg(),
                            StateOf(their_adam, theirs).exp_avg()), 0) << "step " << step;
    ASSERT_EQ(DifferingBits(StateOf(our_adam, ours).exp_avg_sq(),
                            StateOf(their_adam, theirs).exp_avg_sq()), 0) << "step " << step;
    ASSERT_EQ(StateOf(our_adam, ours).step(), step + 1);
  }
}

TEST(AdamStepTest, ItsStateSavesAndLoadsWithTheOptimiser) {
  torch::manual_seed(4);
  torch::Tensor p = torch::randn({kSize});
  p.mutable_grad() = torch::randn({kSize});
  torch::optim::Adam adam({p}, Options());
  for (int step = 0; step < 3; ++step) AdamStep(adam, p, 1.0f);

  std::stringstream bytes;
  {
    torch::serialize::OutputArchive archive;
    adam.save(archive);
    archive.save_to(bytes);
  }
  torch::Tensor q = p.detach().clone();
  q.mutable_grad() = p.grad().clone();
  torch::optim::Adam loaded({q}, Options());
  {
    torch::serialize::InputArchive archive;
    archive.load_from(bytes);
    loaded.load(archive);
  }
  EXPECT_EQ(StateOf(loaded, q).step(), 3);
  AdamStep(adam, p, 1.0f);
  AdamStep(loaded, q, 1.0f);
  EXPECT_EQ(DifferingBits(p, q), 0);
}

}  // namespace
}  // namespace dcs::learner
