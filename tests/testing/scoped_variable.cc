// Copyright 2026 The DCS Authors.
#include "tests/testing/scoped_variable.h"

#include <cstdlib>

namespace dcs::testing {

ScopedVariable::ScopedVariable(const char* name, std::optional<std::string> value) : name_(name) {
  if (const char* old = std::getenv(name)) old_ = old;
  if (value.has_value()) {
    setenv(name, value->c_str(), /*overwrite=*/1);
  } else {
    unsetenv(name);
  }
}

ScopedVariable::~ScopedVariable() {
  if (old_.has_value()) {
    setenv(name_, old_->c_str(), /*overwrite=*/1);
  } else {
    unsetenv(name_);
  }
}

}  // namespace dcs::testing
