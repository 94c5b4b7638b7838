// tests/io/csv_output_test.cpp: what the run's CSV files share (io/csv_output.h): names quoted only
// when they must be, and read back whole by an RFC 4180 reader; metadata fields encoded and
// decoded back; a file appears with its comment and header lines on commit, and not at all
// without it; the temporaries a killed process left are told apart from other files and removed;
// a marker file is never written through a link.
#include "csv_table.h"
#include "io/atomic_file.h"
#include "io/csv_output.h"
#include "io_test_util.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>

namespace frontier::io::test
{
namespace
{

TEST(CsvOutput, NamesAreQuotedOnlyWhenTheyMustBe)
{
    for (const std::string name :
         {"pelvis", "knee left", "elbow, left", "say \"hi\"", "link#3", "two\nlines"})
    {
        std::string line = "1,";
        appendName(line, name);
        line += ",2";
        const std::vector<std::string> fields = frontier::test::splitCsvLine(line);
        ASSERT_EQ(fields.size(), 3u) << line;
        EXPECT_EQ(fields[1], name) << line;
        const bool plain = name.find_first_of(",\"\n#") == std::string::npos;
        EXPECT_EQ(line == "1," + name + ",2", plain) << line;
    }
}

TEST(CsvOutput, MetadataFieldsRoundTrip)
{
    for (const std::string text : {"scenes/a.yaml", "my scene=1, 100%.yaml", "tab\there", ""})
    {
        const std::string encoded = encodeMetadataField(text);
        EXPECT_EQ(encoded.find_first_of(" =,\t"), std::string::npos) << encoded;
        EXPECT_EQ(decodeMetadataField(encoded), text);
    }
}

TEST(CsvOutput, FileAppearsOnCommitWithCommentAndHeader)
{
    TempDir dir;
    const std::string path = dir.file("out.csv");
    {
        CsvFile file(path, "things", {{"scene", "a b.yaml"}, {"dt", "0.001"}}, "time,value");
        file.writeRow("0,1");
        file.writeRow("0.5,2");
        EXPECT_EQ(file.rowsWritten(), 2);
        EXPECT_FALSE(std::filesystem::exists(path));
        EXPECT_EQ(filesIn(dir.path()), 1u); // the temporary file
        file.commit();
    }
    EXPECT_EQ(readTextOf(path), "# frontier things: scene=a%20b.yaml dt=0.001\ntime,value\n0,1\n0.5,2\n");
    EXPECT_EQ(filesIn(dir.path()), 1u);
}

TEST(CsvOutput, UncommittedFileLeavesNothing)
{
    TempDir dir;
    {
        CsvFile file(dir.file("out.csv"), "things", {}, "time,value");
        file.writeRow("0,1");
    }
    EXPECT_EQ(filesIn(dir.path()), 0u);
    EXPECT_THROW(CsvFile("/nonexistent/dir/out.csv", "things", {}, "time"), OutputError);
}

// An AtomicFile's temporary is named as isTemporaryName expects; removeStaleTemporaries removes
// such names in the folder only (not other files, not in subfolders).
TEST(CsvOutput, StaleTemporariesAreRemovedAndNothingElse)
{
    TempDir dir;
    {
        AtomicFile file(dir.file("out.csv"));
        EXPECT_TRUE(isTemporaryName(std::filesystem::path(file.tempPath()).filename().string()))
            << file.tempPath();
    }
    for (const char* name : {"out.csv.tmp-Ab3dEf", "stats.json.tmp-000000", "out.csv", "out.tmp-csv",
                             "notes.tmp-", "x.tmp-1234567", ".tmp-abcdef"})
    {
        std::ofstream(dir.file(name)) << "x";
    }
    std::filesystem::create_directory(dir.file("frames"));
    std::ofstream(dir.file("frames/frame_00000.png.tmp-Qw12Er")) << "x";
    EXPECT_EQ(removeStaleTemporaries(dir.path().string()), 2u);
    EXPECT_FALSE(std::filesystem::exists(dir.file("out.csv.tmp-Ab3dEf")));
    EXPECT_FALSE(std::filesystem::exists(dir.file("stats.json.tmp-000000")));
    EXPECT_EQ(filesIn(dir.path()), 6u); // the five others and frames/
    EXPECT_EQ(removeStaleTemporaries(dir.file("frames")), 1u);
    EXPECT_EQ(removeStaleTemporaries(dir.file("missing")), 0u);
}

// removeStaleTemporariesOf removes the temporaries of one output and no other file of its folder.
TEST(CsvOutput, StaleTemporariesOfOneOutputAreRemovedAndNothingElse)
{
    TempDir dir;
    EXPECT_EQ(temporaryBase("out.csv.tmp-Ab3dEf"), "out.csv");
    EXPECT_EQ(temporaryBase("out.csv.tmp-Ab3dE"), "");
    for (const char* name : {"out.csv.tmp-Ab3dEf", "out.csv.tmp-000000", "out.csv", "out.csv.tmp-1234567",
                             "xout.csv.tmp-Ab3dEf", "other.csv.tmp-Ab3dEf", "out.tmp-Ab3dEf"})
    {
        std::ofstream(dir.file(name)) << "x";
    }
    EXPECT_EQ(removeStaleTemporariesOf(dir.file("out.csv")), 2u);
    EXPECT_EQ(filesIn(dir.path()), 5u);
    EXPECT_FALSE(std::filesystem::exists(dir.file("out.csv.tmp-Ab3dEf")));
    EXPECT_TRUE(std::filesystem::exists(dir.file("out.csv")));
    EXPECT_EQ(removeStaleTemporariesOf(dir.file("missing/out.csv")), 0u);
}

// writeNewFile replaces a symbolic link at its path (the file it points to keeps its bytes, a
// missing one is not created) and an earlier file; a folder at the path is an OutputError.
TEST(CsvOutput, NewFileIsNeverWrittenThroughALink)
{
    TempDir dir;
    std::ofstream(dir.file("victim")) << "keep me\n";
    std::filesystem::create_symlink(dir.file("victim"), dir.file("marker"));
    std::filesystem::create_symlink(dir.file("nowhere"), dir.file("dangling"));
    writeNewFile(dir.file("marker"), "marked\n");
    writeNewFile(dir.file("dangling"), "marked\n");
    writeNewFile(dir.file("dangling"), "again\n");
    EXPECT_EQ(readTextOf(dir.file("victim")), "keep me\n");
    EXPECT_FALSE(std::filesystem::exists(dir.file("nowhere")));
    EXPECT_FALSE(std::filesystem::is_symlink(dir.file("marker")));
    EXPECT_EQ(readTextOf(dir.file("marker")), "marked\n");
    EXPECT_EQ(readTextOf(dir.file("dangling")), "again\n");
    std::filesystem::create_directory(dir.file("folder"));
    EXPECT_THROW(writeNewFile(dir.file("folder"), "x"), OutputError);
}

} // namespace
} // namespace frontier::io::test
