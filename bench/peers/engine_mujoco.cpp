// bench/peers/engine_mujoco.cpp: MuJoCo 2.2 (reduced coordinates), the model written as MJCF text
// (bodies nested along the joint tree, each at its centre of mass with its full inertia; ball and
// hinge joints at the child's anchor, fixed joints as bodies nested without a joint, a free root
// with a free joint; an angle joint as two hinges, the parent's axis first) and read by MuJoCo's
// own XML loader; MuJoCo's usual settings (Euler integrator, Newton solver). Contacts: the shapes
// as geoms (static bodies as bodies without joints, so welded to the world), MuJoCo's soft
// contacts with its default solref/solimp, the scene's friction (pyramidal cone, condim 3); MuJoCo
// has no restitution coefficient, so the scene's is not given. MuJoCo's own parent-child filter is
// turned off and every pair Frontier's filter refuses is listed as an <exclude>. A tree that starts
// moving gets its root's velocity on its free joint (world linear, body-frame angular). A mesh is
// given as its convex hull's vertices (an inline <mesh vertex>: MuJoCo collides meshes as their
// hulls); revolute limits as the hinge's range (radians, 0 at the initial pose as the model's).
//
// Buffers: MuJoCo 2.2 keeps a step's contacts and constraint rows in buffers of fixed size
// (<size nconmax njmax>, 100 and 500 by default) and drops what does not fit: a pile of boxes
// fills the default contact buffer and then sinks through the floor. The buffers are sized from the
// scene (mujocoBuffers below), not oversized blindly: MuJoCo allocates njmax x njmax doubles for
// efc_AR and about 5 njmax^2 for its stack, so 8 000 rows would take 3 GB.
// Warnings: MuJoCo counts its warnings in mjData::warning (a full contact or constraint buffer, a
// bad acceleration after which it resets the simulation to its start, ...); checkStep reads the
// counters after every step into the engine's warnings, with the step each first came at. Its
// message handlers are taken over too: a warning is not printed (nor written to MUJOCO_LOG.TXT),
// an error (by default: print and exit) ends the run with an EngineError.
#include "bench/peers/contacts.h"
#include "bench/peers/engine.h"
#include "bench/peers/mujoco_messages.h"
#include "bench/peers/tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mujoco/mujoco.h>
#include <sstream>
#include <unistd.h>

