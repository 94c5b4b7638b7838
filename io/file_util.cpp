// io/file_util.cpp: reading whole files and resolving paths relative to a scene file.
#include "io/file_util.h"

#include "io/scene.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace frontier::io::detail
{

std::string readTextFile(const std::string& path)
{
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
    {
        throw InputError(path, 0, 0, "is a directory, expected a file");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
        const int err = errno;
        throw InputError(path, 0, 0, std::string("cannot open file: ") + std::strerror(err));
    }
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad())
    {
        throw InputError(path, 0, 0, "cannot read file");
    }
    return buffer.str();
}

std::string directoryOf(const std::string& file)
{
    return std::filesystem::path(file).parent_path().string();
}

std::string resolvePath(const std::string& baseDir, const std::string& relative)
{
    const std::filesystem::path p(relative);
    if (p.is_absolute() || baseDir.empty())
    {
        return p.lexically_normal().string();
    }
    return (std::filesystem::path(baseDir) / p).lexically_normal().string();
}

std::string lowerExtension(const std::string& path)
{
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

TextPosition positionOf(const std::string& text, std::size_t pos)
{
    TextPosition out{1, 1};
    pos = std::min(pos, text.size());
    for (std::size_t i = 0; i < pos; ++i)
    {
        if (text[i] == '\n')
        {
            ++out.line;
            out.column = 1;
        }
        else
        {
            ++out.column;
        }
    }
    return out;
}

} // namespace frontier::io::detail
