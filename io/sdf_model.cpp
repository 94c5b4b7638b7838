// io/sdf_model.cpp: SDF (libsdformat) models and worlds to bodies and joints.
//
// Mapping (scenes/README.md "Models and worlds from SDF" has the user's view):
// * Poses come from the library's own resolution of <pose relative_to> (SemanticPose, in each
//   model's frame), composed with the model's pose in the world (a <model> file: its own <pose>).
// * Links joined by fixed joints are one rigid body (welded), as in a URDF (io/urdf_model.cpp):
//   masses and inertias combined, the body at the combined centre of mass with the axes of its top
//   link's <inertial> frame, named after the top link. A link fixed to the world, and every link of
//   a <static> model, is a static body. A <plane> collision (static links only) is a core Plane.
// * A link without <inertial> has SDF's defaults, mass 1 kg and the identity inertia (the library
//   returns them), with a warning.
// * Joints revolute, continuous, prismatic, ball and universal (core's angle joint, docs/method.md
//   §2: a1 = axis 1 fixed in the parent, b2 = axis 2 fixed in the child) are anchored at the joint
//   frame's origin, axes as the library resolves them; revolute2, screw and gearbox are refused.
// * A model's links collide with each other only under <self_collide>true</self_collide> (SDF's
//   default is false), unless --self-collision says otherwise.
// * <include> of model:// URIs goes through PackagePaths (--package-path, GAZEBO_MODEL_PATH, ...).
//   Gazebo's standard model://sun (a light) and model://ground_plane (a static plane at z = 0,
//   friction 100), when they are not found there, are taken as Gazebo defines them, with a note.
#include "io/sdf_model.h"

#include "io/file_util.h"

#ifdef FRONTIER_HAVE_SDFORMAT
#include "core/interrupt.h"
#include "io/hold_servos.h"
#include "io/mass_properties.h"
#include "io/mesh_file.h"
#include "io/package_paths.h"
#include "io/suggest.h"
#include "io/urdf_model.h"
#include "io/xml_scan.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <numbers>
#include <numeric>
#include <optional>
#include <sdf/sdf.hh>
#include <set>
#include <sstream>
#include <tinyxml.h>
#endif

namespace frontier::io::detail
{

#ifndef FRONTIER_HAVE_SDFORMAT

bool sdfSupported()
{
    return false;
}

core::Model loadSdfScene(const std::string& path, const UrdfOptions& /*options*/, LoadReport* /*report*/)
{
    throw InputError(path, 0, 0,
                     "this build of Frontier has no SDF support: it was built without libsdformat "
                     "(Debian package libsdformat-dev); install it and rebuild to read .sdf, .world and "
                     ".model files");
}

#else

bool sdfSupported()
{
    return true;
}

namespace
{

using Pose = Eigen::Isometry3d;

core::Vec3 toVec(const ignition::math::Vector3d& v)
{
    return {v.X(), v.Y(), v.Z()};
}

Pose toPose(const ignition::math::Pose3d& p)
{
    Pose out = Pose::Identity();
    const ignition::math::Quaterniond& q = p.Rot();
    out.linear() = core::Quat(q.W(), q.X(), q.Y(), q.Z()).normalized().toRotationMatrix();
    out.translation() = toVec(p.Pos());
    return out;
}

core::Quat rotationOf(const Pose& pose)
{
    return core::Quat(pose.linear()).normalized();
}

// Gazebo's standard models that Frontier knows when they are not on the model path.
constexpr const char* cSunUri = "model://sun";
constexpr const char* cGroundPlaneUri = "model://ground_plane";
constexpr double cGroundPlaneFriction = 100.0; // Gazebo's ground_plane: <ode><mu>100</mu>

// Links of all models (nested ones included), each with its world pose at the start.
struct LinkPlace
{
    const sdf::Link* link = nullptr;
    std::string name; // scoped: "model::link" in a world, "link" (or "nested::link") in a model file
    Pose world = Pose::Identity();
    int model = 0; // index into SdfConverter::mModels
    int group = -1;
};

struct ModelPlace
{
    const sdf::Model* model = nullptr;
    std::string scope; // prefix of its links' names ("" or "name::")
    Pose world = Pose::Identity();
    bool isStatic = false;
    int top = 0; // the top-level model it belongs to (a robot of the scene)
};

// Links welded together by fixed joints: one body (static when welded to the world).
struct LinkGroup
{
    std::vector<int> links; // the top first
    bool isStatic = false;
    int body = core::cWorld;
};

class SdfConverter
{
  public:
    SdfConverter(std::string file, const UrdfOptions& options, const PackagePaths& packages)
        : mFile(std::move(file)), mOptions(options), mPackages(packages)
    {
    }

    std::vector<std::string>& warnings() { return mWarnings; }
    std::vector<RobotReport>& robots() { return mRobots; }

    // Every model of `root` (a world's, or the file's one model), then bodies and joints.
    core::Model convert(const sdf::Root& root)
    {
        if (const sdf::Model* model = root.Model())
        {
            addModel(*model, "", toPose(model->RawPose()), model->Static(), -1);
        }
        else if (root.WorldCount() > 0)
        {
            const sdf::World& world = *root.WorldByIndex(0);
            if (root.WorldCount() > 1)
            {
                warn(root.WorldByIndex(1)->Element(), "the file has " + std::to_string(root.WorldCount()) +
                                                          " worlds; only the first, '" + world.Name() +
                                                          "', is read");
            }
            readWorld(world);
        }
        else
        {
            fail(root.Element(), "the file has no <model> and no <world>");
        }
        weld();
        for (LinkGroup& g : mGroups)
        {
            addBody(g);
        }
        for (const ModelPlace& m : mModels)
        {
            for (uint64_t k = 0; k < m.model->JointCount(); ++k)
            {
                addJoint(m, *m.model->JointByIndex(k));
            }
        }
        fillRobots();
        return std::move(mOut);
    }

