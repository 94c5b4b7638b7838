// tests/core/random_model.cpp: random trees, forests and chains for the core tests.
#include "random_model.h"

#include <algorithm>
#include <cmath>

namespace frontier::test
{

using core::Body;
using core::JointType;
using core::Model;

double Rng::logUniform(double lo, double hi)
{
    return std::exp(uniform(std::log(lo), std::log(hi)));
}

Vec3 Rng::unitVec()
{
    Vec3 v = gaussianVec();
    while (v.norm() < 1e-6)
    {
        v = gaussianVec();
    }
    return v.normalized();
}

Quat Rng::rotation()
{
    auto draw = [this]
    {
        const double z = normal(), y = normal(), x = normal(),
                     w = normal(); // one per statement, as gaussianVec
        return Quat(w, x, y, z);
    };
    Quat q = draw();
    while (q.norm() < 1e-6)
    {
        q = draw();
    }
    return q.normalized();
}

Body boxBody(const std::string& name, double mass, const Vec3& size, const Vec3& position,
             const Quat& orientation)
{
    Body body;
    body.name = name;
    body.mass = mass;
    core::Shape box;
    box.type = core::ShapeType::Box;
    box.size = size;
    body.shapes.push_back(box);
    const Vec3 s2 = size.cwiseProduct(size);
    body.inertia_B = (mass / 12.0 * Vec3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y())).asDiagonal();
    body.position_W = position;
    body.orientation_WB = orientation;
    return body;
}

int addJoint(Model& model, const std::string& name, JointType type, int parent, int child,
             const Vec3& anchor_W, const Vec3& axis_W)
{
    core::Joint joint;
    joint.name = name;
    joint.type = type;
    joint.parent = parent;
    joint.child = child;
    core::setJointFrames(model, joint, anchor_W, axis_W);
    model.joints.push_back(joint);
    return static_cast<int>(model.joints.size()) - 1;
}

const std::vector<JointType>& bodyJointTypes()
{
    static const std::vector<JointType> types = {JointType::Ball,      JointType::Revolute,
                                                 JointType::Angle,     JointType::Cylindrical,
                                                 JointType::Prismatic, JointType::Fixed};
    return types;
}

void appendRandomTree(Model& model, Rng& rng, const RandomTreeOptions& options)
{
    const std::vector<JointType>& types = options.types.empty() ? bodyJointTypes() : options.types;
    const int first = static_cast<int>(model.bodies.size());
    const std::string prefix = "t" + std::to_string(first) + "_";
    const Vec3 origin = 3.0 * rng.gaussianVec();
    for (int k = 0; k < options.bodies; ++k)
    {
        const int index = first + k;
        const double mass = rng.logUniform(options.minMass, options.maxMass);
        const double sz = rng.uniform(0.05, 1.0), sy = rng.uniform(0.05, 1.0), sx = rng.uniform(0.05, 1.0);
        const Vec3 size(sx, sy, sz);
        int parent = -1;
        Vec3 position = origin;
        if (k > 0)
        {
            const int lo =
                options.branching >= 1.0 ? 0 : std::max(0, k - 1 - static_cast<int>(options.branching * k));
            parent = first + rng.integer(lo, k - 1);
            const Vec3 direction = rng.unitVec();
            position =
                model.bodies[static_cast<std::size_t>(parent)].position_W + rng.uniform(0.3, 1.0) * direction;
        }
        Body body = boxBody(prefix + "b" + std::to_string(k), mass, size, position, rng.rotation());
        body.velocity_W = rng.gaussianVec();
        body.angularVelocity_W = rng.gaussianVec();
        model.bodies.push_back(body);
        if (parent >= 0)
        {
            const Vec3& xp = model.bodies[static_cast<std::size_t>(parent)].position_W;
            const Vec3 anchor = 0.5 * (xp + position) + 0.2 * rng.gaussianVec();
            const JointType type =
                types[static_cast<std::size_t>(rng.integer(0, static_cast<int>(types.size()) - 1))];
            // Either orientation: the solver must not assume the joint's parent is the tree parent.
            const bool swap = rng.coin();
            addJoint(model, prefix + "j" + std::to_string(k) + "_" + core::jointTypeName(type), type,
                     swap ? index : parent, swap ? parent : index, anchor, rng.unitVec());
        }
    }
    if (options.attachToWorld)
    {
        // Nail most roots; sometimes another joint type to the world (an edge of 3..6 rows).
        const JointType type =
            rng.coin(0.6)
                ? JointType::Nail
                : types[static_cast<std::size_t>(rng.integer(0, static_cast<int>(types.size()) - 1))];
        const int root = first + rng.integer(0, options.bodies - 1);
        const Vec3 anchor = model.bodies[static_cast<std::size_t>(root)].position_W + 0.3 * rng.gaussianVec();
        addJoint(model, prefix + "world_" + core::jointTypeName(type), type, core::cWorld, root, anchor,
                 rng.unitVec());
    }
}

