// Copyright 2026 The DCS Authors.
#ifndef DCS_COMMON_TEXT_TABLE_H_
#define DCS_COMMON_TEXT_TABLE_H_

// Plain-text tables for a terminal: the `dcs` client's listings and the reports' tables.
// Thread-safe (pure function).

#include <string>
#include <vector>

namespace dcs {

// `rows` (the first one the header) as lines of columns two spaces apart, each column padded to
// its widest cell: on the right of the text, or on its left (numbers) where `right_aligned`
// says so. Trailing spaces are dropped. A row may be shorter than the others; `right_aligned`
// may be shorter than the widest row (the columns past it are left-aligned).
std::string RenderTable(const std::vector<std::vector<std::string>>& rows,
                        const std::vector<bool>& right_aligned = {});

}  // namespace dcs

#endif  // DCS_COMMON_TEXT_TABLE_H_
