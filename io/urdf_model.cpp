// io/urdf_model.cpp: URDF (urdfdom) links and joints to bodies and joints.
//
// Mapping (scenes/README.md "Robots from URDF" has the user's view):
// * Links joined by fixed joints are one rigid body (welded): their masses, inertias (parallel-axis
//   theorem), collision and visual elements are combined at load, and the fixed joints make no rows.
//   The body is named after its top link; its frame has its origin at the combined centre of mass
//   and the axes of the top link's <inertial> frame (the link frame when it has none).
// * Links welded to a root link named 'world', and the root itself under `fixedRoot`, are static;
//   so, under `fixedRoot`, is the child of a floating joint from 'world'.
// * A moving body needs mass: a link group with none is an error when a joint moves it or when it
//   floats. A link whose inertia no rigid body can have (inertiaDefect) but whose mass is positive
//   gets the inertia of its collision shapes (else its visual shapes, else a ball of water) at that
//   mass, with a warning.
// * Moving joints are anchored at the child link's frame origin with the axis rotated into the
//   world, in the initial pose; <dynamics damping friction> become the joint's damping and friction.
//   A planar joint (the child moves in the plane normal to its axis) takes no <limit> and no
//   <dynamics> (ignored, with a warning).
// * Mesh URIs resolve through PackagePaths. A collision mesh that cannot be read is an error, a
//   visual one a warning (that link is then drawn from its collision shapes).
#include "io/urdf_model.h"

#include "core/interrupt.h"
#include "core/joints/joint_types.h"
#include "io/file_util.h"
#include "io/mass_properties.h"
#include "io/mesh_file.h"
#include "io/package_paths.h"
#include "io/suggest.h"
#include "io/urdf_xml_index.h"

#include <algorithm>
#include <cmath>
#include <console_bridge/console.h>
#include <filesystem>
#include <map>
#include <mutex>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <urdf_parser/urdf_parser.h>

namespace frontier::io::detail
{

namespace
{

struct Pose
{
    core::Vec3 p = core::Vec3::Zero();
    core::Quat q = core::Quat::Identity();
};

Pose operator*(const Pose& a, const Pose& b)
{
    return {a.p + a.q * b.p, (a.q * b.q).normalized()};
}

Pose inverse(const Pose& a)
{
    const core::Quat qi = a.q.conjugate();
    return {-(qi * a.p), qi};
}

Pose fromUrdf(const urdf::Pose& pose)
{
    const core::Quat q(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
    return {{pose.position.x, pose.position.y, pose.position.z}, q.normalized()};
}

// Collects what urdfdom logs through console_bridge while it parses.
class CapturedLog : public console_bridge::OutputHandler
{
  public:
    void log(const std::string& text, console_bridge::LogLevel level, const char* /*filename*/,
             int /*line*/) override
    {
        if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR)
        {
            errors.push_back(text);
        }
    }
    std::vector<std::string> errors;
};

// console_bridge's handler and level are process-global: one parse at a time.
urdf::ModelInterfaceSharedPtr parseCapturingErrors(const std::string& text, CapturedLog& log)
{
    static std::mutex parseMutex;
    const std::lock_guard<std::mutex> lock(parseMutex);
    const console_bridge::LogLevel previousLevel = console_bridge::getLogLevel();
    console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_WARN);
    console_bridge::useOutputHandler(&log);
    urdf::ModelInterfaceSharedPtr model;
    try
    {
        model = urdf::parseURDF(text);
    }
    catch (const std::exception& e)
    {
        log.errors.push_back(e.what());
        model.reset();
    }
    console_bridge::restorePreviousOutputHandler();
    console_bridge::setLogLevel(previousLevel);
    return model;
}

const char* jointTypeWord(int type)
{
    switch (type)
    {
    case urdf::Joint::REVOLUTE:
        return "revolute";
    case urdf::Joint::CONTINUOUS:
        return "continuous";
    case urdf::Joint::PRISMATIC:
        return "prismatic";
    case urdf::Joint::FLOATING:
        return "floating";
    case urdf::Joint::PLANAR:
        return "planar";
    case urdf::Joint::FIXED:
        return "fixed";
    default:
        return "unknown";
    }
}

// Links welded together by fixed joints: one body (or the world, or a static body).
struct LinkGroup
{
    std::string top;                    // the link nearest the root
    std::vector<std::string> links;     // the top first, then welded links in document order
    bool isStatic = false;              // welded to the world
    bool isWorld = false;               // the 'world' link itself: no body
    const urdf::Joint* joint = nullptr; // the moving joint whose child is the top, if any
    int body = core::cWorld;            // body index (cWorld for the world)
    Pose bodyInTop;                     // body frame in the top link frame
};

struct LinkPlace
{
    int group = -1;
    Pose world;                // link frame in the world, initial pose
    std::optional<Pose> inTop; // link frame in its group's top link frame (none for the top)
};

class UrdfConverter
{
  public:
    UrdfConverter(const std::string& file, const UrdfXmlIndex& index, const urdf::ModelInterface& robot,
                  const UrdfPlacement& placement, const PackagePaths& packages)
        : mFile(file), mIndex(index), mRobot(robot), mPlacement(placement), mPackages(packages)
    {
    }

