// tests/render/renderer_test.cpp: rendered pixels, shadows, caption, determinism, threads.
#include "render/renderer.h"
#include "test_scenes.h"

#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <thread>

namespace frontier::render
{
namespace
{

using testing::TempDir;

const core::Vec3 cLight(0.5, 0.3, -1.0); // travels towards +x, +y and down

RenderOptions smallOptions(bool caption = false)
{
    RenderOptions o;
    o.width = 320;
    o.height = 240;
    o.caption = caption;
    o.lightDirection = cLight;
    return o;
}

// Mean RGB over a 3x3 block centred on (x, y).
std::array<double, 3> pixel(const Image& image, int x, int y)
{
    std::array<double, 3> sum{0, 0, 0};
    for (int dy = -1; dy <= 1; ++dy)
    {
        for (int dx = -1; dx <= 1; ++dx)
        {
            const std::size_t i = (static_cast<std::size_t>(y + dy) * image.width + (x + dx)) * 4;
            for (int k = 0; k < 3; ++k)
            {
                sum[static_cast<std::size_t>(k)] += image.rgba[i + static_cast<std::size_t>(k)];
            }
        }
    }
    for (double& s : sum)
    {
        s /= 9.0;
    }
    return sum;
}

double luminance(const std::array<double, 3>& c)
{
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

// Pixel of a floor point (z = 0) for the red box scene's camera: 3 m above, looking down, +y up.
std::array<int, 2> floorPixel(const Image& image, double x, double y)
{
    const double perMetre = image.height / (2.0 * 3.0 * std::tan(22.5 * std::numbers::pi / 180.0));
    return {static_cast<int>(std::lround(image.width / 2.0 + x * perMetre)),
            static_cast<int>(std::lround(image.height / 2.0 - y * perMetre))};
}

TEST(Renderer, TopDownRedBoxOnTheFloor)
{
    const core::Model model = testing::redBoxScene();
    Renderer renderer(model, smallOptions());
    const Image image = renderer.render(core::initialState(model));
    ASSERT_EQ(image.width, 320);
    ASSERT_EQ(image.height, 240);
    ASSERT_EQ(image.rgba.size(), 320u * 240u * 4u);

    const auto centre = pixel(image, 160, 120);
    EXPECT_GT(centre[0], 150) << "centre should be red";
    EXPECT_LT(centre[1], 90);
    EXPECT_LT(centre[2], 90);

    // The bottom corners show the grey floor, not the bluish background.
    for (int x : {4, 315})
    {
        const auto corner = pixel(image, x, 235);
        EXPECT_LT(std::abs(corner[0] - corner[2]), 12) << "corner " << x;
        EXPECT_LT(std::abs(corner[0] - corner[1]), 12) << "corner " << x;
        EXPECT_GT(luminance(corner), 60) << "corner " << x;
    }
    for (std::size_t i = 3; i < image.rgba.size(); i += 4)
    {
        ASSERT_EQ(image.rgba[i], 255);
    }
}

TEST(Renderer, BoxCastsAShadowAwayFromTheLight)
{
    const core::Model model = testing::redBoxScene();
    Renderer renderer(model, smallOptions());
    EXPECT_TRUE(renderer.lightDirection().isApprox(cLight.normalized()));
    const Image image = renderer.render(core::initialState(model));

    // The same view (camera and floor are fixed by the first render) with the box far away.
    core::State empty = core::initialState(model);
    empty.bodies[1].position_W = core::Vec3(100, 100, 0.2);
    const Image floorOnly = renderer.render(empty);

    // Next to the box, downstream of the light, and the mirror point on the lit side. Point
    // reflection through the origin keeps the checker tile colour (tiles are anchored at 0).
    const auto shadowAt = floorPixel(image, 0.28, 0.17);
    const auto litAt = floorPixel(image, -0.28, -0.17);
    const double shadow = luminance(pixel(image, shadowAt[0], shadowAt[1]));
    const double lit = luminance(pixel(image, litAt[0], litAt[1]));
    const double bareShadow = luminance(pixel(floorOnly, shadowAt[0], shadowAt[1]));
    const double bareLit = luminance(pixel(floorOnly, litAt[0], litAt[1]));
    EXPECT_LT(shadow, 0.75 * lit) << "shadow " << shadow << " lit " << lit;
    EXPECT_LT(shadow, 0.75 * bareShadow);
    EXPECT_NEAR(lit, bareLit, 0.05 * bareLit);
}

bool isRed(const std::array<double, 3>& c)
{
    return c[0] > 150 && c[1] < 90 && c[2] < 90;
}

// The red box body of redBoxScene with a render-only visual: a 0.4 m box 0.8 m to the side of
// its 0.3 m collision box. Seen from above, the red shows where the visual is, not the collision
// box; without the visual it is the other way round.
TEST(Renderer, DrawsTheVisualsInsteadOfTheCollisionShapes)
{
    core::Model model = testing::redBoxScene();
    core::Body& body = model.bodies.at(1);
    body.shapes.at(0).size = core::Vec3(0.3, 0.3, 0.3);
    core::Shape visual;
    visual.type = core::ShapeType::Box;
    visual.size = core::Vec3(0.4, 0.4, 0.4);
    visual.position_BS = core::Vec3(0.8, 0.0, 0.0);
    body.visuals.push_back(visual);

    Renderer withVisual(model, smallOptions());
    const Image drawn = withVisual.render(core::initialState(model));
    const auto visualAt = floorPixel(drawn, 0.8, 0.0);
    const auto collisionAt = floorPixel(drawn, 0.0, 0.0);
    EXPECT_TRUE(isRed(pixel(drawn, visualAt[0], visualAt[1])));
    EXPECT_FALSE(isRed(pixel(drawn, collisionAt[0], collisionAt[1])));

    body.visuals.clear();
    Renderer collisionOnly(model, smallOptions());
    const Image shapes = collisionOnly.render(core::initialState(model));
    EXPECT_FALSE(isRed(pixel(shapes, visualAt[0], visualAt[1])));
    EXPECT_TRUE(isRed(pixel(shapes, collisionAt[0], collisionAt[1])));
}

TEST(Renderer, ImageSizeAsAsked)
{
    const core::Model model = testing::mixedScene(5);
    RenderOptions o;
    o.width = 333;
    o.height = 199;
    Renderer renderer(model, o);
    const Image image = renderer.render(core::initialState(model));
    EXPECT_EQ(image.width, 333);
    EXPECT_EQ(image.height, 199);
    EXPECT_EQ(image.rgba.size(), 333u * 199u * 4u);
}

TEST(Renderer, SameStateGivesIdenticalBytes)
{
    const core::Model model = testing::mixedScene(10);
    const core::State state = core::initialState(model);
    Renderer renderer(model, smallOptions(true));
    const Image first = renderer.render(state);
    const Image second = renderer.render(state);
    EXPECT_EQ(first.rgba, second.rgba);
    Renderer other(model, smallOptions(true));
    EXPECT_EQ(other.render(state).rgba, first.rgba);
}

TEST(Renderer, CameraIsFramedOnceThenKept)
{
    core::Model model = testing::mixedScene(5);
    Renderer renderer(model, smallOptions());
    core::State state = core::initialState(model);
    const Image before = renderer.render(state);
    for (std::size_t i = 1; i < state.bodies.size(); ++i)
    {
        state.bodies[i].position_W += core::Vec3(0, 0, 0.5); // everything rises
    }
    renderer.render(state);
    state = core::initialState(model);
    EXPECT_EQ(renderer.render(state).rgba, before.rgba);
}

TEST(Renderer, RenderedPngReadsBackEqual)
{
    const TempDir dir;
    const core::Model model = testing::mixedScene(10);
    Renderer renderer(model, smallOptions(true));
    const Image image = renderer.render(core::initialState(model));
    const std::string path = (dir.path() / "frame.png").string();
    writePng(path, image);
    const Image back = readPng(path);
    EXPECT_EQ(back.width, image.width);
    EXPECT_EQ(back.height, image.height);
    EXPECT_EQ(back.rgba, image.rgba);
}

TEST(Renderer, CaptionChangesOnlyItsCorner)
{
    const core::Model model = testing::redBoxScene();
    core::State state = core::initialState(model);
    state.time = 1.234;
    Renderer with(model, smallOptions(true));
    Renderer without(model, smallOptions(false));
    const Image a = with.render(state);
    const Image b = without.render(state);
    auto differs = [&](int x0, int y0, int x1, int y1)
    {
        int count = 0;
        for (int y = y0; y < y1; ++y)
        {
            for (int x = x0; x < x1; ++x)
            {
                const std::size_t i = (static_cast<std::size_t>(y) * a.width + x) * 4;
                count += (a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1]) ? 1 : 0;
            }
        }
        return count;
    };
    EXPECT_GT(differs(0, 0, 160, 20), 200);
    EXPECT_EQ(differs(0, 40, 320, 240), 0);

    // A different time changes the caption.
    state.time = 2.5;
    EXPECT_NE(with.render(state).rgba, a.rgba);
}

TEST(Renderer, TwoThreadsWithOwnRenderers)
{
    const core::Model model = testing::mixedScene(10);
    core::State moved = core::initialState(model);
    moved.time = 0.5;
    for (std::size_t i = 1; i < moved.bodies.size(); ++i)
    {
        moved.bodies[i].position_W.z() += 0.1 * static_cast<double>(i);
    }
    // Reference frames, one thread.
    std::vector<Image> expected;
    {
        Renderer r(model, smallOptions(true));
        expected.push_back(r.render(core::initialState(model)));
        expected.push_back(r.render(moved));
    }
    std::vector<Image> results[2];
    auto work = [&](int k)
    {
        Renderer r(model, smallOptions(true));
        for (int repeat = 0; repeat < 5; ++repeat)
        {
            results[k].push_back(r.render(core::initialState(model)));
            results[k].push_back(r.render(moved));
        }
    };
    std::thread t0(work, 0);
    std::thread t1(work, 1);
    t0.join();
    t1.join();
    for (const auto& frames : results)
    {
        ASSERT_EQ(frames.size(), 10u);
        for (std::size_t i = 0; i < frames.size(); ++i)
        {
            EXPECT_EQ(frames[i].rgba, expected[i % 2].rgba) << "frame " << i;
        }
    }
}

TEST(Renderer, StateOfTheWrongSizeThrows)
{
    const core::Model model = testing::redBoxScene();
    Renderer renderer(model, smallOptions());
    core::State state = core::initialState(model);
    state.bodies.pop_back();
    EXPECT_THROW(renderer.render(state), std::invalid_argument);
}

TEST(Renderer, BadImageSizeThrows)
{
    RenderOptions o;
    o.width = 0;
    EXPECT_THROW(Renderer(testing::redBoxScene(), o), std::runtime_error);
}

} // namespace
} // namespace frontier::render
