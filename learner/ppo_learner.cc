// Copyright 2026 The DCS Authors.
#include "learner/ppo_learner.h"

#include <torch/torch.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/synchronization/mutex.h"
#include "common/random.h"
#include "common/status_macros.h"
#include "learner/actor_critic.h"
#include "learner/adam_step.h"
#include "learner/gae.h"
#include "learner/ppo_loss.h"

namespace dcs::learner {
namespace {

absl::Status CheckSize(size_t actual, size_t expected, absl::string_view what) {
  if (actual == expected) return absl::OkStatus();
  return absl::InvalidArgumentError(
      absl::StrCat("rollout: ", what, " has ", actual, " values, expected ", expected));
}

absl::Status CheckFinite(const std::vector<float>& values, int per_transition, int num_envs,
                         absl::string_view what) {
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      const size_t transition = i / per_transition;
      return absl::InvalidArgumentError(absl::StrCat("rollout: ", what, " of step ",
                                                     transition / num_envs, ", slot ",
                                                     transition % num_envs, " is not finite (",
                                                     values[i], ")"));
    }
  }
  return absl::OkStatus();
}

// The elements of a contiguous float tensor, and of an Eigen matrix (column by column).
std::span<const float> Floats(const torch::Tensor& tensor) {
  return {tensor.data_ptr<float>(), static_cast<size_t>(tensor.numel())};
}
std::span<const float> Floats(const Eigen::MatrixXf& matrix) {
  return {matrix.data(), static_cast<size_t>(matrix.size())};
}
std::span<float> MutableFloats(Eigen::MatrixXf& matrix) {
  return {matrix.data(), static_cast<size_t>(matrix.size())};
}

// The Euclidean norm of `values`, for torch.nn.utils.clip_grad_norm_; summed in double (torch
// sums in float, in an order of its own, so the two may differ in the last bit).
float Norm(std::span<const float> values) {
  double squares = 0;
  for (float v : values) squares += static_cast<double>(v) * v;
  return static_cast<float>(std::sqrt(squares));
}

// `values`, `width` per transition, in the order `order`.
template <typename T>
std::vector<T> Gather(const std::vector<T>& values, const std::vector<int64_t>& order,
                      int64_t width) {
  std::vector<T> gathered(values.size());
  for (size_t i = 0; i < order.size(); ++i) {
    std::copy_n(values.begin() + order[i] * width, width, gathered.begin() + i * width);
  }
  return gathered;
}

// The mean of `values` and the sum of their squared deviations from it, in double.
// REQUIRES: `values` non-empty.
struct Spread {
  double mean = 0;
  double squares = 0;
};
template <typename T>
Spread SpreadOf(std::span<const T> values) {
  Spread spread;
  for (T v : values) spread.mean += v;
  spread.mean /= static_cast<double>(values.size());
  for (T v : values) spread.squares += (v - spread.mean) * (v - spread.mean);
  return spread;
}

// Population variance (numpy's var).
template <typename T>
double Variance(std::span<const T> values) {
  return SpreadOf(values).squares / static_cast<double>(values.size());
}

// (x - mean) / (std + 1e-8) with the unbiased std, in place; a single value is left as is.
void NormalizeMinibatch(std::span<float> values) {
  if (values.size() < 2) return;
  const Spread spread = SpreadOf(std::span<const float>(values));
  const double std = std::sqrt(spread.squares / static_cast<double>(values.size() - 1));
  for (float& v : values) v = static_cast<float>((v - spread.mean) / (std + 1e-8));
}

}  // namespace

struct PpoLearner::Impl {
  run::PolicySpec spec;
  run::PpoConfig config;
  int n_envs = 1;
  uint64_t seed = 0;
  ActorCritic network{nullptr};
  // Every parameter is a view into flat_parameters and its gradient a view into
  // flat_gradients, so the gradient-norm clip and Adam run over one array in one pass
  // (learner/adam_step.h). Elementwise the arithmetic is the same as per layer.
  torch::Tensor flat_parameters;
  torch::Tensor flat_gradients;
  std::unique_ptr<torch::optim::Adam> optimizer;
  int64_t updates = 0;
  // Buffers of the network's passes: the rollout's, its bootstrap values', a minibatch's.
  ActorCriticImpl::Pass rollout_pass;
  ActorCriticImpl::Pass bootstrap_pass;
  ActorCriticImpl::Pass minibatch_pass;

