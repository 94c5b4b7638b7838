// io/atomic_file.cpp: temporary file in the target's directory, renamed on commit.
#include "io/atomic_file.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace frontier::io
{

namespace
{
std::string errnoText()
{
    return std::strerror(errno);
}
} // namespace

std::string outputPathProblem(const std::string& path)
{
    if (path.empty())
    {
        return "an empty output path";
    }
    struct stat info
    {
    };
    if (::lstat(path.c_str(), &info) != 0)
    {
        return std::string(); // a new path (a missing folder is reported when the file is created)
    }
    const char* what = S_ISREG(info.st_mode)    ? nullptr
                       : S_ISLNK(info.st_mode)  ? "a symbolic link"
                       : S_ISDIR(info.st_mode)  ? "a folder"
                       : S_ISFIFO(info.st_mode) ? "a fifo"
                       : S_ISSOCK(info.st_mode) ? "a socket"
                                                : "a device";
    if (what == nullptr)
    {
        return std::string();
    }
    return path + " is " + what + ": an output must be a regular file (replaced) or a new path";
}

bool isTemporaryName(const std::string& fileName)
{
    return !temporaryBase(fileName).empty();
}

std::string temporaryBase(const std::string& fileName)
{
    const std::size_t infix = std::char_traits<char>::length(cTemporaryInfix);
    const std::size_t tail = infix + cTemporaryRandomChars;
    if (fileName.size() <= tail || fileName.compare(fileName.size() - tail, infix, cTemporaryInfix) != 0)
    {
        return std::string();
    }
    return fileName.substr(0, fileName.size() - tail);
}

std::size_t removeStaleTemporaries(const std::string& folder,
                                   const std::function<bool(const std::string&)>& ofName)
{
    namespace fs = std::filesystem;
    std::error_code error;
    std::size_t removed = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, error))
    {
        const std::string base = temporaryBase(entry.path().filename().string());
        if (!base.empty() && (!ofName || ofName(base)) && entry.is_regular_file(error) &&
            fs::remove(entry.path(), error))
        {
            ++removed;
        }
    }
    return removed;
}

std::size_t removeStaleTemporariesOf(const std::string& path)
{
    const std::filesystem::path file(path);
    const std::string name = file.filename().string();
    const std::filesystem::path folder = file.parent_path();
    return removeStaleTemporaries(folder.empty() ? std::string(".") : folder.string(),
                                  [&](const std::string& base) { return base == name; });
}

void writeNewFile(const std::string& path, const std::string& text)
{
    if (::unlink(path.c_str()) != 0 && errno != ENOENT)
    {
        throw OutputError(path + ": cannot replace file: " + errnoText());
    }
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0)
    {
        throw OutputError(path + ": cannot create file: " + errnoText());
    }
    std::size_t done = 0;
    while (done < text.size())
    {
        const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR)
        {
            continue;
        }
        if (n <= 0)
        {
            const std::string problem = errnoText();
            ::close(fd);
            throw OutputError(path + ": cannot write: " + problem);
        }
        done += static_cast<std::size_t>(n);
    }
    if (::close(fd) != 0)
    {
        throw OutputError(path + ": cannot write: " + errnoText());
    }
}

AtomicFile::AtomicFile(std::string path) : mPath(std::move(path))
{
    if (const std::string problem = outputPathProblem(mPath); !problem.empty())
    {
        throw OutputError(problem);
    }
    std::string pattern = mPath + cTemporaryInfix + std::string(cTemporaryRandomChars, 'X');
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    const int fd = ::mkstemp(buffer.data());
    if (fd < 0)
    {
        throw OutputError(mPath + ": cannot create file: " + errnoText());
    }
    mTempPath = buffer.data();
    // mkstemp creates mode 0600; output files are for sharing (rw-r--r--).
    ::fchmod(fd, 0644);
    mStream = ::fdopen(fd, "wb");
    if (mStream == nullptr)
    {
        const std::string text = errnoText();
        ::close(fd);
        ::unlink(mTempPath.c_str());
        throw OutputError(mPath + ": cannot open file: " + text);
    }
    static constexpr std::size_t cBufferBytes = 1 << 16;
    std::setvbuf(mStream, nullptr, _IOFBF, cBufferBytes);
}

AtomicFile::~AtomicFile()
{
    if (mStream != nullptr)
    {
        std::fclose(mStream);
    }
    if (!mCommitted && !mTempPath.empty())
    {
        ::unlink(mTempPath.c_str());
    }
}

void AtomicFile::write(const char* data, std::size_t size)
{
    if (mStream == nullptr)
    {
        throw OutputError(mPath + ": write after commit");
    }
    if (size > 0 && std::fwrite(data, 1, size, mStream) != size)
    {
        throw OutputError(mPath + ": cannot write: " + errnoText());
    }
}

void AtomicFile::commit()
{
    commitAs(mPath);
}

void AtomicFile::commitAs(const std::string& path)
{
    if (mStream == nullptr)
    {
        throw OutputError(mPath + ": committed twice");
    }
    std::FILE* stream = mStream;
    mStream = nullptr;
    const bool flushed = std::fflush(stream) == 0 && !std::ferror(stream) && ::fsync(::fileno(stream)) == 0;
    const std::string flushError = flushed ? std::string() : errnoText();
    if (std::fclose(stream) != 0 || !flushed)
    {
        throw OutputError(path + ": cannot write: " + (flushed ? errnoText() : flushError));
    }
    if (const std::string problem = outputPathProblem(path); !problem.empty())
    {
        throw OutputError(problem);
    }
    if (std::rename(mTempPath.c_str(), path.c_str()) != 0)
    {
        throw OutputError(path + ": cannot rename " + mTempPath + ": " + errnoText());
    }
    mPath = path;
    mCommitted = true;
}

std::string failedPath(const std::string& path)
{
    const std::filesystem::path p(path);
    std::filesystem::path out = p.parent_path() / (p.stem().string() + ".failed");
    out += p.extension();
    return out.string();
}

void makeFolderFor(const std::string& file)
{
    const std::filesystem::path parent = std::filesystem::path(file).parent_path();
    std::error_code error;
    if (!parent.empty() && !std::filesystem::create_directories(parent, error) && error)
    {
        throw OutputError("cannot create the folder " + parent.string() + " for " + file + ": " +
                          error.message());
    }
}

std::string replacedInput(const std::string& output, const std::vector<std::string>& inputs)
{
    std::error_code error;
    if (!std::filesystem::exists(output, error))
    {
        return {}; // a new path: no input is there
    }
    for (const std::string& input : inputs)
    {
        if (std::filesystem::equivalent(input, output, error))
        {
            return input;
        }
    }
    return {};
}

} // namespace frontier::io
