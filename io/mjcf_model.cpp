// io/mjcf_model.cpp: MuJoCo's compiled model as Frontier bodies, joints and actuators
// (io/mjcf_model.h; what maps to what: docs/mjcf.md).
#include "io/mjcf_model.h"

#include "io/file_util.h"
#include "io/hold_servos.h"
#include "io/mass_properties.h"
#include "io/mjcf_compile.h"
#include "io/mujoco_util.h"
#include "io/suggest.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <mujoco/mujoco.h>
#include <numbers>
#include <optional>
#include <set>

namespace frontier::io::detail
{

namespace
{

// The surface of an ellipsoid of semi-axes r (m) as a closed polyhedron: cEllipsoidRings rings of
// cEllipsoidSegments vertices between two poles, every vertex on the surface (docs/mjcf.md).
constexpr int cEllipsoidRings = 11;
constexpr int cEllipsoidSegments = 24;
core::Shape ellipsoidMesh(const core::Vec3& r)
{
    core::Shape mesh;
    mesh.type = core::ShapeType::Mesh;
    mesh.meshFile = "ellipsoid";
    mesh.vertices.push_back(core::Vec3(0.0, 0.0, r.z()));
    for (int ring = 1; ring <= cEllipsoidRings; ++ring)
    {
        const double polar = std::numbers::pi * ring / (cEllipsoidRings + 1);
        for (int s = 0; s < cEllipsoidSegments; ++s)
        {
            const double azimuth = 2.0 * std::numbers::pi * s / cEllipsoidSegments;
            mesh.vertices.push_back(core::Vec3(r.x() * std::sin(polar) * std::cos(azimuth),
                                               r.y() * std::sin(polar) * std::sin(azimuth),
                                               r.z() * std::cos(polar)));
        }
    }
    const int south = static_cast<int>(mesh.vertices.size());
    mesh.vertices.push_back(core::Vec3(0.0, 0.0, -r.z()));
    const auto at = [](int ring, int s)
    { return 1 + (ring - 1) * cEllipsoidSegments + s % cEllipsoidSegments; };
    for (int s = 0; s < cEllipsoidSegments; ++s)
    {
        mesh.triangles.push_back({0, at(1, s), at(1, s + 1)});
        for (int ring = 1; ring < cEllipsoidRings; ++ring)
        {
            mesh.triangles.push_back({at(ring, s), at(ring + 1, s), at(ring + 1, s + 1)});
            mesh.triangles.push_back({at(ring, s), at(ring + 1, s + 1), at(ring, s + 1)});
        }
        mesh.triangles.push_back({at(cEllipsoidRings, s), south, at(cEllipsoidRings, s + 1)});
    }
    return mesh;
}

// One MuJoCo model turned into a fragment, step by step.
class MjcfTranslation
{
  public:
    MjcfTranslation(const std::string& path, const MjcfPlacement& placement)
        : mPath(path), mPlacement(placement), mCompiled(compileMjcf(path)), m(mCompiled.model.get()),
          mData(mj_makeData(m))
    {
        mFragment.warnings = mCompiled.warnings;
    }

    ModelFragment run()
    {
        startPose();
        addBodies();
        addShapes();
        addJoints();
        addActuators();
        addJointSprings();
        filterCollisions();
        warnUnsupported();
        dropEmptyWorld();
        if (mFragment.model.bodies.empty())
        {
            throw InputError(mPath, 0, 0,
                             "the model has no bodies: its <worldbody> holds nothing to simulate");
        }
        mFragment.model.name = mModelName;
        mFragment.model.contact.frictionMix = core::FrictionMix::Larger; // MuJoCo's rule for a pair
        mFragment.model.simulation.dt = m->opt.timestep;                 // s
        mFragment.model.simulation.gravity = mPlacement.orientation * mujocoVec3(m->opt.gravity); // m/s^2
        mFragment.report.name = mModelName;
        mFragment.report.prefix = mPlacement.prefix;
        mFragment.report.file = mPath;
        mFragment.report.links = m->nbody - 1;
        return std::move(mFragment);
    }

