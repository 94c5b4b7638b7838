// tests/io/io_test_util.h: temporary directories, files, and catching InputError.
#pragma once

#include "io/scene.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <string>
#include <unistd.h>

namespace frontier::io::test
{

// A fresh directory, removed with its contents at the end of the test.
class TempDir
{
  public:
    TempDir()
    {
        std::string pattern = (std::filesystem::temp_directory_path() / "frontier-io-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr)
        {
            throw std::runtime_error("mkdtemp failed");
        }
        mPath = pattern;
    }
    ~TempDir()
    {
        std::error_code ec;
        std::filesystem::remove_all(mPath, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    std::string file(const std::string& name) const { return (mPath / name).string(); }
    std::string write(const std::string& name, const std::string& text) const
    {
        const std::string path = file(name);
        std::ofstream out(path, std::ios::binary);
        out << text;
        return path;
    }
    const std::filesystem::path& path() const { return mPath; }

  private:
    std::filesystem::path mPath;
};

// Entries of a directory (the output files and any temporary file beside them).
inline std::size_t filesIn(const std::filesystem::path& dir)
{
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir))
    {
        ++n;
    }
    return n;
}

inline std::string readTextOf(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Text of a raw string literal without its first newline, so that R"(
// line 1 ...)" numbers lines from the line after the opening.
inline std::string text(const char* raw)
{
    std::string s = raw;
    if (!s.empty() && s.front() == '\n')
    {
        s.erase(0, 1);
    }
    return s;
}

// Runs `load` and returns the InputError it throws (a test failure if it throws nothing).
template <typename F> InputError captureInputError(F&& load)
{
    try
    {
        load();
    }
    catch (const InputError& e)
    {
        return e;
    }
    ADD_FAILURE() << "expected an InputError, but loading succeeded";
    return InputError("", -1, -1, "no error");
}

inline InputError yamlError(const std::string& yaml, const std::string& sourceName = "scene.yaml")
{
    return captureInputError([&] { loadSceneFromString(yaml, sourceName); });
}

} // namespace frontier::io::test

// Checks file, line, column and that the message contains `needle`.
#define EXPECT_INPUT_ERROR_AT(error, fileName, lineNo, columnNo, needle)                                     \
    do                                                                                                       \
    {                                                                                                        \
        const ::frontier::io::InputError& err_ = (error);                                                    \
        EXPECT_EQ(err_.file(), (fileName)) << err_.what();                                                   \
        EXPECT_EQ(err_.line(), (lineNo)) << err_.what();                                                     \
        EXPECT_EQ(err_.column(), (columnNo)) << err_.what();                                                 \
        EXPECT_NE(std::string(err_.what()).find(needle), std::string::npos)                                  \
            << "message: " << err_.what() << "\nexpected to contain: " << (needle);                          \
    } while (false)
