// core/time_function.cpp: constants, sines and keyframes (linear or monotone cubic).
#include "core/time_function.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace frontier::core
{

namespace
{
std::string format(double value)
{
    std::ostringstream out;
    out << value;
    return out.str();
}
} // namespace

TimeFunction constantFunction(double value)
{
    TimeFunction f;
    f.constant = value;
    return f;
}

TimeFunction sineFunction(double amplitude, double frequency, double phase, double offset)
{
    TimeFunction f;
    f.kind = TimeFunction::Kind::Sine;
    f.amplitude = amplitude;
    f.frequency = frequency;
    f.phase = phase;
    f.offset = offset;
    return f;
}

TimeFunction keyframeFunction(std::vector<double> times, std::vector<double> values, bool smooth)
{
    TimeFunction f;
    f.kind = TimeFunction::Kind::Keyframes;
    f.times = std::move(times);
    f.values = std::move(values);
    if (!smooth)
    {
        return f;
    }
    // Fritsch-Carlson slopes: zero at the ends and where the secants change sign, else the
    // harmonic mean of the two secants weighted by the interval lengths (Fritsch and Butland).
    const std::size_t n = f.times.size();
    f.slopes.assign(n, 0.0);
    for (std::size_t k = 1; k + 1 < n; ++k)
    {
        const double h0 = f.times[k] - f.times[k - 1];
        const double h1 = f.times[k + 1] - f.times[k];
        const double d0 = (f.values[k] - f.values[k - 1]) / h0;
        const double d1 = (f.values[k + 1] - f.values[k]) / h1;
        if (d0 * d1 > 0.0)
        {
            const double w0 = 2.0 * h1 + h0;
            const double w1 = h1 + 2.0 * h0;
            f.slopes[k] = (w0 + w1) / (w0 / d0 + w1 / d1);
        }
    }
    return f;
}

std::string overflowDefect(const TimeFunction& f, double horizon, std::size_t* keyframe)
{
    const auto finite = [](double x) { return std::isfinite(x); };
    switch (f.kind)
    {
    case TimeFunction::Kind::Constant:
        return {};
    case TimeFunction::Kind::Sine:
    {
        const double omega = 2.0 * std::numbers::pi * f.frequency; // rad/s
        if (!finite(omega * horizon + std::abs(f.phase)))
        {
            return "2 pi x frequency x t overflows within a run (t up to " + format(horizon) + " s)";
        }
        if (!finite(f.amplitude * omega))
        {
            return "its rate, amplitude x 2 pi x frequency, overflows";
        }
        if (!finite(std::abs(f.offset) + std::abs(f.amplitude)))
        {
            return "offset + amplitude overflows";
        }
        return {};
    }
    case TimeFunction::Kind::Keyframes:
        break;
    }
    for (std::size_t k = 0; k + 1 < f.times.size(); ++k)
    {
        const double h = f.times[k + 1] - f.times[k];
        const double step = f.values[k + 1] - f.values[k];
        const double slope0 = f.slopes.empty() ? 0.0 : f.slopes[k];
        const double slope1 = f.slopes.empty() ? 0.0 : f.slopes[k + 1];
        std::string defect;
        if (!finite(h))
        {
            defect = "the time from the keyframe before overflows";
        }
        else if (!finite(step))
        {
            defect = "the change of value from the keyframe before overflows";
        }
        else if (!finite(step / h) || !finite(1.5 * std::abs(step / h) + std::abs(slope0) + std::abs(slope1)))
        {
            defect = "the rate from the keyframe before (value change / time) overflows";
        }
        else if (!finite(std::abs(f.values[k]) + std::abs(f.values[k + 1]) + std::abs(h * slope0) +
                         std::abs(h * slope1)))
        {
            defect = "the smooth curve from the keyframe before overflows";
        }
        if (!defect.empty())
        {
            if (keyframe != nullptr)
            {
                *keyframe = k + 1;
            }
            return defect;
        }
    }
    return {};
}

namespace
{
// The keyframe interval [t_k, t_k+1] holding t, for t inside the keyframes' span.
std::size_t intervalOf(const TimeFunction& f, double t)
{
    const auto upper = std::upper_bound(f.times.begin(), f.times.end(), t);
    const std::size_t k = static_cast<std::size_t>(upper - f.times.begin());
    return std::min(k, f.times.size() - 1) - 1;
}

bool beforeOrAfter(const TimeFunction& f, double t)
{
    return f.times.size() < 2 || t <= f.times.front() || t >= f.times.back();
}

double heldValue(const TimeFunction& f, double t)
{
    return t <= f.times.front() ? f.values.front() : f.values.back();
}
} // namespace

double valueAt(const TimeFunction& f, double t)
{
    switch (f.kind)
    {
    case TimeFunction::Kind::Constant:
        return f.constant;
    case TimeFunction::Kind::Sine:
        return f.offset + f.amplitude * std::sin(2.0 * std::numbers::pi * f.frequency * t + f.phase);
    case TimeFunction::Kind::Keyframes:
        break;
    }
    if (beforeOrAfter(f, t))
    {
        return heldValue(f, t);
    }
    const std::size_t k = intervalOf(f, t);
    const double h = f.times[k + 1] - f.times[k];
    const double s = (t - f.times[k]) / h; // 0..1 across the interval
    const double v0 = f.values[k];
    const double v1 = f.values[k + 1];
    if (f.slopes.empty())
    {
        return v0 + s * (v1 - v0);
    }
    // Cubic Hermite basis on [0, 1].
    const double s2 = s * s;
    const double s3 = s2 * s;
    return (2.0 * s3 - 3.0 * s2 + 1.0) * v0 + (s3 - 2.0 * s2 + s) * h * f.slopes[k] +
           (-2.0 * s3 + 3.0 * s2) * v1 + (s3 - s2) * h * f.slopes[k + 1];
}

double rateAt(const TimeFunction& f, double t)
{
    switch (f.kind)
    {
    case TimeFunction::Kind::Constant:
        return 0.0;
    case TimeFunction::Kind::Sine:
    {
        const double omega = 2.0 * std::numbers::pi * f.frequency; // rad/s
        return f.amplitude * omega * std::cos(omega * t + f.phase);
    }
    case TimeFunction::Kind::Keyframes:
        break;
    }
    if (beforeOrAfter(f, t))
    {
        return 0.0; // held
    }
    const std::size_t k = intervalOf(f, t);
    const double h = f.times[k + 1] - f.times[k];
    const double secant = (f.values[k + 1] - f.values[k]) / h;
    if (f.slopes.empty())
    {
        return secant;
    }
    const double s = (t - f.times[k]) / h;
    const double s2 = s * s;
    // d/dt of the Hermite form above.
    return (6.0 * s - 6.0 * s2) * secant + (3.0 * s2 - 4.0 * s + 1.0) * f.slopes[k] +
           (3.0 * s2 - 2.0 * s) * f.slopes[k + 1];
}

} // namespace frontier::core
