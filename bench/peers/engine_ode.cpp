// bench/peers/engine_ode.cpp: ODE 0.16 (double precision), with dWorldQuickStep (projected
// Gauss-Seidel, 20 iterations) or dWorldStep (the direct "big matrix" LCP solver), ODE's usual
// settings otherwise (ERP 0.2, its default CFM, gyroscopic term on).
#include "bench/peers/engine.h"
#include "bench/peers/tree.h"

#include <ode/ode.h>

namespace frontier::peers
{
namespace
{

class OdeEngine final : public Engine
{
  public:
    OdeEngine(const core::Model& model, bool quickStep) : mModel(model), mQuickStep(quickStep)
    {
        jointTree(model); // the scope check
        static const bool initialised = dInitODE2(0) != 0;
        if (!initialised)
            throw Unsupported("ODE failed to initialise");
        mWorld = dWorldCreate();
        const core::Vec3& g = model.simulation.gravity;
        dWorldSetGravity(mWorld, g.x(), g.y(), g.z());
        for (const core::Body& body : model.bodies)
        {
            dBodyID b = dBodyCreate(mWorld);
            dMass mass;
            const core::Mat3& I = body.inertia_B;
            dMassSetParameters(&mass, body.mass, 0, 0, 0, I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2),
                               I(1, 2));
            dBodySetMass(b, &mass);
            dBodySetPosition(b, body.position_W.x(), body.position_W.y(), body.position_W.z());
            const core::Quat& q = body.orientation_WB;
            const dQuaternion dq = {q.w(), q.x(), q.y(), q.z()};
            dBodySetQuaternion(b, dq);
            dBodySetLinearVel(b, body.velocity_W.x(), body.velocity_W.y(), body.velocity_W.z());
            dBodySetAngularVel(b, body.angularVelocity_W.x(), body.angularVelocity_W.y(),
                               body.angularVelocity_W.z());
            mBodies.push_back(b);
        }
        for (const core::Joint& joint : model.joints)
            addJoint(joint);
    }

    ~OdeEngine() override { dWorldDestroy(mWorld); }

    void step() override
    {
        if (mQuickStep)
            dWorldQuickStep(mWorld, mModel.simulation.dt);
        else
            dWorldStep(mWorld, mModel.simulation.dt);
    }

    void poses(std::vector<Pose>& out) override
    {
        out.resize(mBodies.size());
        for (std::size_t b = 0; b < out.size(); ++b)
        {
            const dReal* x = dBodyGetPosition(mBodies[b]);
            const dReal* q = dBodyGetQuaternion(mBodies[b]);
            out[b] = {core::Vec3(x[0], x[1], x[2]), core::Quat(q[0], q[1], q[2], q[3])};
        }
    }

  private:
    void addJoint(const core::Joint& joint)
    {
        dBodyID parent =
            joint.parent == core::cWorld ? nullptr : mBodies[static_cast<std::size_t>(joint.parent)];
        dBodyID child = mBodies[static_cast<std::size_t>(joint.child)];
        const core::Body& c = mModel.bodies[static_cast<std::size_t>(joint.child)];
        const core::Vec3 anchor = c.position_W + c.orientation_WB * joint.anchorChild;
        dJointID j = nullptr;
        switch (joint.type)
        {
        case core::JointType::Ball:
            j = dJointCreateBall(mWorld, nullptr);
            dJointAttach(j, parent, child);
            dJointSetBallAnchor(j, anchor.x(), anchor.y(), anchor.z());
            break;
        case core::JointType::Revolute:
        {
            j = dJointCreateHinge(mWorld, nullptr);
            dJointAttach(j, parent, child);
            dJointSetHingeAnchor(j, anchor.x(), anchor.y(), anchor.z());
            const core::Vec3 axis = c.orientation_WB * joint.axisChild;
            dJointSetHingeAxis(j, axis.x(), axis.y(), axis.z());
            break;
        }
        default: // Fixed
            j = dJointCreateFixed(mWorld, nullptr);
            dJointAttach(j, parent, child);
            dJointSetFixed(j);
            break;
        }
    }

    const core::Model& mModel;
    bool mQuickStep;
    dWorldID mWorld = nullptr;
    std::vector<dBodyID> mBodies;
};

} // namespace

std::unique_ptr<Engine> makeOde(const core::Model& model, bool quickStep)
{
    return std::make_unique<OdeEngine>(model, quickStep);
}

} // namespace frontier::peers