  // The Gaussian policy's log-std (a view of flat_parameters); empty for categorical policies.
  std::span<const float> LogStd() const {
    return spec.discrete() ? std::span<const float>() : Floats(network->log_std());
  }

  // Makes the network's parameters views into flat_parameters (copying their values) and their
  // gradients views into flat_gradients. Again after loading, which replaces the tensors.
  void Flatten() {
    torch::NoGradGuard no_grad;
    std::vector<torch::Tensor> parameters = network->parameters();
    int64_t total = 0;
    for (const torch::Tensor& p : parameters) total += p.numel();
    if (!flat_parameters.defined()) {
      flat_parameters = torch::zeros({total});
      flat_gradients = torch::zeros({total});
      flat_parameters.mutable_grad() = flat_gradients;
    }
    int64_t offset = 0;
    for (torch::Tensor& p : parameters) {
      const int64_t size = p.numel();
      flat_parameters.narrow(0, offset, size).copy_(p.detach().reshape({-1}));
      p.set_data(flat_parameters.narrow(0, offset, size).view(p.sizes()));
      p.mutable_grad() = flat_gradients.narrow(0, offset, size).view(p.sizes());
      offset += size;
    }
  }

  // The observations of `count` transitions as tensors viewing `inputs` and `images` (not
  // copied: the batch lives only as long as they do).
  ObservationBatch Batch(std::span<const float> inputs, std::span<const uint8_t> images,
                         int64_t count) const {
    return {.flat = torch::from_blob(const_cast<float*>(inputs.data()),
                                     {count, spec.flat_input_size()}, torch::kFloat32),
            .images = images};
  }

  absl::Status Validate(const actor::Rollout& r) const {
    if (r.num_envs != n_envs || r.num_steps < 1) {
      return absl::InvalidArgumentError(absl::StrCat("rollout: ", r.num_steps, " steps of ",
                                                     r.num_envs, " slots, expected ", n_envs,
                                                     " slots"));
    }
    const size_t n = static_cast<size_t>(r.num_steps) * r.num_envs;
    const size_t image = spec.image_size();
    DCS_RETURN_IF_ERROR(CheckSize(r.inputs.size(), n * spec.flat_input_size(), "inputs"));
    DCS_RETURN_IF_ERROR(CheckSize(r.images.size(), n * image, "images"));
    DCS_RETURN_IF_ERROR(CheckSize(r.actions.size(), n * spec.action_size, "actions"));
    DCS_RETURN_IF_ERROR(CheckSize(r.rewards.size(), n, "rewards"));
    DCS_RETURN_IF_ERROR(CheckSize(r.episode_starts.size(), n, "episode starts"));
    DCS_RETURN_IF_ERROR(
        CheckSize(r.last_inputs.size(), static_cast<size_t>(n_envs) * spec.flat_input_size(),
                  "last inputs"));
    DCS_RETURN_IF_ERROR(
        CheckSize(r.last_images.size(), static_cast<size_t>(n_envs) * image, "last images"));
    DCS_RETURN_IF_ERROR(CheckSize(r.last_dones.size(), n_envs, "last dones"));
    for (const actor::Rollout::Truncation& cut : r.truncations) {
      if (cut.step < 0 || cut.step >= r.num_steps || cut.env < 0 || cut.env >= n_envs) {
        return absl::InvalidArgumentError(absl::StrCat("rollout: a truncation at step ",
                                                       cut.step, ", slot ", cut.env,
                                                       " is outside the rollout"));
      }
      DCS_RETURN_IF_ERROR(
          CheckSize(cut.input.size(), spec.flat_input_size(), "a truncation's input"));
      DCS_RETURN_IF_ERROR(CheckSize(cut.image.size(), image, "a truncation's image"));
      DCS_RETURN_IF_ERROR(CheckFinite(cut.input, spec.flat_input_size(), 1,
                                      "a truncation's final observation"));
    }
    if (spec.flat_input_size() > 0) {
      DCS_RETURN_IF_ERROR(CheckFinite(r.inputs, spec.flat_input_size(), n_envs, "observation"));
      DCS_RETURN_IF_ERROR(
          CheckFinite(r.last_inputs, spec.flat_input_size(), 1, "last observation"));
    }
    DCS_RETURN_IF_ERROR(CheckFinite(r.actions, spec.action_size, n_envs, "action"));
    return CheckFinite(r.rewards, 1, n_envs, "reward");
  }

