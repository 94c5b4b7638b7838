// io/csv_output.h: what the CSV files of a run share (the trajectory, joints and contacts files,
// docs/files.md): a comment line `# frontier KIND: key=value ...` that makes the file
// self-describing (pandas skips it with comment='#'), a header line, then one line per row;
// numbers with 17 significant digits, so they read back bit for bit; written atomically
// (io/atomic_file.h), so a failed run leaves no file that looks complete.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace frontier::io
{

class AtomicFile;

// Ordered key=value pairs of the comment line.
using FileMetadata = std::vector<std::pair<std::string, std::string>>;

// "# frontier KIND:", the start of the comment line of a file of that kind.
std::string metadataPrefix(const std::string& kind);

// In metadata keys and values '%', ' ', '=', ',' and control characters are written as %XX.
std::string encodeMetadataField(const std::string& text);
std::string decodeMetadataField(std::string_view text);

// 17 significant digits: enough for every double to read back to the same bits.
void appendNumber(std::string& out, double value);

// A name as a CSV field: as it is, or in double quotes (RFC 4180, inner quotes doubled) when it
// holds a comma, a quote, a line break or '#' (which pandas' comment='#' would take for the start
// of a comment outside quotes).
void appendName(std::string& out, const std::string& name);

class CsvFile
{
  public:
    // Creates PATH.tmp-XXXXXX next to `path` and writes the comment line of `kind` with the
    // metadata, then the header. Throws OutputError (io/atomic_file.h).
    CsvFile(const std::string& path, const std::string& kind, const FileMetadata& metadata,
            const char* header);
    ~CsvFile(); // without commit(): removes the temporary file
    CsvFile(const CsvFile&) = delete;
    CsvFile& operator=(const CsvFile&) = delete;

    // Writes `line` and a newline as one row; throws OutputError.
    void writeRow(const std::string& line);
    // Flushes and renames the file into place (atomic); throws OutputError.
    void commit();
    void commitAs(const std::string& path); // into place under another name
    long rowsWritten() const { return mRows; }

  private:
    std::unique_ptr<AtomicFile> mFile;
    long mRows = 0;
};

// What the run's file writers (trajectory, joints, contacts) share: their file and the row they
// are building.
class CsvWriter
{
  public:
    // Flushes and renames the file into place (atomic); throws OutputError. Without it the
    // temporary file is removed.
    void commit() { mFile.commit(); }
    // Under another name: a failed run's rows up to the failure (app/outputs.h failedPath).
    void commitAs(const std::string& path) { mFile.commitAs(path); }
    long rowsWritten() const { return mFile.rowsWritten(); }

  protected:
    CsvWriter(const std::string& path, const std::string& kind, const FileMetadata& metadata,
              const char* header)
        : mFile(path, kind, metadata, header)
    {
    }

    CsvFile mFile;
    std::string mLine; // the row being built
};

} // namespace frontier::io