namespace frontier::peers
{

// MuJoCo's message handlers are global: a warning goes to the messages of the engine that is
// stepping (or being set up) on this thread, an error ends its run.
namespace
{

thread_local std::vector<std::string>* tMessages = nullptr;

void onWarning(const char* message)
{
    if (tMessages)
        tMessages->emplace_back(message);
}

[[noreturn]] void onError(const char* message)
{
    throw EngineError(std::string("MuJoCo error: ") + message);
}

} // namespace

MessageScope::MessageScope(std::vector<std::string>& messages)
{
    static const bool installed = []
    {
        mju_user_warning = onWarning;
        mju_user_error = onError;
        return true;
    }();
    (void)installed;
    tMessages = &messages;
}

MessageScope::~MessageScope()
{
    tMessages = nullptr;
}

namespace
{

std::string numbers(std::initializer_list<double> values)
{
    std::string out;
    char buffer[32];
    for (double v : values)
    {
        std::snprintf(buffer, sizeof buffer, "%.17g", v);
        if (!out.empty())
            out += ' ';
        out += buffer;
    }
    return out;
}

std::string vector3(const core::Vec3& v)
{
    return numbers({v.x(), v.y(), v.z()});
}

std::string quaternion(const core::Quat& q)
{
    return numbers({q.w(), q.x(), q.y(), q.z()});
}

std::string meshName(const core::Model& model, const core::Body& body, std::size_t shape)
{
    return "m" + std::to_string(&body - model.bodies.data()) + "_" + std::to_string(shape);
}

// The meshes' hulls as <mesh> assets, named by meshName.
void writeMeshAssets(std::ostream& out, const core::Model& model)
{
    out << "<asset>\n";
    for (const core::Body& body : model.bodies)
        for (std::size_t k = 0; k < body.shapes.size(); ++k)
        {
            if (body.shapes[k].type != core::ShapeType::Mesh)
                continue;
            out << "<mesh name=\"" << meshName(model, body, k) << "\" vertex=\"";
            const char* separator = "";
            for (const core::Vec3& v : meshHull(body, body.shapes[k]).vertices)
            {
                out << separator << vector3(v);
                separator = " ";
            }
            out << "\"/>\n";
        }
    out << "</asset>\n";
}

// A body's shapes as geoms in its frame (contacts: false gives none).
void writeGeoms(std::ostream& out, const core::Model& model, const core::Body& body, bool contacts)
{
    if (!contacts)
        return;
    const std::string friction = numbers({model.contact.friction, 0.005, 0.0001});
    for (std::size_t k = 0; k < body.shapes.size(); ++k)
    {
        const core::Shape& shape = body.shapes[k];
        core::Vec3 position = shape.position_BS;
        core::Quat rotation = shape.rotation_BS;
        out << "<geom friction=\"" << friction << "\" ";
        switch (shape.type)
        {
        case core::ShapeType::Box:
            out << "type=\"box\" size=\"" << vector3(0.5 * shape.size) << "\"";
            break;
        case core::ShapeType::Sphere:
            out << "type=\"sphere\" size=\"" << numbers({shape.radius}) << "\"";
            break;
        case core::ShapeType::Capsule: // radius and half the cylindrical length, along local z
            out << "type=\"capsule\" size=\"" << numbers({shape.radius, 0.5 * shape.length}) << "\"";
            break;
        case core::ShapeType::Cylinder: // radius and half the height, along local z
            out << "type=\"cylinder\" size=\"" << numbers({shape.radius, 0.5 * shape.length}) << "\"";
            break;
        case core::ShapeType::Plane: // world frame n . x <= offset: an infinite plane in the body frame
        {
            const core::Quat toBody = body.orientation_WB.conjugate();
            position = toBody * (shape.normal * shape.offset - body.position_W);
            rotation = core::Quat::FromTwoVectors(core::Vec3::UnitZ(), toBody * shape.normal);
            out << "type=\"plane\" size=\"0 0 1\"";
            break;
        }
        case core::ShapeType::Mesh:
            out << "type=\"mesh\" mesh=\"" << meshName(model, body, k) << "\"";
            break;
        }
        out << " pos=\"" << vector3(position) << "\" quat=\"" << quaternion(rotation) << "\"/>\n";
    }
}

// MuJoCo's buffers for a model (see the file's header).
struct Buffers
{
    int contacts = 0; // nconmax
    int rows = 0;     // njmax
};

// The most contact points MuJoCo 2.2 gives a pair of geoms of these types, as found by colliding
// two such geoms in 20 000 random overlapping poses: box-box 9; a plane with a box or a cylinder 4,
// with a mesh 3; a capsule with a capsule, a box or a plane 2; every other pair (a sphere, and the
// general convex collider of meshes and cylinders) 1.
int pointsPerPair(core::ShapeType a, core::ShapeType b)
{
    using core::ShapeType;
    const auto pair = [&](ShapeType x, ShapeType y) { return (a == x && b == y) || (a == y && b == x); };
    if (pair(ShapeType::Box, ShapeType::Box))
        return 9;
    if (pair(ShapeType::Plane, ShapeType::Box) || pair(ShapeType::Plane, ShapeType::Cylinder))
        return 4;
    if (pair(ShapeType::Plane, ShapeType::Mesh))
        return 3;
    if (pair(ShapeType::Capsule, ShapeType::Capsule) || pair(ShapeType::Capsule, ShapeType::Box) ||
        pair(ShapeType::Capsule, ShapeType::Plane))
        return 2;
    return 1;
}

// The buffers a model needs, from its geoms and the pairs that may collide. Each moving geom is
// taken to touch two geoms at a time (in a pile a body rests on about one and carries about one),
// the two of its candidate pairs with the most points (pointsPerPair), a pair of two moving geoms
// counted half to each; every contact takes 4 rows (the pyramidal cone of condim 3), every limited
// hinge 1. Never less than MuJoCo's defaults. (Measured: the box pileup of 44 reaches 160 contacts
// where this gives 396, the capsule pileup 86 of 132, DRC-Hubo 28 of 182.)
Buffers mujocoBuffers(const core::Model& model, int growth)
{
    constexpr std::size_t cTouching = 2;
    const collision::PairFilter pairs(model);
    double contacts = 0.0;
    std::vector<double> shares; // of one geom's candidate pairs: points, halved between moving geoms
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (model.bodies[i].isStatic)
            continue;
        for (const core::Shape& mine : model.bodies[i].shapes)
        {
            shares.clear();
            for (std::size_t j = 0; j < model.bodies.size(); ++j)
                if (j != i && pairs.allowed(static_cast<int>(i), static_cast<int>(j)))
                    for (const core::Shape& theirs : model.bodies[j].shapes)
                        shares.push_back(pointsPerPair(mine.type, theirs.type) *
                                         (model.bodies[j].isStatic ? 1.0 : 0.5));
            const std::size_t touching = std::min(shares.size(), cTouching);
            std::partial_sort(shares.begin(), shares.begin() + static_cast<std::ptrdiff_t>(touching),
                              shares.end(), std::greater<>());
            for (std::size_t k = 0; k < touching; ++k)
                contacts += shares[k];
        }
    }
    int limits = 0;
    for (const core::Joint& joint : model.joints)
        limits += joint.limits ? 1 : 0;
    Buffers buffers;
    buffers.contacts = growth * std::max(100, static_cast<int>(std::ceil(contacts)));
    buffers.rows = growth * std::max(500, 4 * static_cast<int>(std::ceil(contacts)) + limits);
    return buffers;
}

// The <option>, <compiler> and <size> of the model's MJCF.
void writeOptions(std::ostream& out, const core::Model& model, MujocoIntegrator integrator,
                  const Buffers& buffers)
{
    const core::Vec3& g = model.simulation.gravity;
    out << "<mujoco model=\"peers\">\n<option timestep=\"" << numbers({model.simulation.dt})
        << "\" gravity=\"" << numbers({g.x(), g.y(), g.z()}) << "\""
        << (integrator == MujocoIntegrator::Rk4 ? " integrator=\"RK4\"" : "")
        << ">\n<flag filterparent=\"disable\"/>\n"
        << "</option>\n<compiler angle=\"radian\"/>\n<size nconmax=\"" << buffers.contacts << "\" njmax=\""
        << buffers.rows << "\"/>\n";
}

// Static bodies: children of the world, without joints.
void writeStaticBodies(std::ostream& out, const core::Model& model, bool contacts)
{
    for (std::size_t b = 0; b < model.bodies.size(); ++b)
    {
        const core::Body& body = model.bodies[b];
        if (!body.isStatic)
            continue;
        out << "<body name=\"b" << b << "\" pos=\"" << vector3(body.position_W) << "\" quat=\""
            << quaternion(body.orientation_WB) << "\">\n";
        writeGeoms(out, model, body, contacts);
        out << "</body>\n";
    }
}

// The joint(s) that hold a link to its parent: a free joint for a root, a ball, a hinge, or two
// hinges for an angle joint.
void writeJoint(std::ostream& out, const core::Model& model, const TreeLink& link)
{
    if (link.joint < 0)
    {
        out << "<freejoint name=\"free" << link.body << "\"/>\n";
        return;
    }
    const core::Joint& joint = model.joints[static_cast<std::size_t>(link.joint)];
    const std::string a = vector3(joint.anchorChild);
    if (joint.type == core::JointType::Ball)
        out << "<joint type=\"ball\" pos=\"" << a << "\"/>\n";
    else if (joint.type == core::JointType::Revolute)
    {
        out << "<joint type=\"hinge\" pos=\"" << a << "\" axis=\"" << vector3(joint.axisChild) << "\"";
        if (joint.limits)
            out << " limited=\"true\" range=\"" << numbers({(*joint.limits)[0], (*joint.limits)[1]}) << "\"";
        out << "/>\n";
    }
    else if (joint.type == core::JointType::Angle)
    {
        // a1 (fixed in the parent) in the child's frame at the initial pose, then b2: MuJoCo
        // turns the body about its joints in order, so the second axis turns with the first.
        const core::Vec3 a1 = relativeRotation(model, link.parent, link.body).conjugate() * joint.perpParent1;
        out << "<joint type=\"hinge\" pos=\"" << a << "\" axis=\"" << vector3(a1) << "\"/>\n"
            << "<joint type=\"hinge\" pos=\"" << a << "\" axis=\"" << vector3(joint.angleChildAxis)
            << "\"/>\n";
    }
}

// A link's opening <body>: its pose in its parent, inertia, geoms and joint (closed by the caller).
void openBody(std::ostream& out, const core::Model& model, const TreeLink& link, bool contacts)
{
    const core::Body& body = model.bodies[static_cast<std::size_t>(link.body)];
    const core::Vec3 x = relativePosition(model, link.parent, link.body);
    const core::Quat q = relativeRotation(model, link.parent, link.body);
    const core::Mat3& I = body.inertia_B;
    out << "<body name=\"b" << link.body << "\" pos=\"" << numbers({x.x(), x.y(), x.z()}) << "\" quat=\""
        << numbers({q.w(), q.x(), q.y(), q.z()}) << "\">\n<inertial pos=\"0 0 0\" mass=\""
        << numbers({body.mass}) << "\" fullinertia=\""
        << numbers({I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)}) << "\"/>\n";
    writeGeoms(out, model, body, contacts);
    writeJoint(out, model, link);
}

