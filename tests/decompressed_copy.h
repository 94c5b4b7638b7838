// tests/decompressed_copy.h: a folder of input files (Debian's dart-doc MJCF and SDF data) copied
// into a test's temporary folder with every FILE.gz decompressed to FILE beside the rest, so that
// the files' includes and meshes resolve as in the package (Debian compresses its larger files).
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <vector>
#include <zlib.h>

// Decompresses gzip file `from` into `to`.
inline void gunzipFile(const std::filesystem::path& from, const std::filesystem::path& to)
{
    gzFile in = gzopen(from.c_str(), "rb");
    ASSERT_NE(in, nullptr) << from;
    std::ofstream out(to, std::ios::binary);
    char buffer[1 << 16];
    int n = 0;
    while ((n = gzread(in, buffer, sizeof buffer)) > 0)
    {
        out.write(buffer, n);
    }
    EXPECT_EQ(n, 0) << "cannot decompress " << from;
    gzclose(in);
}

// `from` copied into `to` (symbolic links kept as links), each FILE.gz also as FILE unless the
// package holds FILE too; the files of the copy but the .gz ones, relative to `to`, sorted.
inline std::vector<std::string> copyDecompressed(const std::filesystem::path& from,
                                                 const std::filesystem::path& to)
{
    namespace fs = std::filesystem;
    fs::copy(from, to, fs::copy_options::recursive | fs::copy_options::copy_symlinks);
    std::vector<std::string> files;
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(to))
    {
        if (entry.is_directory())
        {
            continue;
        }
        fs::path file = entry.path();
        if (file.extension() == ".gz")
        {
            file.replace_extension();
            if (fs::exists(file))
            {
                continue;
            }
            gunzipFile(entry.path(), file);
        }
        files.push_back(fs::relative(file, to).string());
    }
    // A file decompressed during the walk may be visited too.
    std::sort(files.begin(), files.end());
    files.erase(std::unique(files.begin(), files.end()), files.end());
    return files;
}