  private:
    std::string name(mjtObj type, int id, const std::string& fallback) const
    {
        const char* found = mj_id2name(m, type, id);
        return found != nullptr && *found != '\0' ? std::string(found) : fallback;
    }
    std::string bodyName(int b) const
    {
        return name(mjOBJ_BODY, b, b == 0 ? "world" : "body" + std::to_string(b));
    }
    std::string jointName(int j) const
    {
        return name(mjOBJ_JOINT, j, bodyName(m->jnt_bodyid[j]) + "_joint" + std::to_string(j));
    }
    // Where MuJoCo's world frame goes in the scene.
    core::Vec3 toScene(const core::Vec3& p) const { return mPlacement.orientation * p + mPlacement.position; }
    core::Mat3 toScene(const core::Mat3& r) const { return mPlacement.orientation.toRotationMatrix() * r; }

    void warn(const std::string& message, int line = 0)
    {
        mFragment.warnings.push_back(diagnostic(mPath, {line, 0}, "warning", message));
    }

    // A <key> by its name, or by its index (0 first) among the file's keys: MJCF keys often have none.
    int keyframeIndex(const std::string& wanted) const
    {
        const int key = mj_name2id(m, mjOBJ_KEY, wanted.c_str());
        if (key >= 0)
        {
            return key;
        }
        if (const std::optional<long long> index = parseWholeNumber(wanted, 0, m->nkey - 1))
        {
            return static_cast<int>(*index);
        }
        std::vector<std::string> names;
        for (int k = 0; k < m->nkey; ++k)
        {
            names.push_back(name(mjOBJ_KEY, k, "#" + std::to_string(k)));
        }
        throw InputError(mPath, 0, 0,
                         "no keyframe " + quotedName(wanted) + " in the file: " +
                             (m->nkey == 0
                                  ? std::string("it has no <key>")
                                  : "give a <key>'s name or its index from 0 to " +
                                        std::to_string(m->nkey - 1) + suggestionSuffix(wanted, names, true)));
    }

    // qpos, qvel and ctrl of the start: the keyframe's, or MuJoCo's reference pose at rest.
    void startPose()
    {
        // MuJoCo names a <mujoco> without model="..." "MuJoCo Model": it is named after its file, as an
        // unnamed URDF robot is.
        const std::string modelName = m->names != nullptr ? m->names : "";
        mModelName = modelName.empty() || modelName == "MuJoCo Model"
                         ? std::filesystem::path(mPath).stem().string()
                         : modelName;
        mj_resetData(m, mData.get());
        if (mPlacement.keyframe)
        {
            mj_resetDataKeyframe(m, mData.get(), keyframeIndex(*mPlacement.keyframe));
        }
        mj_forward(m, mData.get());
    }

    // The Frontier body holding MuJoCo body b: its weld group's, or the static body for the world's.
    int bodyOf(int b) const { return mBodyOfWeld.at(m->body_weldid[b]); }
    // A joint's parent: cWorld for the world's weld group.
    int jointParentOf(int b) const { return m->body_weldid[b] == 0 ? core::cWorld : bodyOf(b); }

    // Mass, centre of mass and inertia of a weld group (MuJoCo bodies with no joint between them),
    // in the scene's world frame.
    CompositeMass groupInertial(int weld) const
    {
        std::vector<MassPart> parts;
        for (int b = 1; b < m->nbody; ++b)
        {
            if (m->body_weldid[b] == weld)
            {
                const core::Mat3 r = toScene(mujocoMat3(mData->ximat + 9 * b));
                parts.push_back({m->body_mass[b], toScene(mujocoVec3(mData->xipos + 3 * b)),
                                 r * mujocoVec3(m->body_inertia + 3 * b).asDiagonal() * r.transpose()});
            }
        }
        return combineMassParts(parts);
    }

    // The world's weld group (one static body, made when something needs it) and one moving body per
    // other weld group, preceded by the frames of its joints (io/mjcf_model.h).
    void addBodies()
    {
        addWorldBody();
        for (int b = 1; b < m->nbody; ++b)
        {
            if (m->body_mocapid[b] >= 0)
            {
                warn("body " + quotedName(bodyName(b)) +
                     " is a mocap body: it is held where it starts (nothing moves it in Frontier)");
            }
            if (m->body_weldid[b] != b)
            {
                const int group = m->body_weldid[b];
                mFragment.report.welded.emplace_back(bodyName(b), mPlacement.prefix + bodyName(group));
                continue;
            }
            addMovingBody(b);
        }
        addArmature();
        setVelocities();
    }

    // The static body of the world's weld group, at the placement's pose.
    void addWorldBody()
    {
        core::Body world;
        world.name = mPlacement.prefix + bodyName(0);
        world.isStatic = true;
        world.position_W = mPlacement.position;
        world.orientation_WB = mPlacement.orientation;
        mBodyOfWeld[0] = 0;
        mFragment.model.bodies.push_back(world);
    }