// The joint trees, each body nested in its parent's. Iterative depth-first writing: long chains
// nest thousands of bodies deep.
void writeTrees(std::ostream& out, const core::Model& model, const std::vector<TreeLink>& tree, bool contacts)
{
    std::vector<std::vector<const TreeLink*>> children(model.bodies.size());
    for (const TreeLink& link : tree)
        if (!isRoot(link))
            children[static_cast<std::size_t>(link.parent)].push_back(&link);
    struct Frame
    {
        const TreeLink* link;
        std::size_t next; // next child to write
    };
    std::vector<Frame> stack;
    for (const TreeLink& root : tree)
    {
        if (!isRoot(root))
            continue;
        openBody(out, model, root, contacts);
        stack.push_back({&root, 0});
        while (!stack.empty())
        {
            Frame& top = stack.back();
            const auto& kids = children[static_cast<std::size_t>(top.link->body)];
            if (top.next < kids.size())
            {
                const TreeLink* child = kids[top.next++];
                openBody(out, model, *child, contacts);
                stack.push_back({child, 0});
            }
            else
            {
                out << "</body>\n";
                stack.pop_back();
            }
        }
    }
}

// MJCF text of the model's joint trees.
std::string mjcf(const core::Model& model, const std::vector<TreeLink>& tree, MujocoIntegrator integrator,
                 const Buffers& buffers)
{
    const bool contacts = hasContacts(model);
    std::ostringstream out;
    writeOptions(out, model, integrator, buffers);
    if (contacts)
        writeMeshAssets(out, model);
    out << "<worldbody>\n";
    writeStaticBodies(out, model, contacts);
    writeTrees(out, model, tree, contacts);
    out << "</worldbody>\n";
    if (contacts)
    {
        out << "<contact>\n";
        for (const auto& [i, j] : excludedPairs(model, collision::PairFilter(model)))
            out << "<exclude body1=\"b" << i << "\" body2=\"b" << j << "\"/>\n";
        out << "</contact>\n";
    }
    out << "</mujoco>\n";
    return out.str();
}

