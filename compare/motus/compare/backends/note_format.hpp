#pragma once
// The peers' settings and notes in printf's formatting (their figures in %g and %.3g, as the
// peers' own manuals give them), into a string as long as the text needs: a note can run past a
// line (Bullet's contacts note is about 500 characters).
#include <algorithm>
#include <cstdio>
#include <string>

namespace motus::compare {

template <class... A>
std::string format(const char* pattern, A... args) {
  const int size = std::snprintf(nullptr, 0, pattern, args...);
  std::string out(static_cast<size_t>(std::max(size, 0)), '\0');
  std::snprintf(out.data(), out.size() + 1, pattern, args...);
  return out;
}

}  // namespace motus::compare
