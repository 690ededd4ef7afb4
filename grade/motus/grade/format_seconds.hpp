#pragma once
// Seconds as the sandbox's messages write them, to a tenth ("2.5", "10"): for sandbox.cpp and
// wall_timeout.cpp alone (internal to the grade library).
#include <cmath>
#include <cstdio>
#include <string>

namespace motus::grade::detail {

inline std::string format_seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", std::round(s * 10) / 10);
  return text;
}

}  // namespace motus::grade::detail
