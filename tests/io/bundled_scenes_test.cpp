// tests/io/bundled_scenes_test.cpp: every scene under scenes/ loads.
#include "io/scene.h"

#include <filesystem>
#include <gtest/gtest.h>

namespace frontier::io::test
{
namespace
{

TEST(BundledScenes, AllLoad)
{
    const std::filesystem::path dir = std::filesystem::path(FRONTIER_SOURCE_DIR) / "scenes";
    int loaded = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    {
        const std::string ext = entry.path().extension().string();
        if (ext != ".yaml" && ext != ".yml" && ext != ".urdf")
        {
            continue;
        }
        SCOPED_TRACE(entry.path().string());
        try
        {
            const core::Model model = loadScene(entry.path().string());
            EXPECT_FALSE(model.bodies.empty());
            ++loaded;
        }
        catch (const InputError& e)
        {
            ADD_FAILURE() << e.what();
        }
    }
    EXPECT_GT(loaded, 0);
}

TEST(BundledScenes, DollUrdfAlone)
{
    const core::Model model = loadScene(std::string(FRONTIER_SOURCE_DIR) + "/scenes/doll.urdf");
    EXPECT_EQ(model.bodies.back().name, "floor");
    EXPECT_TRUE(model.bodies.back().isStatic);
    int moving = 0;
    for (const core::Body& body : model.bodies)
    {
        moving += body.isStatic ? 0 : 1;
        if (!body.isStatic)
        {
            EXPECT_GT(body.mass, 0.0) << body.name;
        }
    }
    EXPECT_EQ(static_cast<std::size_t>(moving), model.joints.size() + 1); // a tree with a floating root
}

} // namespace
} // namespace frontier::io::test
