// io/input_error.cpp: the InputError message format "FILE:LINE:COL: error: TEXT".
#include "io/scene.h"

#include <utility>

namespace frontier::io
{

namespace
{
std::string formatMessage(const std::string& file, int line, int column, const std::string& message)
{
    std::string out = file;
    if (line > 0)
    {
        out += ':' + std::to_string(line);
        if (column > 0)
        {
            out += ':' + std::to_string(column);
        }
    }
    out += ": error: ";
    out += message;
    return out;
}
} // namespace

InputError::InputError(std::string file, int line, int column, const std::string& message)
    : std::runtime_error(formatMessage(file, line, column, message)), mFile(std::move(file)),
      mMessage(message), mLine(line), mColumn(column)
{
}

} // namespace frontier::io