    bool isWorld() const { return mIsWorld; }

  private:
    std::string fileOf(const sdf::ElementPtr& e) const
    {
        return e && !e->FilePath().empty() && e->FilePath() != "data-string" ? e->FilePath() : mFile;
    }
    static TextPosition at(const sdf::ElementPtr& e) { return {e ? e->LineNumber().value_or(0) : 0, 0}; }

    [[noreturn]] void fail(const sdf::ElementPtr& e, const std::string& message) const
    {
        throw InputError(fileOf(e), at(e).line, 0, message);
    }
    void warn(const sdf::ElementPtr& e, const std::string& message)
    {
        mWarnings.push_back(diagnostic(fileOf(e), at(e), "warning", message));
    }
    void failOn(const sdf::Errors& errors, const sdf::ElementPtr& e, const std::string& what) const
    {
        if (!errors.empty())
        {
            fail(e, what + ": " + errors.front().Message());
        }
    }

    void readWorld(const sdf::World& world)
    {
        mIsWorld = true;
        mOut.name = world.Name();
        const core::Vec3 gravity = toVec(world.Gravity());
        if (!gravity.allFinite() || gravity.norm() > 1e6)
        {
            fail(world.Element(), "the world's <gravity> is (" + formatVector(gravity) +
                                      ") m/s^2; expected a finite vector of at most 1e6 m/s^2");
        }
        mOut.simulation.gravity = gravity;
        if (const sdf::Physics* physics = world.PhysicsDefault())
        {
            const double step = physics->MaxStepSize();
            if (!(step > 0.0 && step <= core::cMaxTimeStep))
            {
                fail(physics->Element(), "<max_step_size> is " + formatNumber(step) +
                                             "; expected a step in (0, " + formatNumber(core::cMaxTimeStep) +
                                             "] s");
            }
            mOut.simulation.dt = step;
        }
        for (uint64_t k = 0; k < world.ModelCount(); ++k)
        {
            const sdf::Model& model = *world.ModelByIndex(k);
            ignition::math::Pose3d pose;
            failOn(model.SemanticPose().Resolve(pose, "world"), model.Element(),
                   "the pose of model '" + model.Name() + "'");
            addModel(model, model.Name() + "::", toPose(pose), model.Static(), -1);
        }
    }

    // The model's links (with world poses) and its nested models, recursively.
    void addModel(const sdf::Model& model, const std::string& scope, const Pose& world, bool isStatic,
                  int top)
    {
        const int index = static_cast<int>(mModels.size());
        mModels.push_back({&model, scope, world, isStatic, top < 0 ? index : top});
        for (sdf::ElementPtr plugin = model.Element()->FindElement("plugin"); plugin;
             plugin = plugin->GetNextElement("plugin"))
        {
            warn(plugin, "model '" + model.Name() + "': <plugin> is not supported and is ignored");
        }
        for (uint64_t k = 0; k < model.LinkCount(); ++k)
        {
            const sdf::Link& link = *model.LinkByIndex(k);
            ignition::math::Pose3d pose;
            failOn(link.SemanticPose().Resolve(pose, "__model__"), link.Element(),
                   "the pose of link '" + link.Name() + "'");
            LinkPlace place;
            place.link = &link;
            place.name = scope + link.Name();
            place.world = world * toPose(pose);
            place.model = index;
            const core::Vec3 p = place.world.translation();
            if (!core::isPosition(p))
            {
                fail(link.Element(), "link '" + place.name + "' is at (" + formatVector(p) +
                                         ") m; expected " + core::cPositionRange);
            }
            mLinkIndex[place.name] = static_cast<int>(mLinks.size());
            mLinks.push_back(std::move(place));
        }
        for (uint64_t k = 0; k < model.ModelCount(); ++k)
        {
            const sdf::Model& nested = *model.ModelByIndex(k);
            ignition::math::Pose3d pose;
            failOn(nested.SemanticPose().Resolve(pose, "__model__"), nested.Element(),
                   "the pose of model '" + nested.Name() + "'");
            addModel(nested, scope + nested.Name() + "::", world * toPose(pose), isStatic || nested.Static(),
                     mModels[static_cast<std::size_t>(index)].top);
        }
    }

    // A joint's parent or child as a link index, cWorld for the world.
    int linkOf(const ModelPlace& m, const sdf::Joint& joint, bool parent) const
    {
        std::string name;
        const sdf::Errors errors = parent ? joint.ResolveParentLink(name) : joint.ResolveChildLink(name);
        failOn(errors, joint.Element(), "joint '" + joint.Name() + "'");
        if (name == "world")
        {
            return core::cWorld;
        }
        const auto found = mLinkIndex.find(m.scope + name);
        if (found == mLinkIndex.end())
        {
            fail(joint.Element(),
                 "joint '" + joint.Name() + "' names link '" + name + "', which the model lacks");
        }
        return found->second;
    }

    // Union of the links joined by fixed joints; a link fixed to the world, or of a static model, is static.
    void weld()
    {
        std::vector<int> up(mLinks.size());
        std::iota(up.begin(), up.end(), 0);
        std::vector<bool> worldFixed(mLinks.size(), false);
        const auto find = [&](int k)
        {
            while (up[static_cast<std::size_t>(k)] != k)
            {
                k = up[static_cast<std::size_t>(k)] =
                    up[static_cast<std::size_t>(up[static_cast<std::size_t>(k)])];
            }
            return k;
        };
        for (const ModelPlace& m : mModels)
        {
            for (uint64_t k = 0; k < m.model->JointCount(); ++k)
            {
                const sdf::Joint& joint = *m.model->JointByIndex(k);
                if (joint.Type() != sdf::JointType::FIXED)
                {
                    continue;
                }
                const int parent = linkOf(m, joint, true);
                const int child = linkOf(m, joint, false);
                if (parent == core::cWorld)
                {
                    worldFixed[static_cast<std::size_t>(child)] = true;
                    continue;
                }
                // The parent's root stays the root: the group is named after its top link.
                up[static_cast<std::size_t>(find(child))] = find(parent);
            }
        }
        std::map<int, int> groupOfRoot;
        for (std::size_t k = 0; k < mLinks.size(); ++k)
        {
            const int root = find(static_cast<int>(k));
            auto [it, inserted] = groupOfRoot.try_emplace(root, static_cast<int>(mGroups.size()));
            if (inserted)
            {
                mGroups.push_back({{root}, false, core::cWorld});
            }
            LinkGroup& g = mGroups[static_cast<std::size_t>(it->second)];
            if (static_cast<int>(k) != root)
            {
                g.links.push_back(static_cast<int>(k));
            }
            g.isStatic =
                g.isStatic || worldFixed[k] || mModels[static_cast<std::size_t>(mLinks[k].model)].isStatic;
            mLinks[k].group = it->second;
        }
    }

