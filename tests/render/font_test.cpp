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
