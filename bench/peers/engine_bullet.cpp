// bench/peers/engine_bullet.cpp: Bullet 3 (double precision), two ways: btMultiBody (reduced
// coordinates, Featherstone's articulated-body algorithm) and rigid bodies with constraints solved
// by sequential impulses (btSequentialImpulseConstraintSolver, 10 iterations), each with Bullet's
// usual settings except damping, which is set to the scene's (none): btMultiBody's default of 0.04
// would take energy out of a scene that has no damping.
#include "bench/peers/engine.h"
#include "bench/peers/tree.h"

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyLink.h>
#include <btBulletDynamicsCommon.h>
#include <cmath>

namespace frontier::peers
{
namespace
{

btVector3 toBt(const core::Vec3& v)
{
    return {v.x(), v.y(), v.z()};
}
btQuaternion toBt(const core::Quat& q)
{
    return {q.x(), q.y(), q.z(), q.w()};
}
core::Vec3 fromBt(const btVector3& v)
{
    return {v.x(), v.y(), v.z()};
}
core::Quat fromBt(const btQuaternion& q)
{
    return {q.w(), q.x(), q.y(), q.z()};
}

// Bullet takes principal moments in the body frame: the model's inertia must be diagonal there.
btVector3 principalInertia(const core::Body& body)
{
    const core::Mat3& I = body.inertia_B;
    const double offDiagonal = std::abs(I(0, 1)) + std::abs(I(0, 2)) + std::abs(I(1, 2));
    if (offDiagonal > 1e-12 * I.trace())
        throw Unsupported("body '" + body.name +
                          "': Bullet needs an inertia that is diagonal in the body frame");
    return {I(0, 0), I(1, 1), I(2, 2)};
}

// Parts every Bullet world needs, owned together (Bullet keeps raw pointers to them).
struct BulletParts
{
    btDefaultCollisionConfiguration configuration;
    btCollisionDispatcher dispatcher{&configuration};
    btDbvtBroadphase broadphase;
};

class BulletMultibody final : public Engine
{
  public:
    explicit BulletMultibody(const core::Model& model) : mModel(model), mTree(jointTree(model))
    {
        mWorld = std::make_unique<btMultiBodyDynamicsWorld>(&mParts.dispatcher, &mParts.broadphase, &mSolver,
                                                            &mParts.configuration);
        mWorld->setGravity(toBt(model.simulation.gravity));
        const bool fixedBase = mTree.front().joint >= 0; // joined to the world: a massless fixed base
        const int links = static_cast<int>(mTree.size()) - (fixedBase ? 0 : 1);
        const core::Body& root = model.bodies[static_cast<std::size_t>(mTree.front().body)];
        if (fixedBase)
            mBody = std::make_unique<btMultiBody>(links, 0.0, btVector3(0, 0, 0), true, false);
        else
        {
            mBody = std::make_unique<btMultiBody>(links, root.mass, principalInertia(root), false, false);
            mBody->setBaseWorldTransform(btTransform(toBt(root.orientation_WB), toBt(root.position_W)));
        }
        mLinkOf.assign(model.bodies.size(), -1); // body -> link index (-1: the base)
        for (std::size_t k = fixedBase ? 0 : 1; k < mTree.size(); ++k)
            mLinkOf[static_cast<std::size_t>(mTree[k].body)] = static_cast<int>(k) - (fixedBase ? 0 : 1);
        for (std::size_t k = fixedBase ? 0 : 1; k < mTree.size(); ++k)
            setupLink(mTree[k]);
        mBody->finalizeMultiDof();
        mBody->setLinearDamping(0.0);
        mBody->setAngularDamping(0.0);
        mBody->setCanSleep(false);
        mWorld->addMultiBody(mBody.get());
    }

    ~BulletMultibody() override { mWorld->removeMultiBody(mBody.get()); }

    void step() override { mWorld->stepSimulation(mModel.simulation.dt, 0, mModel.simulation.dt); }

    void poses(std::vector<Pose>& out) override
    {
        mBody->forwardKinematics(mScratchRotations, mScratchOrigins);
        out.resize(mModel.bodies.size());
        for (std::size_t b = 0; b < out.size(); ++b)
        {
            const int link = mLinkOf[b];
            const btTransform t =
                link < 0 ? mBody->getBaseWorldTransform() : mBody->getLink(link).m_cachedWorldTransform;
            out[b] = {fromBt(t.getOrigin()), fromBt(t.getRotation())};
        }
    }

