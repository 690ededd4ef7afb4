#pragma once
// A number in an error message: `digits` significant figures, "1e-07" rather than
// std::to_string's "0.000000", and a NaN without its sign ("nan": printf writes a negative one
// as "-nan", which reads as a number with a sign).
#include <cmath>
#include <cstdio>
#include <string>

namespace motus {

inline std::string message_number(double x, int digits = 9) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", digits, std::isnan(x) ? std::fabs(x) : x);
  return text;
}

}  // namespace motus
