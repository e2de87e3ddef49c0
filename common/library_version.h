// Copyright 2026 The DCS Authors.
#ifndef DCS_COMMON_LIBRARY_VERSION_H_
#define DCS_COMMON_LIBRARY_VERSION_H_

// The version of a third-party library as linked into this process. Each DCS library reports
// the numeric libraries it computes with (`dcs::env::LibraryVersions()` and its siblings), so
// a run can record exactly which Box2D or libtorch produced its numbers: results are only
// bit-for-bit reproducible across workers that run the same versions.

#include <string>

namespace dcs {

struct LibraryVersion {
  std::string name;     // e.g. "box2d"
  std::string version;  // e.g. "2.4.1"

  friend bool operator==(const LibraryVersion&, const LibraryVersion&) = default;
};

}  // namespace dcs

#endif  // DCS_COMMON_LIBRARY_VERSION_H_
