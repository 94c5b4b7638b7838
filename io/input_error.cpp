// io/input_error.cpp: the InputError message format "FILE:LINE:COL: error: TEXT".
#include "io/file_util.h"
#include "io/scene.h"

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

std::string diagnostic(const std::string& file, TextPosition at, const char* severity,
                       const std::string& message)
{
    std::string out = file;
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
    out += message;
    return out;
}

} // namespace frontier::io::detail
