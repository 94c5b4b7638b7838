// io/urdf_model.cpp: URDF (urdfdom) links and joints to bodies and joints.
//
// Mapping (scenes/README.md has the full rules): a moving link becomes a body whose frame is the
// link frame composed with its <inertial> origin (origin at the centre of mass, axes of the
// inertia tensor); collision elements become shapes posed in that frame; joints are anchored at
// the child link's frame origin with the axis rotated into the world, in the initial pose.
#include "io/urdf_model.h"

#include "io/file_util.h"
#include "io/mass_properties.h"
#include "io/mesh_file.h"
#include "io/scene.h"
#include "io/suggest.h"
#include "io/urdf_xml_index.h"

#include <cmath>
#include <console_bridge/console.h>
#include <map>
#include <mutex>
#include <sstream>
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

std::string formatNumber(double value)
{
    std::ostringstream out;
    out << value;
    return out.str();
}

class UrdfConverter
{
  public:
    UrdfConverter(const std::string& file, const UrdfXmlIndex& index, const urdf::ModelInterface& robot,
                  const UrdfPlacement& placement)
        : mFile(file), mBaseDir(directoryOf(file)), mIndex(index), mRobot(robot), mPlacement(placement)
    {
    }

    core::Model convert()
    {
        core::Model out;
        out.name = mRobot.getName();
        const urdf::LinkConstSharedPtr root = mRobot.getRoot();
        if (!root)
        {
            fail({}, "the URDF has no root link");
        }
        mRootIsWorld = root->name == "world";
        computeLinkPoses(*root, Pose{mPlacement.position, mPlacement.orientation.normalized()});
        for (const std::string& linkName : mIndex.linkNames())
        {
            const urdf::LinkConstSharedPtr link = mRobot.getLink(linkName);
            if (link)
            {
                addLink(*link, link == root, out);
            }
        }
        for (const std::string& jointName : mIndex.jointNames())
        {
            const urdf::JointConstSharedPtr joint = mRobot.getJoint(jointName);
            if (joint)
            {
                addJoint(*joint, out);
            }
        }
        return out;
    }

  private:
    [[noreturn]] void fail(TextPosition at, const std::string& message) const
    {
        throw InputError(mFile, at.line, at.column, message);
    }

    void computeLinkPoses(const urdf::Link& link, const Pose& pose)
    {
        mLinkPose[link.name] = pose;
        for (const urdf::JointSharedPtr& joint : link.child_joints)
        {
            const urdf::LinkConstSharedPtr child = mRobot.getLink(joint->child_link_name);
            if (child)
            {
                computeLinkPoses(*child, pose * fromUrdf(joint->parent_to_joint_origin_transform));
            }
        }
    }

    void addLink(const urdf::Link& link, bool isRoot, core::Model& out)
    {
        const TextPosition at = mIndex.element("link", link.name);
        if (isRoot && mRootIsWorld)
        {
            if (link.inertial || !link.collision_array.empty())
            {
                fail(at, "link 'world' is the fixed world frame; it cannot have <inertial> or <collision> "
                         "(attach a link to it with a fixed joint)");
            }
            mLinkBody[link.name] = core::cWorld;
            return;
        }
        const std::string reason = invalidNameReason(link.name);
        if (!reason.empty())
        {
            fail(at, "invalid link name '" + link.name + "': " + reason);
        }
        core::Body body;
        body.name = mPlacement.prefix + link.name;
        body.isStatic = isRoot && mPlacement.fixedRoot;
        const Pose linkPose = mLinkPose.at(link.name);
        Pose inertialPose; // body (centre of mass) frame in the link frame
        if (!body.isStatic)
        {
            inertialPose = readInertial(link, body);
        }
        const Pose bodyPose = linkPose * inertialPose;
        body.position_W = bodyPose.p;
        body.orientation_WB = bodyPose.q;
        const Pose linkToBody = inverse(inertialPose);
        for (const urdf::CollisionSharedPtr& collision : link.collision_array)
        {
            if (collision && collision->geometry)
            {
                core::Shape shape = readGeometry(link, *collision->geometry);
                const Pose shapePose = linkToBody * fromUrdf(collision->origin);
                shape.position_BS = shapePose.p;
                shape.rotation_BS = shapePose.q;
                body.shapes.push_back(std::move(shape));
            }
        }
        for (const urdf::VisualSharedPtr& visual : link.visual_array)
        {
            if (visual && visual->material && !body.color)
            {
                const urdf::Color& c = visual->material->color;
                body.color = core::Vec3(c.r, c.g, c.b);
            }
        }
        if (!mPlacement.selfCollision)
        {
            body.group = mPlacement.prefix.empty() ? out.name : mPlacement.prefix;
        }
        mLinkBody[link.name] = static_cast<int>(out.bodies.size());
        out.bodies.push_back(std::move(body));
    }

