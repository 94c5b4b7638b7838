// core/time_function.h: a value as a function of time, what an actuator follows (a joint angle,
// length, speed or effort; its unit is the actuator's).
//
//   constant   v(t) = c
//   sine       v(t) = offset + amplitude sin(2 pi frequency t + phase)   (frequency in Hz, phase in rad)
//   keyframes  (t_k, v_k) with t_0 < t_1 < ...: piecewise linear between them, or with `smooth` a
//              monotone cubic: Hermite pieces whose slopes are Fritsch and Carlson's weighted
//              harmonic mean of the neighbouring secants (the PCHIP of Fritsch and Butland, 1984),
//              zero where the data turn (a local extremum) and at the first and last keyframe. So
//              the curve is C1, never overshoots the keyframes (a target between two keyframes stays
//              between their values) and starts and ends at rest. Before t_0 the value is v_0, after
//              the last keyframe the last value.
//
// rate(t) is dv/dt (the value's unit per second): a position servo damps towards it.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace frontier::core
{

struct TimeFunction
{
    enum class Kind
    {
        Constant,
        Sine,
        Keyframes,
    };
    Kind kind = Kind::Constant;
    double constant = 0.0;      // Constant
    double amplitude = 0.0;     // Sine
    double frequency = 0.0;     // Sine (Hz)
    double phase = 0.0;         // Sine (rad)
    double offset = 0.0;        // Sine
    std::vector<double> times;  // Keyframes: strictly increasing (s)
    std::vector<double> values; // Keyframes: one per time
    std::vector<double> slopes; // Keyframes, smooth: dv/dt at each keyframe; empty: piecewise linear
};

TimeFunction constantFunction(double value);
TimeFunction sineFunction(double amplitude, double frequency, double phase, double offset);
// Keyframes (times strictly increasing, at least one); smooth: the monotone cubic above.
TimeFunction keyframeFunction(std::vector<double> times, std::vector<double> values, bool smooth);

// Why a function of finite parameters would still give a non-finite value or rate at some time of a
// run, t in [0, horizon] s (the longest run, core::cMaxDuration): a sine whose 2 pi f t, amplitude
// x 2 pi f or offset + amplitude overflows; keyframes whose interval, value step, slope or curve
// terms do. "" when it never does; for keyframes *keyframe (when given) receives the index of the
// keyframe that ends the interval at fault.
std::string overflowDefect(const TimeFunction& function, double horizon, std::size_t* keyframe = nullptr);

double valueAt(const TimeFunction& function, double t);
double rateAt(const TimeFunction& function, double t);

} // namespace frontier::core
