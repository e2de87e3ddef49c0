// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_TESTING_SCOPED_VARIABLE_H_
#define DCS_TESTS_TESTING_SCOPED_VARIABLE_H_

// An environment variable set (or unset) for one scope: for code that reads it, and for the
// programs a test starts, which inherit it. Not thread-safe: the environment is the process's.

#include <optional>
#include <string>

namespace dcs::testing {

class ScopedVariable {
 public:
  // Sets `name` to `value`, or unsets it if `value` is nullopt, until destroyed; then restores
  // the value it had, or unsets it if it had none.
  ScopedVariable(const char* name, std::optional<std::string> value);
  ~ScopedVariable();

  ScopedVariable(const ScopedVariable&) = delete;
  ScopedVariable& operator=(const ScopedVariable&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

}  // namespace dcs::testing

#endif  // DCS_TESTS_TESTING_SCOPED_VARIABLE_H_
