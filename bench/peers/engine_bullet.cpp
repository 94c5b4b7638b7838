// bench/peers/engine_bullet.cpp: Bullet 3 (double precision), two ways: btMultiBody (reduced
// coordinates, Featherstone's articulated-body algorithm) and rigid bodies with constraints solved
// by sequential impulses (btSequentialImpulseConstraintSolver, 10 iterations or a spelling's), each with
// Bullet's usual settings except damping, which is set to the scene's (none): btMultiBody's default of 0.04
// would take energy out of a scene that has no damping.
//
// Contacts: each body's shapes as one Bullet shape (a btCompoundShape when it has several or one
// off its centre of mass; a static plane as btStaticPlaneShape in the static body's frame), on a
// btRigidBody or a btMultiBodyLinkCollider; static bodies as collision objects. Which pairs
// collide is decided by Frontier's filter in an overlap filter callback. Bullet combines two
// objects' friction and restitution as products, so each object gets the square roots of the
// scene's: every pair then has the scene's values. A mesh is its convex hull (btConvexHullShape).
//
// Bullet takes a body's frame to be its principal axes: a body whose inertia is not diagonal is
// built in the frame of its principal axes (principal.h) and its pose turned back. Revolute limits:
// btMultiBodyJointLimitConstraint on a multibody, btHingeConstraint::setLimit on rigid bodies
// (the hinge frames built so that the initial pose is angle 0, where the model's limits count from).
//
// Limits and warnings: Bullet's pools and pair caches grow as needed; a contact manifold keeps at
// most 4 points per pair of bodies by design. Bullet reports trouble through the world's debug
// drawer (reportErrorWarning: an object whose bounding box overflows is taken out of the
// simulation): the drawer here draws nothing and makes each report a warning of the engine.
// btMultiBody cuts every velocity coordinate to +-100 (m_maxCoordinateVelocity, rad/s or m/s, its
// default): checkStep makes a coordinate at that bound a warning.
#include "bench/peers/contacts.h"
#include "bench/peers/engine.h"
#include "bench/peers/principal.h"
#include "bench/peers/tree.h"

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyLink.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <algorithm>
#include <btBulletDynamicsCommon.h>
#include <cmath>

namespace frontier::peers
{
namespace
{

constexpr double cHullMargin = 0.001; // m

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

// Bullet's error and warning reports (btIDebugDraw::reportErrorWarning) as warnings of the
// engine, at the step it is taking; it draws nothing.
class WarningDrawer final : public btIDebugDraw
{
  public:
    WarningDrawer(WarningLog& log, const long& step) : mLog(log), mStep(step) {}
    void reportErrorWarning(const char* text) override { mLog.raise(std::string("Bullet: ") + text, mStep); }
    void drawLine(const btVector3&, const btVector3&, const btVector3&) override {}
    void drawContactPoint(const btVector3&, const btVector3&, btScalar, int, const btVector3&) override {}
    void draw3dText(const btVector3&, const char*) override {}
    void setDebugMode(int) override {}
    int getDebugMode() const override { return DBG_NoDebug; }

  private:
    WarningLog& mLog;
    const long& mStep;
};

// Parts every Bullet world needs, owned together (Bullet keeps raw pointers to them), with the
// collision geometry, the pair filter and the warning drawer.
struct BulletParts
{
    BulletParts(const core::Model& m, WarningLog& log)
        : model(m), contacts(hasContacts(m)), drawer(log, steps)
    {
        if (contacts)
            pairs = std::make_unique<collision::PairFilter>(m);
    }

    // Frontier's pair filter; the collision objects' user index is their body's index.
    struct Filter final : btOverlapFilterCallback
    {
        const collision::PairFilter* pairs = nullptr;
        bool needBroadphaseCollision(btBroadphaseProxy* p0, btBroadphaseProxy* p1) const override
        {
            const auto* a = static_cast<const btCollisionObject*>(p0->m_clientObject);
            const auto* b = static_cast<const btCollisionObject*>(p1->m_clientObject);
            return pairs->allowed(a->getUserIndex(), b->getUserIndex());
        }
    };

    // The pair filter and the warning drawer.
    void install(btCollisionWorld& world)
    {
        world.setDebugDrawer(&drawer);
        if (!contacts)
            return;
        filter.pairs = pairs.get();
        world.getPairCache()->setOverlapFilterCallback(&filter);
    }