    // SDF's <inertial> of a link (the library's defaults without one), in world axes at its centre.
    MassPart massPart(const LinkPlace& place)
    {
        const sdf::Link& link = *place.link;
        const ignition::math::Inertiald& inertial = link.Inertial();
        const sdf::ElementPtr element = link.Element()->FindElement("inertial");
        if (!link.Element()->HasElement("inertial"))
        {
            const std::string note = "link '" + place.name +
                                     "' has no <inertial>: SDF's defaults are used, mass 1 kg and inertia "
                                     "diag(1, 1, 1) kg m^2 at the link frame's origin";
            warn(link.Element(), note);
            mRepaired[mModels[static_cast<std::size_t>(place.model)].top].push_back(note);
        }
        const sdf::ElementPtr where = element ? element : link.Element();
        MassPart part;
        part.mass = inertial.MassMatrix().Mass();
        if (!std::isfinite(part.mass) || part.mass < 0.0)
        {
            fail(where, "link '" + place.name + "' has mass " + formatNumber(part.mass) +
                            "; expected a non-negative <mass> (kg)");
        }
        if (part.mass == 0.0)
        {
            return part;
        }
        const Pose inertialWorld = place.world * toPose(inertial.Pose());
        const ignition::math::Matrix3d& moi = inertial.MassMatrix().Moi();
        core::Mat3 inertia;
        for (int r = 0; r < 3; ++r)
        {
            for (int c = 0; c < 3; ++c)
            {
                inertia(r, c) = moi(r, c);
            }
        }
        const std::string defect = inertiaDefect(inertia, part.mass);
        if (!defect.empty())
        {
            fail(where, "link '" + place.name + "': its inertia " + defect);
        }
        const core::Mat3 R = inertialWorld.linear();
        part.centre = inertialWorld.translation();
        part.inertia = R * inertia * R.transpose();
        return part;
    }

    void addBody(LinkGroup& g)
    {
        const LinkPlace& top = mLinks[static_cast<std::size_t>(g.links.front())];
        const std::string reason = invalidNameReason(top.name);
        if (!reason.empty())
        {
            fail(top.link->Element(), "invalid link name '" + top.name + "': " + reason);
        }
        core::Body body;
        body.name = top.name;
        body.isStatic = g.isStatic;
        const Pose bodyWorld = g.isStatic ? top.world : setMass(g, top, body);
        body.position_W = bodyWorld.translation();
        body.orientation_WB = rotationOf(bodyWorld);
        addGroupCollisions(g, bodyWorld.inverse(), body);
        const ModelPlace& model = mModels[static_cast<std::size_t>(top.model)];
        const ModelPlace& robot = mModels[static_cast<std::size_t>(model.top)];
        if (!mOptions.selfCollision.value_or(robot.model->SelfCollide()))
        {
            body.group = robot.model->Name();
        }
        g.body = static_cast<int>(mOut.bodies.size());
        mBodyModel.push_back(model.top);
        mOut.bodies.push_back(std::move(body));
    }

    // The mass and inertia (kg, kg m^2) of a moving group's body, from the <inertial> of its links;
    // returns the body's world pose: at the centre of mass, along the top link's inertial axes.
    Pose setMass(const LinkGroup& g, const LinkPlace& top, core::Body& body)
    {
        std::vector<MassPart> parts;
        for (const int k : g.links)
        {
            parts.push_back(massPart(mLinks[static_cast<std::size_t>(k)]));
        }
        const CompositeMass mass = combineMassParts(parts);
        if (!(mass.mass > 0.0))
        {
            fail(top.link->Element(), "link '" + top.name + "' has no mass (<inertial><mass> 0" +
                                          (g.links.size() > 1 ? " in it and the links fixed to it" : "") +
                                          ") but it moves; give it a mass, or make it static");
        }
        Pose bodyWorld = top.world * toPose(top.link->Inertial().Pose());
        bodyWorld.translation() = mass.centre;
        const core::Mat3 R = bodyWorld.linear();
        body.mass = mass.mass;
        body.inertia_B = R.transpose() * mass.inertia * R;
        if (!isPositiveDefinite(body.inertia_B))
        {
            fail(top.link->Element(), "the links welded into body '" + top.name +
                                          "' have an inertia that is not positive-definite");
        }
        return bodyWorld;
    }

    // The shapes of every link of the group, in the body's frame; the links after the first are
    // reported as welded into it.
    void addGroupCollisions(const LinkGroup& g, const Pose& worldToBody, core::Body& body)
    {
        for (const int k : g.links)
        {
            core::throwIfInterrupted(); // a checkpoint between links (core/interrupt.h)
            const LinkPlace& place = mLinks[static_cast<std::size_t>(k)];
            for (uint64_t c = 0; c < place.link->CollisionCount(); ++c)
            {
                addCollision(place, *place.link->CollisionByIndex(c), worldToBody, body);
            }
            if (k != g.links.front())
            {
                mWelded[mModels[static_cast<std::size_t>(place.model)].top].emplace_back(place.name,
                                                                                         body.name);
            }
        }
    }