    // The mass of weld group b; a massless one carries its subtree, as a frame does.
    CompositeMass movingGroupMass(int b)
    {
        CompositeMass group = groupInertial(b);
        if (group.mass <= 0.0)
        {
            const double mass = std::max(cFrameMassFraction * m->body_subtreemass[b], 1e-9); // kg
            warn("body " + quotedName(bodyName(b)) + " has no mass: given " + formatNumber(mass) +
                 " kg, a frame's share of what it carries");
            group.mass = mass;
            group.centre = toScene(mujocoVec3(mData->xpos + 3 * b));
            group.inertia = mass * 1e-4 * core::Mat3::Identity(); // a 1 cm radius of gyration
        }
        return group;
    }

    // The moving body of weld group b, preceded by the frames of its joints but the last.
    void addMovingBody(int b)
    {
        core::Model& model = mFragment.model;
        const CompositeMass group = movingGroupMass(b);
        const core::Mat3 rotation = toScene(mujocoMat3(mData->ximat + 9 * b));
        core::Body body;
        body.name = mPlacement.prefix + bodyName(b);
        body.mass = group.mass;
        body.inertia_B = rotation.transpose() * group.inertia * rotation;
        body.position_W = group.centre;
        body.orientation_WB = core::Quat(rotation).normalized();
        // The frames take their shares of the body's mass and inertia, so that the body and its
        // frames together are the MuJoCo body at the start.
        const int frameCount = std::max(m->body_jntnum[b] - 1, 0);
        std::vector<int> frames;
        for (int k = 0; k < frameCount; ++k)
        {
            core::Body frame = body;
            frame.name = body.name + ":" + jointName(m->body_jntadr[b] + k);
            frame.mass = cFrameMassFraction * group.mass;
            frame.inertia_B = cFrameMassFraction * body.inertia_B;
            frames.push_back(static_cast<int>(model.bodies.size()));
            model.bodies.push_back(std::move(frame));
        }
        body.mass *= 1.0 - frameCount * cFrameMassFraction;
        body.inertia_B *= 1.0 - frameCount * cFrameMassFraction;
        mFramesOf[b] = frames;
        mBodyOfWeld[b] = static_cast<int>(model.bodies.size());
        model.bodies.push_back(std::move(body));
    }

    // The Frontier body MuJoCo joint j moves: the next frame of its body's chain, or the body.
    int movedBy(int j) const
    {
        const int b = m->jnt_bodyid[j];
        const int k = j - m->body_jntadr[b];
        const std::vector<int>& frames = mFramesOf.at(b);
        return k < static_cast<int>(frames.size()) ? frames[k] : mBodyOfWeld.at(b);
    }

    // A joint's armature (rotor inertia, kg m^2 or kg) as inertia of the body it moves: for a hinge
    // a thin disc spinning on the axis (armature about the axis, half of it about every axis across
    // it, so that the body's inertia stays one a rigid body can have: added about the axis alone it
    // breaks the triangle inequality of a light link, whose rotation then blows up), about every
    // axis for a ball, as mass for a slide that moves a frame (docs/mjcf.md says how this differs
    // from MuJoCo's joint-space term).
    void addArmature()
    {
        for (int j = 0; j < m->njnt; ++j)
        {
            const double armature = m->dof_armature[m->jnt_dofadr[j]];
            if (armature == 0.0 || m->jnt_type[j] == mjJNT_FREE)
            {
                continue;
            }
            core::Body& body = mFragment.model.bodies[movedBy(j)];
            const core::Vec3 axis_B =
                body.orientation_WB.conjugate() * (mPlacement.orientation * mujocoVec3(mData->xaxis + 3 * j));
            if (m->jnt_type[j] == mjJNT_HINGE)
            {
                body.inertia_B += 0.5 * armature * (core::Mat3::Identity() + axis_B * axis_B.transpose());
            }
            else if (m->jnt_type[j] == mjJNT_BALL)
            {
                body.inertia_B += armature * core::Mat3::Identity();
            }
            else if (movedBy(j) != mBodyOfWeld.at(m->jnt_bodyid[j]))
            {
                body.mass += armature;
            }
            else
            {
                warn("joint " + quotedName(jointName(j)) +
                     ": the armature of a slide joint that moves its body "
                     "directly is ignored (Frontier bodies have one mass in every direction)");
            }
        }
    }

