// io/file_util.h: reading whole files and resolving paths relative to a scene file.
#pragma once

#include <string>

namespace frontier::io::detail
{

// The file's bytes; throws InputError(path, 0, 0, ...) when it cannot be read.
std::string readTextFile(const std::string& path);

// The directory holding `file` ("" for a bare file name).
std::string directoryOf(const std::string& file);

// `relative` resolved against `baseDir` (absolute paths are kept as they are).
std::string resolvePath(const std::string& baseDir, const std::string& relative);

// Lower-case extension with the dot (".yaml"), or "".
std::string lowerExtension(const std::string& path);

// 1-based line and column of byte offset `pos` in `text`.
struct TextPosition
{
    int line = 0;
    int column = 0;
};
TextPosition positionOf(const std::string& text, std::size_t pos);

// "FILE:LINE:COL: SEVERITY: TEXT" (line and column left out when 0): the one format of every
// error and warning about an input file.
std::string diagnostic(const std::string& file, TextPosition at, const char* severity,
                       const std::string& message);

} // namespace frontier::io::detail
