// io/atomic_file.h: an output file that appears complete or not at all.
//
// Writes go to "PATH.tmp-XXXXXX" in the same directory; commit() flushes and renames it onto PATH
// (atomic on POSIX file systems). Destroying it without commit() removes the temporary file, so a
// failed run never leaves a truncated file that looks complete.
#pragma once

#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace frontier::io
{

// An output file could not be created or written (disk full, missing directory, permissions).
class OutputError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// Why `path` cannot be an output file, or "" when it can: outputs are regular files (replaced)
// or new paths. A symbolic link, a folder, a device, a fifo or a socket at the path is refused
// (renaming onto it would replace the link or the node itself, not write through it).
std::string outputPathProblem(const std::string& path);

// The temporary files AtomicFile names "PATH.tmp-XXXXXX" (render::writePng names its own so too).
inline constexpr const char* cTemporaryInfix = ".tmp-";
inline constexpr std::size_t cTemporaryRandomChars = 6; // mkstemp's XXXXXX
// Whether the file name (no folder) is such a temporary.
bool isTemporaryName(const std::string& fileName);
// The name a temporary stands in for ("out.csv" for "out.csv.tmp-Ab3dEf"), "" when it is none.
std::string temporaryBase(const std::string& fileName);
// Removes the temporaries left in `folder` (not its subfolders) by a process killed with them open
// (SIGKILL: no destructor ran), and returns how many; with `ofName`, only those whose
// temporaryBase it accepts. Only for a folder that no running process writes into (a batch job's
// folder under its lock). A missing folder holds none.
std::size_t removeStaleTemporaries(const std::string& folder,
                                   const std::function<bool(const std::string&)>& ofName = {});
// Removes the temporaries of the one output file `path` ("PATH.tmp-XXXXXX", nothing else of its
// folder) that a killed run left, and returns how many: a run does so before it writes `path`.
std::size_t removeStaleTemporariesOf(const std::string& path);

// Writes `text` to `path` as a new file, in place (not atomically): for marker files in an output
// folder. What was at `path` is removed first (a symbolic link itself, never the file it points
// to), and the file is created with O_EXCL | O_NOFOLLOW, so nothing is ever written through a link.
// Throws OutputError.
void writeNewFile(const std::string& path, const std::string& text);

// Where a failed run keeps an output's rows up to the failure: "out.csv" -> "out.failed.csv"
// (the extension stays last, so the file still opens as what it is).
std::string failedPath(const std::string& path);

// Makes the folder an output file goes into when it is missing. Throws OutputError naming it.
void makeFolderFor(const std::string& file);

// The one of `inputs` that writing `output` would replace (compared as files, so a symbolic link,
// a hard link or another spelling of the path counts), or "" when none is: a run checks its
// outputs against every file its load read before it writes anything.
std::string replacedInput(const std::string& output, const std::vector<std::string>& inputs);

class AtomicFile
{
  public:
    explicit AtomicFile(std::string path); // throws OutputError, also for outputPathProblem

    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::FILE* stream() { return mStream; }
    void write(const char* data, std::size_t size); // throws OutputError
    void write(const std::string& text) { write(text.data(), text.size()); }
    void commit(); // throws OutputError; the file is then at path()
    // Renames onto `path` instead (a failed run's partial file under a name that says so).
    void commitAs(const std::string& path); // throws OutputError
    bool committed() const { return mCommitted; }
    const std::string& path() const { return mPath; }
    const std::string& tempPath() const { return mTempPath; }

  private:
    std::string mPath;
    std::string mTempPath;
    std::FILE* mStream = nullptr;
    bool mCommitted = false;
};

} // namespace frontier::io