    // The motion of the body MuJoCo body b is, at a point (scene frame): its centre of mass.
    void bodyMotion(int b, core::Body& body) const
    {
        mjtNum motion[6]; // angular, then linear at the body's inertial frame origin (world axes)
        mj_objectVelocity(m, mData.get(), mjOBJ_BODY, b, motion, 0);
        const core::Vec3 omega = mPlacement.orientation * mujocoVec3(motion);
        const core::Vec3 v = mPlacement.orientation * mujocoVec3(motion + 3);
        body.angularVelocity_W = omega;
        body.velocity_W = v + omega.cross(body.position_W - toScene(mujocoVec3(mData->xipos + 3 * b)));
    }

    // Starting velocities from qvel (a keyframe's): a frame moves as its body would with the joints
    // after it held still.
    void setVelocities()
    {
        bool moving = false;
        for (int i = 0; i < m->nv; ++i)
        {
            moving = moving || mData->qvel[i] != 0.0;
        }
        if (!moving)
        {
            return;
        }
        std::vector<mjtNum> qvel(mData->qvel, mData->qvel + m->nv);
        for (const auto& [b, frames] : mFramesOf)
        {
            bodyMotion(b, mFragment.model.bodies[mBodyOfWeld.at(b)]);
            for (std::size_t k = 0; k < frames.size(); ++k)
            {
                for (int j = m->body_jntadr[b] + static_cast<int>(k) + 1;
                     j < m->body_jntadr[b] + m->body_jntnum[b]; ++j)
                {
                    const int dofs = m->jnt_type[j] == mjJNT_BALL ? 3 : 1;
                    std::fill_n(mData->qvel + m->jnt_dofadr[j], dofs, 0.0);
                }
                mj_comVel(m, mData.get());
                bodyMotion(b, mFragment.model.bodies[frames[k]]);
                std::copy(qvel.begin(), qvel.end(), mData->qvel);
            }
            mj_comVel(m, mData.get());
        }
    }

    // "geom 'NAME'" (or "geom '#N'" for an unnamed one), as messages name it.
    std::string geomWhat(int g) const
    {
        return "geom " + quotedName(name(mjOBJ_GEOM, g, "#" + std::to_string(g)));
    }

    // Each geom as a shape of its body (docs/mjcf.md: planes, ellipsoids, meshes, visual-only geoms).
    void addShapes()
    {
        core::Model& model = mFragment.model;
        std::set<int> colored;
        for (int g = 0; g < m->ngeom; ++g)
        {
            const int index = bodyOf(m->geom_bodyid[g]);
            core::Body& body = model.bodies[index];
            const core::Vec3 p_W = toScene(mujocoVec3(mData->geom_xpos + 3 * g));
            const core::Mat3 r_W = toScene(mujocoMat3(mData->geom_xmat + 9 * g));
            std::optional<core::Shape> shape = geomShape(g, body, p_W, r_W);
            if (!shape)
            {
                continue;
            }
            shape->position_BS = body.orientation_WB.conjugate() * (p_W - body.position_W);
            shape->rotation_BS = (body.orientation_WB.conjugate() * core::Quat(r_W)).normalized();
            if (colored.insert(index).second)
            {
                const int material = m->geom_matid[g];
                const float* rgba = material >= 0 ? m->mat_rgba + 4 * material : m->geom_rgba + 4 * g;
                body.color = core::Vec3(rgba[0], rgba[1], rgba[2]);
            }
            const bool collides = m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0;
            if (!collides)
            {
                body.visuals.push_back(std::move(*shape));
                continue;
            }
            addCollider(g, index, body, std::move(*shape));
        }
    }