    // The body's shapes as one Bullet shape in its frame; null when it has none.
    btCollisionShape* shapeOf(const core::Body& body)
    {
        if (!contacts || body.shapes.empty())
            return nullptr;
        std::vector<std::pair<btCollisionShape*, btTransform>> parts;
        for (const core::Shape& shape : body.shapes)
        {
            btTransform pose(toBt(shape.rotation_BS), toBt(shape.position_BS));
            std::unique_ptr<btCollisionShape> made;
            switch (shape.type)
            {
            case core::ShapeType::Box:
                made = std::make_unique<btBoxShape>(toBt(0.5 * shape.size));
                break;
            case core::ShapeType::Sphere:
                made = std::make_unique<btSphereShape>(shape.radius);
                break;
            case core::ShapeType::Capsule: // radius, cylindrical length, along local z
                made = std::make_unique<btCapsuleShapeZ>(shape.radius, shape.length);
                break;
            case core::ShapeType::Cylinder: // half extents (radius, radius, half the height)
                made = std::make_unique<btCylinderShapeZ>(
                    btVector3(shape.radius, shape.radius, 0.5 * shape.length));
                break;
            case core::ShapeType::Plane: // world n . x = offset, in the static body's frame
            {
                const core::Quat toBody = body.orientation_WB.conjugate();
                made = std::make_unique<btStaticPlaneShape>(toBt(toBody * shape.normal),
                                                            shape.offset - shape.normal.dot(body.position_W));
                pose.setIdentity();
                break;
            }
            case core::ShapeType::Mesh: // its convex hull, 1 mm margin (Bullet's default 4 cm pads hulls)
            {
                auto hull = std::make_unique<btConvexHullShape>();
                for (const core::Vec3& v : meshHull(body, shape).vertices)
                    hull->addPoint(toBt(v), false);
                hull->recalcLocalAabb();
                hull->setMargin(cHullMargin);
                made = std::move(hull);
                break;
            }
            }
            parts.emplace_back(made.get(), pose);
            shapes.push_back(std::move(made));
        }
        if (parts.size() == 1 && parts.front().second == btTransform::getIdentity())
            return parts.front().first;
        auto compound = std::make_unique<btCompoundShape>();
        for (auto& [shape, pose] : parts)
            compound->addChildShape(pose, shape);
        shapes.push_back(std::move(compound));
        return shapes.back().get();
    }

    void setSurface(btCollisionObject& object, int body) const
    {
        object.setUserIndex(body);
        object.setFriction(std::sqrt(model.contact.friction));
        object.setRestitution(std::sqrt(model.contact.restitution));
    }

    // Static bodies as collision objects.
    void addStatics(btCollisionWorld& world)
    {
        for (std::size_t b = 0; b < model.bodies.size(); ++b)
        {
            const core::Body& body = model.bodies[b];
            btCollisionShape* shape = body.isStatic ? shapeOf(body) : nullptr;
            if (!shape)
                continue;
            auto object = std::make_unique<btCollisionObject>();
            object->setCollisionShape(shape);
            object->setWorldTransform(btTransform(toBt(body.orientation_WB), toBt(body.position_W)));
            setSurface(*object, static_cast<int>(b));
            world.addCollisionObject(object.get(), btBroadphaseProxy::StaticFilter,
                                     btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
            statics.push_back(std::move(object));
        }
    }

    void removeStatics(btCollisionWorld& world)
    {
        for (auto& object : statics)
            world.removeCollisionObject(object.get());
    }

    const core::Model& model;
    bool contacts;
    long steps = 0; // the engine's steps so far (the one it is taking)
    WarningDrawer drawer;
    std::unique_ptr<collision::PairFilter> pairs;
    Filter filter;
    std::vector<std::unique_ptr<btCollisionShape>> shapes;
    std::vector<std::unique_ptr<btCollisionObject>> statics;
    btDefaultCollisionConfiguration configuration;
    btCollisionDispatcher dispatcher{&configuration};
    btDbvtBroadphase broadphase;
};

// One btMultiBody per tree (tree.h): a free root is its base, a tree joined to the world has a
// massless fixed base. An angle (universal) joint is two revolute joints with a small link
// between them (1e-3 of the child's mass and moments, at the anchor): btMultiBody has no
// universal joint.
class BulletMultibody final : public Engine
{
  public:
    explicit BulletMultibody(const core::Model& model)
        : mModel(inPrincipalFrames(model, mRotation_BP)), mTree(jointTree(mModel)), mParts(mModel, mLog)
    {
        mWorld = std::make_unique<btMultiBodyDynamicsWorld>(&mParts.dispatcher, &mParts.broadphase, &mSolver,
                                                            &mParts.configuration);
        mWorld->setGravity(toBt(mModel.simulation.gravity));
        mParts.install(*mWorld);
        mParts.addStatics(*mWorld);
        mLinkOf.assign(mModel.bodies.size(), {-1, -1});
        std::size_t k = 0;
        while (k < mTree.size())
        {
            std::size_t end = k + 1;
            while (end < mTree.size() && !isRoot(mTree[end]))
                ++end;
            buildTree(k, end);
            k = end;
        }
    }

