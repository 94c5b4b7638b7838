// io/input_error.cpp: the InputError message format "FILE:LINE:COL: error: TEXT".
#include "io/file_util.h"
#include "io/scene.h"

#include <string_view>
#include <utility>

namespace frontier::io
{

InputError::InputError(std::string file, int line, int column, const std::string& message)
    : std::runtime_error(detail::diagnostic(file, {line, column}, "error", message)), mFile(std::move(file)),
      mMessage(message), mLine(line), mColumn(column)
{
}

} // namespace frontier::io

namespace frontier::io::detail
{

std::string printable(std::string_view text)
{
    std::string out;
    out.reserve(text.size());
    const auto escape = [&out](unsigned char byte)
    {
        static const char* const cHex = "0123456789abcdef";
        out += "\\x";
        out += cHex[byte >> 4];
        out += cHex[byte & 15];
    };
    for (std::size_t i = 0; i < text.size();)
    {
        const auto byte = static_cast<unsigned char>(text[i]);
        if (byte < 0x80)
        {
            if (byte < 0x20 || byte == 0x7f)
            {
                escape(byte);
            }
            else
            {
                out += static_cast<char>(byte);
            }
            ++i;
            continue;
        }
        // A well-formed UTF-8 sequence (no overlong forms, no surrogates) is kept as it is.
        const std::size_t length = byte >= 0xc2 && byte <= 0xdf   ? 2
                                   : byte >= 0xe0 && byte <= 0xef ? 3
                                   : byte >= 0xf0 && byte <= 0xf4 ? 4
                                                                  : 0;
        bool valid = length > 0 && i + length <= text.size();
        for (std::size_t k = 1; valid && k < length; ++k)
        {
            valid = (static_cast<unsigned char>(text[i + k]) & 0xc0) == 0x80;
        }
        if (valid && length >= 3)
        {
            const auto second = static_cast<unsigned char>(text[i + 1]);
            valid = !(byte == 0xe0 && second < 0xa0) && !(byte == 0xed && second > 0x9f) &&
                    !(byte == 0xf0 && second < 0x90) && !(byte == 0xf4 && second > 0x8f);
        }
        if (!valid)
        {
            escape(byte);
            ++i;
            continue;
        }
        out.append(text.substr(i, length));
        i += length;
    }
    return out;
}

std::string diagnostic(const std::string& file, TextPosition at, const char* severity,
                       const std::string& message)
{
    std::string out = printable(file);
    if (at.line > 0)
    {
        out += ':' + std::to_string(at.line);
        if (at.column > 0)
        {
            out += ':' + std::to_string(at.column);
        }
    }
    out += ": ";
    out += severity;
    out += ": ";
    out += printable(message);
    return out;
}

} // namespace frontier::io::detail