    ModelFragment convert()
    {
        mOut.model.name = mRobot.getName();
        mOut.report.file = mFile;
        const urdf::LinkConstSharedPtr root = mRobot.getRoot();
        if (!root)
        {
            fail({}, "the URDF has no root link");
        }
        placeLinks(*root);
        checkJointPositionsUsed();
        for (const std::string& linkName : mIndex.linkNames())
        {
            if (mPlaces.contains(linkName) &&
                mGroups[static_cast<std::size_t>(mPlaces[linkName].group)].top == linkName)
            {
                addBody(mGroups[static_cast<std::size_t>(mPlaces[linkName].group)]);
            }
        }
        for (const std::string& jointName : mIndex.jointNames())
        {
            const urdf::JointConstSharedPtr joint = mRobot.getJoint(jointName);
            if (joint)
            {
                addJoint(*joint);
            }
        }
        mOut.report.links = static_cast<int>(mPlaces.size());
        return std::move(mOut);
    }

  private:
    [[noreturn]] void fail(TextPosition at, const std::string& message) const
    {
        throw InputError(mFile, at.line, at.column, message);
    }

    // An <origin xyz> (or a placement made of them) within the range of core/model.h.
    void checkPosition(TextPosition at, const core::Vec3& p, const std::string& what) const
    {
        if (!core::isPosition(p))
        {
            fail(at, what + " is (" + formatVector(p) + ") m; expected " + core::cPositionRange);
        }
    }

    void warn(TextPosition at, const std::string& message)
    {
        mOut.warnings.push_back(diagnostic(mFile, at, "warning", message));
    }

    const urdf::Link& link(const std::string& name) const
    {
        const urdf::LinkConstSharedPtr l = mRobot.getLink(name);
        if (!l)
        {
            fail({}, "link '" + name + "' is named by a joint but not defined");
        }
        return *l;
    }

    LinkGroup& groupOf(const std::string& linkName)
    {
        return mGroups[static_cast<std::size_t>(mPlaces[linkName].group)];
    }

    int newGroup(const std::string& top, bool isStatic, const urdf::Joint* joint)
    {
        LinkGroup g;
        g.top = top;
        g.links.push_back(top);
        g.isStatic = isStatic;
        g.joint = joint;
        mGroups.push_back(std::move(g));
        return static_cast<int>(mGroups.size()) - 1;
    }

    // The joint's own motion at its start position: the placement's joint position if it gives
    // one; else 0, or the nearest limit when 0 lies outside them (robot files such as quadrupeds'
    // knees do that), with a warning.
    Pose startMotion(const urdf::Joint& joint)
    {
        const core::Vec3 axis(joint.axis.x, joint.axis.y, joint.axis.z);
        const bool limited = joint.limits && joint.type != urdf::Joint::CONTINUOUS && axis.allFinite() &&
                             axis.norm() > 1e-12 && joint.limits->lower <= joint.limits->upper;
        const bool slides = joint.type == urdf::Joint::PRISMATIC;
        const char* unit = slides ? "m" : "rad";
        double start = 0.0;
        if (const auto given = mPlacement.jointPositions.find(joint.name);
            given != mPlacement.jointPositions.end())
        {
            start = given->second;
            if (limited && !(start >= joint.limits->lower && start <= joint.limits->upper))
            {
                throw JointPositionError(
                    joint.name, "expected a position in [" + formatNumber(joint.limits->lower) + ", " +
                                    formatNumber(joint.limits->upper) + "] " + unit + " for joint '" +
                                    joint.name + "' (its limits), got " + formatNumber(start));
            }
            if (!std::isfinite(start))
            {
                throw JointPositionError(joint.name,
                                         "expected a finite position for joint '" + joint.name + "'");
            }
            mUsedJointPositions.insert(joint.name);
        }
        else if (limited)
        {
            start = std::clamp(0.0, joint.limits->lower, joint.limits->upper);
            if (start != 0.0)
            {
                warn(mIndex.element("joint", joint.name, "limit"),
                     "joint '" + joint.name + "': its zero position lies outside its limits [" +
                         formatNumber(joint.limits->lower) + ", " + formatNumber(joint.limits->upper) + "] " +
                         unit + "; it starts at " + formatNumber(start));
            }
        }
        if (start == 0.0 || !axis.allFinite() || !(axis.norm() > 1e-12))
        {
            return {}; // a bad axis is reported with the joint
        }
        mStartPosition[joint.name] = start;
        const core::Vec3 u = axis.normalized();
        if (slides)
        {
            return {start * u, core::Quat::Identity()};
        }
        return {core::Vec3::Zero(), core::Quat(Eigen::AngleAxisd(start, u))};
    }

    // Every joint position the placement gives was taken (placeLinks found its joint movable).
    void checkJointPositionsUsed() const
    {
        for (const auto& [name, value] : mPlacement.jointPositions)
        {
            if (mUsedJointPositions.contains(name))
            {
                continue;
            }
            const urdf::JointConstSharedPtr joint = mRobot.getJoint(name);
            if (joint)
            {
                throw JointPositionError(name, "joint '" + name + "' has no position to start from (it is " +
                                                   jointTypeWord(joint->type) +
                                                   "; revolute, continuous and prismatic joints have one)");
            }
            std::vector<std::string> names;
            for (const auto& [jointName, j] : mRobot.joints_)
            {
                names.push_back(jointName);
            }
            throw JointPositionError(name, "the URDF has no joint " + quotedName(name) +
                                               suggestionSuffix(name, names, names.size() <= 12));
        }
    }