    // The geom's shape without its pose in the body (a plane's in the world: p_W, r_W); none, after
    // a warning, for a geom Frontier does not take.
    std::optional<core::Shape> geomShape(int g, const core::Body& body, const core::Vec3& p_W,
                                         const core::Mat3& r_W)
    {
        const mjtNum* size = m->geom_size + 3 * g;
        core::Shape shape;
        switch (m->geom_type[g])
        {
        case mjGEOM_PLANE:
            if (!body.isStatic)
            {
                warn(geomWhat(g) + ": a plane on a moving body is not supported; it is ignored");
                return std::nullopt;
            }
            shape.type = core::ShapeType::Plane;
            shape.normal = r_W.col(2);
            shape.offset = shape.normal.dot(p_W);
            break;
        case mjGEOM_SPHERE:
            shape.type = core::ShapeType::Sphere;
            shape.radius = size[0];
            break;
        case mjGEOM_CAPSULE:
            shape.type = core::ShapeType::Capsule;
            shape.radius = size[0];
            shape.length = 2.0 * size[1];
            break;
        case mjGEOM_CYLINDER:
            shape.type = core::ShapeType::Cylinder;
            shape.radius = size[0];
            shape.length = 2.0 * size[1];
            break;
        case mjGEOM_BOX:
            shape.type = core::ShapeType::Box;
            shape.size = 2.0 * mujocoVec3(size);
            break;
        case mjGEOM_ELLIPSOID:
            shape = ellipsoidMesh(mujocoVec3(size));
            break;
        case mjGEOM_MESH:
            shape = meshShape(m->geom_dataid[g]);
            break;
        default:
        {
            const auto where = mCompiled.unsupported.find("hfield");
            warn(geomWhat(g) + ": height fields are not supported; it is ignored (nothing collides with it)",
                 where == mCompiled.unsupported.end() ? 0 : where->second.line);
            return std::nullopt;
        }
        }
        return shape;
    }

    // A colliding geom's shape into its body (index), with its friction.
    void addCollider(int g, int index, core::Body& body, core::Shape shape)
    {
        // A body takes the largest friction of its geoms, a pair the larger of its two bodies'
        // (core::FrictionMix::Larger): MuJoCo's larger of the two geoms' where each body has one.
        const double friction = m->geom_condim[g] == 1 ? 0.0 : m->geom_friction[3 * g];
        body.friction = std::max(body.friction.value_or(0.0), friction);
        if (m->geom_condim[g] > 3 && !mWarnedCondim)
        {
            mWarnedCondim = true;
            warn(geomWhat(g) + ": condim " + std::to_string(m->geom_condim[g]) +
                 " asks for torsional or rolling friction, which Frontier does not model (sliding "
                 "friction only); the same holds for every such geom");
        }
        mColliders[index].push_back(g);
        body.shapes.push_back(std::move(shape));
    }

    core::Shape meshShape(int mesh) const
    {
        core::Shape shape;
        shape.type = core::ShapeType::Mesh;
        shape.meshFile = name(mjOBJ_MESH, mesh, "mesh" + std::to_string(mesh));
        const float* vertices = m->mesh_vert + 3 * m->mesh_vertadr[mesh];
        for (int v = 0; v < m->mesh_vertnum[mesh]; ++v)
        {
            shape.vertices.push_back(core::Vec3(vertices[3 * v], vertices[3 * v + 1], vertices[3 * v + 2]));
        }
        const int* faces = m->mesh_face + 3 * m->mesh_faceadr[mesh];
        for (int f = 0; f < m->mesh_facenum[mesh]; ++f)
        {
            shape.triangles.push_back({faces[3 * f], faces[3 * f + 1], faces[3 * f + 2]});
        }
        return shape;
    }

    void addJoints()
    {
        core::Model& model = mFragment.model;
        mJointIndex.assign(m->njnt, -1);
        for (int j = 0; j < m->njnt; ++j)
        {
            const int type = m->jnt_type[j];
            if (type == mjJNT_FREE)
            {
                continue;
            }
            const int b = m->jnt_bodyid[j];
            const int k = j - m->body_jntadr[b];
            core::Joint joint;
            joint.name = mPlacement.prefix + jointName(j);
            joint.type = type == mjJNT_BALL    ? core::JointType::Ball
                         : type == mjJNT_HINGE ? core::JointType::Revolute
                                               : core::JointType::Prismatic;
            joint.parent = k == 0 ? jointParentOf(m->body_parentid[b]) : mFramesOf.at(b)[k - 1];
            joint.child = movedBy(j);
            const int dof = m->jnt_dofadr[j];
            if (type == mjJNT_BALL)
            {
                if (m->dof_damping[dof] != 0.0 || m->dof_frictionloss[dof] != 0.0 ||
                    m->jnt_stiffness[j] != 0.0 || m->jnt_limited[j])
                {
                    warn("ball joint " + quotedName(jointName(j)) +
                         ": its damping, frictionloss, stiffness and range are not supported; ignored");
                }
            }
            else
            {
                const double q0 = mData->qpos[m->jnt_qposadr[j]]; // rad or m
                joint.initialPosition = q0;
                joint.damping = m->dof_damping[dof];
                joint.friction = m->dof_frictionloss[dof];
                if (m->jnt_limited[j])
                {
                    const mjtNum* range = m->jnt_range + 2 * j;
                    joint.limits = std::array<double, 2>{range[0] - q0, range[1] - q0};
                    if (q0 < range[0] || q0 > range[1])
                    {
                        warn("joint " + quotedName(jointName(j)) + " starts at " + formatNumber(q0) +
                             ", outside its range [" + formatNumber(range[0]) + ", " +
                             formatNumber(range[1]) + "]");
                    }
                }
            }
            core::setJointFrames(model, joint, toScene(mujocoVec3(mData->xanchor + 3 * j)),
                                 mPlacement.orientation * mujocoVec3(mData->xaxis + 3 * j));
            mJointIndex[j] = static_cast<int>(model.joints.size());
            model.joints.push_back(std::move(joint));
        }
    }

