// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_TRAJECTORY_RECORDER_H_
#define DCS_ENV_TRAJECTORY_RECORDER_H_

// A record of transitions (s_t, a_t, r_t, c_t, c_visible_t) as struct-of-arrays: the state the
// action was taken in, the action, the reward, every context feature's true value during the
// transition, and the context the policy saw with s_t. Used for diagnostics (coverage, schedule
// previews) and tests; training does not record. Thread-compatible.

#include <cstdint>
#include <span>
#include <vector>

namespace dcs::env {

class TrajectoryRecorder {
 public:
  // Sizes of one transition's state, action, true context (every feature) and visible context.
  TrajectoryRecorder(int state_size, int action_size, int context_size, int visible_size)
      : state_size_(state_size),
        action_size_(action_size),
        context_size_(context_size),
        visible_size_(visible_size) {}

  // Records the start of a transition. REQUIRES: the spans have the sizes given at construction.
  template <typename State, typename Action>
  void BeginStep(int64_t episode, int64_t t, std::span<const State> state,
                 std::span<const Action> action, std::span<const float> visible) {
    episodes_.push_back(episode);
    steps_.push_back(t);
    states_.insert(states_.end(), state.begin(), state.end());
    actions_.insert(actions_.end(), action.begin(), action.end());
    visible_.insert(visible_.end(), visible.begin(), visible.end());
  }

  // Completes the transition begun last: its reward and `feature(i)` for every feature i.
  template <typename FeatureValue>
  void EndStep(double reward, FeatureValue feature) {
    rewards_.push_back(reward);
    for (int i = 0; i < context_size_; ++i) contexts_.push_back(feature(i));
  }

  size_t size() const { return rewards_.size(); }
  int64_t episode(size_t i) const { return episodes_[i]; }
  int64_t t(size_t i) const { return steps_[i]; }
  double reward(size_t i) const { return rewards_[i]; }
  std::span<const float> state(size_t i) const { return Row(states_, state_size_, i); }
  std::span<const double> action(size_t i) const { return Row(actions_, action_size_, i); }
  std::span<const double> context(size_t i) const { return Row(contexts_, context_size_, i); }
  std::span<const float> visible(size_t i) const { return Row(visible_, visible_size_, i); }

 private:
  template <typename T>
  static std::span<const T> Row(const std::vector<T>& values, int width, size_t i) {
    return std::span<const T>(values).subspan(i * width, width);
  }

  const int state_size_;
  const int action_size_;
  const int context_size_;
  const int visible_size_;
  std::vector<int64_t> episodes_;
  std::vector<int64_t> steps_;
  std::vector<float> states_;
  std::vector<double> actions_;
  std::vector<double> rewards_;
  std::vector<double> contexts_;
  std::vector<float> visible_;
};

}  // namespace dcs::env

#endif  // DCS_ENV_TRAJECTORY_RECORDER_H_
