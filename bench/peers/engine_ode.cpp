// bench/peers/engine_ode.cpp: ODE 0.16 (double precision), with dWorldQuickStep (projected
// Gauss-Seidel, 20 iterations or a spelling's) or dWorldStep (the direct "big matrix" LCP solver), ODE's
// usual settings otherwise (ERP 0.2, its default CFM, gyroscopic term on). Contacts: the shapes as ODE geoms
// in one hash space (a static plane as dCreatePlane), dCollide on the pairs Frontier's filter allows (every
// point it gives: below), contact joints with Coulomb friction (dContactApprox1, the friction pyramid) of the
// scene's mu and its restitution as bounce. A mesh is its convex hull (dCreateConvex). Revolute limits are
// the hinge's stops (dParamLoStop, dParamHiStop), its angle 0 at the initial pose as the model's.
//
// Limits and messages: the contact joints live in a joint group that grows as needed. dCollide
// writes at most as many points per pair of geoms as it is given room for, and drops the rest
// without a word (a convex hull on the floor gives one point per corner below it: up to 78 for a
// foot of Debian's DRC-Hubo): the room is sized from the scene, 8 (the most of ODE's colliders of
// primitive shapes, box-box) plus the corners of the two largest hulls, and a pair that fills it
// anyway is a warning.
//
// ODE's message handlers are global and print (a message) or print and end the process (an error,
// an internal error): here a message is a warning of the engine that is stepping (or being set
// up), an error ends its run with an EngineError. QuickStep reorders its rows with ODE's global
// random generator: every engine starts it from ODE's initial seed, as a new process would, so
// that a run does not depend on the runs before it.
#include "bench/peers/contacts.h"
#include "bench/peers/engine.h"
#include "bench/peers/tree.h"

#include <algorithm>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <functional>
#include <ode/ode.h>
#include <vector>

namespace frontier::peers
{
namespace
{

constexpr int cPrimitivePoints = 8; // the most points ODE's colliders give two primitive shapes (box-box)

thread_local WarningLog* tLog = nullptr;
thread_local long tStep = 0;

std::string formatted(const char* format, va_list arguments)
{
    char buffer[512];
    std::vsnprintf(buffer, sizeof buffer, format, arguments);
    return buffer;
}

void onMessage(int number, const char* format, va_list arguments)
{
    const std::string text = "ODE message " + std::to_string(number) + ": " + formatted(format, arguments);
    if (tLog)
        tLog->raise(text, tStep);
    else
        std::fprintf(stderr, "%s\n", text.c_str());
}

[[noreturn]] void onError(int number, const char* format, va_list arguments)
{
    throw EngineError("ODE error " + std::to_string(number) + ": " + formatted(format, arguments));
}

// Sends ODE's messages to `log`, as raised at `step`, while it lives.
class MessageScope
{
  public:
    MessageScope(WarningLog& log, long step)
    {
        static const bool installed = []
        {
            dSetMessageHandler(onMessage);
            dSetErrorHandler(onError);
            dSetDebugHandler(onError);
            return true;
        }();
        (void)installed;
        tLog = &log;
        tStep = step;
    }
    ~MessageScope() { tLog = nullptr; }
    MessageScope(const MessageScope&) = delete;
    MessageScope& operator=(const MessageScope&) = delete;
};

class OdeEngine final : public Engine
{
  public:
    OdeEngine(const core::Model& model, bool quickStep, const EngineSettings& settings)
        : mModel(model), mQuickStep(quickStep)
    {
        jointTree(model); // the scope check
        const bool contacts = hasContacts(model);
        static const bool initialised = dInitODE2(0) != 0;
        if (!initialised)
            throw Unsupported("ODE failed to initialise");
        const MessageScope scope(mLog, 0);
        dRandSetSeed(0); // ODE's initial seed
        mWorld = dWorldCreate();
        const core::Vec3& g = model.simulation.gravity;
        dWorldSetGravity(mWorld, g.x(), g.y(), g.z());
        if (settings.iterations)
            dWorldSetQuickStepNumIterations(mWorld, *settings.iterations);
        if (contacts)
        {
            mSpace = dHashSpaceCreate(nullptr);
            mContactJoints = dJointGroupCreate(0);
            mPairs = std::make_unique<collision::PairFilter>(model);
        }
        for (const core::Body& body : model.bodies)
        {
            if (body.isStatic)
            {
                mBodies.push_back(nullptr);
                if (contacts)
                    addGeoms(body, nullptr);
                continue;
            }
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
            if (contacts)
                addGeoms(body, b);
        }
        for (const core::Joint& joint : model.joints)
            addJoint(joint);
        std::sort(mHullCorners.begin(), mHullCorners.end(), std::greater<>());
        std::size_t room = cPrimitivePoints;
        for (std::size_t k = 0; k < std::min<std::size_t>(2, mHullCorners.size()); ++k)
            room += mHullCorners[k];
        mContacts.resize(room);
    }

