#include "motus/scene_file/spelling.hpp"

#include <algorithm>
#include <cctype>

namespace motus {
namespace {

std::string lower(const std::string& s) {
  std::string out = s;
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Edits from a to b (optimal string alignment: Levenshtein's three edits and a swap of two
// neighbouring letters, "eluer" for "euler").
size_t edits(const std::string& a, const std::string& b) {
  const size_t n = a.size(), m = b.size();
  std::vector<std::vector<size_t>> d(n + 1, std::vector<size_t>(m + 1));
  for (size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (size_t i = 1; i <= n; ++i)
    for (size_t j = 1; j <= m; ++j) {
      const size_t change = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + change});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

}  // namespace

std::optional<std::string> closest_known(const std::string& word, const std::vector<std::string>& known) {
  // (A word of hundreds of letters is no slip: nothing to compare, and no quadratic work on it.)
  if (word.empty() || word.size() > 64) return std::nullopt;
  const std::string w = lower(word);
  // Leading dashes are the option's, not its name's: "--dtt" is one edit from "--dt", not a third of "dt".
  const size_t dashes = std::min(w.find_first_not_of('-'), w.size());
  const size_t letters = w.size() - dashes;
  if (letters < 2) return std::nullopt;  // (one letter is a slip away from every short word: no guess)
  const size_t allowed = letters <= 4 ? 1 : letters <= 8 ? 2 : 3;
  std::optional<std::string> best;
  size_t best_edits = allowed + 1;
  for (const std::string& k : known) {
    if (k == word) return std::nullopt;  // known as it is: no slip to correct
    if (k.size() > 64) continue;
    const size_t e = edits(w, lower(k));  // (0 for a slip of case alone, "Euler" for "euler")
    if (e < best_edits) best_edits = e, best = k;
  }
  return best;
}

std::string did_you_mean(const std::string& word, const std::vector<std::string>& known) {
  const auto k = closest_known(word, known);
  return k ? ", did you mean " + *k + "?" : "";
}

std::string unknown_one_of(const std::string& kind, const std::string& word, const std::vector<std::string>& known) {
  std::string listed;
  for (const std::string& k : known) listed += (listed.empty() ? "" : ", ") + k;
  return "unknown " + kind + " \"" + word + "\"" + did_you_mean(word, known) + " (known: " + listed + ")";
}

}  // namespace motus
