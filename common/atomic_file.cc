// Copyright 2026 The DCS Authors.
#include "common/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"

namespace dcs {
namespace {

absl::Status WriteAll(int fd, absl::string_view contents, const std::string& path) {
  while (!contents.empty()) {
    const ssize_t written = ::write(fd, contents.data(), contents.size());
    if (written < 0) {
      if (errno == EINTR) continue;
      return FileError(errno, "cannot write", path);
    }
    contents.remove_prefix(static_cast<size_t>(written));
  }
  if (::fsync(fd) != 0) return FileError(errno, "cannot sync", path);
  return absl::OkStatus();
}

}  // namespace

absl::Status FileError(int error, absl::string_view what, const std::string& path) {
  const std::string message = absl::StrCat(what, " ", path, ": ", std::strerror(error));
  switch (error) {
    case ENOSPC:
    case EDQUOT: return absl::ResourceExhaustedError(message);
    case ENOENT:
    case ENOTDIR: return absl::NotFoundError(message);
    case EACCES:
    case EPERM:
    case EROFS: return absl::PermissionDeniedError(message);
    default: return absl::InternalError(message);
  }
}

absl::Status WriteFileAtomically(const std::string& path, absl::string_view contents,
                                 mode_t mode) {
  const std::string temporary = absl::StrCat(path, ".tmp.", ::getpid());
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, mode);
  if (fd < 0) return FileError(errno, "cannot create", temporary);
  absl::Status status = WriteAll(fd, contents, temporary);
  if (::close(fd) != 0 && status.ok()) status = FileError(errno, "cannot close", temporary);
  if (!status.ok()) {
    ::unlink(temporary.c_str());
    return status;
  }
  return RenameDurably(temporary, path);
}

absl::Status RenameDurably(const std::string& temporary, const std::string& path) {
  if (::rename(temporary.c_str(), path.c_str()) != 0) {
    const absl::Status status = FileError(errno, "cannot rename onto", path);
    ::unlink(temporary.c_str());
    return status;
  }
  // The rename is durable only once the directory entry is.
  std::string directory = std::filesystem::path(path).parent_path().string();
  if (directory.empty()) directory = ".";
  const int dir_fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd < 0) return FileError(errno, "cannot open directory", directory);
  const int sync_result = ::fsync(dir_fd);
  const int sync_errno = errno;
  ::close(dir_fd);
  if (sync_result != 0) return FileError(sync_errno, "cannot sync directory", directory);
  return absl::OkStatus();
}

absl::StatusOr<std::string> ReadFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return FileError(errno, "cannot read", path);
  std::ostringstream contents;
  contents << file.rdbuf();
  if (file.bad()) return FileError(errno, "cannot read", path);
  return contents.str();
}

}  // namespace dcs
