// app/scene_loading.cpp: loading a scene for a command.
#include "app/scene_loading.h"

#include "app/run_loop.h"
#include "collision/contacts.h"

#include <iostream>

namespace frontier::app
{

void checkFiniteEnergy(const core::Model& model, const std::string& path)
{
    const int body = bodyWithInfiniteEnergy(model);
    if (body >= 0)
    {
        const core::Body& b = model.bodies[static_cast<std::size_t>(body)];
        throw io::InputError(path, 0, 0,
                             "body '" + b.name +
                                 "': its initial energy is not finite (position, velocity or mass too large "
                                 "for doubles); no run could report its energy");
    }
}

namespace
{
// What every loaded scene goes through: finite energy, robots' starting overlaps excluded.
LoadedScene finishLoading(LoadedScene out, const std::string& path)
{
    checkFiniteEnergy(out.model, path);
    for (const auto& [a, b] : collision::startingOverlaps(out.model))
    {
        out.model.contact.ignore.push_back({a, b});
        const std::string& nameA = out.model.bodies[static_cast<std::size_t>(a)].name;
        const std::string& nameB = out.model.bodies[static_cast<std::size_t>(b)].name;
        for (std::size_t r = 0; r < out.model.robots.size() && r < out.report.robots.size(); ++r)
        {
            const core::Robot& robot = out.model.robots[r];
            if (a >= robot.firstBody && a < robot.firstBody + robot.bodyCount)
            {
                out.report.robots[r].excluded.emplace_back(nameA, nameB);
            }
        }
    }
    return out;
}
} // namespace

LoadedScene loadSceneWithRobots(const std::string& path, const io::UrdfOptions& options)
{
    LoadedScene out;
    out.model = io::loadScene(path, options, &out.report);
    return finishLoading(std::move(out), path);
}

LoadedScene loadSceneTextWithRobots(const std::string& yamlText, const std::string& path,
                                    const io::UrdfOptions& options)
{
    LoadedScene out;
    out.model = io::loadSceneFromString(yamlText, path, options, &out.report);
    return finishLoading(std::move(out), path);
}

void printLoadWarnings(const io::LoadReport& report)
{
    for (const std::string& warning : report.warnings)
    {
        std::cerr << "frontier: " << warning << "\n";
    }
}

} // namespace frontier::app