    void addCollision(const LinkPlace& place, const sdf::Collision& collision, const Pose& worldToBody,
                      core::Body& body)
    {
        const std::string what = "collision '" + collision.Name() + "' of link '" + place.name + "'";
        ignition::math::Pose3d pose;
        failOn(collision.SemanticPose().Resolve(pose), collision.Element(), "the pose of " + what);
        const Pose shapeWorld = place.world * toPose(pose);
        const sdf::Geometry& geometry = *collision.Geom();
        const sdf::ElementPtr at = geometry.Element() ? geometry.Element() : collision.Element();
        if (geometry.Type() == sdf::GeometryType::EMPTY)
        {
            return;
        }
        if (geometry.Type() == sdf::GeometryType::PLANE)
        {
            body.shapes.push_back(
                planeShape(geometry, at, what, shapeWorld, body)); // world frame: no pose in the body
            takeFriction(place, collision, body);
            return;
        }
        core::Shape shape = solidShape(geometry, at, what);
        const Pose inBody = worldToBody * shapeWorld;
        shape.position_BS = inBody.translation();
        shape.rotation_BS = rotationOf(inBody);
        body.shapes.push_back(std::move(shape));
        takeFriction(place, collision, body);
    }

    // A <plane> (of a static link only) in the world frame, where shapeWorld puts it.
    core::Shape planeShape(const sdf::Geometry& geometry, const sdf::ElementPtr& at, const std::string& what,
                           const Pose& shapeWorld, const core::Body& body) const
    {
        if (!body.isStatic)
        {
            fail(at, what + " is a <plane>, which only a static link may have (a plane has no mass); "
                            "make the model <static>, or fix the link to the world");
        }
        const core::Vec3 normal = toVec(geometry.PlaneShape()->Normal());
        if (!(normal.allFinite() && normal.norm() > 1e-12))
        {
            fail(at, "the <normal> of " + what + " is (" + formatVector(normal) +
                         "); expected a non-zero direction");
        }
        core::Shape shape;
        shape.type = core::ShapeType::Plane;
        shape.normal = (shapeWorld.linear() * normal.normalized()).normalized();
        shape.offset = shape.normal.dot(shapeWorld.translation());
        return shape;
    }

    // A box, sphere, cylinder, capsule or mesh, without its pose in the body.
    core::Shape solidShape(const sdf::Geometry& geometry, const sdf::ElementPtr& at, const std::string& what)
    {
        core::Shape shape;
        switch (geometry.Type())
        {
        case sdf::GeometryType::BOX:
            shape.type = core::ShapeType::Box;
            shape.size = toVec(geometry.BoxShape()->Size());
            if (!(core::isLength(shape.size.x()) && core::isLength(shape.size.y()) &&
                  core::isLength(shape.size.z())))
            {
                fail(at, "box size of " + what + " is (" + formatVector(shape.size) + "); expected each " +
                             core::cLengthRange);
            }
            break;
        case sdf::GeometryType::SPHERE:
            shape.type = core::ShapeType::Sphere;
            shape.radius = geometry.SphereShape()->Radius();
            checkLengths(at, what, "sphere radius", shape.radius, 1.0);
            break;
        case sdf::GeometryType::CYLINDER:
            shape.type = core::ShapeType::Cylinder;
            shape.radius = geometry.CylinderShape()->Radius();
            shape.length = geometry.CylinderShape()->Length();
            checkLengths(at, what, "cylinder radius and length", shape.radius, shape.length);
            break;
        case sdf::GeometryType::CAPSULE:
            shape.type = core::ShapeType::Capsule;
            shape.radius = geometry.CapsuleShape()->Radius();
            shape.length = geometry.CapsuleShape()->Length();
            checkLengths(at, what, "capsule radius and length", shape.radius, shape.length);
            break;
        case sdf::GeometryType::MESH:
            shape = readMesh(*geometry.MeshShape(), at, what);
            break;
        default:
            fail(at, what + " has a geometry Frontier does not support (supported: box, sphere, cylinder, "
                            "capsule, mesh, plane)");
        }
        return shape;
    }

    void checkLengths(const sdf::ElementPtr& at, const std::string& what, const std::string& quantity,
                      double a, double b) const
    {
        if (!(core::isLength(a) && core::isLength(b)))
        {
            fail(at, quantity + " of " + what + ": " + formatNumber(a) +
                         (quantity.find(" and ") != std::string::npos ? " and " + formatNumber(b) : "") +
                         "; expected each " + core::cLengthRange);
        }
    }

    core::Shape readMesh(const sdf::Mesh& mesh, const sdf::ElementPtr& at, const std::string& what)
    {
        const core::Vec3 scale = toVec(mesh.Scale());
        if (!scale.allFinite() || (scale.array() == 0.0).any())
        {
            fail(at, "the mesh <scale> of " + what + " is (" + formatVector(scale) +
                         "); expected three nonzero numbers (a negative one mirrors the mesh)");
        }
        if (!mesh.Submesh().empty())
        {
            fail(at, what + " names <submesh> '" + mesh.Submesh() +
                         "'; Frontier reads whole mesh files only (leave <submesh> out)");
        }
        const ResolvedUri resolved = mPackages.resolve(mesh.Uri(), fileOf(at));
        if (!resolved.notFound.empty())
        {
            fail(at, "mesh '" + mesh.Uri() + "' of " + what + ": " + resolved.notFound);
        }
        if (!resolved.note.empty() && mNotedPackages.insert(resolved.note).second)
        {
            warn(at, resolved.note);
        }
        core::Shape shape;
        try
        {
            shape = loadMeshFile(resolved.path, scale);
        }
        catch (const InputError& e)
        {
            if (e.line() > 0)
            {
                throw; // the error is inside the mesh file: keep its location
            }
            fail(at, "mesh '" + mesh.Uri() + "' of " + what + ": " + e.what());
        }
        if (!(core::shapeReach(shape) <= core::cMaxDistance))
        {
            fail(at, "mesh '" + mesh.Uri() + "' of " + what + " reaches " +
                         formatNumber(core::shapeReach(shape)) + " m from its origin; expected " +
                         core::cLengthRange);
        }
        return shape;
    }