    ~BulletMultibody() override
    {
        for (auto& c : mLimits)
            mWorld->removeMultiBodyConstraint(c.get());
        for (auto& c : mColliders)
            mWorld->removeCollisionObject(c.get());
        mParts.removeStatics(*mWorld);
        for (auto& b : mBodies)
            mWorld->removeMultiBody(b.get());
    }

    void step() override
    {
        ++mParts.steps;
        mWorld->stepSimulation(mModel.simulation.dt, 0, mModel.simulation.dt);
    }

    // A velocity coordinate at btMultiBody's bound was cut there.
    void checkStep() override
    {
        for (const auto& b : mBodies)
        {
            const btScalar* v = b->getVelocityVector();
            const btScalar bound = b->getMaxCoordinateVelocity();
            for (int k = 0; k < 6 + b->getNumDofs(); ++k)
                if (std::abs(v[k]) >= bound)
                {
                    mLog.raise("Bullet: a velocity coordinate of a btMultiBody reached its bound of " +
                                   std::to_string(static_cast<int>(bound)) +
                                   " (m_maxCoordinateVelocity, rad/s or m/s), which cuts it",
                               mParts.steps);
                    break;
                }
        }
    }

    void poses(std::vector<Pose>& out) override
    {
        for (auto& b : mBodies)
            b->forwardKinematics(mScratchRotations, mScratchOrigins);
        out.resize(mModel.bodies.size());
        for (std::size_t b = 0; b < out.size(); ++b)
        {
            const auto [tree, link] = mLinkOf[b];
            if (tree < 0)
            {
                out[b] = {mModel.bodies[b].position_W, mModel.bodies[b].orientation_WB};
                continue;
            }
            const btMultiBody& body = *mBodies[static_cast<std::size_t>(tree)];
            const btTransform t =
                link < 0 ? body.getBaseWorldTransform() : body.getLink(link).m_cachedWorldTransform;
            out[b] = {fromBt(t.getOrigin()), fromBt(t.getRotation()) * mRotation_BP[b].conjugate()};
        }
    }

  private:
    // The tree mTree[first, end).
    void buildTree(std::size_t first, std::size_t end)
    {
        const int tree = static_cast<int>(mBodies.size());
        const bool fixedBase = mTree[first].joint >= 0; // joined to the world: a massless fixed base
        int links = 0;
        for (std::size_t k = first; k < end; ++k)
        {
            if (k == first && !fixedBase)
                continue;
            const core::Joint& joint = mModel.joints[static_cast<std::size_t>(mTree[k].joint)];
            links += joint.type == core::JointType::Angle ? 2 : 1;
        }
        const core::Body& root = mModel.bodies[static_cast<std::size_t>(mTree[first].body)];
        std::unique_ptr<btMultiBody> body;
        if (fixedBase)
            body = std::make_unique<btMultiBody>(links, 0.0, btVector3(0, 0, 0), true, false);
        else
        {
            body = std::make_unique<btMultiBody>(links, root.mass, principalInertia(root), false, false);
            body->setBaseWorldTransform(btTransform(toBt(root.orientation_WB), toBt(root.position_W)));
            mLinkOf[static_cast<std::size_t>(mTree[first].body)] = {tree, -1};
        }
        mBodies.push_back(std::move(body));
        int next = 0;
        for (std::size_t k = fixedBase ? first : first + 1; k < end; ++k)
            next = setupLink(tree, mTree[k], next);
        btMultiBody& mb = *mBodies.back();
        mb.finalizeMultiDof();
        if (!fixedBase)
        {
            // The tree's rigid velocity (tree.h): the base's, in world axes; the joints at rest.
            // (After finalizeMultiDof, which sizes the velocity buffer.)
            mb.setBaseVel(toBt(root.velocity_W));
            mb.setBaseOmega(toBt(root.angularVelocity_W));
        }
        mb.setLinearDamping(0.0);
        mb.setAngularDamping(0.0);
        mb.setCanSleep(false);
        mWorld->addMultiBody(&mb);
        addColliders(tree, first, end);
        addLimits(tree, first, end);
    }