    Pose readInertial(const urdf::Link& link, core::Body& body) const
    {
        if (!link.inertial)
        {
            fail(mIndex.element("link", link.name),
                 "link '" + link.name + "' has no <inertial>; every moving link needs a mass and an inertia");
        }
        const urdf::Inertial& inertial = *link.inertial;
        if (!std::isfinite(inertial.mass) || !(inertial.mass > 0.0))
        {
            fail(mIndex.element("link", link.name, "inertial/mass"),
                 "link '" + link.name + "' has mass " + formatNumber(inertial.mass) +
                     "; expected a positive <mass value> (kg)");
        }
        body.mass = inertial.mass;
        body.inertia_B << inertial.ixx, inertial.ixy, inertial.ixz, inertial.ixy, inertial.iyy, inertial.iyz,
            inertial.ixz, inertial.iyz, inertial.izz;
        if (!isPositiveDefinite(body.inertia_B))
        {
            fail(mIndex.element("link", link.name, "inertial/inertia"),
                 "link '" + link.name + "' has an inertia that is not positive-definite (ixx=" +
                     formatNumber(inertial.ixx) + " ixy=" + formatNumber(inertial.ixy) +
                     " ixz=" + formatNumber(inertial.ixz) + " iyy=" + formatNumber(inertial.iyy) +
                     " iyz=" + formatNumber(inertial.iyz) + " izz=" + formatNumber(inertial.izz) + ")");
        }
        return fromUrdf(inertial.origin);
    }

    core::Shape readGeometry(const urdf::Link& link, const urdf::Geometry& geometry) const
    {
        const TextPosition at = mIndex.element("link", link.name, "collision/geometry");
        const std::string where = "a collision of link '" + link.name + "'";
        core::Shape shape;
        switch (geometry.type)
        {
        case urdf::Geometry::BOX:
        {
            const auto& box = static_cast<const urdf::Box&>(geometry);
            shape.type = core::ShapeType::Box;
            shape.size = core::Vec3(box.dim.x, box.dim.y, box.dim.z);
            if (!(shape.size.minCoeff() > 0.0) || !shape.size.allFinite())
            {
                fail(at, "box size of " + where + " must be positive");
            }
            break;
        }
        case urdf::Geometry::SPHERE:
            shape.type = core::ShapeType::Sphere;
            shape.radius = static_cast<const urdf::Sphere&>(geometry).radius;
            if (!(shape.radius > 0.0) || !std::isfinite(shape.radius))
            {
                fail(at, "sphere radius of " + where + " must be positive");
            }
            break;
        case urdf::Geometry::CYLINDER:
        {
            const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
            shape.type = core::ShapeType::Cylinder;
            shape.radius = cylinder.radius;
            shape.length = cylinder.length;
            if (!(shape.radius > 0.0 && shape.length > 0.0) || !std::isfinite(shape.radius + shape.length))
            {
                fail(at, "cylinder radius and length of " + where + " must be positive");
            }
            break;
        }
        case urdf::Geometry::MESH:
            shape = readMesh(link, static_cast<const urdf::Mesh&>(geometry));
            break;
        }
        return shape;
    }

    core::Shape readMesh(const urdf::Link& link, const urdf::Mesh& mesh) const
    {
        const TextPosition at = mIndex.find("\"" + mesh.filename + "\"").line > 0
                                    ? mIndex.find("\"" + mesh.filename + "\"")
                                    : mIndex.element("link", link.name, "collision/geometry/mesh");
        std::string filename = mesh.filename;
        if (filename.starts_with("package://"))
        {
            fail(at, "mesh '" + filename +
                         "': package:// URIs are not supported; give a path relative to the URDF file");
        }
        if (filename.starts_with("file://"))
        {
            filename = filename.substr(7);
        }
        const core::Vec3 scale(mesh.scale.x, mesh.scale.y, mesh.scale.z);
        if (!(scale.minCoeff() > 0.0) || !scale.allFinite())
        {
            fail(at, "mesh '" + filename + "' of link '" + link.name + "' needs a positive scale");
        }
        const std::string path = resolvePath(mBaseDir, filename);
        try
        {
            return loadMeshFile(path, scale);
        }
        catch (const InputError& e)
        {
            if (e.line() > 0)
            {
                throw; // the error is inside the mesh file: keep its location
            }
            fail(at, "mesh '" + path + "' of link '" + link.name + "': " + e.message());
        }
    }

