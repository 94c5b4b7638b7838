// tests/render/framing_test.cpp: the automatic camera framed over a whole run (Renderer::frameRun)
// and the shadow of a resting body under the default light.
#include "render/font.h"
#include "render/renderer.h"
#include "test_scenes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>

namespace frontier::render
{
namespace
{

RenderOptions framingOptions()
{
    RenderOptions o;
    o.width = 160;
    o.height = 120;
    o.caption = false;
    o.msaaSamples = 1;
    o.shadowMapSize = 256;
    return o;
}

// Pixels of the bodies: strongly coloured, unlike the grey floor, the grey-blue sky and shadows.
bool isBody(const Image& image, int x, int y)
{
    const std::size_t i = (static_cast<std::size_t>(y) * image.width + x) * 4;
    const int r = image.rgba[i];
    const int g = image.rgba[i + 1];
    const int b = image.rgba[i + 2];
    return std::max({r, g, b}) - std::min({r, g, b}) > 60;
}

struct PixelBox
{
    int x0 = 1 << 30;
    int y0 = 1 << 30;
    int x1 = -1; // inclusive
    int y1 = -1;
    long count = 0;
};

PixelBox bodyPixels(const Image& image)
{
    PixelBox box;
    for (int y = 0; y < image.height; ++y)
    {
        for (int x = 0; x < image.width; ++x)
        {
            if (isBody(image, x, y))
            {
                box.x0 = std::min(box.x0, x);
                box.y0 = std::min(box.y0, y);
                box.x1 = std::max(box.x1, x);
                box.y1 = std::max(box.y1, y);
                ++box.count;
            }
        }
    }
    return box;
}

// A red ball thrown sideways: 6 m along x in an arc 2 m high, landing on the floor.
std::vector<core::State> throwBall(const core::Model& model)
{
    std::vector<core::State> states;
    for (int k = 0; k <= 12; ++k)
    {
        const double s = k / 12.0;
        core::State state = core::initialState(model);
        state.time = s;
        state.bodies[1].position_W = core::Vec3(-3.0 + 6.0 * s, 0.5 * s, 0.15 + 8.0 * s * (1.0 - s));
        states.push_back(state);
    }
    return states;
}

core::Model ballScene()
{
    core::Model model;
    model.name = "thrown ball";
    model.bodies.push_back(testing::groundBody());
    core::Shape ball;
    ball.type = core::ShapeType::Sphere;
    ball.radius = 0.15;
    core::Body body = testing::movingBody("ball", ball, core::Vec3(-3, 0, 0.15));
    body.color = core::Vec3(0.9, 0.1, 0.1);
    model.bodies.push_back(body);
    return model;
}

TEST(Framing, ThrownBallStaysInsideEveryFrame)
{
    const core::Model model = ballScene();
    const std::vector<core::State> states = throwBall(model);
    Renderer renderer(model, framingOptions());
    renderer.frameRun(states);
    const int border = 2; // pixels
    for (const core::State& state : states)
    {
        const Image image = renderer.render(state);
        const PixelBox box = bodyPixels(image);
        ASSERT_GT(box.count, 20) << "t = " << state.time << ": the ball is not in the frame";
        EXPECT_GE(box.x0, border) << "t = " << state.time;
        EXPECT_GE(box.y0, border) << "t = " << state.time;
        EXPECT_LT(box.x1, image.width - border) << "t = " << state.time;
        EXPECT_LT(box.y1, image.height - border) << "t = " << state.time;
    }

    // Framed from the first pose alone, the ball leaves the picture: the run framing is needed.
    Renderer firstOnly(model, framingOptions());
    firstOnly.frameFrom(states.front());
    const PixelBox last = bodyPixels(firstOnly.render(states.back()));
    EXPECT_TRUE(last.count == 0 || last.x1 >= framingOptions().width - border);
}

TEST(Framing, BodiesStayBelowTheCaption)
{
    const core::Model model = ballScene();
    const std::vector<core::State> states = throwBall(model);
    RenderOptions options = framingOptions();
    options.caption = true;
    Renderer renderer(model, options);
    renderer.frameRun(states);
    int top = options.height;
    for (const core::State& state : states)
    {
        const PixelBox box = bodyPixels(renderer.render(state));
        ASSERT_GT(box.count, 20);
        top = std::min(top, box.y0);
    }
    EXPECT_GE(top, captionRows(options.width, options.height));
    EXPECT_LT(top, captionRows(options.width, options.height) + 12); // the arc's top is close to it
}

// Twelve coloured bars dropped from a stack up to 1.2 m high that end scattered over 2 m x 2 m of
// floor: the last frame of the pile fills the picture.
TEST(Framing, PileupFillsTheFrame)
{
    core::Model model;
    model.name = "pile";
    model.bodies.push_back(testing::groundBody());
    core::Shape bar;
    bar.type = core::ShapeType::Box;
    bar.size = core::Vec3(0.6, 0.1, 0.1);
    const int count = 12;
    for (int i = 0; i < count; ++i)
    {
        core::Body body =
            testing::movingBody("bar" + std::to_string(i), bar, core::Vec3(0, 0, 0.05 + 0.1 * i));
        body.orientation_WB = core::Quat(Eigen::AngleAxisd(0.5 * i, core::Vec3::UnitZ()));
        model.bodies.push_back(body);
    }
    core::State start = core::initialState(model);
    core::State end = start;
    end.time = 2.0;
    for (int i = 0; i < count; ++i)
    {
        const double angle = 2.0 * 3.14159265358979 * i / count;
        const double reach = 0.4 + 0.5 * (i % 3);
        end.bodies[static_cast<std::size_t>(i) + 1].position_W =
            core::Vec3(reach * std::cos(angle), reach * std::sin(angle), 0.05);
    }
    core::State middle = start;
    middle.time = 1.0;
    for (std::size_t b = 1; b < middle.bodies.size(); ++b)
    {
        middle.bodies[b].position_W = 0.5 * (start.bodies[b].position_W + end.bodies[b].position_W);
    }
    const std::vector<core::State> states = {start, middle, end};
    Renderer renderer(model, framingOptions());
    renderer.frameRun(states);
    const Image image = renderer.render(end);
    const PixelBox box = bodyPixels(image);
    const double width = static_cast<double>(box.x1 - box.x0 + 1) / image.width;
    const double height = static_cast<double>(box.y1 - box.y0 + 1) / image.height;
    EXPECT_GT(width, 0.75) << "the pile spans " << width << " of the width";
    EXPECT_GT(height, 0.3) << "the pile spans " << height << " of the height";
    EXPECT_GT(static_cast<double>(box.count) / (image.width * image.height), 0.08);
    for (const core::State& state : states)
    {
        const PixelBox b = bodyPixels(renderer.render(state));
        EXPECT_GE(b.x0, 1);
        EXPECT_GE(b.y0, 1);
        EXPECT_LT(b.x1, image.width - 1);
        EXPECT_LT(b.y1, image.height - 1);
    }
}

// Mean luminance (0..255) over a 3x3 block centred on (x, y).
double luminance(const Image& image, int x, int y)
{
    double sum = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
    {
        for (int dx = -1; dx <= 1; ++dx)
        {
            const std::size_t i = (static_cast<std::size_t>(y + dy) * image.width + (x + dx)) * 4;
            sum += 0.2126 * image.rgba[i] + 0.7152 * image.rgba[i + 1] + 0.0722 * image.rgba[i + 2];
        }
    }
    return sum / 9.0;
}

// The red box of redBoxScene resting on the floor under the default light (from +x, 55 degrees
// up): the floor next to it on the -x side is in its shadow and visibly darker than the floor on
// the +x side, and than the same spot with the box gone.
TEST(Framing, RestingBoxCastsAVisibleShadowUnderTheDefaultLight)
{
    const core::Model model = testing::redBoxScene();
    RenderOptions options = framingOptions();
    options.width = 320;
    options.height = 240;
    options.shadowMapSize = 1024;
    Renderer renderer(model, options);
    const Image image = renderer.render(core::initialState(model));
    core::State gone = core::initialState(model);
    gone.bodies[1].position_W = core::Vec3(100, 100, 0.2);
    const Image bare = renderer.render(gone);
    // 3 m above, 45 degree field of view: pixels per metre on the floor.
    const double perMetre = options.height / (2.0 * 3.0 * std::tan(22.5 * 3.14159265358979 / 180.0));
    auto px = [&](double x) { return static_cast<int>(std::lround(options.width / 2.0 + x * perMetre)); };
    const int row = options.height / 2;
    // Mirror points through the box's centre keep the checker tile (tiles are anchored at 0).
    const double shadow = luminance(image, px(-0.3), row);
    const double lit = luminance(image, px(0.3), row);
    const double bareShadowSpot = luminance(bare, px(-0.3), row);
    EXPECT_LT(shadow, 0.7 * lit) << "shadow " << shadow << ", lit floor " << lit;
    EXPECT_LT(shadow, 0.7 * bareShadowSpot);
    EXPECT_NEAR(luminance(bare, px(0.3), row), lit, 0.05 * lit);
}

} // namespace
} // namespace frontier::render
