// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_DID_YOU_MEAN_H_
#define DCS_SERVICES_DID_YOU_MEAN_H_

// "Did you mean": the flag or command a mistyped one was closest to, for the error of a command
// line CLI11 refused (it suggests nothing itself):
//
//   dcs: error: unknown flag --adr for `dcs status`; did you mean --addr? (see --help)
//   dcs: error: unknown command 'cancle' for `dcs runs`; did you mean cancel? (see --help)
//
// Thread-safe (pure functions; the CLI::App is only read).

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "absl/strings/string_view.h"

namespace dcs::services {

// The edits (insert, delete or replace a character, or swap two neighbours) that turn `a`
// into `b`: "statsu" is 1 from "status".
int EditDistance(absl::string_view a, absl::string_view b);

// The candidate closest to `word`, if one is close enough to be a typing slip: at most 2 edits,
// and fewer than half of `word`'s length. The first of equally close ones.
std::optional<std::string> ClosestName(absl::string_view word,
                                       const std::vector<std::string>& candidates);

// The first flag or command in `args` (argv without argv[0]) that `program` does not know,
// described with its closest known name when there is one; nullopt if every one is known (the
// error is another: a missing or a bad value).
std::optional<std::string> UnknownNameError(const CLI::App& program,
                                            const std::vector<std::string>& args);

}  // namespace dcs::services

#endif  // DCS_SERVICES_DID_YOU_MEAN_H_
