#pragma once
// "Did you mean …?": the known word nearest to a misspelt one (a command, an option, a scene, an
// integrator, a scene file's field), so that an error can point at what the user meant instead of
// only listing everything.
#include <optional>
#include <string>
#include <vector>

namespace motus {

// The word of `known` closest to `word` by edits (a letter added, dropped, changed, or two
// neighbours swapped; a slip of case alone counts as none), when it is close enough to be a slip of the fingers:
// at most one edit in a word of up to four letters, two up to eight, three beyond. Ties go to the
// earlier word of `known`. Nothing for a word of one letter, when no word is that close, or `word` is one of them as it is.
std::optional<std::string> closest_known(const std::string& word, const std::vector<std::string>& known);

// ", did you mean X?", or "" when closest_known finds nothing: to follow what was not known in an
// error message ("unknown option --dtt, did you mean --dt?").
std::string did_you_mean(const std::string& word, const std::vector<std::string>& known);

// `unknown KIND "WORD", did you mean X? (known: A, B, C)` (the guess only when closest_known has
// one): a word that is none of a list's, as motus's errors say it.
std::string unknown_one_of(const std::string& kind, const std::string& word, const std::vector<std::string>& known);

}  // namespace motus