    // World poses and link groups, walking the tree from the root (no recursion: a URDF may be
    // deep, and a joint from a link to itself must not loop).
    void placeLinks(const urdf::Link& root)
    {
        placeRoot(root);
        std::vector<const urdf::Link*> stack{&root};
        while (!stack.empty())
        {
            const urdf::Link& parent = *stack.back();
            stack.pop_back();
            const LinkPlace parentPlace = mPlaces[parent.name];
            for (const urdf::JointSharedPtr& joint : parent.child_joints)
            {
                const std::string& childName = joint->child_link_name;
                if (mPlaces.contains(childName))
                {
                    fail(mIndex.element("joint", joint->name),
                         "joint '" + joint->name + "' makes link '" + childName +
                             "' its own ancestor; the links must form a tree");
                }
                const urdf::Link& child = link(childName);
                mPlaces[childName] = childPlace(parentPlace, *joint, root.name == "world");
                stack.push_back(&child);
            }
        }
        sortWeldedLinks();
    }

    // The root link where the placement puts it, a group of its own ('world' fixed and bare).
    void placeRoot(const urdf::Link& root)
    {
        const bool worldRoot = root.name == "world";
        LinkPlace& rootPlace = mPlaces[root.name];
        rootPlace.world = Pose{mPlacement.position, mPlacement.orientation.normalized()};
        rootPlace.group = newGroup(root.name, worldRoot || mPlacement.fixedRoot, nullptr);
        mGroups.back().isWorld = worldRoot;
        if (worldRoot && (root.inertial || !root.collision_array.empty()))
        {
            fail(mIndex.element("link", root.name),
                 "link 'world' is the fixed world frame; it cannot have <inertial> or <collision> (attach a "
                 "link to it with a fixed joint)");
        }
    }

    // The joint's child link: its world pose, and its group (a new one, or welded into the parent's).
    LinkPlace childPlace(const LinkPlace& parentPlace, const urdf::Joint& joint, bool worldRoot)
    {
        const bool dropWorld = worldRoot && mPlacement.freeRoot;
        const bool parentIsWorld = mGroups[static_cast<std::size_t>(parentPlace.group)].isWorld;
        const std::string& childName = joint.child_link_name;
        const TextPosition origin = mIndex.element("joint", joint.name, "origin");
        checkPosition(origin, fromUrdf(joint.parent_to_joint_origin_transform).p,
                      "the <origin xyz> of joint '" + joint.name + "'");
        LinkPlace place;
        place.world = parentPlace.world * fromUrdf(joint.parent_to_joint_origin_transform);
        switch (joint.type)
        {
        case urdf::Joint::FIXED:
            if (parentIsWorld)
            {
                place.group = newGroup(childName, !dropWorld, nullptr);
                break;
            }
            place.group = parentPlace.group;
            place.inTop =
                parentPlace.inTop.value_or(Pose{}) * fromUrdf(joint.parent_to_joint_origin_transform);
            mGroups[static_cast<std::size_t>(place.group)].links.push_back(childName);
            break;
        case urdf::Joint::FLOATING:
            // Under --fixed-base a floating joint from 'world' holds the robot's root link:
            // it is bolted where the joint places it.
            place.group = newGroup(childName, parentIsWorld && mPlacement.fixedRoot, nullptr);
            break;
        case urdf::Joint::REVOLUTE:
        case urdf::Joint::CONTINUOUS:
        case urdf::Joint::PRISMATIC:
            place.group = newGroup(childName, false, &joint);
            place.world = place.world * startMotion(joint);
            break;
        case urdf::Joint::PLANAR: // no coordinate to start away from
            place.group = newGroup(childName, false, &joint);
            break;
        default:
            fail(mIndex.element("joint", joint.name), "joint '" + joint.name + "' has an unknown type");
        }
        checkPosition(origin, place.world.p,
                      "joint '" + joint.name + "' places link '" + childName + "' where its frame");
        return place;
    }

    // Welded links in document order after their top (the walk above visits them depth first):
    // sorted by their place in the file, O(n log n) over all groups.
    void sortWeldedLinks()
    {
        std::map<std::string_view, std::size_t> documentOrder;
        for (std::size_t k = 0; k < mIndex.linkNames().size(); ++k)
        {
            documentOrder.emplace(mIndex.linkNames()[k], k);
        }
        for (LinkGroup& g : mGroups)
        {
            std::vector<std::pair<std::size_t, std::string>> welded;
            for (std::size_t k = 1; k < g.links.size(); ++k)
            {
                if (const auto at = documentOrder.find(g.links[k]); at != documentOrder.end())
                {
                    welded.emplace_back(at->second, std::move(g.links[k]));
                }
            }
            std::sort(welded.begin(), welded.end());
            g.links.resize(1);
            for (auto& [order, name] : welded)
            {
                g.links.push_back(std::move(name));
            }
        }
    }

