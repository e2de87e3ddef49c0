// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_ENV_SCHEDULE_TEST_CONFIG_H_
#define DCS_TESTS_ENV_SCHEDULE_TEST_CONFIG_H_

// A terse way for schedule tests to write configs: Config("sinusoidal", {{"period", 100.0}}).

#include <map>
#include <string>
#include <utility>

#include "env/schedule_config.h"

namespace dcs::env {

using Params = std::map<std::string, ScheduleParam>;

inline ScheduleConfig Config(std::string family, Params params = {}) {
  return ScheduleConfig{.family = std::move(family), .params = std::move(params)};
}

}  // namespace dcs::env

#endif  // DCS_TESTS_ENV_SCHEDULE_TEST_CONFIG_H_
