// io/file_util.cpp: reading whole input files (regular files of bounded size only) and resolving paths
// relative to a scene file.
#include "io/file_util.h"

#include "io/scene.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>

namespace frontier::io::detail
{

namespace
{

constexpr const char* cMaxInputVariable = "FRONTIER_MAX_INPUT_BYTES";

[[noreturn]] void failTooLarge(const std::string& path, const std::string& what, std::uintmax_t bytes,
                               std::uintmax_t limit, bool exact)
{
    throw InputError(path, 0, 0,
                     what + " has " + (exact ? "" : "more than ") + std::to_string(bytes) +
                         " bytes, above the limit of " + std::to_string(limit) + " bytes (set " +
                         cMaxInputVariable + " to raise it)");
}

// Refuses what is not a regular file: type from stat() or fstat().
void checkType(const std::string& path, const std::string& what, mode_t mode)
{
    if (S_ISDIR(mode))
    {
        throw InputError(path, 0, 0, "is a directory, expected a " + what);
    }
    if (!S_ISREG(mode))
    {
        const char* kind = S_ISFIFO(mode)                   ? " (a FIFO)"
                           : S_ISCHR(mode) || S_ISBLK(mode) ? " (a device)"
                           : S_ISSOCK(mode)                 ? " (a socket)"
                                                            : "";
        throw InputError(path, 0, 0, std::string("is not a regular file") + kind + ", expected a " + what);
    }
}

// The innermost open InputFileLog of this thread (loads of parallel batch jobs run on their own threads).
thread_local InputFileLog* tInnermostLog = nullptr;

[[noreturn]] void failErrno(const std::string& path, const std::string& verb, int err)
{
    throw InputError(path, 0, 0, "cannot " + verb + " file: " + std::strerror(err));
}

} // namespace

std::uintmax_t maxInputBytes()
{
    const char* text = std::getenv(cMaxInputVariable);
    if (text == nullptr || *text == '\0')
    {
        return cDefaultMaxInputBytes;
    }
    std::uintmax_t value = 0;
    const char* last = text + std::strlen(text);
    const auto result = std::from_chars(text, last, value);
    if (result.ec != std::errc() || result.ptr != last || value == 0)
    {
        throw InputError(cMaxInputVariable, 0, 0,
                         std::string("expected a positive whole number of bytes, got '") + text + "'");
    }
    return value;
}

void checkInputFile(const std::string& path, const std::string& what)
{
    struct stat info
    {
    };
    if (::stat(path.c_str(), &info) != 0)
    {
        const int err = errno;
        if (err == ENOENT)
        {
            throw InputError(path, 0, 0, "no such " + what);
        }
        failErrno(path, "open", err);
    }
    checkType(path, what, info.st_mode);
    const std::uintmax_t limit = maxInputBytes();
    if (static_cast<std::uintmax_t>(info.st_size) > limit)
    {
        failTooLarge(path, what, static_cast<std::uintmax_t>(info.st_size), limit, true);
    }
    if (InputFileLog::recording())
    {
        readTextFile(path, what); // its reader opens it itself; the log needs its bytes
    }
}

std::string readTextFile(const std::string& path, const std::string& what)
{
    const std::uintmax_t limit = maxInputBytes();
    // O_NONBLOCK: opening a FIFO without a writer would block; the type check below refuses it.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
    {
        failErrno(path, "open", errno);
    }
    struct Closer
    {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat info
    {
    };
    if (::fstat(fd, &info) != 0)
    {
        failErrno(path, "read", errno);
    }
    checkType(path, what, info.st_mode);
    const auto size = static_cast<std::uintmax_t>(info.st_size);
    if (size > limit)
    {
        failTooLarge(path, what, size, limit, true);
    }
    // Read until end of file but never past the limit (the file may grow while it is read).
    std::string out;
    out.reserve(static_cast<std::size_t>(size));
    char buffer[1 << 16];
    while (true)
    {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0)
        {
            if (errno == EINTR)
            {
                continue;
            }
            failErrno(path, "read", errno);
        }
        if (n == 0)
        {
            InputFileLog::record(path, out);
            return out;
        }
        out.append(buffer, static_cast<std::size_t>(n));
        if (out.size() > limit)
        {
            failTooLarge(path, what, limit, limit, false);
        }
    }
}

InputFileLog::InputFileLog() : mOuter(tInnermostLog)
{
    tInnermostLog = this;
}

InputFileLog::~InputFileLog()
{
    tInnermostLog = mOuter;
}

bool InputFileLog::recording()
{
    return tInnermostLog != nullptr;
}

void InputFileLog::record(const std::string& path, std::string_view bytes)
{
    std::string digest; // computed once, for the first log that lacks the file
    for (InputFileLog* log = tInnermostLog; log != nullptr; log = log->mOuter)
    {
        const bool known = std::any_of(log->mFiles.begin(), log->mFiles.end(),
                                       [&](const InputFile& file) { return file.path == path; });
        if (!known)
        {
            if (digest.empty())
            {
                digest = sha256Hex(bytes);
            }
            log->mFiles.push_back({path, digest});
        }
    }
}

std::optional<double> parseFiniteNumber(std::string_view text)
{
    if (text.size() > 1 && text.front() == '+' && text[1] != '-' && text[1] != '+')
    {
        text.remove_prefix(1);
    }
    double value = 0.0;
    const char* last = text.data() + text.size();
    const auto result = std::from_chars(text.data(), last, value);
    if (text.empty() || result.ec != std::errc() || result.ptr != last || !std::isfinite(value))
    {
        return std::nullopt;
    }
    return value;
}

std::optional<long long> parseWholeNumber(std::string_view text, long long min, long long max)
{
    if (text.size() > 1 && text.front() == '+' && text[1] != '-' && text[1] != '+')
    {
        text.remove_prefix(1);
    }
    long long value = 0;
    const char* last = text.data() + text.size();
    const auto result = std::from_chars(text.data(), last, value);
    if (text.empty() || result.ec != std::errc() || result.ptr != last || value < min || value > max)
    {
        return std::nullopt;
    }
    return value;
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