    // The link's <inertial> as a part of its group, in the top link frame, axes of the body
    // (bodyAxes: the body's axes in the top link frame, none when they are this link's inertial
    // frame); repaired when its inertia is impossible.
    MassPart massPart(const urdf::Link& l, const std::optional<core::Quat>& bodyAxes)
    {
        MassPart part;
        if (!l.inertial)
        {
            return part;
        }
        const urdf::Inertial& inertial = *l.inertial;
        const TextPosition at = mIndex.element("link", l.name, "inertial/mass");
        if (!std::isfinite(inertial.mass) || inertial.mass < 0.0)
        {
            fail(at, "link '" + l.name + "' has mass " + formatNumber(inertial.mass) +
                         "; expected a non-negative <mass value> (kg)");
        }
        part.mass = inertial.mass;
        if (part.mass == 0.0)
        {
            return part;
        }
        const Pose inertialPose = fromUrdf(inertial.origin);
        checkPosition(mIndex.element("link", l.name, "inertial/origin"), inertialPose.p,
                      "the <inertial><origin xyz> of link '" + l.name + "'");
        const std::optional<Pose>& inTop = mPlaces[l.name].inTop;
        const Pose inertialInTop = inTop ? *inTop * inertialPose : inertialPose;
        part.centre = inertialInTop.p;
        core::Mat3 inertia;
        inertia << inertial.ixx, inertial.ixy, inertial.ixz, inertial.ixy, inertial.iyy, inertial.iyz,
            inertial.ixz, inertial.iyz, inertial.izz;
        const std::string defect = inertiaDefect(inertia, part.mass);
        if (!defect.empty())
        {
            inertia = repairedInertia(l, part.mass, inertialPose.q);
            mOut.report.repaired.push_back(
                "link '" + l.name + "': its inertia " + defect +
                "; used that of its shapes at its mass: " + describeInertia(inertia));
            warn(mIndex.element("link", l.name, "inertial/inertia"),
                 "link '" + l.name + "': the inertia " + defect +
                     "; using the inertia of its shapes at its mass " + formatNumber(part.mass) +
                     " kg instead (" + describeInertia(inertia) + ")");
        }
        if (!bodyAxes)
        {
            part.inertia = inertia; // the top link's own inertial frame is the body frame
            return part;
        }
        const core::Mat3 R =
            (bodyAxes->conjugate() * inertialInTop.q).toRotationMatrix(); // inertial to body axes
        part.inertia = R * inertia * R.transpose();
        return part;
    }

    static std::string describeInertia(const core::Mat3& inertia)
    {
        return "ixx=" + formatNumber(inertia(0, 0)) + " iyy=" + formatNumber(inertia(1, 1)) +
               " izz=" + formatNumber(inertia(2, 2)) + " ixy=" + formatNumber(inertia(0, 1)) +
               " ixz=" + formatNumber(inertia(0, 2)) + " iyz=" + formatNumber(inertia(1, 2)) + " kg m^2";
    }

    // The inertia (axes of the link's inertial frame, rotation inertialAxes in the link frame) of the
    // link's collision shapes at `mass`, else of its visual shapes, else of a ball of water.
    core::Mat3 repairedInertia(const urdf::Link& l, double mass, const core::Quat& inertialAxes)
    {
        for (const bool collision : {true, false})
        {
            std::vector<core::Shape> shapes = linkShapes(l, collision, /*quiet=*/true);
            for (core::Shape& s : shapes) // into the inertial frame's axes
            {
                s.position_BS = inertialAxes.conjugate() * s.position_BS;
                s.rotation_BS = inertialAxes.conjugate() * s.rotation_BS;
            }
            const CompositeMass c = compositeMassProperties(shapes, 1.0);
            if (c.mass > 0.0)
            {
                const core::Mat3 inertia = c.inertia * (mass / c.mass);
                if (inertiaDefect(inertia, mass).empty())
                {
                    return inertia;
                }
            }
        }
        const double radius = std::cbrt(3.0 * mass / (4.0 * std::numbers::pi * 1000.0)); // water, 1000 kg/m^3
        return core::Mat3::Identity() * (0.4 * mass * radius * radius);
    }

    // The link's collision (or visual) elements as shapes posed in the link frame. Collision
    // meshes that cannot be read are errors; visual ones warnings (quiet: skipped silently), and
    // set *unreadable when given.
    std::vector<core::Shape> linkShapes(const urdf::Link& l, bool collision, bool quiet,
                                        bool* unreadable = nullptr)
    {
        std::vector<core::Shape> out;
        const std::size_t count = collision ? l.collision_array.size() : l.visual_array.size();
        for (std::size_t k = 0; k < count; ++k)
        {
            const urdf::GeometrySharedPtr& geometry =
                collision ? l.collision_array[k]->geometry : l.visual_array[k]->geometry;
            const urdf::Pose& origin = collision ? l.collision_array[k]->origin : l.visual_array[k]->origin;
            if (!geometry)
            {
                continue;
            }
            const std::string element =
                std::string(collision ? "collision" : "visual") + "#" + std::to_string(k);
            std::optional<core::Shape> shape = readGeometry(l, *geometry, element, collision, quiet);
            if (!shape)
            {
                if (unreadable != nullptr)
                {
                    *unreadable = true;
                }
                continue;
            }
            const Pose pose = fromUrdf(origin);
            checkPosition(mIndex.element("link", l.name, element + "/origin"), pose.p,
                          "the <origin xyz> of " + std::string(collision ? "a collision" : "a visual") +
                              " of link '" + l.name + "'");
            shape->position_BS = pose.p;
            shape->rotation_BS = pose.q;
            out.push_back(std::move(*shape));
        }
        return out;
    }