    // <surface><friction><ode><mu> of the collision: the body's friction (its first collision that
    // gives one; another value later is a warning).
    void takeFriction(const LinkPlace& place, const sdf::Collision& collision, core::Body& body)
    {
        sdf::ElementPtr e = collision.Element();
        for (const char* name : {"surface", "friction", "ode", "mu"})
        {
            if (!e || !e->HasElement(name))
            {
                return;
            }
            e = e->GetElement(name);
        }
        if (!e->GetExplicitlySetInFile())
        {
            return;
        }
        const double mu = e->Get<double>();
        if (!core::isFriction(mu))
        {
            fail(e, "<mu> of collision '" + collision.Name() + "' of link '" + place.name + "' is " +
                        formatNumber(mu) + "; expected a friction in [0, 1e6]");
        }
        if (!body.friction)
        {
            body.friction = mu;
        }
        else if (*body.friction != mu)
        {
            warn(e, "body '" + body.name + "' has friction " + formatNumber(*body.friction) +
                        " from an earlier collision; the " + formatNumber(mu) + " of collision '" +
                        collision.Name() + "' is not used");
        }
    }

    int bodyOfLink(int link) const
    {
        return link == core::cWorld
                   ? core::cWorld
                   : mGroups[static_cast<std::size_t>(mLinks[static_cast<std::size_t>(link)].group)].body;
    }

    void addJoint(const ModelPlace& m, const sdf::Joint& joint)
    {
        const sdf::ElementPtr element = joint.Element();
        const std::string name = m.scope + joint.Name();
        const sdf::JointType type = joint.Type();
        if (type == sdf::JointType::FIXED || m.isStatic)
        {
            return; // welded (weld()), or a joint of a static model: nothing moves
        }
        core::Joint j;
        j.name = name;
        j.type = jointType(type, name, element);
        const std::string reason = invalidNameReason(name);
        if (!reason.empty())
        {
            fail(element, "invalid joint name '" + name + "': " + reason);
        }
        if (!setJointBodies(m, joint, element, j))
        {
            return;
        }
        ignition::math::Pose3d pose;
        failOn(joint.SemanticPose().Resolve(pose, "__model__"), element, "the pose of joint '" + name + "'");
        const Pose jointWorld = m.world * toPose(pose);
        const core::Vec3 anchor = jointWorld.translation();
        const std::array<core::Vec3, 2> axes = readAxes(m, joint, type, element, j);
        if (type == sdf::JointType::UNIVERSAL)
        {
            setUniversalFrames(j, anchor, axes, name, element);
        }
        else
        {
            core::setJointFrames(mOut, j, anchor, axes[0]);
        }
        mOut.joints.push_back(std::move(j));
    }

    // Frontier's joint type for a moving SDF joint type.
    core::JointType jointType(sdf::JointType type, const std::string& name,
                              const sdf::ElementPtr& element) const
    {
        switch (type)
        {
        case sdf::JointType::REVOLUTE:
        case sdf::JointType::CONTINUOUS:
            return core::JointType::Revolute;
        case sdf::JointType::PRISMATIC:
            return core::JointType::Prismatic;
        case sdf::JointType::BALL:
            return core::JointType::Ball;
        case sdf::JointType::UNIVERSAL:
            return core::JointType::Angle;
        default:
        {
            const std::string word = element ? element->Get<std::string>("type") : "unknown";
            fail(element,
                 "joint '" + name + "' has type " + word +
                     ", which Frontier does not support (supported: revolute, continuous, prismatic, "
                     "ball, universal, fixed)");
        }
        }
    }

    // The joint's parent and child bodies; false (after a warning) for a joint between two static links.
    bool setJointBodies(const ModelPlace& m, const sdf::Joint& joint, const sdf::ElementPtr& element,
                        core::Joint& j)
    {
        const std::string& name = j.name;
        j.parent = bodyOfLink(linkOf(m, joint, true));
        j.child = bodyOfLink(linkOf(m, joint, false));
        const bool parentStatic =
            j.parent == core::cWorld || mOut.bodies[static_cast<std::size_t>(j.parent)].isStatic;
        if (mOut.bodies[static_cast<std::size_t>(j.child)].isStatic)
        {
            if (parentStatic)
            {
                warn(element,
                     "joint '" + name + "' joins two static links (fixed to the world); it is ignored");
                return false;
            }
            fail(element, "joint '" + name +
                              "' has a static child link (fixed to the world); expected a moving "
                              "child (swap <parent> and <child>)");
        }
        if (j.parent == j.child)
        {
            fail(element, "joint '" + name + "' joins links that fixed joints weld into one body");
        }
        return true;
    }

    // The joint's axes in the world (none for a ball, two for a universal joint), each axis's
    // settings into the joint.
    std::array<core::Vec3, 2> readAxes(const ModelPlace& m, const sdf::Joint& joint, sdf::JointType type,
                                       const sdf::ElementPtr& element, core::Joint& j)
    {
        const std::string& name = j.name;
        std::array<core::Vec3, 2> axes{core::Vec3::UnitZ(), core::Vec3::UnitX()};
        const int axisCount = type == sdf::JointType::BALL ? 0 : type == sdf::JointType::UNIVERSAL ? 2 : 1;
        for (int k = 0; k < axisCount; ++k)
        {
            const sdf::JointAxis* axis = joint.Axis(static_cast<unsigned>(k));
            if (axis == nullptr)
            {
                fail(element, "joint '" + name + "' needs an <axis" + (k == 0 ? "" : "2") + ">");
            }
            ignition::math::Vector3d xyz;
            failOn(axis->ResolveXyz(xyz, "__model__"), axis->Element(), "the axis of joint '" + name + "'");
            const core::Vec3 local = toVec(xyz);
            if (!(local.allFinite() && local.norm() > 1e-12))
            {
                fail(axis->Element(), "joint '" + name + "' has a zero <xyz>; expected a non-zero direction");
            }
            axes[static_cast<std::size_t>(k)] = (m.world.linear() * local.normalized()).normalized();
            readAxisSettings(name, type, k, *axis, j);
        }
        return axes;
    }