    // MuJoCo's actuators on hinge and slide joints (docs/mjcf.md): motor -> effort, position ->
    // servo, velocity -> motor, with the gear folded in so targets are in joint units.
    void addActuators()
    {
        core::Model& model = mFragment.model;
        std::set<int> driven;
        for (int u = 0; u < m->nu; ++u)
        {
            const std::string what =
                "actuator " + quotedName(name(mjOBJ_ACTUATOR, u, "#" + std::to_string(u)));
            const int j = m->actuator_trnid[2 * u];
            if (m->actuator_trntype[u] != mjTRN_JOINT || j < 0 || mJointIndex[j] < 0 ||
                m->jnt_type[j] == mjJNT_BALL)
            {
                warn(what + ": only actuators on hinge and slide joints are supported (not on tendons, "
                            "sites, ball or free joints); it is ignored");
                continue;
            }
            core::Actuator actuator;
            actuator.joint = mJointIndex[j];
            actuator.coordinate = m->jnt_type[j] == mjJNT_HINGE ? core::JointCoordinate::Rotation
                                                                : core::JointCoordinate::Slide;
            if (!setActuatorKind(u, what, actuator))
            {
                continue;
            }
            if (m->actuator_dyntype[u] != mjDYN_NONE)
            {
                warn(what +
                     ": actuator dynamics (dyntype) are not supported; it acts on its control at once");
            }
            if (m->actuator_forcelimited[u])
            {
                const mjtNum* range = m->actuator_forcerange + 2 * u;
                actuator.effortLimit =
                    std::min(actuator.effortLimit, std::max(std::abs(range[0]), std::abs(range[1])) *
                                                       std::abs(m->actuator_gear[6 * u]));
            }
            if (!driven.insert(mJointIndex[j]).second)
            {
                warn(what + ": its joint " + quotedName(jointName(j)) +
                     " has an actuator already; Frontier takes one per joint, the first");
                continue;
            }
            model.actuators.push_back(std::move(actuator));
        }
    }

    // The actuator's kind, gain and constant target from its gain, bias, gear and control; false,
    // after a warning, for one Frontier does not take.
    bool setActuatorKind(int u, const std::string& what, core::Actuator& actuator)
    {
        const double gear = m->actuator_gear[6 * u];
        const double gain = m->actuator_gainprm[mjNGAIN * u];
        const mjtNum* bias = m->actuator_biasprm + mjNBIAS * u;
        // MuJoCo clamps a control into its range.
        const double ctrl =
            m->actuator_ctrllimited[u]
                ? std::clamp(mData->ctrl[u], m->actuator_ctrlrange[2 * u], m->actuator_ctrlrange[2 * u + 1])
                : mData->ctrl[u];
        if (m->actuator_gaintype[u] != mjGAIN_FIXED || gear == 0.0)
        {
            warn(what + ": only fixed gains and a nonzero gear are supported; it is ignored");
            return false;
        }
        if (m->actuator_biastype[u] == mjBIAS_NONE)
        {
            actuator.kind = core::ActuatorKind::Effort;
            actuator.target = core::constantFunction(gain * gear * ctrl); // N m or N
            if (m->actuator_ctrllimited[u])
            {
                const mjtNum* range = m->actuator_ctrlrange + 2 * u;
                actuator.effortLimit =
                    std::max(std::abs(range[0]), std::abs(range[1])) * std::abs(gain * gear);
            }
        }
        else if (m->actuator_biastype[u] == mjBIAS_AFFINE && bias[0] == 0.0 && bias[1] == -gain &&
                 bias[2] == 0.0)
        {
            actuator.kind = core::ActuatorKind::Position;
            actuator.kp = gain * gear * gear; // N m/rad or N/m
            actuator.target = core::constantFunction(ctrl / gear);
        }
        else if (m->actuator_biastype[u] == mjBIAS_AFFINE && bias[0] == 0.0 && bias[1] == 0.0 &&
                 bias[2] == -gain)
        {
            actuator.kind = core::ActuatorKind::Velocity;
            actuator.kd = gain * gear * gear; // N m s/rad or N s/m
            actuator.target = core::constantFunction(ctrl / gear);
        }
        else
        {
            warn(what + ": a general actuator other than a motor, position or velocity servo is not "
                        "supported; it is ignored");
            return false;
        }
        return true;
    }

