// tests/render/png_io_test.cpp: PNG round trip and atomic, failing writes.
#include "render/renderer.h"
#include "test_scenes.h"

#include <filesystem>
#include <gtest/gtest.h>
#include <unistd.h>

namespace frontier::render
{
namespace
{

using testing::TempDir;

Image patternImage(int w, int h)
{
    Image image;
    image.width = w;
    image.height = h;
    image.rgba.resize(static_cast<std::size_t>(w) * h * 4);
    for (std::size_t i = 0; i < image.rgba.size(); ++i)
    {
        image.rgba[i] = static_cast<std::uint8_t>((i * 37 + i / 7) & 0xff); // includes partial alpha
    }
    return image;
}

std::size_t entries(const std::filesystem::path& dir)
{
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir))
    {
        ++n;
    }
    return n;
}

TEST(PngIo, RoundTripIsExact)
{
    const TempDir dir;
    const Image image = patternImage(37, 23);
    const std::string path = (dir.path() / "pattern.png").string();
    writePng(path, image);
    const Image back = readPng(path);
    EXPECT_EQ(back.width, 37);
    EXPECT_EQ(back.height, 23);
    EXPECT_EQ(back.rgba, image.rgba);
    EXPECT_EQ(entries(dir.path()), 1u); // no temporary left behind

    // Overwriting replaces the file.
    const Image second = patternImage(5, 4);
    writePng(path, second);
    EXPECT_EQ(readPng(path).rgba, second.rgba);
    EXPECT_EQ(entries(dir.path()), 1u);
}

TEST(PngIo, MissingDirectoryThrowsWithThePath)
{
    const TempDir dir;
    const std::string path = (dir.path() / "no" / "such" / "dir" / "a.png").string();
    try
    {
        writePng(path, patternImage(4, 4));
        FAIL() << "expected an exception";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "no"));
    EXPECT_EQ(entries(dir.path()), 0u);
}

TEST(PngIo, TargetIsADirectoryThrowsAndLeavesNothing)
{
    const TempDir dir;
    const std::filesystem::path target = dir.path() / "taken";
    std::filesystem::create_directory(target);
    EXPECT_THROW(writePng(target.string(), patternImage(4, 4)), std::runtime_error);
    EXPECT_EQ(entries(dir.path()), 1u); // only the directory itself
    EXPECT_TRUE(std::filesystem::is_directory(target));
}

TEST(PngIo, ReadOnlyDirectoryThrowsAndLeavesNothing)
{
    if (geteuid() == 0)
    {
        GTEST_SKIP() << "root ignores directory permissions";
    }
    const TempDir dir;
    std::filesystem::permissions(dir.path(),
                                 std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    EXPECT_THROW(writePng((dir.path() / "a.png").string(), patternImage(4, 4)), std::runtime_error);
    std::filesystem::permissions(dir.path(), std::filesystem::perms::owner_all);
    EXPECT_EQ(entries(dir.path()), 0u);
}

TEST(PngIo, BadInputsThrow)
{
    const TempDir dir;
    Image wrong = patternImage(4, 4);
    wrong.rgba.pop_back();
    EXPECT_THROW(writePng((dir.path() / "a.png").string(), wrong), std::runtime_error);
    EXPECT_THROW(writePng((dir.path() / "b.png").string(), Image{}), std::runtime_error);
    EXPECT_EQ(entries(dir.path()), 0u);
    EXPECT_THROW(readPng((dir.path() / "missing.png").string()), std::runtime_error);
}

} // namespace
} // namespace frontier::render