  absl::StatusOr<UpdateStats> Update(const actor::Rollout& r);
};

absl::StatusOr<UpdateStats> PpoLearner::Impl::Update(const actor::Rollout& r) {
  const int64_t n = static_cast<int64_t>(r.num_steps) * r.num_envs;
  const ObservationBatch all = Batch(r.inputs, r.images, n);
  const auto image_size = static_cast<int64_t>(spec.image_size());
  const auto gamma = static_cast<float>(config.gamma);

  // Values and log-probabilities at collection time (the policy has not changed since).
  std::vector<float> values(n);
  std::vector<float> old_log_probs(n);
  std::vector<float> rewards = r.rewards;
  std::vector<float> last_values(r.num_envs);
  network->Forward(all, /*for_backward=*/false, rollout_pass);
  std::ranges::copy(Floats(rollout_pass.values), values.begin());
  ActionLogProbs(spec, Floats(rollout_pass.head), LogStd(), r.actions, old_log_probs);
  // A time-limit cut continues in expectation: r += gamma * V(final observation).
  for (const actor::Rollout::Truncation& cut : r.truncations) {
    network->Forward(Batch(cut.input, cut.image, 1), false, bootstrap_pass);
    rewards[static_cast<size_t>(cut.step) * r.num_envs + cut.env] +=
        gamma * bootstrap_pass.values(0, 0);
  }
  network->Forward(Batch(r.last_inputs, r.last_images, r.num_envs), false, bootstrap_pass);
  std::ranges::copy(Floats(bootstrap_pass.values), last_values.begin());

  std::vector<float> advantages(n);
  std::vector<float> returns(n);
  ComputeGae({r.num_steps, r.num_envs, rewards, values, r.episode_starts, last_values,
              r.last_dones},
             gamma, static_cast<float>(config.gae_lambda), advantages, returns);

  UpdateStats stats;
  // Sums over minibatches of what SB3 logs.
  PpoLoss sums;
  int minibatches = 0;
  double grad_norms = 0;  // summed over gradient steps
  Eigen::MatrixXf d_head;
  Eigen::MatrixXf d_values;
  std::vector<float> d_log_std(spec.discrete() ? 0 : spec.action_size);
  std::vector<int64_t> order(n);
  for (int epoch = 0; epoch < config.n_epochs && !stats.stopped_early; ++epoch) {
    // A fresh permutation each epoch (Fisher-Yates), from a stream of (update, epoch); the
    // epoch's data is gathered once in that order and each minibatch is a slice of it.
    std::iota(order.begin(), order.end(), 0);
    Random random(StreamSeed(seed, "minibatch", {static_cast<uint64_t>(updates),
                                                 static_cast<uint64_t>(epoch)}));
    for (int64_t i = n - 1; i > 0; --i) std::swap(order[i], order[random.Integers(0, i + 1)]);
    std::vector<float> epoch_inputs = Gather(r.inputs, order, spec.flat_input_size());
    const std::vector<uint8_t> epoch_images = Gather(r.images, order, image_size);
    const std::vector<float> epoch_actions = Gather(r.actions, order, spec.action_size);
    const std::vector<float> epoch_returns = Gather(returns, order, 1);
    const std::vector<float> epoch_log_probs = Gather(old_log_probs, order, 1);
    const std::vector<float> epoch_values = Gather(values, order, 1);
    // Advantages normalised per minibatch (mean 0, unbiased std 1, +1e-8 as SB3).
    std::vector<float> epoch_advantages = Gather(advantages, order, 1);
    if (config.normalize_advantage) {
      for (int64_t start = 0; start < n; start += config.batch_size) {
        NormalizeMinibatch(std::span<float>(epoch_advantages)
                               .subspan(start, std::min<int64_t>(config.batch_size, n - start)));
      }
    }

    for (int64_t start = 0; start < n; start += config.batch_size) {
      const int64_t size = std::min<int64_t>(config.batch_size, n - start);
      ObservationBatch batch{
          .flat = torch::from_blob(epoch_inputs.data() + start * spec.flat_input_size(),
                                   {size, spec.flat_input_size()})};
      batch.images = std::span<const uint8_t>(epoch_images).subspan(start * image_size,
                                                                      size * image_size);
      network->Forward(batch, /*for_backward=*/true, minibatch_pass);
      d_head.resize(spec.head_size(), size);
      d_values.resize(1, size);
      const auto slice = [start, size](const std::vector<float>& v, int64_t width = 1) {
        return std::span<const float>(v).subspan(start * width, size * width);
      };
      const PpoLoss loss = ComputePpoLoss(
          spec, config,
          {.size = static_cast<int>(size),
           .head = Floats(minibatch_pass.head),
           .values = Floats(minibatch_pass.values),
           .log_std = LogStd(),
           .actions = slice(epoch_actions, spec.action_size),
           .advantages = slice(epoch_advantages),
           .returns = slice(epoch_returns),
           .old_log_probs = slice(epoch_log_probs),
           .old_values = slice(epoch_values)},
          {.head = MutableFloats(d_head), .values = MutableFloats(d_values), .log_std = d_log_std});
      sums.policy += loss.policy;
      sums.value += loss.value;
      sums.entropy += loss.entropy;
      sums.clip_fraction += loss.clip_fraction;
      sums.approx_kl += loss.approx_kl;
      ++minibatches;
      if (config.target_kl.has_value() && loss.approx_kl > 1.5 * *config.target_kl) {
        stats.stopped_early = true;  // before this minibatch's step, as SB3
        break;
      }
      stats.loss = loss.total;
      if (!std::isfinite(stats.loss)) {
        return absl::InternalError(absl::StrCat("the loss became ", stats.loss, " in update ",
                                                updates, ", epoch ", epoch,
                                                "; the minibatch was not applied"));
      }
      network->Backward(minibatch_pass, d_head, d_values, d_log_std);
      // torch.nn.utils.clip_grad_norm_ over every parameter: one norm of the flat gradient,
      // coefficient max_norm / (norm + 1e-6) in float32 as torch computes it, clamped to 1;
      // Adam's step applies it to the gradient.
      const float grad_norm = Norm(Floats(flat_gradients));
      const float coefficient =
          static_cast<float>(config.max_grad_norm) / (grad_norm + static_cast<float>(1e-6));
      AdamStep(*optimizer, flat_parameters, std::min(coefficient, 1.0f));
      grad_norms += grad_norm;
      ++stats.gradient_steps;
    }
  }
  ++updates;

  stats.policy_loss = sums.policy / minibatches;
  stats.value_loss = sums.value / minibatches;
  stats.entropy_loss = sums.entropy / minibatches;
  stats.clip_fraction = sums.clip_fraction / minibatches;
  stats.approx_kl = sums.approx_kl / minibatches;
  // 1 - Var(returns - values) / Var(returns), NaN when the returns do not vary (as SB3).
  std::vector<double> residuals(n);
  for (int64_t i = 0; i < n; ++i) residuals[i] = static_cast<double>(returns[i]) - values[i];
  const double return_variance = Variance(std::span<const float>(returns));
  stats.explained_variance =
      return_variance == 0
          ? std::nan("")
          : 1 - Variance(std::span<const double>(residuals)) / return_variance;
  if (stats.gradient_steps > 0) stats.grad_norm = grad_norms / stats.gradient_steps;
  stats.learning_rate =
      static_cast<const torch::optim::AdamOptions&>(optimizer->param_groups().front().options())
          .lr();
  if (!spec.discrete()) {
    double std = 0;
    for (float log_std : LogStd()) std += std::exp(static_cast<double>(log_std));
    stats.std = std / spec.action_size;
  }
  return stats;
}