    // A joint's spring (stiffness, springref) is a servo of that stiffness towards springref.
    void addJointSprings()
    {
        core::Model& model = mFragment.model;
        std::string stiffDriven; // joints with both, named in one warning
        for (int j = 0; j < m->njnt; ++j)
        {
            if (m->jnt_stiffness[j] == 0.0 || mJointIndex[j] < 0 || m->jnt_type[j] == mjJNT_BALL)
            {
                continue;
            }
            const bool driven =
                std::any_of(model.actuators.begin(), model.actuators.end(),
                            [&](const core::Actuator& a) { return a.joint == mJointIndex[j]; });
            if (driven)
            {
                stiffDriven += (stiffDriven.empty() ? "" : ", ") + quotedName(jointName(j));
                continue;
            }
            core::Actuator spring;
            spring.joint = mJointIndex[j];
            spring.coordinate = m->jnt_type[j] == mjJNT_HINGE ? core::JointCoordinate::Rotation
                                                              : core::JointCoordinate::Slide;
            spring.kind = core::ActuatorKind::Position;
            spring.kp = m->jnt_stiffness[j];
            spring.target = core::constantFunction(m->qpos_spring[m->jnt_qposadr[j]]);
            model.actuators.push_back(std::move(spring));
        }
        if (!stiffDriven.empty())
        {
            warn("the stiffness of joints " + stiffDriven +
                 " is ignored, as each has an actuator (Frontier takes one per joint)");
        }
    }

    // MuJoCo's contact filter (contype/conaffinity, a body and its parent, <exclude>) as the pairs of
    // bodies that never collide.
    void filterCollisions()
    {
        core::Model& model = mFragment.model;
        std::set<std::array<int, 2>> excluded;
        for (int e = 0; e < m->nexclude; ++e)
        {
            const int signature = m->exclude_signature[e];
            const int a = bodyOf((signature >> 16) - 1);
            const int b = bodyOf((signature & 0xFFFF) - 1);
            excluded.insert({std::min(a, b), std::max(a, b)});
        }
        const auto parentWeld = [&](int weld) { return m->body_weldid[m->body_parentid[weld]]; };
        for (auto a = mColliders.begin(); a != mColliders.end(); ++a)
        {
            for (auto b = std::next(a); b != mColliders.end(); ++b)
            {
                const int weldA = weldOf(a->first);
                const int weldB = weldOf(b->first);
                bool collide = (weldA != 0 || weldB != 0) && !excluded.count({a->first, b->first});
                // A body and its parent never collide unless one is the world (MuJoCo's filterparent).
                if (weldA != 0 && weldB != 0 && (parentWeld(weldB) == weldA || parentWeld(weldA) == weldB) &&
                    !(m->opt.disableflags & mjDSBL_FILTERPARENT))
                {
                    collide = false;
                }
                bool bitsMatch = false;
                for (const int ga : a->second)
                {
                    for (const int gb : b->second)
                    {
                        bitsMatch = bitsMatch || (m->geom_contype[ga] & m->geom_conaffinity[gb]) ||
                                    (m->geom_contype[gb] & m->geom_conaffinity[ga]);
                    }
                }
                if (!(collide && bitsMatch) && (weldA != 0 || weldB != 0))
                {
                    model.contact.ignore.push_back({a->first, b->first});
                }
            }
        }
        if (!mPlacement.selfCollision)
        {
            for (core::Body& body : model.bodies)
            {
                // The model's own ground still holds it up.
                body.group = body.isStatic ? std::string() : mPlacement.prefix + mModelName;
            }
        }
    }