    void addJoint(const urdf::Joint& joint, core::Model& out) const
    {
        const TextPosition at = mIndex.element("joint", joint.name);
        core::Joint j;
        j.name = mPlacement.prefix + joint.name;
        const std::string reason = invalidNameReason(joint.name);
        if (!reason.empty())
        {
            fail(at, "invalid joint name '" + joint.name + "': " + reason);
        }
        bool hasAxis = true;
        switch (joint.type)
        {
        case urdf::Joint::REVOLUTE:
        case urdf::Joint::CONTINUOUS:
            j.type = core::JointType::Revolute;
            break;
        case urdf::Joint::PRISMATIC:
            j.type = core::JointType::Prismatic;
            break;
        case urdf::Joint::FIXED:
            j.type = core::JointType::Fixed;
            hasAxis = false;
            break;
        case urdf::Joint::FLOATING:
            return; // a free child: no joint
        case urdf::Joint::PLANAR:
            fail(at,
                 "joint '" + joint.name +
                     "' has type planar, which is unsupported (supported: revolute, continuous, prismatic, "
                     "fixed, floating)");
        default:
            fail(at, "joint '" + joint.name + "' has an unknown type");
        }
        j.parent = mLinkBody.at(joint.parent_link_name);
        j.child = mLinkBody.at(joint.child_link_name);
        const Pose childPose = mLinkPose.at(joint.child_link_name);
        core::Vec3 axis_W = core::Vec3::UnitZ();
        if (hasAxis)
        {
            const core::Vec3 axis(joint.axis.x, joint.axis.y, joint.axis.z);
            if (!(axis.norm() > 1e-12) || !axis.allFinite())
            {
                fail(mIndex.element("joint", joint.name, "axis"),
                     "joint '" + joint.name + "' has a zero <axis>; expected a non-zero direction");
            }
            axis_W = childPose.q * axis.normalized();
        }
        if (joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::PRISMATIC)
        {
            if (!joint.limits)
            {
                fail(at, "joint '" + joint.name + "' needs a <limit>");
            }
            const double lower = joint.limits->lower;
            const double upper = joint.limits->upper;
            if (!std::isfinite(lower) || !std::isfinite(upper) || lower > upper)
            {
                fail(mIndex.element("joint", joint.name, "limit"),
                     "joint '" + joint.name + "' has limits lower=" + formatNumber(lower) +
                         " > upper=" + formatNumber(upper) + "; expected lower <= upper");
            }
            j.limits = std::array<double, 2>{lower, upper};
        }
        core::setJointFrames(out, j, childPose.p, axis_W);
        out.joints.push_back(std::move(j));
    }

    const std::string& mFile;
    std::string mBaseDir;
    const UrdfXmlIndex& mIndex;
    const urdf::ModelInterface& mRobot;
    const UrdfPlacement& mPlacement;
    bool mRootIsWorld = false;
    std::map<std::string, Pose> mLinkPose; // link frame in the world (initial pose)
    std::map<std::string, int> mLinkBody;  // body index, or cWorld
};

} // namespace

core::Model loadUrdfFragment(const std::string& path, const UrdfPlacement& placement)
{
    const std::string text = readTextFile(path);
    const UrdfXmlIndex index(path, text); // XML syntax errors with row and column
    CapturedLog log;
    const urdf::ModelInterfaceSharedPtr robot = parseCapturingErrors(text, log);
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
        throw InputError(path, at.line, at.column, message);
    }
    UrdfConverter converter(path, index, *robot, placement);
    return converter.convert();
}

core::Model loadUrdfScene(const std::string& path)
{
    core::Model model = loadUrdfFragment(path, UrdfPlacement{});
    model.sourceFile = path;
    core::Body floor;
    floor.name = model.findBody("floor") < 0 ? "floor" : "floor_";
    floor.isStatic = true;
    core::Shape plane;
    plane.type = core::ShapeType::Plane;
    plane.normal = core::Vec3::UnitZ();
    plane.offset = 0.0;
    floor.shapes.push_back(plane);
    model.bodies.push_back(std::move(floor));
    return model;
}

} // namespace frontier::io::detail