    // Limits, effort, damping and friction of axis k (the first axis only for all but universal).
    void readAxisSettings(const std::string& name, sdf::JointType type, int k, const sdf::JointAxis& axis,
                          core::Joint& j)
    {
        const sdf::ElementPtr element = axis.Element();
        const double lower = axis.Lower();
        const double upper = axis.Upper();
        const bool limited =
            type != sdf::JointType::CONTINUOUS && std::abs(lower) < 1e16 && std::abs(upper) < 1e16;
        if (limited && type == sdf::JointType::UNIVERSAL)
        {
            warn(element,
                 "joint '" + name + "': limits of a universal joint are not supported and are ignored");
        }
        else if (limited)
        {
            if (!(lower <= upper))
            {
                fail(element, "joint '" + name + "' has limits lower=" + formatNumber(lower) +
                                  " > upper=" + formatNumber(upper) + "; expected lower <= upper");
            }
            if (lower > 0.0 || upper < 0.0)
            {
                warn(element, "joint '" + name + "': its zero position lies outside its limits [" +
                                  formatNumber(lower) + ", " + formatNumber(upper) +
                                  "]; it starts at zero and its limit pushes it in");
            }
            j.limits = std::array<double, 2>{lower, upper};
        }
        if (k == 0 && std::isfinite(axis.Effort()) && axis.Effort() > 0.0)
        {
            j.effortLimit = axis.Effort();
        }
        const double damping = axis.Damping();
        const double friction = axis.Friction();
        if (!(std::isfinite(damping) && damping >= 0.0 && std::isfinite(friction) && friction >= 0.0))
        {
            fail(element, "joint '" + name + "' has <dynamics> damping " + formatNumber(damping) +
                              " and friction " + formatNumber(friction) + "; expected non-negative numbers");
        }
        if (j.type == core::JointType::Angle && (damping > 0.0 || friction > 0.0))
        {
            warn(element, "joint '" + name +
                              "': damping and friction of a universal joint are not supported "
                              "and are ignored");
        }
        else if (k == 0)
        {
            j.damping = damping;
            j.friction = friction;
        }
        if (axis.SpringStiffness() != 0.0)
        {
            warn(element, "joint '" + name + "': <spring_stiffness> is not supported and is ignored");
        }
    }

    // core's angle joint (docs/method.md §2): a1 = axis 1 fixed in the parent, b2 = axis 2 fixed
    // in the child, held perpendicular; d_k = a1 x b2.
    void setUniversalFrames(core::Joint& j, const core::Vec3& anchor, const std::array<core::Vec3, 2>& axes,
                            const std::string& name, const sdf::ElementPtr& element)
    {
        if (std::abs(axes[0].dot(axes[1])) > 1e-6)
        {
            fail(element, "universal joint '" + name + "' has axes at " +
                              formatNumber(std::acos(std::clamp(axes[0].dot(axes[1]), -1.0, 1.0)) * 180.0 /
                                           std::numbers::pi) +
                              " degrees; expected perpendicular <axis> and <axis2>");
        }
        core::setJointFrames(mOut, j, anchor, axes[0].cross(axes[1]));
        const core::Quat parent = j.parent == core::cWorld
                                      ? core::Quat::Identity()
                                      : mOut.bodies[static_cast<std::size_t>(j.parent)].orientation_WB;
        const core::Quat child = mOut.bodies[static_cast<std::size_t>(j.child)].orientation_WB;
        j.perpParent1 = parent.conjugate() * axes[0];
        j.perpParent2 = parent.conjugate() * axes[1];
        j.perpChild1 = child.conjugate() * axes[0];
        j.angleChildAxis = child.conjugate() * axes[1];
    }

    // One robot (and report) per top-level model, its bodies contiguous.
    void fillRobots()
    {
        // Bodies were made group by group in link order, so a top-level model's bodies may
        // interleave with nested ones of another only if models nest across each other: they do not.
        for (std::size_t k = 0; k < mModels.size(); ++k)
        {
            const ModelPlace& m = mModels[k];
            if (m.top != static_cast<int>(k))
            {
                continue;
            }
            const auto first = std::find(mBodyModel.begin(), mBodyModel.end(), static_cast<int>(k));
            const auto last =
                std::find_if(first, mBodyModel.end(), [&](int b) { return b != static_cast<int>(k); });
            RobotReport report;
            report.name = m.model->Name();
            report.prefix = m.scope;
            report.file = fileOf(m.model->Element());
            for (const LinkPlace& l : mLinks)
            {
                report.links += mModels[static_cast<std::size_t>(l.model)].top == static_cast<int>(k) ? 1 : 0;
            }
            report.welded = mWelded[static_cast<int>(k)];
            report.repaired = mRepaired[static_cast<int>(k)];
            report.placement = m.isStatic ? "static, where the file puts it" : "where the file puts it";
            if (first != mBodyModel.end())
            {
                mOut.robots.push_back({m.model->Name(), report.file,
                                       static_cast<int>(first - mBodyModel.begin()),
                                       static_cast<int>(last - first),
                                       mOptions.selfCollision.value_or(m.model->SelfCollide())});
            }
            mRobots.push_back(std::move(report));
        }
    }