    std::optional<core::Shape> readGeometry(const urdf::Link& l, const urdf::Geometry& geometry,
                                            const std::string& element, bool collision, bool quiet)
    {
        const TextPosition at = mIndex.element("link", l.name, element + "/geometry");
        const std::string where =
            std::string(collision ? "a collision" : "a visual") + " of link '" + l.name + "'";
        core::Shape shape;
        switch (geometry.type)
        {
        case urdf::Geometry::BOX:
        {
            const auto& box = static_cast<const urdf::Box&>(geometry);
            shape.type = core::ShapeType::Box;
            shape.size = core::Vec3(box.dim.x, box.dim.y, box.dim.z);
            if (!(core::isLength(shape.size.x()) && core::isLength(shape.size.y()) &&
                  core::isLength(shape.size.z())))
            {
                fail(at, "box size of " + where + " is (" + formatVector(shape.size) + "); expected each " +
                             core::cLengthRange);
            }
            break;
        }
        case urdf::Geometry::SPHERE:
            shape.type = core::ShapeType::Sphere;
            shape.radius = static_cast<const urdf::Sphere&>(geometry).radius;
            if (!core::isLength(shape.radius))
            {
                fail(at, "sphere radius of " + where + " is " + formatNumber(shape.radius) + "; expected " +
                             core::cLengthRange);
            }
            break;
        case urdf::Geometry::CYLINDER:
        {
            const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
            shape.type = core::ShapeType::Cylinder;
            shape.radius = cylinder.radius;
            shape.length = cylinder.length;
            if (!(core::isLength(shape.radius) && core::isLength(shape.length)))
            {
                fail(at, "cylinder radius and length of " + where + " are " + formatNumber(shape.radius) +
                             " and " + formatNumber(shape.length) + "; expected each " + core::cLengthRange);
            }
            break;
        }
        case urdf::Geometry::MESH:
            return readMesh(l, static_cast<const urdf::Mesh&>(geometry), element, collision, quiet);
        }
        return shape;
    }

    std::optional<core::Shape> readMesh(const urdf::Link& l, const urdf::Mesh& mesh,
                                        const std::string& element, bool collision, bool quiet)
    {
        const TextPosition at = mIndex.element("link", l.name, element + "/geometry/mesh");
        const std::string what = std::string(collision ? "collision" : "visual") + " mesh '" + mesh.filename +
                                 "' of link '" + l.name + "'";
        const core::Vec3 scale(mesh.scale.x, mesh.scale.y, mesh.scale.z);
        if (!scale.allFinite() || (scale.array() == 0.0).any())
        {
            fail(at, what + " has scale=\"" + formatNumber(scale.x()) + " " + formatNumber(scale.y()) + " " +
                         formatNumber(scale.z()) +
                         "\"; expected three nonzero numbers (a negative one mirrors the mesh)");
        }
        const ResolvedUri resolved = mPackages.resolve(mesh.filename, mFile);
        std::string problem = resolved.notFound;
        if (problem.empty())
        {
            if (!resolved.note.empty() && mNotedPackages.insert(resolved.note).second && !quiet)
            {
                warn(at, resolved.note);
            }
            try
            {
                core::Shape shape = loadMeshFile(resolved.path, scale);
                if (!(core::shapeReach(shape) <= core::cMaxDistance))
                {
                    fail(at, what + " reaches " + formatNumber(core::shapeReach(shape)) +
                                 " m from its origin at scale (" + formatVector(scale) + "); expected " +
                                 core::cLengthRange);
                }
                return shape;
            }
            catch (const InputError& e)
            {
                if (collision && e.line() > 0)
                {
                    throw; // the error is inside the mesh file: keep its location
                }
                problem = e.what();
            }
        }
        if (collision)
        {
            fail(at, what + ": " + problem);
        }
        if (!quiet)
        {
            warn(at, what + " cannot be read (" + problem + "); the link is drawn from its collision shapes" +
                         (l.collision_array.empty() ? ", and it has none: it is not drawn" : ""));
        }
        return std::nullopt;
    }

    void addBody(LinkGroup& g)
    {
        if (g.isWorld)
        {
            g.body = core::cWorld;
            return;
        }
        const std::string reason = invalidNameReason(g.top);
        if (!reason.empty())
        {
            fail(mIndex.element("link", g.top), "invalid link name '" + g.top + "': " + reason);
        }
        core::Body body;
        body.name = mPlacement.prefix + g.top;
        body.isStatic = g.isStatic;
        if (!g.isStatic)
        {
            setGroupMass(g, body);
        }
        const LinkPlace& topPlace = mPlaces[g.top];
        const Pose bodyPose = topPlace.world * g.bodyInTop;
        body.position_W = bodyPose.p;
        body.orientation_WB = bodyPose.q;
        const Pose topInBody = inverse(g.bodyInTop);
        for (const std::string& name : g.links)
        {
            core::throwIfInterrupted(); // a checkpoint between links (core/interrupt.h)
            addLinkShapes(g, name, topInBody, body);
        }
        if (!mPlacement.selfCollision)
        {
            body.group = mPlacement.prefix.empty() ? mOut.model.name : mPlacement.prefix;
        }
        setMaterial(g, body);
        g.body = static_cast<int>(mOut.model.bodies.size());
        mOut.model.bodies.push_back(std::move(body));
    }

