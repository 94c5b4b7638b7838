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
#include "bench/peers/contacts.h"
#include "bench/peers/engine.h"
#include "bench/peers/tree.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mujoco/mujoco.h>
#include <sstream>
#include <unistd.h>

namespace frontier::peers
{
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

// MJCF text of the model's joint trees.
std::string mjcf(const core::Model& model, const std::vector<TreeLink>& tree, MujocoIntegrator integrator)
{
    const bool contacts = hasContacts(model);
    std::vector<std::vector<const TreeLink*>> children(model.bodies.size());
    for (const TreeLink& link : tree)
        if (!isRoot(link))
            children[static_cast<std::size_t>(link.parent)].push_back(&link);
    std::ostringstream out;
    const core::Vec3& g = model.simulation.gravity;
    out << "<mujoco model=\"peers\">\n<option timestep=\"" << numbers({model.simulation.dt})
        << "\" gravity=\"" << numbers({g.x(), g.y(), g.z()}) << "\""
        << (integrator == MujocoIntegrator::Rk4 ? " integrator=\"RK4\"" : "")
        << ">\n<flag filterparent=\"disable\"/>\n"
        << "</option>\n<compiler angle=\"radian\"/>\n";
    if (contacts)
        writeMeshAssets(out, model);
    out << "<worldbody>\n";
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
    // Iterative depth-first writing: long chains nest thousands of bodies deep.
    struct Frame
    {
        const TreeLink* link;
        std::size_t next; // next child to write
    };
    std::vector<Frame> stack;
    auto open = [&](const TreeLink& link)
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
                out << " limited=\"true\" range=\"" << numbers({(*joint.limits)[0], (*joint.limits)[1]})
                    << "\"";
            out << "/>\n";
        }
        else if (joint.type == core::JointType::Angle)
        {
            // a1 (fixed in the parent) in the child's frame at the initial pose, then b2: MuJoCo
            // turns the body about its joints in order, so the second axis turns with the first.
            const core::Vec3 a1 =
                relativeRotation(model, link.parent, link.body).conjugate() * joint.perpParent1;
            out << "<joint type=\"hinge\" pos=\"" << a << "\" axis=\"" << vector3(a1) << "\"/>\n"
                << "<joint type=\"hinge\" pos=\"" << a << "\" axis=\"" << vector3(joint.angleChildAxis)
                << "\"/>\n";
        }
    };
    for (const TreeLink& root : tree)
    {
        if (!isRoot(root))
            continue;
        open(root);
        stack.push_back({&root, 0});
        while (!stack.empty())
        {
            Frame& top = stack.back();
            const auto& kids = children[static_cast<std::size_t>(top.link->body)];
            if (top.next < kids.size())
            {
                const TreeLink* child = kids[top.next++];
                open(*child);
                stack.push_back({child, 0});
            }
            else
            {
                out << "</body>\n";
                stack.pop_back();
            }
        }
    }
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
    MujocoEngine(const core::Model& model, MujocoIntegrator integrator) : mTree(jointTree(model))
    {
        const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                           ("frontier_peers_" + std::to_string(::getpid()) + ".xml");
        {
            std::ofstream xml(file);
            xml << mjcf(model, mTree, integrator);
        }
        char error[1000] = "";
        mModel = mj_loadXML(file.c_str(), nullptr, error, sizeof error);
        std::filesystem::remove(file);
        if (!mModel)
            throw Unsupported(std::string("MuJoCo refused the model: ") + error);
        mData = mj_makeData(mModel);
        for (const TreeLink& link : mTree)
            if (isRoot(link) && link.joint < 0) // a free root: its tree's rigid velocity (tree.h)
            {
                const core::Body& body = model.bodies[static_cast<std::size_t>(link.body)];
                const int joint =
                    mj_name2id(mModel, mjOBJ_JOINT, ("free" + std::to_string(link.body)).c_str());
                mjtNum* v = mData->qvel + mModel->jnt_dofadr[joint];
                const core::Vec3 w_B = body.orientation_WB.conjugate() * body.angularVelocity_W;
                for (int k = 0; k < 3; ++k)
                {
                    v[k] = body.velocity_W[k];
                    v[3 + k] = w_B[k];
                }
            }
        mj_forward(mModel, mData);
        mBodyOf.resize(model.bodies.size());
        for (std::size_t b = 0; b < model.bodies.size(); ++b)
            mBodyOf[b] = mj_name2id(mModel, mjOBJ_BODY, ("b" + std::to_string(b)).c_str());
    }

    ~MujocoEngine() override
    {
        mj_deleteData(mData);
        mj_deleteModel(mModel);
    }

    void step() override { mj_step(mModel, mData); }

    void poses(std::vector<Pose>& out) override
    {
        mj_kinematics(mModel, mData); // mj_step leaves xpos at the step's start
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
    mjModel* mModel = nullptr;
    mjData* mData = nullptr;
    std::vector<int> mBodyOf;
};

} // namespace

std::unique_ptr<Engine> makeMujoco(const core::Model& model, MujocoIntegrator integrator)
{
    return std::make_unique<MujocoEngine>(model, integrator);
}

} // namespace frontier::peers
