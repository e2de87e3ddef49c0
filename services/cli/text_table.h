// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_TEXT_TABLE_H_
#define DCS_SERVICES_CLI_TEXT_TABLE_H_

// Plain-text tables for the `dcs` client's human-readable output. Thread-safe.

#include <string>
#include <vector>

namespace dcs::services::cli {

// Left-aligned columns two spaces apart, one line per row (the first row is the header).
std::string RenderTable(const std::vector<std::vector<std::string>>& rows);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_TEXT_TABLE_H_