PpoLearner::PpoLearner(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
PpoLearner::~PpoLearner() = default;

absl::StatusOr<std::unique_ptr<PpoLearner>> PpoLearner::Create(const run::PolicySpec& spec,
                                                               const run::PpoConfig& config,
                                                               int n_envs, uint64_t seed) {
  DCS_RETURN_IF_ERROR(run::ValidatePolicySpec(spec));
  DCS_RETURN_IF_ERROR(run::ValidatePpoConfig(config, n_envs));
  auto impl = std::make_unique<Impl>();
  impl->spec = spec;
  impl->config = config;
  impl->n_envs = n_envs;
  impl->seed = seed;
  try {
    // Initial weights are the only draws from libtorch's own generator, which is one per
    // process: learners created at once on several threads take turns.
    static absl::Mutex generator_mutex;
    absl::MutexLock lock(&generator_mutex);
    torch::manual_seed(StreamSeed(seed, "init").GenerateState64(1)[0]);
    impl->network = ActorCritic(spec, config);
    impl->Flatten();
    impl->optimizer = std::make_unique<torch::optim::Adam>(
        std::vector<torch::Tensor>{impl->flat_parameters},
        torch::optim::AdamOptions(config.learning_rate).eps(config.adam_eps));
  } catch (const c10::Error& e) {
    return absl::InternalError(absl::StrCat("cannot build the policy network: ",
                                            e.what_without_backtrace()));
  }
  return std::unique_ptr<PpoLearner>(new PpoLearner(std::move(impl)));
}

absl::StatusOr<UpdateStats> PpoLearner::Update(const actor::Rollout& rollout) {
  DCS_RETURN_IF_ERROR(impl_->Validate(rollout));
  try {
    return impl_->Update(rollout);
  } catch (const c10::Error& e) {
    return absl::InternalError(absl::StrCat("PPO update failed: ", e.what_without_backtrace()));
  }
}

int64_t PpoLearner::updates() const { return impl_->updates; }

actor::PolicyWeights PpoLearner::ActorWeights() const { return impl_->network->ExportActor(); }

std::vector<float> PpoLearner::Values(std::span<const float> inputs,
                                      std::span<const uint8_t> images, int count) const {
  ActorCriticImpl::Pass pass;
  impl_->network->Forward(impl_->Batch(inputs, images, count), /*for_backward=*/false, pass);
  const std::span<const float> values = Floats(pass.values);
  return {values.begin(), values.end()};
}

absl::StatusOr<std::string> PpoLearner::Sb3StateDict() const {
  try {
    c10::Dict<std::string, torch::Tensor> state_dict;
    for (auto& [name, tensor] : impl_->network->Sb3Parameters(kSb3ImageKey, kSb3ContextKey)) {
      state_dict.insert(std::move(name), std::move(tensor));
    }
    const std::vector<char> bytes = torch::pickle_save(state_dict);
    return std::string(bytes.begin(), bytes.end());
  } catch (const c10::Error& e) {
    return absl::InternalError(absl::StrCat("cannot write the state dict: ",
                                            e.what_without_backtrace()));
  }
}

std::vector<float> PpoLearner::Parameters() const {
  std::vector<float> flat;
  for (const torch::Tensor& parameter : impl_->network->parameters()) {
    const torch::Tensor p = parameter.detach().contiguous();
    flat.insert(flat.end(), p.data_ptr<float>(), p.data_ptr<float>() + p.numel());
  }
  return flat;
}

absl::StatusOr<std::string> PpoLearner::SaveState() const {
  try {
    torch::serialize::OutputArchive archive;
    impl_->network->save(archive);
    torch::serialize::OutputArchive optimizer;
    impl_->optimizer->save(optimizer);
    archive.write("optimizer", optimizer);
    archive.write("updates", torch::tensor(impl_->updates));
    archive.write("seed", torch::tensor(static_cast<int64_t>(impl_->seed)));
    std::ostringstream bytes;
    archive.save_to(bytes);
    return bytes.str();
  } catch (const c10::Error& e) {
    return absl::InternalError(absl::StrCat("cannot save the learner: ",
                                            e.what_without_backtrace()));
  }
}

absl::Status PpoLearner::LoadState(absl::string_view bytes) {
  try {
    std::istringstream stream{std::string(bytes)};
    torch::serialize::InputArchive archive;
    archive.load_from(stream);
    torch::Tensor seed;
    archive.read("seed", seed);
    if (static_cast<uint64_t>(seed.item<int64_t>()) != impl_->seed) {
      // The minibatch streams derive from the seed: another run's state would diverge.
      return absl::FailedPreconditionError(
          absl::StrCat("the learner state is of seed ", seed.item<int64_t>(),
                       ", this learner's seed is ", impl_->seed));
    }
    impl_->network->load(archive);
    impl_->Flatten();
    torch::serialize::InputArchive optimizer;
    archive.read("optimizer", optimizer);
    impl_->optimizer->load(optimizer);
    torch::Tensor updates;
    archive.read("updates", updates);
    impl_->updates = updates.item<int64_t>();
  } catch (const std::exception& e) {
    // libtorch throws c10::Error, and std::runtime_error for some malformed archives.
    return absl::DataLossError(absl::StrCat("the learner state does not load: ", e.what()));
  }
  return absl::OkStatus();
}

}  // namespace dcs::learner
