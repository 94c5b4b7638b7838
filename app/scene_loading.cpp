// app/scene_loading.cpp: loading a scene for a command.
#include "app/scene_loading.h"

#include "collision/contacts.h"

#include <cstdlib>
#include <iostream>
#include <sstream>

namespace frontier::app
{

LoadedScene loadSceneWithRobots(const std::string& path, const io::UrdfOptions& options)
{
    LoadedScene out;
    out.model = io::loadScene(path, options, &out.report);
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

void printLoadWarnings(const io::LoadReport& report)
{
    for (const std::string& warning : report.warnings)
    {
        std::cerr << "frontier: " << warning << "\n";
    }
}

namespace
{
constexpr const char* cFixedBase = "fixed_base";
constexpr const char* cFreeBase = "free_base";
constexpr const char* cDropHeight = "drop_height";
constexpr const char* cSelfCollision = "self_collision";
constexpr const char* cPackagePath = "package_path"; // entries joined by ';'
constexpr const char* cHold = "hold";
} // namespace

void addUrdfOptions(io::TrajectoryMetadata& metadata, const io::UrdfOptions& options)
{
    if (options.fixedBase)
    {
        metadata.emplace_back(cFixedBase, "1");
    }
    if (options.freeBase)
    {
        metadata.emplace_back(cFreeBase, "1");
    }
    if (options.dropHeight)
    {
        std::ostringstream value;
        value.precision(17);
        value << *options.dropHeight;
        metadata.emplace_back(cDropHeight, value.str());
    }
    if (options.selfCollision)
    {
        metadata.emplace_back(cSelfCollision, *options.selfCollision ? "on" : "off");
    }
    if (options.hold)
    {
        metadata.emplace_back(cHold, "1");
    }
    if (!options.packagePaths.empty())
    {
        std::string joined;
        for (const std::string& entry : options.packagePaths)
        {
            joined += (joined.empty() ? "" : ";") + entry;
        }
        metadata.emplace_back(cPackagePath, joined);
    }
}

io::UrdfOptions urdfOptionsFrom(const std::map<std::string, std::string>& metadata, const std::string& file)
{
    io::UrdfOptions options;
    const auto value = [&](const char* key) -> const std::string*
    {
        const auto it = metadata.find(key);
        return it == metadata.end() ? nullptr : &it->second;
    };
    options.fixedBase = value(cFixedBase) && *value(cFixedBase) == "1";
    options.freeBase = value(cFreeBase) && *value(cFreeBase) == "1";
    options.hold = value(cHold) && *value(cHold) == "1";
    if (const std::string* height = value(cDropHeight))
    {
        char* end = nullptr;
        options.dropHeight = std::strtod(height->c_str(), &end);
        if (height->empty() || *end != '\0')
        {
            throw io::InputError(file, 1, 0, "the header's drop_height=" + *height + " is not a number");
        }
    }
    if (const std::string* self = value(cSelfCollision))
    {
        options.selfCollision = *self == "on";
    }
    if (const std::string* paths = value(cPackagePath))
    {
        std::stringstream in(*paths);
        std::string entry;
        while (std::getline(in, entry, ';'))
        {
            if (!entry.empty())
            {
                options.packagePaths.push_back(entry);
            }
        }
    }
    return options;
}

} // namespace frontier::app