    // The mass and inertia of the group's links together, and the body's frame in its top link
    // (at their centre of mass, axes of the top link's <inertial> when it has mass).
    void setGroupMass(LinkGroup& g, core::Body& body)
    {
        const urdf::Link& top = link(g.top);
        const bool topHasMass = top.inertial && top.inertial->mass > 0.0;
        const core::Quat axes = topHasMass ? fromUrdf(top.inertial->origin).q : core::Quat::Identity();
        std::vector<MassPart> parts;
        for (const std::string& name : g.links)
        {
            const bool ownFrame = topHasMass && name == g.top;
            parts.push_back(massPart(link(name), ownFrame ? std::nullopt : std::optional<core::Quat>(axes)));
        }
        const CompositeMass mass = combineMassParts(parts);
        if (!(mass.mass > 0.0))
        {
            failMassless(g);
        }
        body.mass = mass.mass;
        body.inertia_B = mass.inertia;
        g.bodyInTop = Pose{mass.centre, axes};
        if (!isPositiveDefinite(body.inertia_B))
        {
            fail(mIndex.element("link", g.top),
                 "the links welded into body '" + g.top + "' have an inertia that is not positive-definite");
        }
    }

    // One link's collision and visual shapes posed in the body, its colour if the body has none yet.
    void addLinkShapes(const LinkGroup& g, const std::string& name, const Pose& topInBody, core::Body& body)
    {
        const urdf::Link& l = link(name);
        const std::optional<Pose>& inTop = mPlaces[name].inTop;
        const Pose linkInBody = inTop ? topInBody * *inTop : topInBody;
        std::vector<core::Shape> collisionShapes = linkShapes(l, true, false);
        bool visualUnreadable = false;
        std::vector<core::Shape> visualShapes = linkShapes(l, false, false, &visualUnreadable);
        if (visualUnreadable)
        {
            visualShapes = collisionShapes; // as readMesh's warning says
        }
        appendPosed(collisionShapes, linkInBody, body.shapes);
        appendPosed(visualShapes, linkInBody, body.visuals);
        for (const urdf::VisualSharedPtr& visual : l.visual_array)
        {
            if (visual && visual->material && !body.color)
            {
                const urdf::Color& c = visual->material->color;
                body.color = core::Vec3(c.r, c.g, c.b);
            }
        }
        if (name != g.top)
        {
            mOut.report.welded.emplace_back(name, body.name);
        }
    }

    // The body's friction and restitution from its links' <contact> (or Gazebo's mu1): the first
    // link of the group that gives each (its top link first); a welded link that gives another
    // value is a warning.
    void setMaterial(const LinkGroup& g, core::Body& body)
    {
        // quantity: "friction" or "restitution"; range: the values its rule allows.
        const auto take = [&](const std::string& linkName, const std::optional<std::string>& text,
                              TextPosition at, bool (*rule)(double), const std::string& quantity,
                              const char* range, std::optional<double>& out)
        {
            if (!text)
            {
                return;
            }
            const std::optional<double> value = parseFiniteNumber(*text);
            if (!value || !rule(*value))
            {
                fail(at, "expected a " + quantity + " in " + range + " for link '" + linkName + "', got '" +
                             *text + "'");
            }
            if (!out)
            {
                out = value;
            }
            else if (*out != *value)
            {
                warn(at, "link '" + linkName + "' is welded into body '" + body.name + "', whose " +
                             quantity + " is " + formatNumber(*out) + " from an earlier link; its " +
                             formatNumber(*value) + " is not used");
            }
        };
        for (const std::string& name : g.links)
        {
            if (const UrdfXmlIndex::LinkMaterial* m = mIndex.material(name))
            {
                take(name, m->friction, m->frictionAt, core::isFriction, "friction", "[0, 1e6]",
                     body.friction);
                take(name, m->restitution, m->restitutionAt, core::isRestitution, "restitution", "[0, 1]",
                     body.restitution);
            }
        }
    }

    // `shapes` (posed in a link frame) appended to `out`, posed in the body frame.
    static void appendPosed(std::vector<core::Shape>& shapes, const Pose& linkInBody,
                            std::vector<core::Shape>& out)
    {
        for (core::Shape& shape : shapes)
        {
            const Pose shapePose = linkInBody * Pose{shape.position_BS, shape.rotation_BS};
            shape.position_BS = shapePose.p;
            shape.rotation_BS = shapePose.q;
            out.push_back(std::move(shape));
        }
    }

    [[noreturn]] void failMassless(const LinkGroup& g) const
    {
        const std::string what =
            "link '" + g.top + "' has no mass (no <inertial> with a positive mass" +
            (g.links.size() > 1 ? " in it or in the links welded to it by fixed joints" : "") + ")";
        if (g.joint != nullptr)
        {
            fail(mIndex.element("joint", g.joint->name),
                 what + " but " + jointTypeWord(g.joint->type) + " joint '" + g.joint->name +
                     "' moves it; give it an <inertial>, or make the joint fixed");
        }
        fail(mIndex.element("link", g.top),
             what + " but floats freely (the robot's root, or the child of a floating joint); give it an "
                    "<inertial>, or weld the robot to the world (--fixed-base; in a scene, 'fixed: true')");
    }