    bool hasLimits() const
    {
        return std::any_of(mModel.joints.begin(), mModel.joints.end(),
                           [](const core::Joint& joint) { return joint.limits.has_value(); });
    }

    // The revolute joints' limits (the link's coordinate is 0 at the initial pose, as the model's).
    void addLimits(int tree, std::size_t first, std::size_t end)
    {
        btMultiBody& mb = *mBodies[static_cast<std::size_t>(tree)];
        for (std::size_t k = first; k < end; ++k)
        {
            if (mTree[k].joint < 0)
                continue;
            const core::Joint& joint = mModel.joints[static_cast<std::size_t>(mTree[k].joint)];
            if (!joint.limits)
                continue;
            const int link = mLinkOf[static_cast<std::size_t>(mTree[k].body)].second;
            auto limit = std::make_unique<btMultiBodyJointLimitConstraint>(&mb, link, (*joint.limits)[0],
                                                                           (*joint.limits)[1]);
            mWorld->addMultiBodyConstraint(limit.get());
            mLimits.push_back(std::move(limit));
        }
    }

    // Sets up the link(s) of one tree link from link index i; returns the next free index.
    int setupLink(int tree, const TreeLink& link, int i)
    {
        btMultiBody& mb = *mBodies[static_cast<std::size_t>(tree)];
        const core::Body& body = mModel.bodies[static_cast<std::size_t>(link.body)];
        const core::Joint& joint = mModel.joints[static_cast<std::size_t>(link.joint)];
        const int parentLink =
            link.parent == core::cWorld ? -1 : mLinkOf[static_cast<std::size_t>(link.parent)].second;
        // rotParentToThis rotates a parent-frame vector into this frame: q_child^-1 q_parent.
        const btQuaternion parentToThis = toBt(relativeRotation(mModel, link.parent, link.body).conjugate());
        const btVector3 parentComToPivot = toBt(parentAnchor(mModel, joint));
        const btVector3 pivotToCom = toBt(-joint.anchorChild);
        // Parent-child collisions are left to the overlap filter (Frontier's rule).
        switch (joint.type)
        {
        case core::JointType::Ball:
            mb.setupSpherical(i, body.mass, principalInertia(body), parentLink, parentToThis,
                              parentComToPivot, pivotToCom, false);
            break;
        case core::JointType::Revolute:
            mb.setupRevolute(i, body.mass, principalInertia(body), parentLink, parentToThis,
                             toBt(joint.axisChild), parentComToPivot, pivotToCom, false);
            break;
        case core::JointType::Angle:
        {
            // The small link: the parent's orientation, its centre at the anchor, turning about a1.
            const double scale = 1e-3;
            const btVector3 inertia = principalInertia(body);
            const double least = std::min({inertia.x(), inertia.y(), inertia.z()});
            const core::Vec3 a1 = link.parent == core::cWorld
                                      ? parentRotation(mModel, joint) * joint.perpParent1
                                      : joint.perpParent1;
            mb.setupRevolute(i, scale * body.mass, btVector3(1, 1, 1) * (scale * least), parentLink,
                             btQuaternion::getIdentity(), toBt(a1), parentComToPivot, btVector3(0, 0, 0),
                             false);
            ++i;
            mb.setupRevolute(i, body.mass, inertia, i - 1, parentToThis, toBt(joint.angleChildAxis),
                             btVector3(0, 0, 0), pivotToCom, false);
            break;
        }
        default: // Fixed (jointTree refuses the rest)
            mb.setupFixed(i, body.mass, principalInertia(body), parentLink, parentToThis, parentComToPivot,
                          pivotToCom, false);
            break;
        }
        mLinkOf[static_cast<std::size_t>(link.body)] = {tree, i};
        return i + 1;
    }