  private:
    void setupLink(const TreeLink& link)
    {
        const core::Body& body = mModel.bodies[static_cast<std::size_t>(link.body)];
        const core::Joint& joint = mModel.joints[static_cast<std::size_t>(link.joint)];
        const int parentLink =
            link.parent == core::cWorld ? -1 : mLinkOf[static_cast<std::size_t>(link.parent)];
        // rotParentToThis rotates a parent-frame vector into this frame: q_child^-1 q_parent.
        const btQuaternion parentToThis = toBt(relativeRotation(mModel, link.parent, link.body).conjugate());
        const btVector3 parentComToPivot = toBt(joint.anchorParent);
        const btVector3 pivotToCom = toBt(-joint.anchorChild);
        const int i = mLinkOf[static_cast<std::size_t>(link.body)];
        switch (joint.type)
        {
        case core::JointType::Ball:
            mBody->setupSpherical(i, body.mass, principalInertia(body), parentLink, parentToThis,
                                  parentComToPivot, pivotToCom, true);
            break;
        case core::JointType::Revolute:
            mBody->setupRevolute(i, body.mass, principalInertia(body), parentLink, parentToThis,
                                 toBt(joint.axisChild), parentComToPivot, pivotToCom, true);
            break;
        default: // Fixed (jointTree refuses the rest)
            mBody->setupFixed(i, body.mass, principalInertia(body), parentLink, parentToThis,
                              parentComToPivot, pivotToCom, true);
            break;
        }
    }

    const core::Model& mModel;
    std::vector<TreeLink> mTree;
    BulletParts mParts;
    btMultiBodyConstraintSolver mSolver;
    std::unique_ptr<btMultiBodyDynamicsWorld> mWorld;
    std::unique_ptr<btMultiBody> mBody;
    std::vector<int> mLinkOf;
    btAlignedObjectArray<btQuaternion> mScratchRotations;
    btAlignedObjectArray<btVector3> mScratchOrigins;
};

class BulletSequentialImpulses final : public Engine
{
  public:
    explicit BulletSequentialImpulses(const core::Model& model) : mModel(model)
    {
        jointTree(model); // the scope check
        mWorld = std::make_unique<btDiscreteDynamicsWorld>(&mParts.dispatcher, &mParts.broadphase, &mSolver,
                                                           &mParts.configuration);
        mWorld->setGravity(toBt(model.simulation.gravity));
        for (const core::Body& body : model.bodies)
        {
            btRigidBody::btRigidBodyConstructionInfo info(body.mass, nullptr, &mShape,
                                                          principalInertia(body));
            info.m_startWorldTransform = btTransform(toBt(body.orientation_WB), toBt(body.position_W));
            auto rigid = std::make_unique<btRigidBody>(info);
            rigid->setActivationState(DISABLE_DEACTIVATION);
            mWorld->addRigidBody(rigid.get(), 0, 0); // no collision group or mask: no contacts
            mBodies.push_back(std::move(rigid));
        }
        for (const core::Joint& joint : model.joints)
            addJoint(joint);
    }

    ~BulletSequentialImpulses() override
    {
        for (auto& c : mConstraints)
            mWorld->removeConstraint(c.get());
        for (auto& b : mBodies)
            mWorld->removeRigidBody(b.get());
    }

    void step() override { mWorld->stepSimulation(mModel.simulation.dt, 0, mModel.simulation.dt); }

    void poses(std::vector<Pose>& out) override
    {
        out.resize(mBodies.size());
        for (std::size_t b = 0; b < out.size(); ++b)
        {
            const btTransform& t = mBodies[b]->getCenterOfMassTransform();
            out[b] = {fromBt(t.getOrigin()), fromBt(t.getRotation())};
        }
    }

  private:
    void addJoint(const core::Joint& joint)
    {
        btRigidBody& a = joint.parent == core::cWorld ? btTypedConstraint::getFixedBody()
                                                      : *mBodies[static_cast<std::size_t>(joint.parent)];
        btRigidBody& b = *mBodies[static_cast<std::size_t>(joint.child)];
        const btVector3 pivotA = toBt(joint.anchorParent);
        const btVector3 pivotB = toBt(joint.anchorChild);
        std::unique_ptr<btTypedConstraint> c;
        switch (joint.type)
        {
        case core::JointType::Ball:
            c = std::make_unique<btPoint2PointConstraint>(a, b, pivotA, pivotB);
            break;
        case core::JointType::Revolute:
            c = std::make_unique<btHingeConstraint>(a, b, pivotA, pivotB, toBt(joint.axisParent),
                                                    toBt(joint.axisChild));
            break;
        default: // Fixed: the frames at the initial pose
        {
            const core::Quat rotation = relativeRotation(mModel, joint.parent, joint.child);
            c = std::make_unique<btFixedConstraint>(a, b, btTransform(toBt(rotation), pivotA),
                                                    btTransform(btQuaternion::getIdentity(), pivotB));
            break;
        }
        }
        mWorld->addConstraint(c.get(), true);
        mConstraints.push_back(std::move(c));
    }

    const core::Model& mModel;
    BulletParts mParts;
    btSequentialImpulseConstraintSolver mSolver;
    btEmptyShape mShape;
    std::unique_ptr<btDiscreteDynamicsWorld> mWorld;
    std::vector<std::unique_ptr<btRigidBody>> mBodies;
    std::vector<std::unique_ptr<btTypedConstraint>> mConstraints;
};

} // namespace

std::unique_ptr<Engine> makeBulletMultibody(const core::Model& model)
{
    return std::make_unique<BulletMultibody>(model);
}

std::unique_ptr<Engine> makeBulletSequentialImpulses(const core::Model& model)
{
    return std::make_unique<BulletSequentialImpulses>(model);
}

} // namespace frontier::peers