class MujocoEngine final : public Engine
{
  public:
    MujocoEngine(const core::Model& model, MujocoIntegrator integrator, const EngineOptions& options,
                 const EngineSettings& settings)
        : mTree(jointTree(model))
    {
        Buffers buffers = mujocoBuffers(model, options.bufferGrowth);
        if (options.mujocoContacts > 0)
            buffers.contacts = options.bufferGrowth * options.mujocoContacts;
        if (options.mujocoRows > 0)
            buffers.rows = options.bufferGrowth * options.mujocoRows;
        const MessageScope scope(mMessages);
        const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                           ("frontier_peers_" + std::to_string(::getpid()) + ".xml");
        {
            std::ofstream xml(file);
            xml << mjcf(model, mTree, integrator, buffers);
        }
        char error[1000] = "";
        mModel.reset(mj_loadXML(file.c_str(), nullptr, error, sizeof error));
        std::filesystem::remove(file);
        if (!mModel)
            throw Unsupported(std::string("MuJoCo refused the model: ") + error);
        if (settings.iterations)
            mModel->opt.iterations = *settings.iterations;
        if (settings.tolerance)
            mModel->opt.tolerance = *settings.tolerance;
        mData.reset(mj_makeData(mModel.get()));
        for (const TreeLink& link : mTree)
            if (isRoot(link) && link.joint < 0) // a free root: its tree's rigid velocity (tree.h)
            {
                const core::Body& body = model.bodies[static_cast<std::size_t>(link.body)];
                const int joint =
                    mj_name2id(mModel.get(), mjOBJ_JOINT, ("free" + std::to_string(link.body)).c_str());
                mjtNum* v = mData->qvel + mModel->jnt_dofadr[joint];
                const core::Vec3 w_B = body.orientation_WB.conjugate() * body.angularVelocity_W;
                for (int k = 0; k < 3; ++k)
                {
                    v[k] = body.velocity_W[k];
                    v[3 + k] = w_B[k];
                }
            }
        mj_forward(mModel.get(), mData.get());
        checkStep();
        mBodyOf.resize(model.bodies.size());
        for (std::size_t b = 0; b < model.bodies.size(); ++b)
            mBodyOf[b] = mj_name2id(mModel.get(), mjOBJ_BODY, ("b" + std::to_string(b)).c_str());
    }

