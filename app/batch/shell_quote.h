// app/batch/shell_quote.h: one word for the shell, also read as one argument on an #SBATCH line.
#pragma once

#include <string>

namespace frontier::app
{

// `text` as one word of sh and bash: runs of characters in single quotes (nothing inside them is
// special to the shell), each ' and \ outside them escaped with a backslash ('' for the empty
// text). sbatch reads the words of its #SBATCH lines with the same effect (quotes group, a
// backslash escapes the next character, an unquoted # starts a comment), so the word carries the
// same text there; a line break stays a line break, so callers refuse control characters in what
// goes onto a script's line of directives.
inline std::string shellQuote(const std::string& text)
{
    std::string out;
    bool quoted = false;
    for (const char c : text)
    {
        const bool escaped = c == '\'' || c == '\\';
        if (escaped == quoted)
        {
            out += '\''; // opens a run of quoted characters, or closes it before an escaped one
            quoted = !quoted;
        }
        if (escaped)
        {
            out += '\\';
        }
        out += c;
    }
    if (quoted)
    {
        out += '\'';
    }
    return out.empty() ? std::string("''") : out;
}

} // namespace frontier::app
