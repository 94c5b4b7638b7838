// io/suggest.cpp: edit distance and "did you mean" suggestions.
#include "io/suggest.h"

#include <algorithm>
#include <cctype>

namespace frontier::io::detail
{

int editDistance(std::string_view a, std::string_view b)
{
    const std::size_t n = a.size();
    const std::size_t m = b.size();
    // d[i][j]: distance between the first i characters of a and the first j of b.
    std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1, 0));
    for (std::size_t i = 0; i <= n; ++i)
    {
        d[i][0] = static_cast<int>(i);
    }
    for (std::size_t j = 0; j <= m; ++j)
    {
        d[0][j] = static_cast<int>(j);
    }
    for (std::size_t i = 1; i <= n; ++i)
    {
        for (std::size_t j = 1; j <= m; ++j)
        {
            const int cost = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                                     std::tolower(static_cast<unsigned char>(b[j - 1]))
                                 ? 0
                                 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
            {
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
            }
        }
    }
    return d[n][m];
}

std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates)
{
    std::string best;
    int bestDistance = 1 << 30;
    for (const std::string& candidate : candidates)
    {
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