    ~OdeEngine() override
    {
        if (mSpace)
        {
            dJointGroupDestroy(mContactJoints);
            dSpaceDestroy(mSpace); // and its geoms
        }
        dWorldDestroy(mWorld);
    }

    void step() override
    {
        const MessageScope scope(mLog, ++mSteps);
        if (mSpace)
            dSpaceCollide(mSpace, this, &OdeEngine::nearCallback);
        if (mQuickStep)
            dWorldQuickStep(mWorld, mModel.simulation.dt);
        else
            dWorldStep(mWorld, mModel.simulation.dt);
        if (mSpace)
            dJointGroupEmpty(mContactJoints);
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
            const dReal* x = dBodyGetPosition(mBodies[b]);
            const dReal* q = dBodyGetQuaternion(mBodies[b]);
            out[b] = {core::Vec3(x[0], x[1], x[2]), core::Quat(q[0], q[1], q[2], q[3])};
        }
    }

  private:
    // The body's shapes as geoms: on a moving body at their offset in its frame, or placed in
    // the world for a static body (no ODE body).
    void addGeoms(const core::Body& body, dBodyID b)
    {
        const auto index = static_cast<std::intptr_t>(&body - mModel.bodies.data());
        for (const core::Shape& shape : body.shapes)
        {
            dGeomID geom = nullptr;
            core::Vec3 centre_S = core::Vec3::Zero(); // the geom's origin in the shape frame (m)
            switch (shape.type)
            {
            case core::ShapeType::Box:
                geom = dCreateBox(mSpace, shape.size.x(), shape.size.y(), shape.size.z());
                break;
            case core::ShapeType::Sphere:
                geom = dCreateSphere(mSpace, shape.radius);
                break;
            case core::ShapeType::Capsule: // radius, cylindrical length, along local z
                geom = dCreateCapsule(mSpace, shape.radius, shape.length);
                break;
            case core::ShapeType::Cylinder: // radius, full height, along local z
                geom = dCreateCylinder(mSpace, shape.radius, shape.length);
                break;
            case core::ShapeType::Plane: // static only (the model's rule), world frame
                geom =
                    dCreatePlane(mSpace, shape.normal.x(), shape.normal.y(), shape.normal.z(), shape.offset);
                break;
            case core::ShapeType::Mesh:
            {
                const collision::ConvexHull hull = meshHull(body, shape);
                for (const core::Vec3& v : hull.vertices)
                    centre_S += v / static_cast<double>(hull.vertices.size());
                geom = convexGeom(hull, centre_S);
                mHullCorners.push_back(hull.vertices.size());
                break;
            }
            }
            dGeomSetData(geom, reinterpret_cast<void*>(index));
            if (shape.type == core::ShapeType::Plane)
                continue;
            const core::Quat& r = shape.rotation_BS;
            const dQuaternion dr = {r.w(), r.x(), r.y(), r.z()};
            const core::Vec3 position_B = shape.position_BS + r * centre_S;
            if (b)
            {
                dGeomSetBody(geom, b);
                dGeomSetOffsetPosition(geom, position_B.x(), position_B.y(), position_B.z());
                dGeomSetOffsetQuaternion(geom, dr);
            }
            else
            {
                const core::Vec3 x = body.position_W + body.orientation_WB * position_B;
                const core::Quat q = body.orientation_WB * shape.rotation_BS;
                const dQuaternion dq = {q.w(), q.x(), q.y(), q.z()};
                dGeomSetPosition(geom, x.x(), x.y(), x.z());
                dGeomSetQuaternion(geom, dq);
            }
        }
    }

