// tests/render/font_test.cpp: the 5x7 glyph table and text drawing.
#include "render/font.h"

#include <gtest/gtest.h>
#include <set>

namespace frontier::render
{
namespace
{

TEST(Font, GlyphsAreDistinctAndSpaceIsBlank)
{
    const std::string chars = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz.=-+:/()_";
    std::set<std::array<std::uint8_t, cGlyphHeight>> seen;
    for (char c : chars)
    {
        const auto rows = glyph(c);
        bool ink = false;
        for (std::uint8_t r : rows)
        {
            EXPECT_LT(r, 32) << c;
            ink = ink || r != 0;
        }
        EXPECT_TRUE(ink) << c;
        EXPECT_TRUE(seen.insert(rows).second) << "duplicate glyph for " << c;
    }
    for (std::uint8_t r : glyph(' '))
    {
        EXPECT_EQ(r, 0);
    }
    EXPECT_EQ(glyph('~'), glyph('?')); // unknown characters
}

bool inkBelowBaseline(char c)
{
    const auto rows = glyph(c);
    for (int r = cGlyphBaseline; r < cGlyphHeight; ++r)
    {
        if (rows[static_cast<std::size_t>(r)] != 0)
        {
            return true;
        }
    }
    return false;
}

bool inkOnBaselineRow(char c)
{
    return glyph(c)[static_cast<std::size_t>(cGlyphBaseline - 1)] != 0;
}

TEST(Font, DescendersDropBelowTheBaseline)
{
    for (char c : std::string("gjpqy,"))
    {
        EXPECT_TRUE(inkBelowBaseline(c)) << c;
    }
    for (char c : std::string("aceimnorsuvwxzABGJPQY0123456789."))
    {
        EXPECT_FALSE(inkBelowBaseline(c)) << c;
        EXPECT_TRUE(inkOnBaselineRow(c)) << c << " should stand on the baseline";
    }
}

TEST(Font, DrawnDescenderInksBelowTheBaseline)
{
    // "ag" at scale 1 from the top: 'a' ends on the baseline row, 'g' inks the rows below it.
    Image image;
    image.width = 12;
    image.height = cGlyphHeight;
    image.rgba.assign(static_cast<std::size_t>(12 * cGlyphHeight * 4), 0);
    drawText(image, 0, 0, "ag", 1, {255, 255, 255});
    auto inkedInRows = [&](int x0, int x1, int y0, int y1)
    {
        int n = 0;
        for (int y = y0; y < y1; ++y)
        {
            for (int x = x0; x < x1; ++x)
            {
                n += image.rgba[(static_cast<std::size_t>(y) * 12 + static_cast<std::size_t>(x)) * 4] == 255;
            }
        }
        return n;
    };
    EXPECT_EQ(inkedInRows(0, cGlyphWidth, cGlyphBaseline, cGlyphHeight), 0); // 'a'
    EXPECT_GT(inkedInRows(cGlyphAdvance, cGlyphAdvance + cGlyphWidth, cGlyphBaseline, cGlyphHeight), 0);
}

TEST(Font, DrawTextClipsAndInks)
{
    Image image;
    image.width = 20;
    image.height = 10;
    image.rgba.assign(20 * 10 * 4, 0);
    drawText(image, 15, 5, "888", 2, {255, 255, 255}); // mostly outside the image
    int inked = 0;
    for (std::size_t i = 0; i < image.rgba.size(); i += 4)
    {
        inked += image.rgba[i] == 255 ? 1 : 0;
    }
    EXPECT_GT(inked, 0);
    EXPECT_EQ(textWidth("ab", 1), 11);
    EXPECT_EQ(textWidth("", 3), 0);
}

} // namespace
} // namespace frontier::render
