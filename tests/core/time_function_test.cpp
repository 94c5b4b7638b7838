// tests/core/time_function_test.cpp: actuator targets as functions of time (core/time_function.h)
// against their formulas: a constant, a sine and its derivative, keyframes linear and the
// monotone cubic (values at the keyframes, a value worked out by hand from the Hermite form, C1
// continuity at the keyframes, no overshoot, rest at the ends, rate = derivative of value).
#include "core/time_function.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

namespace frontier::core
{
namespace
{

// dv/dt by a central difference (value unit per second).
double numericRate(const TimeFunction& f, double t)
{
    constexpr double h = 1e-6;
    return (valueAt(f, t + h) - valueAt(f, t - h)) / (2.0 * h);
}

TEST(TimeFunction, ConstantHasNoRate)
{
    const TimeFunction f = constantFunction(0.3);
    for (double t : {-1.0, 0.0, 2.5})
    {
        EXPECT_EQ(valueAt(f, t), 0.3);
        EXPECT_EQ(rateAt(f, t), 0.0);
    }
}

TEST(TimeFunction, SineIsOffsetPlusAmplitudeSineOfTwoPiFrequencyTimePlusPhase)
{
    const TimeFunction f = sineFunction(3.0, 0.5, 0.25, -1.0);
    for (double t : {0.0, 0.3, 1.0, 2.7})
    {
        const double angle = 2.0 * std::numbers::pi * 0.5 * t + 0.25;
        EXPECT_NEAR(valueAt(f, t), -1.0 + 3.0 * std::sin(angle), 1e-15);
        EXPECT_NEAR(rateAt(f, t), 3.0 * std::numbers::pi * std::cos(angle), 1e-14);
    }
}

TEST(TimeFunction, LinearKeyframesInterpolateAndHoldTheEnds)
{
    const TimeFunction f = keyframeFunction({0.0, 1.0, 3.0}, {0.0, 1.2, 0.2}, false);
    EXPECT_DOUBLE_EQ(valueAt(f, 0.5), 0.6);
    EXPECT_DOUBLE_EQ(valueAt(f, 2.0), 0.7);
    EXPECT_DOUBLE_EQ(rateAt(f, 0.5), 1.2);
    EXPECT_DOUBLE_EQ(rateAt(f, 2.0), -0.5);
    EXPECT_EQ(valueAt(f, -1.0), 0.0);
    EXPECT_EQ(valueAt(f, 5.0), 0.2);
    EXPECT_EQ(rateAt(f, 5.0), 0.0);
    EXPECT_EQ(valueAt(f, 1.0), 1.2);
}

TEST(TimeFunction, OneKeyframeIsAConstant)
{
    const TimeFunction f = keyframeFunction({2.0}, {0.7}, true);
    for (double t : {0.0, 2.0, 3.0})
    {
        EXPECT_EQ(valueAt(f, t), 0.7);
        EXPECT_EQ(rateAt(f, t), 0.0);
    }
}

// (0, 0), (1, 1), (2, 3): secants 1 and 2 over equal intervals, so the middle slope is the
// harmonic mean 2 / (1/1 + 1/2) = 4/3, the end slopes 0. At t = 0.5 the Hermite basis is
// h00 = 1/2, h10 = 1/8, h01 = 1/2, h11 = -1/8: v = 1/2 * 1 - 1/8 * 4/3 = 1/3; at t = 1.5,
// v = 1/2 + 1/8 * 4/3 + 1/2 * 3 = 13/6.
TEST(TimeFunction, SmoothKeyframesMatchTheHermiteFormWorkedByHand)
{
    const TimeFunction f = keyframeFunction({0.0, 1.0, 2.0}, {0.0, 1.0, 3.0}, true);
    EXPECT_NEAR(valueAt(f, 0.5), 1.0 / 3.0, 1e-15);
    EXPECT_NEAR(valueAt(f, 1.5), 13.0 / 6.0, 1e-15);
    EXPECT_NEAR(rateAt(f, 1.0), 4.0 / 3.0, 1e-15);
    EXPECT_EQ(rateAt(f, 0.0), 0.0);
    EXPECT_EQ(rateAt(f, 2.0), 0.0);
}

TEST(TimeFunction, SmoothKeyframesAreC1AndDoNotOvershoot)
{
    const std::vector<double> times = {0.0, 0.4, 1.0, 1.3, 2.5, 3.0};
    const std::vector<double> values = {0.0, 1.0, 1.1, 1.1, -0.5, 0.2};
    const TimeFunction f = keyframeFunction(times, values, true);
    for (std::size_t k = 0; k < times.size(); ++k)
    {
        const double t = times[k];
        EXPECT_NEAR(valueAt(f, t), values[k], 1e-15) << "keyframe " << k;
        constexpr double e = 1e-9;
        EXPECT_NEAR(valueAt(f, t - e), valueAt(f, t + e), 1e-8) << "value continuous at " << t;
        EXPECT_NEAR(rateAt(f, t - e), rateAt(f, t + e), 1e-7) << "rate continuous at " << t;
    }
    for (std::size_t k = 0; k + 1 < times.size(); ++k)
    {
        const double low = std::min(values[k], values[k + 1]);
        const double high = std::max(values[k], values[k + 1]);
        for (int i = 1; i < 100; ++i)
        {
            const double t = times[k] + (times[k + 1] - times[k]) * i / 100.0;
            EXPECT_GE(valueAt(f, t), low - 1e-15) << "t = " << t;
            EXPECT_LE(valueAt(f, t), high + 1e-15) << "t = " << t;
            EXPECT_NEAR(rateAt(f, t), numericRate(f, t), 1e-6) << "t = " << t;
        }
    }
    // Equal neighbours (1.1, 1.1) hold still between them; a turn (1.1 -> -0.5 -> 0.2) is flat.
    EXPECT_NEAR(valueAt(f, 1.15), 1.1, 1e-15);
    EXPECT_EQ(rateAt(f, 2.5), 0.0);
}

TEST(TimeFunction, LinearKeyframeRateIsTheDerivativeInsideIntervals)
{
    const TimeFunction f = keyframeFunction({0.0, 0.5, 2.0}, {1.0, -1.0, 2.0}, false);
    for (double t : {0.1, 0.3, 0.7, 1.9})
    {
        EXPECT_NEAR(rateAt(f, t), numericRate(f, t), 1e-8) << "t = " << t;
    }
}

} // namespace
} // namespace frontier::core
