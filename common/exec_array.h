// Copyright 2026 The DCS Authors.
#ifndef DCS_COMMON_EXEC_ARRAY_H_
#define DCS_COMMON_EXEC_ARRAY_H_

// The arrays the exec family takes (argv, envp) over strings the caller owns. Thread-safe
// (pure function).

#include <string>
#include <vector>

namespace dcs {

// A pointer to each of `strings`, then a null pointer: argv or envp for execv and execve.
// Borrows `strings`: valid while they live unchanged.
inline std::vector<char*> ExecArray(std::vector<std::string>& strings) {
  std::vector<char*> array;
  array.reserve(strings.size() + 1);
  for (std::string& text : strings) array.push_back(text.data());
  array.push_back(nullptr);
  return array;
}

}  // namespace dcs

#endif  // DCS_COMMON_EXEC_ARRAY_H_
