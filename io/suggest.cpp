// io/suggest.cpp: edit distance and "did you mean" suggestions.
#include "io/suggest.h"

#include <algorithm>
#include <cctype>

namespace frontier::io::detail
{

namespace
{
constexpr std::size_t cMaxSuggestedLength = 100; // characters: longer words and names get no suggestion
constexpr std::size_t cSuggestionCells = std::size_t{1} << 25; // distance-table cells one suggestion may fill
constexpr std::size_t cMaxQuotedLength = 80;                   // bytes of a name quoted in a message

char folded(char c)
{
    return static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
}
} // namespace

int editDistance(std::string_view a, std::string_view b)
{
    const std::size_t m = b.size();
    // Rows i - 2, i - 1 and i of the table d[i][j]: the distance between the first i characters
    // of a and the first j of b.
    std::vector<int> before(m + 1), previous(m + 1), current(m + 1);
    for (std::size_t j = 0; j <= m; ++j)
    {
        previous[j] = static_cast<int>(j);
    }
    for (std::size_t i = 1; i <= a.size(); ++i)
    {
        current[0] = static_cast<int>(i);
        for (std::size_t j = 1; j <= m; ++j)
        {
            const int cost = folded(a[i - 1]) == folded(b[j - 1]) ? 0 : 1;
            current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
            {
                current[j] = std::min(current[j], before[j - 2] + 1);
            }
        }
        std::swap(before, previous);
        std::swap(previous, current);
    }
    return previous[m];
}

std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates)
{
    if (word.size() > cMaxSuggestedLength)
    {
        return {};
    }
    std::string best;
    int bestDistance = 1 << 30;
    std::size_t cells = 0;
    for (const std::string& candidate : candidates)
    {
        // The difference in length is a lower bound of the distance: such a candidate cannot be
        // closer than the best so far.
        const std::size_t longer = std::max(word.size(), candidate.size());
        const std::size_t shorter = std::min(word.size(), candidate.size());
        if (candidate.size() > cMaxSuggestedLength || static_cast<int>(longer - shorter) > bestDistance)
        {
            continue;
        }
        cells += (word.size() + 1) * (candidate.size() + 1);
        if (cells > cSuggestionCells)
        {
            break; // very many names: the best of those compared so far
        }
        const int distance = editDistance(word, candidate);
        if (distance < bestDistance)
        {
            bestDistance = distance;
            best = candidate;
        }
    }
    if (best.empty())
    {
        return {};
    }
    // Plausible typo: a few edits, relative to the length, or one word a prefix of the other.
    const int allowed = std::max<int>(2, static_cast<int>(std::max(word.size(), best.size())) / 3);
    const bool prefix = word.size() >= 3 && (best.starts_with(word) || word.starts_with(best));
    if (bestDistance <= allowed || prefix)
    {
        return best;
    }
    return {};
}

std::string quotedName(std::string_view name)
{
    if (name.size() <= cMaxQuotedLength)
    {
        return "'" + std::string(name) + "'";
    }
    std::size_t keep = cMaxQuotedLength - 20;
    while (keep > 0 && (static_cast<unsigned char>(name[keep]) & 0xC0) == 0x80)
    {
        --keep; // not inside a UTF-8 character
    }
    return "'" + std::string(name.substr(0, keep)) + "...' (" + std::to_string(name.size()) + " bytes)";
}

std::string joinNames(const std::vector<std::string>& names)
{
    std::string out;
    for (const std::string& name : names)
    {
        if (!out.empty())
        {
            out += ", ";
        }
        out += name;
    }
    return out;
}

std::string suggestionSuffix(std::string_view word, const std::vector<std::string>& candidates,
                             bool listKnown)
{
    const std::string match = closestMatch(word, candidates);
    if (!match.empty())
    {
        return "; did you mean '" + match + "'?";
    }
    if (listKnown && !candidates.empty())
    {
        return " (known: " + joinNames(candidates) + ")";
    }
    return {};
}

} // namespace frontier::io::detail

namespace frontier::io::detail
{
std::string invalidNameReason(std::string_view name)
{
    if (name.empty())
    {
        return "a name cannot be empty";
    }
    if (name == "world")
    {
        return "'world' is reserved for the fixed world frame";
    }
    for (const char c : name)
    {
        if (c == ',' || c == '"' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
        {
            return "a name cannot contain commas, double quotes or control characters";
        }
    }
    return {};
}
} // namespace frontier::io::detail
