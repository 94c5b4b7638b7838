// io/suggest.h: "did you mean" suggestions for misspelled keys and names.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace frontier::io::detail
{

// Optimal string alignment distance (insertions, deletions, substitutions, adjacent swaps).
int editDistance(std::string_view a, std::string_view b);

// The closest candidate when it is close enough to be a plausible typo, else "". Words and
// candidates longer than 100 characters are not compared, and among very many candidates only
// the first (some 30 million table cells' worth) are.
std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates);

// "; did you mean 'x'?" or "; known: a, b, c" (listKnown) or "".
std::string suggestionSuffix(std::string_view word, const std::vector<std::string>& candidates,
                             bool listKnown);

// 'name' for a message; a name longer than 80 bytes is cut: 'first 60 bytes...' (N bytes).
std::string quotedName(std::string_view name);

// "a, b, c"
std::string joinNames(const std::vector<std::string>& names);

} // namespace frontier::io::detail

namespace frontier::io::detail
{
// Why `name` cannot name a body or joint ("" when it can): empty, "world", or containing a comma,
// a double quote or a control character (names go into CSV files unquoted).
std::string invalidNameReason(std::string_view name);
} // namespace frontier::io::detail