    void addColliders(int tree, std::size_t first, std::size_t end)
    {
        btMultiBody& mb = *mBodies[static_cast<std::size_t>(tree)];
        mb.forwardKinematics(mScratchRotations, mScratchOrigins);
        for (std::size_t k = first; k < end; ++k)
        {
            const int b = mTree[k].body;
            const core::Body& body = mModel.bodies[static_cast<std::size_t>(b)];
            btCollisionShape* shape = mParts.shapeOf(body);
            // Bullet solves a joint limit in the island of its link's collider, and skips it when
            // the link has none: links without shapes get an empty one that collides with nothing.
            if (!shape && !hasLimits())
                continue;
            const int link = mLinkOf[static_cast<std::size_t>(b)].second;
            auto collider = std::make_unique<btMultiBodyLinkCollider>(&mb, link);
            collider->setCollisionShape(shape ? shape : &mNoShape);
            collider->setWorldTransform(btTransform(toBt(body.orientation_WB), toBt(body.position_W)));
            mParts.setSurface(*collider, b);
            if (shape)
                mWorld->addCollisionObject(collider.get(), btBroadphaseProxy::DefaultFilter,
                                           btBroadphaseProxy::AllFilter);
            else
                mWorld->addCollisionObject(collider.get(), 0, 0);
            if (link < 0)
                mb.setBaseCollider(collider.get());
            else
                mb.getLink(link).m_collider = collider.get();
            mColliders.push_back(std::move(collider));
        }
    }

    std::vector<core::Quat> mRotation_BP; // per body: principal frame to the model's (principal.h)
    core::Model mModel;                   // in principal frames
    std::vector<TreeLink> mTree;
    BulletParts mParts;
    btMultiBodyConstraintSolver mSolver;
    std::unique_ptr<btMultiBodyDynamicsWorld> mWorld;
    std::vector<std::unique_ptr<btMultiBody>> mBodies; // one per tree
    btEmptyShape mNoShape;                             // the collider of a link without shapes (addColliders)
    std::vector<std::unique_ptr<btMultiBodyLinkCollider>> mColliders;
    std::vector<std::unique_ptr<btMultiBodyJointLimitConstraint>> mLimits;
    std::vector<std::pair<int, int>> mLinkOf; // body -> (tree, link; -1: the base); tree -1: static
    btAlignedObjectArray<btQuaternion> mScratchRotations;
    btAlignedObjectArray<btVector3> mScratchOrigins;
};

class BulletSequentialImpulses final : public Engine
{
  public:
    BulletSequentialImpulses(const core::Model& model, const EngineSettings& settings)
        : mModel(inPrincipalFrames(model, mRotation_BP)), mParts(mModel, mLog)
    {
        jointTree(mModel); // the scope check
        mWorld = std::make_unique<btDiscreteDynamicsWorld>(&mParts.dispatcher, &mParts.broadphase, &mSolver,
                                                           &mParts.configuration);
        if (settings.iterations)
            mWorld->getSolverInfo().m_numIterations = *settings.iterations;
        mWorld->setGravity(toBt(mModel.simulation.gravity));
        mParts.install(*mWorld);
        mParts.addStatics(*mWorld);
        for (std::size_t b = 0; b < mModel.bodies.size(); ++b)
        {
            const core::Body& body = mModel.bodies[b];
            if (body.isStatic)
            {
                mBodies.push_back(nullptr);
                continue;
            }
            btCollisionShape* shape = mParts.shapeOf(body);
            btRigidBody::btRigidBodyConstructionInfo info(body.mass, nullptr, shape ? shape : &mEmpty,
                                                          principalInertia(body));
            info.m_startWorldTransform = btTransform(toBt(body.orientation_WB), toBt(body.position_W));
            auto rigid = std::make_unique<btRigidBody>(info);
            rigid->setActivationState(DISABLE_DEACTIVATION);
            rigid->setLinearVelocity(toBt(body.velocity_W));
            rigid->setAngularVelocity(toBt(body.angularVelocity_W));
            mParts.setSurface(*rigid, static_cast<int>(b));
            if (shape)
                mWorld->addRigidBody(rigid.get());
            else
                mWorld->addRigidBody(rigid.get(), 0, 0); // no collision group or mask: no contacts
            mBodies.push_back(std::move(rigid));
        }
        for (const core::Joint& joint : mModel.joints)
            addJoint(joint);
    }

    ~BulletSequentialImpulses() override
    {
        for (auto& c : mConstraints)
            mWorld->removeConstraint(c.get());
        for (auto& b : mBodies)
            if (b)
                mWorld->removeRigidBody(b.get());
        mParts.removeStatics(*mWorld);
    }

