// Copyright 2026 The DCS Authors.
#include "services/pieces.h"

namespace dcs::services {

std::vector<absl::string_view> SplitIntoPieces(absl::string_view bytes) {
  std::vector<absl::string_view> pieces;
  do {
    pieces.push_back(bytes.substr(0, kPieceBytes));
    bytes.remove_prefix(pieces.back().size());
  } while (!bytes.empty());
  return pieces;
}

}  // namespace dcs::services