    std::string mFile;
    const UrdfOptions& mOptions;
    const PackagePaths& mPackages;
    bool mIsWorld = false;
    std::vector<ModelPlace> mModels;
    std::vector<LinkPlace> mLinks;
    std::map<std::string, int> mLinkIndex; // scoped name -> index into mLinks
    std::vector<LinkGroup> mGroups;
    std::vector<int> mBodyModel; // body -> its top-level model
    std::map<int, std::vector<std::pair<std::string, std::string>>> mWelded;
    std::map<int, std::vector<std::string>> mRepaired;
    std::set<std::string> mNotedPackages;
    std::vector<std::string> mWarnings;
    std::vector<RobotReport> mRobots;
    core::Model mOut;
};

// An <include> as the file's text has it: the library drops an include it cannot resolve, and
// with it the pose of a standard model taken as Gazebo defines it (addStandardModels).
struct IncludeText
{
    std::string uri;
    std::string name;
    std::string pose;
    TextPosition at;
};

// A <joint type> SDF knows (libsdformat refuses another without saying where).
void checkJointType(const std::string& path, const std::string& text, const XmlTag& tag)
{
    static const std::set<std::string> known = {"revolute", "continuous", "prismatic", "ball",   "universal",
                                                "fixed",    "revolute2",  "screw",     "gearbox"};
    const std::optional<std::string> type = xmlAttribute(tag.attributes, "type");
    if (type && !known.contains(*type))
    {
        const TextPosition at = positionOf(text, tag.offset);
        throw InputError(path, at.line, at.column,
                         "joint '" + xmlAttribute(tag.attributes, "name").value_or("") +
                             "' has an unknown type '" + *type +
                             "'; expected revolute, continuous, prismatic, ball, universal or fixed (SDF's "
                             "revolute2, screw and gearbox Frontier does not support)");
    }
}

// The file's <include>s, and the depth check of every XML input (TinyXML recurses per level).
std::vector<IncludeText> scanIncludes(const std::string& path, const std::string& text)
{
    XmlDepthCheck depth(path, text, "an SDF file needs a few");
    std::vector<IncludeText> includes;
    std::optional<IncludeText> open;
    std::size_t valueStart = 0;
    scanXmlTags(path, text, "SDF file", "an <sdf> element",
                [&](const XmlTag& tag)
                {
                    depth.visit(tag);
                    if (tag.name == "joint" && !tag.end)
                    {
                        checkJointType(path, text, tag);
                    }
                    if (tag.name == "include" && !tag.empty)
                    {
                        if (tag.end && open)
                        {
                            includes.push_back(std::move(*open));
                            open.reset();
                        }
                        else if (!tag.end)
                        {
                            open = IncludeText{};
                            open->at = positionOf(text, tag.offset);
                        }
                        return;
                    }
                    if (!open || tag.empty ||
                        !(tag.name == "uri" || tag.name == "name" || tag.name == "pose"))
                    {
                        return;
                    }
                    if (!tag.end)
                    {
                        valueStart = text.find('>', tag.offset) + 1;
                        return;
                    }
                    std::string value = text.substr(valueStart, tag.offset - valueStart);
                    const std::size_t first = value.find_first_not_of(" \t\r\n");
                    const std::size_t last = value.find_last_not_of(" \t\r\n");
                    value = first == std::string::npos ? "" : value.substr(first, last - first + 1);
                    (tag.name == "uri" ? open->uri : tag.name == "name" ? open->name : open->pose) = value;
                });
    return includes;
}

// The world's <include>s of model://sun and model://ground_plane that the model path lacks, taken
// as Gazebo defines them: the sun is a light (nothing for the physics), the ground a static plane
// (normal +z in the include's frame, friction 100).
void addStandardModels(const std::vector<IncludeText>& includes, const std::set<std::string>& missing,
                       core::Model& model, std::vector<std::string>& warnings, const std::string& file)
{
    for (const IncludeText& include : includes)
    {
        if (!missing.contains(include.uri))
        {
            continue;
        }
        if (include.uri == cSunUri)
        {
            warnings.push_back(diagnostic(file, include.at, "warning",
                                          "model://sun is not on the model path; it is Gazebo's sun, a "
                                          "light, which has no part in the physics"));
            continue;
        }
        std::istringstream numbers(include.pose);
        std::array<double, 6> xyzrpy{};
        for (double& v : xyzrpy)
        {
            numbers >> v;
        }
        std::string rest;
        if (!include.pose.empty() && (numbers.fail() || (numbers >> rest, !rest.empty())))
        {
            throw InputError(file, include.at.line, include.at.column,
                             "the <pose> of the <include> of model://ground_plane is '" + include.pose +
                                 "'; expected six numbers x y z roll pitch yaw");
        }
        const core::Quat rotation = core::Quat(Eigen::AngleAxisd(xyzrpy[5], core::Vec3::UnitZ()) *
                                               Eigen::AngleAxisd(xyzrpy[4], core::Vec3::UnitY()) *
                                               Eigen::AngleAxisd(xyzrpy[3], core::Vec3::UnitX()));
        const core::Vec3 origin(xyzrpy[0], xyzrpy[1], xyzrpy[2]);
        core::Body ground;
        ground.name = include.name.empty() ? "ground_plane" : include.name;
        ground.isStatic = true;
        ground.friction = cGroundPlaneFriction;
        core::Shape plane;
        plane.type = core::ShapeType::Plane;
        plane.normal = rotation * core::Vec3::UnitZ();
        plane.offset = plane.normal.dot(origin);
        ground.shapes.push_back(plane);
        model.bodies.push_back(std::move(ground));
        warnings.push_back(diagnostic(file, include.at, "warning",
                                      "model://ground_plane is not on the model path; using Gazebo's "
                                      "ground_plane: a static plane through (" +
                                          formatVector(origin) + ") m with normal (" +
                                          formatVector(plane.normal) + "), friction 100"));
    }
}

// The text as XML: libsdformat reports bad XML as "Unable to read file" without a place, TinyXML
// has it.
void checkXml(const std::string& path, const std::string& text)
{
    TiXmlDocument document;
    document.Parse(text.c_str());
    if (document.Error())
    {
        throw InputError(path, std::max(1, document.ErrorRow()), std::max(1, document.ErrorCol()),
                         std::string("invalid XML: ") + document.ErrorDesc());
    }
}

// libsdformat's lookup of model:// URIs through the package paths, and what it did not find.
struct ModelLookup
{
    const PackagePaths& packages;
    const std::string& path;
    std::set<std::string> missingStandard;       // model://sun, model://ground_plane not on the path
    std::map<std::string, std::string> notFound; // uri -> where it was looked for