    // The static body (index 0) goes when nothing is drawn or collides there: joints to the world
    // hold their anchors in world coordinates (core::cWorld).
    void dropEmptyWorld()
    {
        core::Model& model = mFragment.model;
        if (!model.bodies.front().shapes.empty() || !model.bodies.front().visuals.empty())
        {
            return;
        }
        std::erase_if(mFragment.report.welded,
                      [&](const auto& welded) { return welded.second == model.bodies.front().name; });
        model.bodies.erase(model.bodies.begin());
        for (core::Joint& joint : model.joints)
        {
            joint.parent = joint.parent == core::cWorld ? core::cWorld : joint.parent - 1;
            joint.child -= 1;
        }
        for (std::array<int, 2>& pair : model.contact.ignore)
        {
            pair = {pair[0] - 1, pair[1] - 1};
        }
    }

    // The MuJoCo weld group a Frontier body stands for (0: the world's).
    int weldOf(int index) const
    {
        for (const auto& [weld, body] : mBodyOfWeld)
        {
            if (body == index)
            {
                return weld;
            }
        }
        return 0;
    }

    void warnUnsupported()
    {
        const auto element = [&](const char* tag, int count, const std::string& consequence)
        {
            if (count == 0)
            {
                return;
            }
            const auto where = mCompiled.unsupported.find(tag);
            const bool found = where != mCompiled.unsupported.end();
            mFragment.warnings.push_back(diagnostic(found ? where->second.file : mPath,
                                                    {found ? where->second.line : 0, 0}, "warning",
                                                    std::string("<") + tag + "> is not supported: its " +
                                                        std::to_string(count) + " " + consequence));
        };
        element("tendon", m->ntendon,
                "tendon(s) are ignored; their limits, springs and actuators do not act");
        element("equality", m->neq,
                "constraint(s) are ignored; the bodies and joints they would tie move freely");
        element("sensor", m->nsensor, "sensor(s) are ignored (they do not change the motion)");
        element("pair", m->npair,
                "explicit contact pair(s) are ignored; geoms collide by contype and conaffinity");
    }

    std::string mPath;
    MjcfPlacement mPlacement;
    CompiledMjcf mCompiled;
    const mjModel* m;
    MujocoData mData;
    std::string mModelName;
    ModelFragment mFragment;
    std::map<int, int> mBodyOfWeld;             // MuJoCo weld group -> Frontier body (0: the static body)
    std::map<int, std::vector<int>> mFramesOf;  // MuJoCo body -> its frames (Frontier bodies)
    std::map<int, std::vector<int>> mColliders; // Frontier body -> its colliding geoms
    std::vector<int> mJointIndex;               // MuJoCo joint -> Frontier joint (-1: none)
    bool mWarnedCondim = false;
};

} // namespace

ModelFragment loadMjcfFragment(const std::string& path, const MjcfPlacement& placement)
{
    std::vector<std::string> warnings;
    ModelFragment fragment;
    {
        const MujocoMessages messages(path, warnings);
        fragment = MjcfTranslation(path, placement).run();
    }
    fragment.warnings.insert(fragment.warnings.end(), warnings.begin(), warnings.end());
    return fragment;
}

core::Model loadMjcfScene(const std::string& path, const UrdfOptions& options, LoadReport* report)
{
    if (options.fixedBase || options.freeBase || options.dropHeight || !options.jointPositions.empty())
    {
        throw InputError(
            path, 0, 0,
            "--fixed-base, --free-base, --drop-height and --joint-position place a bare .urdf; an "
            "MJCF file places its bodies itself (a <key> chosen with --keyframe sets its pose)");
    }
    MjcfPlacement placement;
    placement.selfCollision = options.selfCollision.value_or(true);
    placement.keyframe = options.keyframe;
    ModelFragment fragment = loadMjcfFragment(path, placement);
    core::Model model = std::move(fragment.model);
    model.sourceFile = path;
    RobotReport& robot = fragment.report;
    robot.placement = "where the MJCF file puts it" +
                      (options.keyframe ? ", in keyframe " + quotedName(*options.keyframe) : std::string());
    model.robots.push_back(
        {robot.name, path, 0, static_cast<int>(model.bodies.size()), placement.selfCollision});
    if (options.hold)
    {
        addHoldServos(model, 0, static_cast<int>(model.joints.size()));
    }
    checkStartingState(model, path);
    reportRobot(fragment, report);
    return model;
}

} // namespace frontier::io::detail
