// Copyright 2026 The DCS Authors.
#ifndef DCS_COMMON_CONFIG_DOC_H_
#define DCS_COMMON_CONFIG_DOC_H_

// A config key as the reference shows it (docs/config.md, which tools/config_reference.cc
// writes). Each row is made by the table or reader that reads and checks the key
// (run/config_keys.h; a schedule's parameters: env/schedule_config.h), never by hand, so the
// reference says what the code does. Plain data; thread-safe.

#include <string>
#include <vector>

namespace dcs {

struct KeyDoc {
  std::string name;
  std::string type;           // as a user writes it: "integer", "list of numbers", "mapping"
  std::string default_value;  // "required", "none", or the value a missing key takes
  std::string range;          // the values its check allows ("at least 1"); empty: no check
  std::string meaning;        // one line
};

// The keys of one mapping of a config, by its YAML path ("evaluation", "stages[i]"; empty for
// the top level).
struct KeySection {
  std::string path;
  std::vector<KeyDoc> keys;
};

}  // namespace dcs

#endif  // DCS_COMMON_CONFIG_DOC_H_