    // The hull as a convex geom whose origin is `centre` (ODE needs its origin inside the hull: a
    // mesh's own origin is often at a joint, outside it). ODE keeps pointers to the arrays: they
    // live in mHulls.
    dGeomID convexGeom(const collision::ConvexHull& hull, const core::Vec3& centre)
    {
        HullArrays& h = mHulls.emplace_back();
        for (std::size_t f = 0; f < hull.normals.size(); ++f)
        {
            const core::Vec3& n = hull.normals[f];
            h.planes.insert(h.planes.end(), {n.x(), n.y(), n.z(), hull.offsets[f] - n.dot(centre)});
        }
        for (const core::Vec3& v : hull.vertices)
        {
            const core::Vec3 p = v - centre;
            h.points.insert(h.points.end(), {p.x(), p.y(), p.z()});
        }
        h.polygons.assign(hull.faces.begin(), hull.faces.end()); // [n, i0, ..., in-1] per face
        return dCreateConvex(mSpace, h.planes.data(), static_cast<unsigned>(hull.normals.size()),
                             h.points.data(), static_cast<unsigned>(hull.vertices.size()), h.polygons.data());
    }

    static void nearCallback(void* data, dGeomID o1, dGeomID o2)
    {
        auto& self = *static_cast<OdeEngine*>(data);
        const auto a = static_cast<int>(reinterpret_cast<std::intptr_t>(dGeomGetData(o1)));
        const auto b = static_cast<int>(reinterpret_cast<std::intptr_t>(dGeomGetData(o2)));
        if (a == b || !self.mPairs->allowed(a, b))
            return;
        dContact* contact = self.mContacts.data();
        const int room = static_cast<int>(self.mContacts.size());
        const int n = dCollide(o1, o2, room, &contact[0].geom, sizeof(dContact));
        if (n == room)
            self.mLog.raise("ODE: a pair of geoms filled the room for " + std::to_string(room) +
                                " contact points given to dCollide (it may have had more)",
                            self.mSteps);
        for (int k = 0; k < n; ++k)
        {
            contact[k].surface.mode = dContactApprox1 | dContactBounce;
            contact[k].surface.mu = self.mModel.contact.friction;
            contact[k].surface.bounce = self.mModel.contact.restitution;
            contact[k].surface.bounce_vel = 0.0;
            dJointID j = dJointCreateContact(self.mWorld, self.mContactJoints, &contact[k]);
            dJointAttach(j, dGeomGetBody(o1), dGeomGetBody(o2));
        }
    }

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
            if (joint.limits)
            {
                // ODE's hinge angle is the first body's about the axis from the second, the
                // model's the child's from the parent: the same when the parent is the world
                // (ODE then makes the child its first body), opposite otherwise.
                const double sign = parent ? -1.0 : 1.0;
                dJointSetHingeParam(j, dParamLoStop,
                                    std::min(sign * (*joint.limits)[0], sign * (*joint.limits)[1]));
                dJointSetHingeParam(j, dParamHiStop,
                                    std::max(sign * (*joint.limits)[0], sign * (*joint.limits)[1]));
            }
            break;
        }
        case core::JointType::Angle: // universal: a1 fixed in the parent, b2 in the child
        {
            j = dJointCreateUniversal(mWorld, nullptr);
            dJointAttach(j, parent, child);
            dJointSetUniversalAnchor(j, anchor.x(), anchor.y(), anchor.z());
            const core::Vec3 a1 = joint.parent == core::cWorld
                                      ? joint.perpParent1
                                      : mModel.bodies[static_cast<std::size_t>(joint.parent)].orientation_WB *
                                            joint.perpParent1;
            const core::Vec3 b2 = c.orientation_WB * joint.angleChildAxis;
            dJointSetUniversalAxis1(j, a1.x(), a1.y(), a1.z());
            dJointSetUniversalAxis2(j, b2.x(), b2.y(), b2.z());
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
    long mSteps = 0;
    dWorldID mWorld = nullptr;
    dSpaceID mSpace = nullptr;              // null: no contacts
    dJointGroupID mContactJoints = nullptr; // this step's contact joints
    std::unique_ptr<collision::PairFilter> mPairs;
    std::vector<dBodyID> mBodies; // per model body; null for static ones
    struct HullArrays
    {
        std::vector<dReal> planes;      // n.x n.y n.z offset per face
        std::vector<dReal> points;      // x y z per vertex
        std::vector<unsigned> polygons; // [n, i0, ..., in-1] per face
    };
    std::deque<HullArrays> mHulls;
    std::vector<std::size_t> mHullCorners; // per convex geom: its hull's corners
    std::vector<dContact> mContacts;       // room for one pair's contact points
};

} // namespace

std::unique_ptr<Engine> makeOde(const core::Model& model, bool quickStep, const EngineSettings& settings)
{
    return std::make_unique<OdeEngine>(model, quickStep, settings);
}

} // namespace frontier::peers
