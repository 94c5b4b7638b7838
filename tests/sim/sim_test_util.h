// tests/sim/sim_test_util.h: scene paths, stepping helpers and state comparisons for the
// physics tests.
#pragma once

#include "core/model.h"
#include "core/simulator.h"
#include "core/state.h"
#include "io/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>

namespace frontier::sim::test
{

inline std::string scenePath(const std::string& file)
{
    return std::string(FRONTIER_SOURCE_DIR) + "/scenes/" + file;
}

inline core::Model loadBundled(const std::string& file)
{
    return io::loadScene(scenePath(file));
}

// FRONTIER_BINARY_DIR/test-tmp/<suite>.<test>, created empty, removed with its contents at the end.
class TestDir
{
  public:
    TestDir()
    {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = std::string("sim.") + info->test_suite_name() + "." + info->name();
        for (char& c : name)
        {
            c = (c == '/') ? '_' : c;
        }
        mPath = std::filesystem::path(FRONTIER_BINARY_DIR) / "test-tmp" / name;
        std::filesystem::remove_all(mPath);
        std::filesystem::create_directories(mPath);
    }
    ~TestDir()
    {
        std::error_code ec;
        std::filesystem::remove_all(mPath, ec);
    }
    TestDir(const TestDir&) = delete;
    TestDir& operator=(const TestDir&) = delete;

    std::string write(const std::string& name, const std::string& text) const
    {
        const std::string path = (mPath / name).string();
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }
    const std::filesystem::path& path() const { return mPath; }

  private:
    std::filesystem::path mPath;
};

// A number for RecordProperty (which would truncate a double to an int), 6 significant digits.
inline std::string sci(double value)
{
    char text[32];
    std::snprintf(text, sizeof(text), "%.6g", value);
    return text;
}

inline long stepsFor(double duration, double dt)
{
    return static_cast<long>(std::llround(duration / dt));
}

// The 13 numbers of a body state: position, quaternion (x y z w as Eigen stores them), velocity,
// angular velocity.
inline void flatten(const core::BodyState& s, double out[13])
{
    std::memcpy(out, s.position_W.data(), 3 * sizeof(double));
    std::memcpy(out + 3, s.orientation_WB.coeffs().data(), 4 * sizeof(double));
    std::memcpy(out + 7, s.velocity_W.data(), 3 * sizeof(double));
    std::memcpy(out + 10, s.angularVelocity_W.data(), 3 * sizeof(double));
}

// True when both states hold the same bits in every number (time, step and every body).
inline bool bitIdentical(const core::State& a, const core::State& b)
{
    if (a.bodies.size() != b.bodies.size() || a.step != b.step ||
        std::memcmp(&a.time, &b.time, sizeof(double)) != 0)
    {
        return false;
    }
    for (std::size_t i = 0; i < a.bodies.size(); ++i)
    {
        double x[13];
        double y[13];
        flatten(a.bodies[i], x);
        flatten(b.bodies[i], y);
        if (std::memcmp(x, y, sizeof(x)) != 0)
        {
            return false;
        }
    }
    return true;
}

// Largest difference between two states over positions (m), orientations (quaternion
// coefficients, sign-insensitive), velocities (m/s) and angular velocities (rad/s).
inline double stateDifference(const core::State& a, const core::State& b)
{
    double d = 0.0;
    for (std::size_t i = 0; i < std::min(a.bodies.size(), b.bodies.size()); ++i)
    {
        const core::BodyState& s = a.bodies[i];
        const core::BodyState& t = b.bodies[i];
        d = std::max(d, (s.position_W - t.position_W).cwiseAbs().maxCoeff());
        d = std::max(d,
                     std::min((s.orientation_WB.coeffs() - t.orientation_WB.coeffs()).cwiseAbs().maxCoeff(),
                              (s.orientation_WB.coeffs() + t.orientation_WB.coeffs()).cwiseAbs().maxCoeff()));
        d = std::max(d, (s.velocity_W - t.velocity_W).cwiseAbs().maxCoeff());
        d = std::max(d, (s.angularVelocity_W - t.angularVelocity_W).cwiseAbs().maxCoeff());
    }
    return d;
}

inline bool allFinite(const core::State& state)
{
    for (const core::BodyState& s : state.bodies)
    {
        if (!s.position_W.allFinite() || !s.orientation_WB.coeffs().allFinite() ||
            !s.velocity_W.allFinite() || !s.angularVelocity_W.allFinite())
        {
            return false;
        }
    }
    return true;
}

// The world position of a joint's anchor on its parent side (m) in a state.
inline core::Vec3 parentAnchor_W(const core::State& state, const core::Joint& joint)
{
    if (joint.parent == core::cWorld)
    {
        return joint.anchorParent;
    }
    // A moving or a static parent: the anchor is in its frame.
    const core::BodyState& p = state.bodies[static_cast<std::size_t>(joint.parent)];
    return p.position_W + p.orientation_WB * joint.anchorParent;
}

} // namespace frontier::sim::test