    void addJoint(const urdf::Joint& joint)
    {
        if (joint.type == urdf::Joint::FIXED || joint.type == urdf::Joint::FLOATING)
        {
            return; // welded, or a free child: no joint
        }
        const TextPosition at = mIndex.element("joint", joint.name);
        const std::string reason = invalidNameReason(joint.name);
        if (!reason.empty())
        {
            fail(at, "invalid joint name '" + joint.name + "': " + reason);
        }
        core::Joint j;
        j.name = mPlacement.prefix + joint.name;
        j.type = joint.type == urdf::Joint::PRISMATIC ? core::JointType::Prismatic
                 : joint.type == urdf::Joint::PLANAR  ? core::JointType::Planar
                                                      : core::JointType::Revolute;
        j.parent = groupOf(joint.parent_link_name).body;
        j.child = groupOf(joint.child_link_name).body;
        const Pose childPose = mPlaces[joint.child_link_name].world;
        const core::Vec3 axis(joint.axis.x, joint.axis.y, joint.axis.z);
        if (!(axis.norm() > 1e-12) || !axis.allFinite())
        {
            fail(mIndex.element("joint", joint.name, "axis"),
                 "joint '" + joint.name + "' has a zero <axis>; expected a non-zero direction");
        }
        const core::Vec3 axis_W = childPose.q * axis.normalized();
        if (joint.type != urdf::Joint::CONTINUOUS && core::hasLimits(j.type))
        {
            readLimits(joint, j);
        }
        if (joint.limits && !core::hasLimits(j.type))
        {
            warn(mIndex.element("joint", joint.name, "limit"), "joint '" + joint.name + "': <limit> of a " +
                                                                   core::jointTypeName(j.type) +
                                                                   " joint is not supported and is ignored");
        }
        else if (joint.limits && std::isfinite(joint.limits->effort) && joint.limits->effort > 0.0)
        {
            j.effortLimit = joint.limits->effort; // N m or N; 0 (a file that leaves it out) means none
        }
        readDynamics(joint, j);
        if (joint.mimic)
        {
            warn(mIndex.element("joint", joint.name, "mimic"),
                 "joint '" + joint.name +
                     "': <mimic> is not supported and is ignored (the joint moves freely)");
        }
        core::setJointFrames(mOut.model, j, childPose.p, axis_W);
        mOut.model.joints.push_back(std::move(j));
    }

    void readLimits(const urdf::Joint& joint, core::Joint& j)
    {
        if (!joint.limits)
        {
            fail(mIndex.element("joint", joint.name), "joint '" + joint.name + "' needs a <limit>");
        }
        const double lower = joint.limits->lower;
        const double upper = joint.limits->upper;
        const TextPosition at = mIndex.element("joint", joint.name, "limit");
        if (!std::isfinite(lower) || !std::isfinite(upper) || lower > upper)
        {
            fail(at, "joint '" + joint.name + "' has limits lower=" + formatNumber(lower) +
                         " > upper=" + formatNumber(upper) + "; expected lower <= upper");
        }
        if (lower == upper)
        {
            warn(at, "joint '" + joint.name + "' has lower = upper = " + formatNumber(lower) +
                         " (a <limit> without lower and upper means 0 and 0): it is locked");
        }
        const auto start = mStartPosition.find(joint.name);
        j.initialPosition = start == mStartPosition.end() ? 0.0 : start->second;
        j.limits = std::array<double, 2>{lower - j.initialPosition, upper - j.initialPosition};
    }

    void readDynamics(const urdf::Joint& joint, core::Joint& j)
    {
        if (!joint.dynamics)
        {
            return;
        }
        if (!core::hasLimits(j.type))
        {
            warn(mIndex.element("joint", joint.name, "dynamics"),
                 "joint '" + joint.name + "': <dynamics> of a " + core::jointTypeName(j.type) +
                     " joint is not supported and is ignored");
            return;
        }
        const TextPosition at = mIndex.element("joint", joint.name, "dynamics");
        const double damping = joint.dynamics->damping;
        const double friction = joint.dynamics->friction;
        if (!std::isfinite(damping) || damping < 0.0 || !std::isfinite(friction) || friction < 0.0)
        {
            fail(at, "joint '" + joint.name + "' has <dynamics damping=\"" + formatNumber(damping) +
                         "\" friction=\"" + formatNumber(friction) + "\">; expected non-negative numbers");
        }
        j.damping = damping;
        j.friction = friction;
    }