Model randomTree(unsigned seed, const RandomTreeOptions& options)
{
    Rng rng(seed);
    Model model;
    model.name = "random tree " + std::to_string(seed);
    appendRandomTree(model, rng, options);
    return model;
}

Model randomForest(unsigned seed, int trees, int maxBodiesPerTree)
{
    Rng rng(seed);
    Model model;
    model.name = "random forest " + std::to_string(seed);
    for (int t = 0; t < trees; ++t)
    {
        RandomTreeOptions options;
        options.bodies = rng.integer(1, maxBodiesPerTree);
        options.attachToWorld = rng.coin();
        options.branching = rng.uniform(0.0, 1.0);
        appendRandomTree(model, rng, options);
    }
    return model;
}

Model straightChain(const std::vector<double>& masses, JointType type, bool nailToWorld, double length)
{
    Model model;
    model.name = "chain";
    const int n = static_cast<int>(masses.size());
    const Vec3 size(length, 0.1 * length, 0.1 * length);
    for (int i = 0; i < n; ++i)
    {
        model.bodies.push_back(boxBody("link" + std::to_string(i), masses[static_cast<std::size_t>(i)], size,
                                       Vec3((i + 0.5) * length, 0.0, 0.0)));
    }
    for (int i = 1; i < n; ++i)
    {
        addJoint(model, "joint" + std::to_string(i), type, i - 1, i, Vec3(i * length, 0.0, 0.0),
                 Vec3::UnitZ());
    }
    if (nailToWorld)
    {
        addJoint(model, "nail", JointType::Nail, core::cWorld, 0, Vec3::Zero(), Vec3::UnitZ());
    }
    return model;
}

std::unique_ptr<Problem> makeProblem(const Model& model)
{
    auto problem = std::make_unique<Problem>();
    problem->layout = core::buildFrontierLayout(model);
    problem->state = core::initialState(model);
    core::assembleRows(model, problem->layout, problem->state, model.simulation.dt, problem->system);
    return problem;
}

core::BlockVector momentumRhs(const Model& model, const core::State& state, const core::RowSystem& system)
{
    core::BlockVector rhs;
    rhs.resize(model.bodies.size(), model.joints.size());
    rhs.setZero();
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (model.bodies[i].isStatic)
        {
            continue;
        }
        rhs.body[i].head<3>() = system.mass[i] * state.bodies[i].velocity_W;
        rhs.body[i].tail<3>() = system.inertia_W[i] * state.bodies[i].angularVelocity_W;
    }
    return rhs;
}

JointResidual jointResidual(const Model& model, const core::RowSystem& system, const core::BlockVector& x)
{
    JointResidual out;
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        if (system.layout->jointBlock[k] < 0)
        {
            continue;
        }
        const core::Joint& joint = model.joints[k];
        const core::JointRows& rows = system.joints[k];
        const int r = rows.count;
        Eigen::VectorXd a = Eigen::VectorXd::Zero(r);
        if (!core::jointToWorld(model, joint))
        {
            a = rows.J_a.topRows(r) * x.body[static_cast<std::size_t>(joint.parent)];
        }
        const Eigen::VectorXd b = rows.J_b.topRows(r) * x.body[static_cast<std::size_t>(joint.child)];
        out.maxResidual = std::max(out.maxResidual, (a + b).cwiseAbs().maxCoeff());
        out.scale = std::max(out.scale, a.cwiseAbs().maxCoeff() + b.cwiseAbs().maxCoeff());
    }
    return out;
}

double bodyNorm(const core::BlockVector& x)
{
    double m = 0.0;
    for (const Vec6& v : x.body)
    {
        m = std::max(m, v.cwiseAbs().maxCoeff());
    }
    return m;
}

double jointNorm(const core::RowSystem& system, const core::BlockVector& x)
{
    double m = 0.0;
    for (std::size_t k = 0; k < x.joint.size(); ++k)
    {
        if (system.layout->jointBlock[k] >= 0)
        {
            m = std::max(m, x.joint[k].head(system.joints[k].count).cwiseAbs().maxCoeff());
        }
    }
    return m;
}

double bodyDiff(const core::BlockVector& x, const core::BlockVector& y)
{
    double m = 0.0;
    for (std::size_t i = 0; i < x.body.size(); ++i)
    {
        m = std::max(m, (x.body[i] - y.body[i]).cwiseAbs().maxCoeff());
    }
    return m;
}

double jointDiff(const core::RowSystem& system, const core::BlockVector& x, const core::BlockVector& y)
{
    double m = 0.0;
    for (std::size_t k = 0; k < x.joint.size(); ++k)
    {
        if (system.layout->jointBlock[k] >= 0)
        {
            const int r = system.joints[k].count;
            m = std::max(m, (x.joint[k].head(r) - y.joint[k].head(r)).cwiseAbs().maxCoeff());
        }
    }
    return m;
}

} // namespace frontier::test
