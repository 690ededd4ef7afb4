#pragma once
// The one wording of a failed write, for every file motus writes: "PATH: could not be written
// (REASON)", the reason errno's when the failed call set it (reset errno before writing), else a
// guess at the usual one.
#include <cerrno>
#include <cstring>
#include <string>

namespace motus::plot {

inline std::string write_failure(const std::string& path) {
  const int e = errno;
  return path + ": could not be written (" + (e ? std::strerror(e) : "disk full?") + ")";
}

}  // namespace motus::plot
