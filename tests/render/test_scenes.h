// tests/render/test_scenes.h: small scenes built in code, and a per-test temporary directory.
#pragma once

#include "core/model.h"
#include "core/state.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace frontier::render::testing
{

inline core::Body groundBody()
{
    core::Body ground;
    ground.name = "ground";
    ground.isStatic = true;
    core::Shape plane;
    plane.type = core::ShapeType::Plane;
    plane.normal = core::Vec3::UnitZ();
    plane.offset = 0.0;
    ground.shapes.push_back(plane);
    return ground;
}

inline core::Body movingBody(const std::string& name, const core::Shape& shape, const core::Vec3& position)
{
    core::Body body;
    body.name = name;
    body.mass = 1.0;
    body.inertia_B = core::Mat3::Identity() * 0.01;
    body.shapes.push_back(shape);
    body.position_W = position;
    return body;
}

// A 0.4 m red box resting on the floor at the origin, seen from 3 m straight above.
inline core::Model redBoxScene()
{
    core::Model model;
    model.name = "red box";
    model.bodies.push_back(groundBody());
    core::Shape box;
    box.type = core::ShapeType::Box;
    box.size = core::Vec3(0.4, 0.4, 0.4);
    core::Body body = movingBody("box", box, core::Vec3(0, 0, 0.2));
    body.color = core::Vec3(0.9, 0.1, 0.1);
    model.bodies.push_back(body);
    model.camera.automatic = false;
    model.camera.position = core::Vec3(0, 0, 3);
    model.camera.lookAt = core::Vec3(0, 0, 0);
    model.camera.fovDegrees = 45.0;
    return model;
}

// One body of every shape type (and a tilted one), automatic camera.
inline core::Model mixedScene(int count)
{
    core::Model model;
    model.name = "mixed shapes";
    model.bodies.push_back(groundBody());
    for (int i = 0; i < count; ++i)
    {
        core::Shape s;
        switch (i % 5)
        {
        case 0:
            s.type = core::ShapeType::Box;
            s.size = core::Vec3(0.4, 0.3, 0.2);
            break;
        case 1:
            s.type = core::ShapeType::Sphere;
            s.radius = 0.18;
            break;
        case 2:
            s.type = core::ShapeType::Capsule;
            s.radius = 0.1;
            s.length = 0.3;
            break;
        case 3:
            s.type = core::ShapeType::Cylinder;
            s.radius = 0.15;
            s.length = 0.3;
            break;
        default:
            s.type = core::ShapeType::Mesh; // a tetrahedron
            s.vertices = {{0, 0, 0}, {0.35, 0, 0}, {0, 0.35, 0}, {0, 0, 0.35}};
            s.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
            break;
        }
        const double x = -1.2 + 0.6 * (i % 5);
        const double y = -0.6 + 0.6 * (i / 5);
        core::Body body = movingBody("body" + std::to_string(i), s, core::Vec3(x, y, 0.25 + 0.15 * (i % 3)));
        body.orientation_WB = core::Quat(Eigen::AngleAxisd(0.4 * i, core::Vec3(1, 2, 3).normalized()));
        model.bodies.push_back(body);
    }
    return model;
}

// A fresh directory under the build tree, removed by the destructor.
class TempDir
{
  public:
    TempDir()
    {
        const std::filesystem::path base = std::filesystem::path(FRONTIER_BINARY_DIR) / "test-tmp";
        std::filesystem::create_directories(base);
        std::string pattern = (base / "render-XXXXXX").string();
        if (mkdtemp(pattern.data()) == nullptr)
        {
            throw std::runtime_error("mkdtemp failed in " + base.string());
        }
        path_ = pattern;
    }
    ~TempDir()
    {
        std::error_code ignored;
        std::filesystem::permissions(path_, std::filesystem::perms::owner_all, ignored);
        std::filesystem::remove_all(path_, ignored);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }

  private:
    std::filesystem::path path_;
};

} // namespace frontier::render::testing