    void step() override
    {
        ++mParts.steps;
        mWorld->stepSimulation(mModel.simulation.dt, 0, mModel.simulation.dt);
    }

    void poses(std::vector<Pose>& out) override
    {
        out.resize(mBodies.size());
        for (std::size_t b = 0; b < out.size(); ++b)
        {
            if (!mBodies[b])
            {
                out[b] = {mModel.bodies[b].position_W, mModel.bodies[b].orientation_WB};
                continue;
            }
            const btTransform& t = mBodies[b]->getCenterOfMassTransform();
            out[b] = {fromBt(t.getOrigin()), fromBt(t.getRotation()) * mRotation_BP[b].conjugate()};
        }
    }

  private:
    void addJoint(const core::Joint& joint)
    {
        const int parent = treeParent(mModel, joint);
        btRigidBody& a = parent == core::cWorld ? btTypedConstraint::getFixedBody()
                                                : *mBodies[static_cast<std::size_t>(parent)];
        btRigidBody& b = *mBodies[static_cast<std::size_t>(joint.child)];
        const btVector3 pivotA = toBt(parentAnchor(mModel, joint));
        const btVector3 pivotB = toBt(joint.anchorChild);
        std::unique_ptr<btTypedConstraint> c;
        switch (joint.type)
        {
        case core::JointType::Ball:
            c = std::make_unique<btPoint2PointConstraint>(a, b, pivotA, pivotB);
            break;
        case core::JointType::Revolute:
        {
            // Frames with z along the axis that coincide at the initial pose: the hinge angle is 0
            // there, where the model's limits count from.
            const core::Body& child = mModel.bodies[static_cast<std::size_t>(joint.child)];
            const core::Quat toAxis_W =
                core::Quat::FromTwoVectors(core::Vec3::UnitZ(), child.orientation_WB * joint.axisChild);
            const core::Quat parentWorld =
                parent == core::cWorld ? core::Quat::Identity() : parentRotation(mModel, joint);
            auto hinge = std::make_unique<btHingeConstraint>(
                a, b, btTransform(toBt(parentWorld.conjugate() * toAxis_W), pivotA),
                btTransform(toBt(child.orientation_WB.conjugate() * toAxis_W), pivotB));
            if (joint.limits) // btHingeConstraint's angle turns the other way: A's about the axis from B
                hinge->setLimit(-(*joint.limits)[1], -(*joint.limits)[0]);
            c = std::move(hinge);
            break;
        }
        case core::JointType::Angle:
        {
            // btUniversalConstraint takes world anchor and axes at the initial pose (a1 on the
            // parent, b2 on the child). It is a 6-dof constraint with Euler-angle limits: the
            // second angle stays within +-90 degrees.
            const core::Body& child = mModel.bodies[static_cast<std::size_t>(joint.child)];
            const core::Vec3 anchor = child.position_W + child.orientation_WB * joint.anchorChild;
            c = std::make_unique<btUniversalConstraint>(
                a, b, toBt(anchor), toBt(parentRotation(mModel, joint) * joint.perpParent1),
                toBt(child.orientation_WB * joint.angleChildAxis));
            break;
        }
        default: // Fixed: the frames at the initial pose
        {
            const core::Quat rotation = relativeRotation(mModel, parent, joint.child);
            c = std::make_unique<btFixedConstraint>(a, b, btTransform(toBt(rotation), pivotA),
                                                    btTransform(btQuaternion::getIdentity(), pivotB));
            break;
        }
        }
        mWorld->addConstraint(c.get(), true);
        mConstraints.push_back(std::move(c));
    }

    std::vector<core::Quat> mRotation_BP; // per body: principal frame to the model's (principal.h)
    core::Model mModel;                   // in principal frames
    BulletParts mParts;
    btSequentialImpulseConstraintSolver mSolver;
    btEmptyShape mEmpty;
    std::unique_ptr<btDiscreteDynamicsWorld> mWorld;
    std::vector<std::unique_ptr<btRigidBody>> mBodies; // per model body; null for static ones
    std::vector<std::unique_ptr<btTypedConstraint>> mConstraints;
};

} // namespace

std::unique_ptr<Engine> makeBulletMultibody(const core::Model& model)
{
    return std::make_unique<BulletMultibody>(model);
}

std::unique_ptr<Engine> makeBulletSequentialImpulses(const core::Model& model, const EngineSettings& settings)
{
    return std::make_unique<BulletSequentialImpulses>(model, settings);
}

} // namespace frontier::peers
