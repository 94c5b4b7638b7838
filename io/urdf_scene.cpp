// io/urdf_scene.cpp: a URDF alone as a scene: the robot, placed on a floor (README "Robots").
#include "core/state.h"
#include "io/file_util.h"
#include "io/hold_servos.h"
#include "io/package_paths.h"
#include "io/scene.h"
#include "io/urdf_model.h"

#include <cmath>
#include <limits>

namespace frontier::io::detail
{

// Lowest point of the robot's collision shapes along z (m); +infinity when it has none.
double lowestPoint(const core::Model& model)
{
    double lowest = std::numeric_limits<double>::infinity();
    for (const core::Body& body : model.bodies)
    {
        for (const core::Shape& shape : body.shapes)
        {
            const double top =
                core::shapeSupportWorld(shape, body.position_W, body.orientation_WB, -core::Vec3::UnitZ());
            lowest = std::min(lowest, -top);
        }
    }
    return lowest;
}

// Every body (and every joint anchor held by the world) moved by `offset` (m).
void translate(core::Model& model, const core::Vec3& offset)
{
    for (core::Body& body : model.bodies)
    {
        body.position_W += offset;
    }
    for (core::Joint& joint : model.joints)
    {
        if (joint.parent == core::cWorld)
        {
            joint.anchorParent += offset;
        }
    }
}

bool heldByWorld(const core::Model& model)
{
    for (const core::Body& body : model.bodies)
    {
        if (body.isStatic)
        {
            return true;
        }
    }
    for (const core::Joint& joint : model.joints)
    {
        if (joint.parent == core::cWorld)
        {
            return true;
        }
    }
    return false;
}

void checkStartingState(const core::Model& model, const std::string& path)
{
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        // Placed on the floor, a body may have moved out of range (core::startingStateDefect).
        const std::string defect = core::startingStateDefect(model, i);
        if (!defect.empty())
        {
            throw InputError(path, 0, 0, "body '" + model.bodies[i].name + "': " + defect);
        }
    }
}

void placeOnFloor(core::Model& model, const std::string& path, std::optional<double> dropHeight,
                  const std::string& heldBy, const std::string& fileKind, RobotReport& robot,
                  std::vector<std::string>& warnings)
{
    if (dropHeight && !(std::isfinite(*dropHeight) && *dropHeight >= 0.0))
    {
        throw InputError(path, 0, 0, "--drop-height must be a non-negative number of metres");
    }
    const double lowest = lowestPoint(model);
    double floorHeight = 0.0; // m
    if (heldByWorld(model))
    {
        // The robot stays where the file puts it; the floor goes under it when a link reaches below
        // z = 0 (an arm mounted on its side), so that no link starts inside the floor.
        floorHeight = std::isfinite(lowest) ? std::min(0.0, lowest) : 0.0;
        robot.placement = heldBy + "; floor at z = " + formatNumber(floorHeight) + " m";
        if (dropHeight)
        {
            warnings.push_back(diagnostic(path, {}, "warning",
                                          "--drop-height is for a free-floating robot; this one is " +
                                              robot.placement + ", so it stays where it is"));
        }
    }
    else if (std::isfinite(lowest))
    {
        const double height = dropHeight.value_or(0.0);
        const double shift = height - lowest;
        translate(model, core::Vec3(0.0, 0.0, shift));
        robot.placement = "free-floating, moved " + std::string(shift < 0.0 ? "down " : "up ") +
                          formatNumber(std::abs(shift)) + " m so that its lowest collision point is " +
                          formatNumber(height) + " m above the floor";
    }
    else
    {
        robot.placement = "free-floating, where the " + fileKind + " puts it (it has no collision shapes)";
        warnings.push_back(diagnostic(path, {}, "warning",
                                      "the robot has no collision shapes: nothing stops it falling through "
                                      "the floor"));
    }
    core::Body floor;
    floor.name = model.findBody("floor") < 0 ? "floor" : "floor_";
    floor.isStatic = true;
    core::Shape plane;
    plane.type = core::ShapeType::Plane;
    plane.normal = core::Vec3::UnitZ();
    plane.offset = floorHeight;
    floor.shapes.push_back(plane);
    model.bodies.push_back(std::move(floor));
    checkStartingState(model, path);
}

core::Model loadUrdfScene(const std::string& path, const UrdfOptions& options, LoadReport* report)
{
    if (options.fixedBase && options.freeBase)
    {
        throw InputError(path, 0, 0, "--fixed-base and --free-base exclude each other");
    }
    const PackagePaths packages(options.packagePaths);
    UrdfPlacement placement;
    placement.fixedRoot = options.fixedBase;
    placement.freeRoot = options.freeBase;
    placement.selfCollision = options.selfCollision.value_or(true);
    placement.jointPositions = options.jointPositions;
    ModelFragment fragment;
    try
    {
        fragment = loadUrdfFragment(path, placement, packages);
    }
    catch (const JointPositionError& e)
    {
        throw InputError(path, 0, 0, "--joint-position " + e.joint() + ": " + e.what());
    }
    core::Model model = std::move(fragment.model);
    model.sourceFile = path;
    RobotReport& robot = fragment.report;
    model.robots.push_back(
        {robot.name, path, 0, static_cast<int>(model.bodies.size()), placement.selfCollision});
    if (options.hold)
    {
        addHoldServos(model, 0, static_cast<int>(model.joints.size()));
    }
    const std::string heldBy = options.fixedBase
                                   ? "fixed to the world where the URDF puts it (--fixed-base)"
                                   : "fixed to the world by the URDF (a joint to its 'world' link)";
    placeOnFloor(model, path, options.dropHeight, heldBy, "URDF", robot, fragment.warnings);
    reportRobot(fragment, report);
    return model;
}

void reportRobot(ModelFragment& fragment, LoadReport* report)
{
    if (report)
    {
        report->robots.push_back(std::move(fragment.report));
        report->warnings.insert(report->warnings.end(), fragment.warnings.begin(), fragment.warnings.end());
    }
}

} // namespace frontier::io::detail