    void step() override
    {
        const MessageScope scope(mMessages);
        ++mSteps;
        mj_step(mModel.get(), mData.get());
    }

    // The warning counters: a counter that grew raised its warning in the last step. A bad
    // position, velocity or acceleration makes MuJoCo reset the simulation to its start (the time
    // then goes back), which also clears every counter: each nonzero one after it is new. MuJoCo
    // also prints (here: hands its handler) the first of each counted warning: those messages are
    // left out, any other is a warning of its own.
    void checkStep() override
    {
        const bool reset = mData->time <= mLastTime;
        mLastTime = mData->time;
        for (int w = 0; w < mjNWARNING; ++w)
        {
            const int number = mData->warning[w].number;
            const int fresh = reset ? number : number - mSeen[static_cast<std::size_t>(w)];
            mSeen[static_cast<std::size_t>(w)] = number;
            if (fresh <= 0)
                continue;
            std::string& text = mText[static_cast<std::size_t>(w)];
            if (text.empty()) // its first: with the info (the DOF of a bad value) of that one
                text = std::string("MuJoCo: ") + mju_warningText(w, mData->warning[w].lastinfo) +
                       (w == mjWARN_BADQPOS || w == mjWARN_BADQVEL || w == mjWARN_BADQACC
                            ? " MuJoCo reset the simulation to its start."
                            : "");
            mLog.raise(text, mSteps, w == mjWARN_CONTACTFULL || w == mjWARN_CNSTRFULL);
        }
        for (const std::string& message : mMessages)
        {
            bool counted = false;
            for (int w = 0; w < mjNWARNING && !counted; ++w)
                counted = message.rfind(mju_warningText(w, mData->warning[w].lastinfo), 0) == 0;
            if (!counted)
                mLog.raise("MuJoCo: " + message, mSteps);
        }
        mMessages.clear();
    }

    std::string bufferSizes() const override
    {
        return "nconmax " + std::to_string(mModel->nconmax) + ", njmax " + std::to_string(mModel->njmax);
    }

    void poses(std::vector<Pose>& out) override
    {
        mj_kinematics(mModel.get(), mData.get()); // mj_step leaves xpos at the step's start
        out.resize(mBodyOf.size());
        for (std::size_t b = 0; b < out.size(); ++b)
        {
            const mjtNum* x = mData->xpos + 3 * mBodyOf[b];
            const mjtNum* q = mData->xquat + 4 * mBodyOf[b];
            out[b] = {core::Vec3(x[0], x[1], x[2]), core::Quat(q[0], q[1], q[2], q[3])};
        }
    }

  private:
    std::vector<TreeLink> mTree;
    std::unique_ptr<mjModel, decltype(&mj_deleteModel)> mModel{nullptr, mj_deleteModel};
    std::unique_ptr<mjData, decltype(&mj_deleteData)> mData{nullptr, mj_deleteData};
    std::vector<int> mBodyOf;
    long mSteps = 0;
    double mLastTime = -1.0;                     // s, mData->time at the last checkStep
    std::array<int, mjNWARNING> mSeen{};         // the counters at the last checkStep
    std::array<std::string, mjNWARNING> mText{}; // each warning's text, from its first
    std::vector<std::string> mMessages;          // from MuJoCo's warning handler, since checkStep
};

} // namespace

std::unique_ptr<Engine> makeMujoco(const core::Model& model, MujocoIntegrator integrator,
                                   const EngineOptions& options, const EngineSettings& settings)
{
    return std::make_unique<MujocoEngine>(model, integrator, options, settings);
}

} // namespace frontier::peers
