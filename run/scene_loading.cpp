// run/scene_loading.cpp: loading a scene for a command.
#include "run/scene_loading.h"

#include "collision/contacts.h"
#include "run/run_loop.h"

#include <algorithm>
#include <cstdio>
#include <iostream>

namespace frontier::run
{

void checkStartingStates(const core::Model& model, const std::string& path)
{
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        const std::string defect = core::startingStateDefect(model, i);
        if (!defect.empty())
        {
            throw io::InputError(path, 0, 0, "body '" + model.bodies[i].name + "': " + defect);
        }
    }
}

namespace
{
// The deepest penetration of the initial pose between bodies that may collide, warned about when
// deeper than the scene's contact.start_penetration (a robot placed inside the floor, bodies
// inside each other): the first steps would push them apart with whatever speed that takes.
void warnDeepStart(LoadedScene& scene)
{
    std::vector<core::Contact> contacts;
    collision::ContactDetector(scene.model).detect(core::initialState(scene.model), contacts);
    const auto deepest =
        std::max_element(contacts.begin(), contacts.end(),
                         [](const core::Contact& a, const core::Contact& b) { return a.depth < b.depth; });
    if (deepest == contacts.end() || !(deepest->depth > scene.model.contact.startPenetration))
    {
        return;
    }
    scene.startPenetration = *deepest;
    scene.report.warnings.push_back(
        scene.model.sourceFile + ": warning: " + startPenetrationText(scene) +
        "; the first steps push them apart (place them apart, or raise a robot with "
        "its model's 'position' or 'drop_height')");
}
} // namespace

std::string startPenetrationText(const LoadedScene& scene)
{
    if (!scene.startPenetration)
    {
        return {};
    }
    const core::Contact& c = *scene.startPenetration;
    const auto name = [&](int body)
    { return "'" + scene.model.bodies[static_cast<std::size_t>(body)].name + "'"; };
    char depth[96];
    std::snprintf(depth, sizeof depth, "%.3g m (more than contact.start_penetration = %g m)", c.depth,
                  scene.model.contact.startPenetration);
    return "bodies " + name(c.bodyA) + " and " + name(c.bodyB) + " start inside each other by " + depth;
}

namespace
{
// What every loaded scene goes through (io::loadScene checked the starting states): robots'
// starting overlaps excluded.
LoadedScene finishLoading(LoadedScene out)
{
    core::throwIfInterrupted(); // checkpoints between the phases (core/interrupt.h)
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
    core::throwIfInterrupted();
    warnDeepStart(out);
    return out;
}
} // namespace

LoadedScene loadScene(const std::string& path, const io::UrdfOptions& options)
{
    LoadedScene out;
    out.model = io::loadScene(path, options, &out.report);
    return finishLoading(std::move(out));
}

LoadedScene loadSceneText(const std::string& yamlText, const std::string& path,
                          const io::UrdfOptions& options)
{
    LoadedScene out;
    out.model = io::loadSceneFromString(yamlText, path, options, &out.report);
    return finishLoading(std::move(out));
}

void printLoadWarnings(const io::LoadReport& report)
{
    for (const std::string& warning : report.warnings)
    {
        std::cerr << "frontier: " << warning << "\n";
    }
}

} // namespace frontier::run
