// bench/peers/engine_mujoco.cpp: MuJoCo 2.2 (reduced coordinates), the model written as MJCF text
// (bodies nested along the joint tree, each at its centre of mass with its full inertia; ball and
// hinge joints at the child's anchor, fixed joints as bodies nested without a joint, a free root
// with a free joint) and read by MuJoCo's own XML loader; MuJoCo's usual settings (Euler
// integrator, Newton solver).
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

// MJCF text of the model's joint tree.
std::string mjcf(const core::Model& model, const std::vector<TreeLink>& tree)
{
    std::vector<std::vector<const TreeLink*>> children(model.bodies.size());
    for (std::size_t k = 1; k < tree.size(); ++k)
        children[static_cast<std::size_t>(tree[k].parent)].push_back(&tree[k]);
    std::ostringstream out;
    const core::Vec3& g = model.simulation.gravity;
    out << "<mujoco model=\"peers\">\n<option timestep=\"" << numbers({model.simulation.dt})
        << "\" gravity=\"" << numbers({g.x(), g.y(), g.z()}) << "\"/>\n<worldbody>\n";
    // Iterative depth-first writing: long chains nest thousands of bodies deep.
    struct Frame
    {
        const TreeLink* link;
        std::size_t next; // next child to write
    };
    std::vector<Frame> stack{{&tree.front(), 0}};
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
        if (link.joint < 0)
        {
            out << "<freejoint/>\n";
            return;
        }
        const core::Joint& joint = model.joints[static_cast<std::size_t>(link.joint)];
        const core::Vec3& a = joint.anchorChild;
        if (joint.type == core::JointType::Ball)
            out << "<joint type=\"ball\" pos=\"" << numbers({a.x(), a.y(), a.z()}) << "\"/>\n";
        else if (joint.type == core::JointType::Revolute)
            out << "<joint type=\"hinge\" pos=\"" << numbers({a.x(), a.y(), a.z()}) << "\" axis=\""
                << numbers({joint.axisChild.x(), joint.axisChild.y(), joint.axisChild.z()}) << "\"/>\n";
    };
    open(tree.front());
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
    out << "</worldbody>\n</mujoco>\n";
    return out.str();
}

class MujocoEngine final : public Engine
{
  public:
    explicit MujocoEngine(const core::Model& model) : mTree(jointTree(model))
    {
        const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                           ("frontier_peers_" + std::to_string(::getpid()) + ".xml");
        {
            std::ofstream xml(file);
            xml << mjcf(model, mTree);
        }
        char error[1000] = "";
        mModel = mj_loadXML(file.c_str(), nullptr, error, sizeof error);
        std::filesystem::remove(file);
        if (!mModel)
            throw Unsupported(std::string("MuJoCo refused the model: ") + error);
        mData = mj_makeData(mModel);
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

std::unique_ptr<Engine> makeMujoco(const core::Model& model)
{
    return std::make_unique<MujocoEngine>(model);
}

} // namespace frontier::peers