    std::string find(const std::string& uri)
    {
        if (!uri.starts_with("model://"))
        {
            return {};
        }
        std::string name = uri.substr(8);
        while (!name.empty() && name.back() == '/')
        {
            name.pop_back();
        }
        const ResolvedUri found = packages.resolve("model://" + name + "/model.config", path);
        if (!found.path.empty() && found.note.empty())
        {
            return std::filesystem::path(found.path).parent_path().string();
        }
        if (uri == cSunUri || uri == cGroundPlaneUri)
        {
            missingStandard.insert(uri);
        }
        notFound[uri] =
            found.notFound.empty() ? "not found (only files beside the SDF file match)" : found.notFound;
        return {};
    }

    // libsdformat's errors as InputErrors; a standard model not on the path is none (added after).
    void throwErrors(const sdf::Errors& errors) const
    {
        for (const sdf::Error& error : errors)
        {
            const std::string file = error.FilePath().value_or(path);
            const int line = error.LineNumber().value_or(0);
            if (error.Code() == sdf::ErrorCode::URI_LOOKUP)
            {
                const auto it =
                    std::find_if(notFound.begin(), notFound.end(),
                                 [&](const auto& entry)
                                 { return error.Message().find(entry.first) != std::string::npos; });
                if (it != notFound.end() && missingStandard.contains(it->first))
                {
                    continue;
                }
                throw InputError(
                    file, line, 0,
                    "<include> " +
                        (it == notFound.end() ? error.Message() : "'" + it->first + "': " + it->second) +
                        "; add its folder with --package-path or GAZEBO_MODEL_PATH");
            }
            throw InputError(file, line, 0, "invalid SDF: " + error.Message());
        }
    }
};

bool hasPlane(const core::Model& model)
{
    bool plane = false;
    for (const core::Body& body : model.bodies)
    {
        for (const core::Shape& shape : body.shapes)
        {
            plane = plane || shape.type == core::ShapeType::Plane;
        }
    }
    return plane;
}

// A world (or a file with its own ground) stays where it is; a robot alone is put on a floor.
void placeScene(core::Model& model, bool isWorld, const UrdfOptions& options, const std::string& path,
                std::vector<RobotReport>& robots, std::vector<std::string>& warnings)
{
    if (isWorld || hasPlane(model))
    {
        if (options.dropHeight)
        {
            throw InputError(
                path, 0, 0,
                "--drop-height places a robot alone on a floor; this file is a world (or has its "
                "own ground plane) and places its models itself");
        }
        checkStartingState(model, path);
        return;
    }
    if (model.name.empty() && !robots.empty())
    {
        model.name = robots.front().name;
    }
    if (robots.empty())
    {
        throw InputError(path, 0, 0, "the file has no <model>");
    }
    placeOnFloor(model, path, options.dropHeight,
                 "held by the world as the SDF file says (static, or a joint "
                 "to 'world')",
                 "SDF file", robots.front(), warnings);
}

// The file through libsdformat (the caller holds its lock), its messages turned into InputErrors.
// Gives back the standard models it found missing.
std::set<std::string> loadRoot(sdf::Root& root, const std::string& path, const PackagePaths& packages)
{
    sdf::Console::Instance()->SetQuiet(true);
    ModelLookup lookup{packages, path, {}, {}};
    sdf::ParserConfig config;
    config.SetFindCallback([&lookup](const std::string& uri) -> std::string { return lookup.find(uri); });
    lookup.throwErrors(root.Load(path, config));
    return lookup.missingStandard;
}

} // namespace

core::Model loadSdfScene(const std::string& path, const UrdfOptions& options, LoadReport* report)
{
    if (options.fixedBase || options.freeBase || !options.jointPositions.empty())
    {
        throw InputError(
            path, 0, 0,
            "--fixed-base, --free-base and --joint-position place a bare .urdf; an SDF file places "
            "its models itself (<static>, a fixed joint to 'world', <pose>)");
    }
    const std::string text = readTextFile(path, "SDF file");
    const std::vector<IncludeText> includes = scanIncludes(path, text);
    checkXml(path, text);
    const PackagePaths packages(options.packagePaths);
    // The library's console and parse are process-global; its messages become InputErrors here.
    static std::mutex parseMutex;
    const std::lock_guard<std::mutex> lock(parseMutex);
    sdf::Root root;
    const std::set<std::string> missingStandard = loadRoot(root, path, packages);
    SdfConverter converter(path, options, packages);
    core::Model model = converter.convert(root);
    model.sourceFile = path;
    std::vector<std::string>& warnings = converter.warnings();
    std::vector<RobotReport>& robots = converter.robots();
    for (const RobotReport& robot : robots)
    {
        if (robot.file != path)
        {
            checkInputFile(robot.file, "included SDF file"); // recorded among the inputs
        }
    }
    addStandardModels(includes, missingStandard, model, warnings, path);
    if (model.bodies.empty())
    {
        throw InputError(path, 0, 0,
                         "the file has no links (no model, or models without links); expected "
                         "something to simulate");
    }
    if (options.hold)
    {
        addHoldServos(model, 0, static_cast<int>(model.joints.size()));
    }
    placeScene(model, converter.isWorld(), options, path, robots, warnings);
    if (report)
    {
        for (RobotReport& robot : robots)
        {
            report->robots.push_back(std::move(robot));
        }
        report->warnings.insert(report->warnings.end(), warnings.begin(), warnings.end());
    }
    return model;
}

#endif

} // namespace frontier::io::detail
