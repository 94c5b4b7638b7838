// io/file_util.h: reading whole files and resolving paths relative to a scene file.
#pragma once

#include "io/input_digest.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace frontier::io::detail
{

// The one place input files are read from (scenes, URDF, meshes, trajectories, target tables):
// only a regular file is read, and only up to maxInputBytes(), so that a device (/dev/zero), a
// FIFO or a huge file named by mistake fails at once instead of hanging or filling memory.

// Bytes an input file may have: FRONTIER_MAX_INPUT_BYTES when set (a positive whole number; anything
// else throws InputError naming the variable), else cDefaultMaxInputBytes (README.md and
// scenes/README.md say it).
inline constexpr std::uintmax_t cDefaultMaxInputBytes = std::uintmax_t{256} << 20; // 256 MiB
std::uintmax_t maxInputBytes();

// Throws InputError(path, 0, 0, ...) unless `path` names a regular file (symbolic links followed)
// of at most maxInputBytes(); `what` names the file in messages ("mesh file"). For readers that
// open the file themselves (assimp).
void checkInputFile(const std::string& path, const std::string& what = "file");

// The file's bytes, under the same rules as checkInputFile (checked on the open file, so that a
// FIFO never blocks); throws InputError(path, 0, 0, ...) when it cannot be read.
std::string readTextFile(const std::string& path, const std::string& what = "file");

// While it lives, records the input files this thread reads: each file readTextFile returns and
// each file checkInputFile accepts (read again for its digest), every path once, in the order of
// its first read, with the SHA-256 of its bytes. Logs nest: a file goes into every open log of the
// thread. The readers take no part, so any reader going through the two functions above, also one
// added later, has its files recorded (io::LoadReport::inputFiles, a batch job's inputs digest).
class InputFileLog
{
  public:
    InputFileLog();
    ~InputFileLog();
    InputFileLog(const InputFileLog&) = delete;
    InputFileLog& operator=(const InputFileLog&) = delete;

    const std::vector<InputFile>& files() const { return mFiles; }

    // True while a log is open on this thread.
    static bool recording();
    // Adds `path` with the digest of `bytes` to the open logs that lack it (readTextFile calls it).
    static void record(const std::string& path, std::string_view bytes);

  private:
    InputFileLog* mOuter; // the log that was innermost when this one opened
    std::vector<InputFile> mFiles;
};

// The one rule for numbers in text input files (trajectory headers and rows, target tables): the
// whole field is a finite decimal number ("-1.5e3", an optional leading '+'); std::nullopt otherwise
// (empty, trailing text, nan, inf, out of double range).
std::optional<double> parseFiniteNumber(std::string_view text);
// A count: the whole field is a whole number written in digits (optional sign) within
// [min, max]; std::nullopt otherwise ("3.0", "1e3" and out-of-range values included).
std::optional<long long> parseWholeNumber(std::string_view text, long long min, long long max);

// The most PGS iterations per step a file may ask for (a scene's simulation.pgs_iterations, a
// trajectory's pgs_iterations): more is a typo that would make every step take minutes.
inline constexpr int cMaxPgsIterations = 1000000;

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

// `text` with each byte that would not print as text (a control character, a line break
// included, or a byte outside well-formed UTF-8) written as \xNN.
std::string printable(std::string_view text);

// "FILE:LINE:COL: SEVERITY: TEXT" (line and column left out when 0): the one format of every
// error and warning about an input file. FILE and TEXT go through printable(): a message quoting
// a file's bytes (a binary header, a name with control characters) cannot reach the terminal raw.
std::string diagnostic(const std::string& file, TextPosition at, const char* severity,
                       const std::string& message);

} // namespace frontier::io::detail
