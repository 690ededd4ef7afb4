#pragma once
// What an accessibility audit checked on motus's pages, as test helpers.
//
// WCAG 2's contrast ratio (https://www.w3.org/TR/WCAG21/#dfn-contrast-ratio) of two "#rrggbb" colours:
// (L1 + 0.05) / (L2 + 0.05), L the relative luminance of the lighter (L1) and the darker (L2), from
// the sRGB channels linearised. At least 4.5 for text (1.4.3, AA), 3 for lines and shapes (1.4.11).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <regex>
#include <string>

#include <gtest/gtest.h>

namespace motus_test {

inline double relative_luminance(const std::string& hex) {
  std::string h = hex.substr(hex[0] == '#' ? 1 : 0);
  if (h.size() == 3) h = {h[0], h[0], h[1], h[1], h[2], h[2]};  // #abc is #aabbcc
  if (h.size() != 6) throw std::invalid_argument("not a colour: " + hex);
  auto channel = [&](int k) {
    const double c = std::stoi(h.substr(2 * k, 2), nullptr, 16) / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  };
  return 0.2126 * channel(0) + 0.7152 * channel(1) + 0.0722 * channel(2);
}

inline double contrast_ratio(const std::string& a, const std::string& b) {
  const double la = relative_luminance(a), lb = relative_luminance(b);
  return (std::max(la, lb) + 0.05) / (std::min(la, lb) + 0.05);
}

// The page's start: its language and a viewport (WCAG 3.1.1; a phone shows the page at its width).
inline ::testing::AssertionResult starts_as_a_page(const std::string& html) {
  const size_t head_end = html.find("</head>");
  if (html.rfind("<!doctype html>\n<html lang=\"en\">", 0) != 0)
    return ::testing::AssertionFailure() << "no <html lang=\"en\">: " << html.substr(0, 200);
  if (html.find("<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">") > head_end)
    return ::testing::AssertionFailure() << "no viewport in the head: " << html.substr(0, 300);
  return ::testing::AssertionSuccess();
}

// Every table of the page named (a <caption>, or aria-labelledby an element of the page), its first
// row all column headers (<th scope="col">), and every other row starting with its row's header
// (<th scope="row">): what a screen reader reads a cell by.
inline ::testing::AssertionResult tables_have_headers(const std::string& html) {
  int tables = 0;
  for (size_t at = html.find("<table"); at != std::string::npos; at = html.find("<table", at + 1)) {
    ++tables;
    const size_t tag_end = html.find('>', at), end = html.find("</table>", at);
    const std::string tag = html.substr(at, tag_end + 1 - at), table = html.substr(tag_end + 1, end - tag_end - 1);
    std::smatch m;
    const bool captioned = table.rfind("<caption>", 0) == 0;
    if (!captioned) {
      if (!std::regex_search(tag, m, std::regex("aria-labelledby=\"([^\"]+)\"")))
        return ::testing::AssertionFailure() << "table " << tables << " has no name: " << tag << table.substr(0, 200);
      if (html.find("id=\"" + m[1].str() + "\"") == std::string::npos)
        return ::testing::AssertionFailure() << "table " << tables << " is labelled by " << m[1] << ", not in the page";
    }
    int row = 0;
    for (size_t r = table.find("<tr>"); r != std::string::npos; r = table.find("<tr>", r + 1), ++row) {
      const std::string cells = table.substr(r + 4, table.find("</tr>", r) - r - 4);
      if (row == 0) {
        if (cells.find("<td") != std::string::npos || cells.rfind("<th scope=\"col\">", 0) != 0)
          return ::testing::AssertionFailure() << "table " << tables << "'s first row is not all headers: " << cells;
        for (size_t h = cells.find("<th"); h != std::string::npos; h = cells.find("<th", h + 1))
          if (cells.compare(h, 16, "<th scope=\"col\">") != 0)
            return ::testing::AssertionFailure() << "table " << tables << ": a header without scope: " << cells;
      } else if (cells.rfind("<th scope=\"row\">", 0) != 0) {
        return ::testing::AssertionFailure() << "table " << tables << ", row " << row << " has no row header: " << cells;
      }
    }
    if (row < 2) return ::testing::AssertionFailure() << "table " << tables << " has no rows: " << table;
  }
  if (tables == 0) return ::testing::AssertionFailure() << "no table";
  return ::testing::AssertionSuccess() << tables << " tables";
}

}  // namespace motus_test