    const std::string& mFile;
    const UrdfXmlIndex& mIndex;
    const urdf::ModelInterface& mRobot;
    const UrdfPlacement& mPlacement;
    const PackagePaths& mPackages;
    std::map<std::string, LinkPlace> mPlaces; // by link name
    std::vector<LinkGroup> mGroups;
    std::set<std::string> mNotedPackages;         // last-resort package matches already warned about
    std::map<std::string, double> mStartPosition; // joints that start away from 0 (rad or m)
    std::set<std::string> mUsedJointPositions;    // names of mPlacement.jointPositions taken
    ModelFragment mOut;
};

// The joints must join the links into a tree, checked on the file's text before urdfdom reads it
// (urdfdom accepts some loops, and its "failed to find root link" names no place): no joint from
// a link to itself, no link that is the child of two joints, no loop of joints.
void checkJointTree(const std::string& file, const UrdfXmlIndex& index)
{
    using JointLinks = UrdfXmlIndex::JointLinks;
    std::map<std::string, const JointLinks*> parentJoint; // child link -> the joint above it
    for (const JointLinks& j : index.jointLinks())
    {
        if (j.parent == j.child)
        {
            throw InputError(file, j.at.line, j.at.column,
                             "joint '" + j.joint + "' joins link '" + j.child +
                                 "' to itself; expected a parent and a child link that differ");
        }
        const auto [it, inserted] = parentJoint.try_emplace(j.child, &j);
        if (!inserted)
        {
            throw InputError(file, j.at.line, j.at.column,
                             "link '" + j.child + "' is the child of joint '" + it->second->joint +
                                 "' and of joint '" + j.joint +
                                 "'; a link has one parent joint (the links must form a tree)");
        }
    }
    // Each link has at most one parent now: walk up from every link; a walk that comes back to a
    // link of its own is a loop. `done` links are known to lead to a root.
    std::set<std::string> done;
    for (const JointLinks& start : index.jointLinks())
    {
        std::vector<std::string> path;
        std::set<std::string> onPath; // the links of `path`
        std::string link = start.child;
        while (!done.contains(link))
        {
            if (!onPath.insert(link).second)
            {
                const JointLinks& closing = *parentJoint.at(path.back()); // the joint that led back
                throw InputError(file, closing.at.line, closing.at.column,
                                 "joint '" + closing.joint + "' closes a loop of joints through link '" +
                                     link + "'; the links must form a tree");
            }
            path.push_back(link);
            const auto up = parentJoint.find(link);
            if (up == parentJoint.end())
            {
                break; // a root
            }
            link = up->second->parent;
        }
        done.insert(path.begin(), path.end());
    }
}

// urdfdom's links own their child links through shared pointers, so releasing a model freed a
// chain of links one nested call per link (a chain of 300 000 overflowed the stack). Cutting
// those edges first leaves every link to the model's own map, freed one after the other.
struct ShallowRelease
{
    explicit ShallowRelease(urdf::ModelInterface* released) : model(released) {}
    ShallowRelease(const ShallowRelease&) = delete;
    ShallowRelease& operator=(const ShallowRelease&) = delete;
    ~ShallowRelease()
    {
        if (model != nullptr)
        {
            for (auto& [name, link] : model->links_)
            {
                link->child_links.clear();
                link->child_joints.clear();
            }
        }
    }
    urdf::ModelInterface* model;
};

// `text` with ` attribute` inserted after the "<robot" of the <robot> element at `robotAt`, on
// the same line, so that every line keeps its number.
std::string withRobotAttribute(const std::string& text, TextPosition robotAt, const std::string& attribute)
{
    std::size_t lineStart = 0;
    for (int line = 1; line < robotAt.line && lineStart != std::string::npos; ++line)
    {
        lineStart = text.find('\n', lineStart);
        lineStart = lineStart == std::string::npos ? lineStart : lineStart + 1;
    }
    const std::size_t tag = text.find("<robot", lineStart == std::string::npos ? 0 : lineStart);
    std::string out = text;
    out.insert(tag == std::string::npos ? 0 : tag + 6, " " + attribute);
    return out;
}

// `value` as the text of a double-quoted XML attribute.
std::string xmlAttributeText(const std::string& value)
{
    std::string out;
    for (const char c : value)
    {
        switch (c)
        {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '"':
            out += "&quot;";
            break;
        default:
            out += c;
        }
    }
    return out;
}

// A <robot> without a name (which urdfdom refuses) is named after the file's stem, with a warning.
std::string nameTheRobot(const std::string& path, const std::string& text, const UrdfXmlIndex& index,
                         std::vector<std::string>& warnings)
{
    if (index.robotNamed())
    {
        return text;
    }
    const std::string stem = std::filesystem::path(path).stem().string();
    warnings.push_back(
        diagnostic(path, index.robot(), "warning",
                   "the <robot> has no name attribute; naming the robot '" + stem + "' after the file"));
    return withRobotAttribute(text, index.robot(), "name=\"" + xmlAttributeText(stem) + "\"");
}

} // namespace

std::string formatNumber(double value)
{
    std::ostringstream out;
    out << value;
    return out.str();
}

std::string formatVector(const core::Vec3& v)
{
    return formatNumber(v.x()) + ", " + formatNumber(v.y()) + ", " + formatNumber(v.z());
}

ModelFragment loadUrdfFragment(const std::string& path, const UrdfPlacement& placement,
                               const PackagePaths& packages)
{
    const std::string original = readTextFile(path, "URDF file");
    const UrdfXmlIndex index(path, original); // XML syntax errors with row and column
    checkJointTree(path, index);
    std::vector<std::string> warnings;
    const std::string text = nameTheRobot(path, original, index, warnings);
    CapturedLog log;
    const urdf::ModelInterfaceSharedPtr robot = parseCapturingErrors(text, log);
    const ShallowRelease release(robot.get());
    if (!log.errors.empty() || !robot)
    {
        std::string message = "invalid URDF";
        for (const std::string& error : log.errors)
        {
            message += (message == "invalid URDF" ? ": " : "; ") + error;
        }
        TextPosition at;
        for (const std::string& error : log.errors)
        {
            at = index.locateMessage(error);
            if (at.line > 0)
            {
                break;
            }
        }
        if (at.line == 0)
        {
            at = index.robot(); // a message about the whole robot ("No link elements found")
        }
        throw InputError(path, at.line, at.column, message);
    }
    UrdfConverter converter(path, index, *robot, placement, packages);
    ModelFragment fragment = converter.convert();
    fragment.warnings.insert(fragment.warnings.begin(), warnings.begin(), warnings.end());
    fragment.report.name = placement.prefix.empty() ? fragment.model.name : placement.prefix;
    fragment.report.prefix = placement.prefix;
    return fragment;
}

} // namespace frontier::io::detail
