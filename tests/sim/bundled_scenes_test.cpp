// tests/sim/bundled_scenes_test.cpp: every bundled scene without contacts runs 2 s, finite, with
// its joints held.
#include "sim_test_util.h"

#include <algorithm>
#include <cctype>
#include <exception>
#include <filesystem>
#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace frontier::sim::test
{
namespace
{

// Scenes that need contacts: those with a static body (a floor to land on) and those whose moving
// bodies are meant to hit each other. They run with the contact detector in tests/contact and in
// the determinism tests; here every other scene with joints runs without one.
bool needsContacts(const core::Model& model, const std::string& file)
{
    if (file == "newtons_cradle.yaml")
    {
        return true; // no floor, but the balls must collide
    }
    return std::any_of(model.bodies.begin(), model.bodies.end(),
                       [](const core::Body& b) { return b.isStatic; });
}

// Called while the tests are registered, so it must not throw.
std::vector<std::string> contactFreeScenes()
{
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator(scenePath("")))
    {
        const std::string ext = entry.path().extension().string();
        const std::string name = entry.path().filename().string();
        if (!entry.is_regular_file() || (ext != ".yaml" && ext != ".yml" && ext != ".urdf"))
        {
            continue;
        }
        try
        {
            const core::Model model = loadBundled(name);
            if (!needsContacts(model, name) && !model.joints.empty())
            {
                files.push_back(name);
            }
        }
        catch (const std::exception&)
        {
            files.push_back(name); // its test reports the error
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

// The scenes without contacts the issue lists are all picked (and the ones with contacts are not).
TEST(BundledScenes, TheContactFreeOnesAreAllFound)
{
    const std::vector<std::string> files = contactFreeScenes();
    for (const char* expected :
         {"pendulum.yaml", "double_pendulum.yaml", "chain30.yaml", "cart_pendulum.yaml",
          "cylindrical_slide.yaml", "universal_shaft.yaml", "nail_and_weld.yaml", "doll_zero_g.yaml"})
    {
        EXPECT_NE(std::find(files.begin(), files.end(), expected), files.end()) << expected;
    }
    for (const char* excluded : {"falling_doll.yaml", "doll.urdf"})
    {
        EXPECT_EQ(std::find(files.begin(), files.end(), excluded), files.end()) << excluded;
    }
}

class ContactFreeScene : public ::testing::TestWithParam<std::string>
{
};

TEST_P(ContactFreeScene, RunsTwoSecondsFiniteWithJointsHeld)
{
    const core::Model model = loadBundled(GetParam());
    core::State state = core::initialState(model);
    core::Simulator simulator(model);
    double jointError = simulator.jointErrors(state).first;
    EXPECT_LT(jointError, 1e-6) << "the initial pose already violates a joint";
    const long steps = stepsFor(2.0, model.simulation.dt);
    for (long k = 0; k < steps; ++k)
    {
        ASSERT_NO_THROW(simulator.step(state)) << "step " << k;
        jointError = std::max(jointError, simulator.lastStep().maxJointErrorM);
        ASSERT_LT(simulator.lastStep().maxJointErrorM, 1e-6) << "at step " << state.step;
    }
    EXPECT_TRUE(allFinite(state));
    EXPECT_NEAR(state.time, 2.0, 1e-9);
    EXPECT_EQ(state.step, steps);
    RecordProperty("max_joint_error_m", sci(jointError));
}

std::string testName(const ::testing::TestParamInfo<std::string>& info)
{
    std::string name = info.param;
    std::replace_if(
        name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
    return name;
}

INSTANTIATE_TEST_SUITE_P(Scenes, ContactFreeScene, ::testing::ValuesIn(contactFreeScenes()), testName);

} // namespace
} // namespace frontier::sim::test
