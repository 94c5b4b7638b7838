// app/info_command.cpp: `frontier info`: what the solver will see for a scene.
#include "app/cli_options.h"
#include "app/commands.h"
#include "collision/contacts.h"
#include "core/frontier_order.h"
#include "core/joints/joint_types.h"
#include "io/scene.h"
#include "run/scene_loading.h"

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

namespace frontier::app
{

namespace
{
// `info` lists the collision pairs only up to this many pairs and bodies; beyond, it gives their count.
constexpr long long cListedPairsMax = 1000;
constexpr std::size_t cListedPairBodiesMax = 2000;

std::string bodyName(const core::Model& model, int body)
{
    return body == core::cWorld ? "world" : model.bodies[static_cast<std::size_t>(body)].name;
}

// The actuators: type, joint and coordinate, gains (N m/rad, N m s/rad or N/m, N s/m) and effort
// limit (N m or N) where they have them (a --hold servo's gains are shown as chosen).
nlohmann::json describeActuators(const core::Model& model)
{
    nlohmann::json actuators = nlohmann::json::array();
    for (const core::Actuator& actuator : model.actuators)
    {
        const bool position = actuator.kind == core::ActuatorKind::Position;
        nlohmann::json entry = {{"joint", model.joints[static_cast<std::size_t>(actuator.joint)].name},
                                {"type", core::actuatorTypeName(actuator.kind)},
                                {"coordinate", core::coordinateName(actuator.coordinate)}};
        if (position)
        {
            entry["kp"] = actuator.kp;
        }
        if (actuator.kind != core::ActuatorKind::Effort)
        {
            entry["kd"] = actuator.kd;
        }
        if (std::isfinite(actuator.effortLimit))
        {
            entry["effort_limit"] = actuator.effortLimit;
        }
        actuators.push_back(entry);
    }
    return actuators;
}

// What loading did to each robot: welded links, repaired inertias, placement, excluded pairs.
nlohmann::json describeRobots(const io::LoadReport& report)
{
    nlohmann::json robots = nlohmann::json::array();
    for (const io::RobotReport& robot : report.robots)
    {
        nlohmann::json welded = nlohmann::json::array();
        for (const auto& [link, body] : robot.welded)
        {
            welded.push_back({{"link", link}, {"body", body}});
        }
        nlohmann::json excluded = nlohmann::json::array();
        for (const auto& [a, b] : robot.excluded)
        {
            excluded.push_back({a, b});
        }
        robots.push_back({{"name", robot.name},
                          {"file", robot.file},
                          {"links", robot.links},
                          {"welded", welded},
                          {"repaired", robot.repaired},
                          {"placement", robot.placement},
                          {"excluded_pairs", excluded}});
    }
    return robots;
}

// A joint: type, rows, bodies, whether it closes a loop; damping, friction, limits, start and
// effort limit when it has them.
nlohmann::json describeJoint(const core::Model& model, const core::FrontierLayout& layout, std::size_t k)
{
    const core::Joint& joint = model.joints[k];
    nlohmann::json entry = {{"name", joint.name},
                            {"type", core::jointTypeName(joint.type)},
                            {"rows", core::jointRowCount(joint.type)},
                            {"parent", bodyName(model, joint.parent)},
                            {"child", bodyName(model, joint.child)},
                            {"loop", layout.jointBlock[k] < 0}};
    // SI: N m s/rad and N m about a revolute axis, N s/m and N along a prismatic one.
    if (joint.damping > 0.0)
    {
        entry["damping"] = joint.damping;
    }
    if (joint.friction > 0.0)
    {
        entry["friction"] = joint.friction;
    }
    if (joint.limits)
    {
        // In the file's own coordinate (a URDF joint may start at a limit: initial_position).
        entry["limits"] = {(*joint.limits)[0] + joint.initialPosition,
                           (*joint.limits)[1] + joint.initialPosition};
    }
    if (joint.initialPosition != 0.0)
    {
        entry["initial_position"] = joint.initialPosition;
    }
    if (std::isfinite(joint.effortLimit))
    {
        entry["effort_limit"] = joint.effortLimit; // N m or N
    }
    return entry;
}

// The blocks in the frontier order, and the joints that close loops.
void describeOrder(const core::Model& model, const core::FrontierLayout& layout, nlohmann::json& out)
{
    out["trees"] = layout.treeCount;
    nlohmann::json order = nlohmann::json::array();
    for (const core::LayoutBlock& block : layout.blocks)
    {
        const bool node = block.kind == core::LayoutBlock::Kind::Node;
        order.push_back(node ? "body " + model.bodies[static_cast<std::size_t>(block.index)].name
                             : "joint " + model.joints[static_cast<std::size_t>(block.index)].name);
    }
    out["frontier_order"] = order;
    nlohmann::json loops = nlohmann::json::array();
    for (int joint : layout.loopJoints)
    {
        loops.push_back(model.joints[static_cast<std::size_t>(joint)].name);
    }
    out["loops"] = loops;
}

// The pairs are O(bodies^2): counted always, listed only for a scene small enough to read them
// (listing them also takes O(bodies^2) time).
void describePairs(const core::Model& model, nlohmann::json& out)
{
    collision::ContactDetector detector(model);
    const long long pairCount = detector.candidatePairCount();
    out["collision_pair_count"] = pairCount;
    if (pairCount <= cListedPairsMax && model.bodies.size() <= cListedPairBodiesMax)
    {
        nlohmann::json pairs = nlohmann::json::array();
        for (const auto& [a, b] : detector.candidatePairs())
        {
            pairs.push_back({bodyName(model, a), bodyName(model, b)});
        }
        out["collision_pairs"] = pairs;
    }
}

nlohmann::json describe(const core::Model& model, const io::LoadReport& report, const std::string& scene)
{
    const core::FrontierLayout layout = core::buildFrontierLayout(model);
    nlohmann::json out;
    out["scene"] = scene;
    out["name"] = model.name;
    int moving = 0;
    for (const core::Body& body : model.bodies)
    {
        moving += body.isStatic ? 0 : 1;
        out["bodies"].push_back({{"name", body.name}, {"static", body.isStatic}, {"mass_kg", body.mass}});
    }
    int rows = 0;
    out["joints"] = nlohmann::json::array();
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        rows += core::jointRowCount(model.joints[k].type);
        out["joints"].push_back(describeJoint(model, layout, k));
    }
    out["actuators"] = describeActuators(model);
    out["loads"] = model.loads.size();
    out["moving_bodies"] = moving;
    out["constraint_rows"] = rows;
    out["degrees_of_freedom"] = 6 * moving - rows;
    describeOrder(model, layout, out);
    describePairs(model, out);
    out["robots"] = describeRobots(report);
    return out;
}

void printBodies(const nlohmann::json& info)
{
    std::cout << "bodies: " << info["bodies"].size() << " (" << info["moving_bodies"].get<int>()
              << " moving)\n";
    for (const auto& body : info["bodies"])
    {
        std::cout << "  " << body["name"].get<std::string>();
        if (body["static"].get<bool>())
        {
            std::cout << "  static\n";
        }
        else
        {
            std::cout << "  " << body["mass_kg"].get<double>() << " kg\n";
        }
    }
}

// A joint's line: type, rows, bodies, loop, damping, friction, limits, start.
void printJoint(const nlohmann::json& joint)
{
    std::cout << "  " << joint["name"].get<std::string>() << "  " << joint["type"].get<std::string>() << " ("
              << joint["rows"].get<int>() << " rows)  " << joint["parent"].get<std::string>() << " -> "
              << joint["child"].get<std::string>() << (joint["loop"].get<bool>() ? "  [closes a loop]" : "");
    const std::optional<core::JointType> type = core::jointTypeFromName(joint["type"].get<std::string>());
    const bool turns = type && core::jointTypeInfo(*type).limitCoordinate == core::JointCoordinate::Rotation;
    if (joint.contains("damping"))
    {
        std::cout << "  damping " << joint["damping"].get<double>() << (turns ? " N m s/rad" : " N s/m");
    }
    if (joint.contains("friction"))
    {
        std::cout << "  friction " << joint["friction"].get<double>() << (turns ? " N m" : " N");
    }
    if (joint.contains("limits"))
    {
        std::cout << "  limits [" << joint["limits"][0].get<double>() << ", "
                  << joint["limits"][1].get<double>() << "]" << (turns ? " rad" : " m");
    }
    if (joint.contains("initial_position"))
    {
        std::cout << "  starts at " << joint["initial_position"].get<double>();
    }
    std::cout << "\n";
}

void printJoints(const nlohmann::json& info)
{
    std::cout << "joints: " << info["joints"].size() << ", " << info["constraint_rows"].get<int>()
              << " constraint rows\n";
    for (const auto& joint : info["joints"])
    {
        printJoint(joint);
    }
}

void printActuators(const nlohmann::json& info)
{
    std::cout << "actuators: " << info["actuators"].size() << ", loads: " << info["loads"].get<int>() << "\n";
    for (const auto& actuator : info["actuators"])
    {
        std::cout << "  " << actuator["type"].get<std::string>() << " on "
                  << actuator["joint"].get<std::string>() << " (" << actuator["coordinate"].get<std::string>()
                  << ")";
        if (actuator.contains("kp"))
        {
            std::cout << "  kp " << actuator["kp"].get<double>();
        }
        if (actuator.contains("kd"))
        {
            std::cout << "  kd " << actuator["kd"].get<double>();
        }
        if (actuator.contains("effort_limit"))
        {
            std::cout << "  effort limit " << actuator["effort_limit"].get<double>();
        }
        std::cout << "\n";
    }
}

// Degrees of freedom, the frontier order, the loops.
void printOrder(const nlohmann::json& info)
{
    std::cout << "degrees of freedom: " << info["degrees_of_freedom"].get<int>() << "\n";
    std::cout << "frontier order (" << info["trees"].get<int>() << " trees):";
    for (const auto& entry : info["frontier_order"])
    {
        std::cout << "\n  " << entry.get<std::string>();
    }
    std::cout << "\nloops: " << (info["loops"].empty() ? "none" : "");
    for (const auto& loop : info["loops"])
    {
        std::cout << loop.get<std::string>() << " ";
    }
}

// Each robot: placement, welded links, repairs, pairs excluded from collision.
void printRobots(const nlohmann::json& info)
{
    for (const auto& robot : info["robots"])
    {
        std::cout << "\nrobot " << robot["name"].get<std::string>() << " ("
                  << robot["file"].get<std::string>() << "): " << robot["links"].get<int>()
                  << " links\n  placement: " << robot["placement"].get<std::string>()
                  << "\n  welded (by fixed joints, or no joint between them): "
                  << (robot["welded"].empty() ? "none" : "");
        for (const auto& w : robot["welded"])
        {
            std::cout << "\n    " << w["link"].get<std::string>() << " -> " << w["body"].get<std::string>();
        }
        std::cout << "\n  repaired: " << (robot["repaired"].empty() ? "none" : "");
        for (const auto& r : robot["repaired"])
        {
            std::cout << "\n    " << r.get<std::string>();
        }
        std::cout << "\n  excluded from collision (overlapping at the start): "
                  << (robot["excluded_pairs"].empty() ? "none" : "");
        for (const auto& pair : robot["excluded_pairs"])
        {
            std::cout << "\n    " << pair[0].get<std::string>() << " - " << pair[1].get<std::string>();
        }
    }
}

void printPairs(const nlohmann::json& info)
{
    std::cout << "\ncollision pairs: " << info["collision_pair_count"].get<long long>();
    if (!info.contains("collision_pairs"))
    {
        std::cout << " (not listed: more than " << cListedPairsMax << " pairs or " << cListedPairBodiesMax
                  << " bodies)";
    }
    std::cout << "\n";
    for (const auto& pair : info.value("collision_pairs", nlohmann::json::array()))
    {
        std::cout << "  " << pair[0].get<std::string>() << " - " << pair[1].get<std::string>() << "\n";
    }
}

void printText(const nlohmann::json& info)
{
    std::cout << "scene: " << info["scene"].get<std::string>() << " (" << info["name"].get<std::string>()
              << ")\n";
    printBodies(info);
    printJoints(info);
    printActuators(info);
    printOrder(info);
    printRobots(info);
    printPairs(info);
}
} // namespace

int infoCommand(const InfoOptions& options)
{
    try
    {
        const run::LoadedScene loaded = run::loadScene(options.scene, options.urdf);
        run::printLoadWarnings(loaded.report);
        const nlohmann::json info = describe(loaded.model, loaded.report, options.scene);
        if (options.json)
        {
            std::cout << info.dump(2) << "\n";
        }
        else
        {
            printText(info);
        }
        return cExitOk;
    }
    catch (const io::InputError& error)
    {
        std::cerr << "frontier: " << error.what() << "\n";
        return cExitBadInput;
    }
}

namespace
{
void addInfoOptions(CLI::App& command, InfoOptions& o)
{

    command.add_option("scene", o.scene, cSceneFiles)->required();
    command.add_flag("--json", o.json, "machine-readable output");
    addRobotOptions(command, o.urdf);
}
} // namespace

Command addInfoCommand(CLI::App& app)
{
    return addCommand<InfoOptions>(app, "info",
                                   "bodies, joints, degrees of freedom, frontier order, loops, pairs",
                                   addInfoOptions, infoCommand);
}

} // namespace frontier::app
