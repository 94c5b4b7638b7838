// core/model.h: the scene as loaded (io/ builds it, everything else reads it; const while stepping).
//
// Units: SI throughout (metres, kilograms, seconds, radians). Frames: "world" W is z-up unless the
// scene's gravity says otherwise; each body's frame B has its origin at the body's centre of mass
// and rotates with the body. Shapes carry their pose in B (a URDF collision origin is not the
// centre of mass).
#pragma once

#include "core/time_function.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace frontier::core
{

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

enum class ShapeType
{
    Box,      // size = full extents along local x, y, z (m)
    Sphere,   // radius (m)
    Capsule,  // radius (m), length = cylindrical segment along local z (m); total height length + 2 radius
    Cylinder, // radius (m), length = full height along local z (m)
    Plane,    // static bodies only: the half-space n . x <= offset is solid (n unit, world frame)
    Mesh,     // triangle mesh, vertices in the shape frame (m), already scaled
};

struct Shape
{
    ShapeType type = ShapeType::Box;
    Vec3 size = Vec3::Zero();                  // Box: full extents (m)
    double radius = 0.0;                       // Sphere, Capsule, Cylinder (m)
    double length = 0.0;                       // Capsule (segment), Cylinder (full height) (m)
    Vec3 normal = Vec3::UnitZ();               // Plane: unit outward normal, world frame
    double offset = 0.0;                       // Plane: n . x = offset on the surface (m)
    std::string meshFile;                      // Mesh: the file it was read from (for messages)
    std::vector<Vec3> vertices;                // Mesh: vertices in the shape frame (m), nverts
    std::vector<std::array<int, 3>> triangles; // Mesh: vertex indices, counter-clockwise seen from outside
    Vec3 position_BS = Vec3::Zero();           // shape origin in the body frame (m)
    Quat rotation_BS = Quat::Identity();       // shape orientation in the body frame
};

struct Body
{
    std::string name;
    bool isStatic = false; // static bodies do not move and are not nodes of the solver (docs/method.md §5)
    double mass = 0.0;     // kg (> 0 for moving bodies)
    Mat3 inertia_B = Mat3::Zero(); // kg m^2, about the centre of mass, in the body frame
    std::vector<Shape> shapes;     // collision geometry, also drawn when `visuals` is empty (may be empty)
    std::vector<Shape> visuals;    // render-only geometry (URDF <visual>); no mass, no contacts
    std::optional<Vec3> color;     // RGB in [0, 1], for the renderer
    std::string group;             // bodies of one non-empty group never collide with each other
    // The body's material (a scene body's `friction`, `restitution`; a URDF link's <contact>): none
    // takes the scene's contact settings. A pair combines them by contactFriction, contactRestitution.
    std::optional<double> friction;    // Coulomb coefficient, >= 0
    std::optional<double> restitution; // Newton e in [0, 1]
    // Initial state.
    Vec3 position_W = Vec3::Zero();         // centre of mass (m)
    Quat orientation_WB = Quat::Identity(); // body to world
    Vec3 velocity_W = Vec3::Zero();         // m/s, of the centre of mass
    Vec3 angularVelocity_W = Vec3::Zero();  // rad/s
};

// docs/method.md §2; what each type is (name, rows, coordinates, limits, axis, row writer): the table
// of core/joints/joint_types.h, one row per value in this order.
enum class JointType
{
    Ball,
    Nail,
    Revolute,
    Angle,
    Cylindrical,
    Prismatic,
    Fixed,
    Planar,
};

// Which body is the "world": a joint's parent index when it is attached to the world.
inline constexpr int cWorld = -1;

struct Joint
{
    std::string name;
    JointType type = JointType::Ball;
    int parent = cWorld; // body index, or cWorld; a static parent acts as the world
    int child = 0;       // body index (a moving body)
    // Anchor in each body's frame (m). For a world or static parent, anchorParent is in that
    // static frame (world coordinates for cWorld).
    Vec3 anchorParent = Vec3::Zero();
    Vec3 anchorChild = Vec3::Zero();
    // Joint frame fixed in the parent (unit, orthonormal): axis d_k and the two directions d_i,
    // d_j orthogonal to it, in the parent's frame. axisChild is d_k expressed in the child frame
    // at the initial pose (the child's copy of the axis).
    Vec3 axisParent = Vec3::UnitZ();
    Vec3 perpParent1 = Vec3::UnitX(); // d_i
    Vec3 perpParent2 = Vec3::UnitY(); // d_j
    Vec3 axisChild = Vec3::UnitZ();
    Vec3 perpChild1 = Vec3::UnitX(); // d_i in the child frame at the initial pose (angles, limits)
    // Angle (universal) joint: a1 = perpParent1 fixed in the parent, b2 fixed in the child,
    // with d_k = a1 x b2 (docs/method.md §2, the holonomic form).
    Vec3 angleChildAxis = Vec3::UnitY();
    // Relative orientation q_A^-1 q_B at the initial pose (prismatic, fixed).
    Quat restRotation_AB = Quat::Identity();
    // Joint limits (rad for revolute, m for prismatic), of the coordinate measured from the initial
    // pose (0 there); one-sided rows near them.
    std::optional<std::array<double, 2>> limits;
    // The coordinate of the initial pose in the model file's own convention (rad or m): a URDF
    // joint whose zero lies outside its limits starts at the nearest limit, and its limits are
    // shifted by this much. 0 for YAML joints (their initial pose is their zero).
    double initialPosition = 0.0;
    // Revolute and prismatic joints (URDF <dynamics>): viscous damping of the joint coordinate
    // (N m s/rad or N s/m) and Coulomb friction (N m or N); 0 = none.
    double damping = 0.0;
    double friction = 0.0;
    // The largest force or torque an actuator may apply along the joint (N or N m; URDF <limit
    // effort>), used when the actuator gives none; +infinity: none.
    double effortLimit = std::numeric_limits<double>::infinity();
    bool collideConnected = false; // the two bodies may collide with each other
};

// A coordinate of a joint (core/joints/coordinates.h): what a limit bounds and an actuator drives.
enum class JointCoordinate
{
    Rotation, // rad, about the joint axis (revolute, cylindrical)
    Slide,    // m, along the joint axis (prismatic, cylindrical)
};

enum class ActuatorKind
{
    Position, // a servo: stiffness kp and damping kd towards a target coordinate (implicit)
    Velocity, // a motor: the coordinate's speed to a target, within the effort limit
    Effort,   // a commanded force or torque
};

// An actuator on one coordinate of a joint (core/actuation.h). Its target is in the model file's
// coordinate: Joint::initialPosition + the coordinate measured from the initial pose (rad or m) for
// a servo, rad/s or m/s for a motor, N m or N for an effort.
struct Actuator
{
    int joint = 0; // index into Model::joints: revolute, prismatic or cylindrical
    JointCoordinate coordinate = JointCoordinate::Rotation;
    ActuatorKind kind = ActuatorKind::Position;
    double kp = 0.0; // Position: stiffness (N m/rad or N/m)
    // Position: damping towards the target's rate (N m s/rad or N s/m). Velocity: damping towards
    // the target speed; 0 makes the motor rigid (it holds the speed exactly within its limit).
    double kd = 0.0;
    double effortLimit = std::numeric_limits<double>::infinity(); // N m or N; +infinity: none
    TimeFunction target;
};

enum class LoadFrame
{
    World, // force and torque in world axes; `point` a world point
    Body,  // force and torque in the body's axes; `point` in the body frame (from its centre of mass)
};

// An external load on a body: a force (and torque) over [from, to), or an impulse at one instant.
struct Load
{
    int body = 0; // a moving body
    LoadFrame frame = LoadFrame::World;
    Vec3 force = Vec3::Zero();  // N (an impulse: N s)
    Vec3 torque = Vec3::Zero(); // N m (an impulse: N m s)
    std::optional<Vec3> point;  // where the force acts (m, see LoadFrame); none: the centre of mass
    double from = 0.0;          // s
    double to = std::numeric_limits<double>::infinity(); // s
    std::optional<double> instant; // s: an impulse at this time instead of a force over [from, to)
};

struct Camera
{
    bool automatic = true; // frame the bodies when no camera is given
    Vec3 position = Vec3(3, -3, 2);
    Vec3 lookAt = Vec3(0, 0, 0.5);
    double fovDegrees = 45.0;
};

// How a contact between two bodies takes its friction from theirs (contactFriction).
enum class FrictionMix
{
    GeometricMean, // sqrt(mu_a mu_b), as Box2D mixes materials
    Larger,        // max(mu_a, mu_b), as MuJoCo mixes geoms (an MJCF file's)
};

struct ContactSettings
{
    double friction = 0.5; // Coulomb mu
    FrictionMix frictionMix = FrictionMix::GeometricMean;
    double restitution = 0.0; // Newton e
    // When the contact solve stops (docs/method.md §5): each row's condition met to
    // max(tolerance, relativeTolerance x the largest residual when the step's solve starts), in m/s
    // (rad/s for angular rows). The absolute part holds resting contact; the relative part lets an
    // impact stop at a fraction of its own speeds.
    double tolerance = 3e-5;        // m/s: 30 nm of motion in a 1 ms step
    double relativeTolerance = 0.0; // of the starting residual, in [0, 1)
    // m: a start with a deeper penetration is warned about (an error under --strict).
    double startPenetration = 0.01;
    std::vector<std::array<int, 2>> ignore; // body index pairs that never collide
};

// The contact tolerances a model may ask (a scene file's `contact:` keys, bench/peers' Frontier
// variants): tolerance in [0, cMaxContactTolerance] m/s (more would let resting bodies slide),
// relativeTolerance a fraction in [0, 1). NaN is neither.
inline constexpr double cMaxContactTolerance = 1.0; // m/s
inline constexpr const char* cContactToleranceRange = "a velocity in [0, 1] m/s";
inline constexpr const char* cRelativeContactToleranceRange = "a fraction in [0, 1)";
inline bool isContactTolerance(double mPerS)
{
    return mPerS >= 0.0 && mPerS <= cMaxContactTolerance;
}
inline bool isRelativeContactTolerance(double fraction)
{
    return fraction >= 0.0 && fraction < 1.0;
}

// Contact tolerances asked over a scene's (the flags of run and sweep, a trajectory's header):
// each one given replaces the setting's value.
struct ContactTolerances
{
    std::optional<double> tolerance;         // m/s
    std::optional<double> relativeTolerance; // of the starting residual
    void applyTo(ContactSettings& contact) const
    {
        contact.tolerance = tolerance.value_or(contact.tolerance);
        contact.relativeTolerance = relativeTolerance.value_or(contact.relativeTolerance);
    }
};

enum class SolverKind
{
    Linear,
    Dense,
    Pgs,
};

enum class IntegratorKind
{
    Euler,
    Rattle,
    Rattle4, // three RATTLE stages composed to fourth order (docs/method.md §11)
};

// The ranges of a run's times (a scene's `simulation:`, --dt and --duration, a batch plan): a step of
// (0, cMaxTimeStep] s, a run of (0, cMaxDuration] s. Longer could only be a typo; a function of time
// (an actuator's target) is checked to stay finite up to cMaxDuration.
inline constexpr double cMaxTimeStep = 1e6;  // s
inline constexpr double cMaxDuration = 1e12; // s

struct SimulationSettings
{
    double dt = 0.001;                // s
    double duration = 1.0;            // s
    Vec3 gravity = Vec3(0, 0, -9.81); // m/s^2
    SolverKind solver = SolverKind::Linear;
    int pgsIterations = 20;
    IntegratorKind integrator = IntegratorKind::Euler;
};

// A robot model (URDF) placed in the scene: its links became bodies [firstBody, firstBody + bodyCount).
struct Robot
{
    std::string name;
    std::string sourceFile;
    int firstBody = 0;
    int bodyCount = 0;
    bool selfCollision = true; // false: its bodies share one collision group
};

struct Model
{
    std::string name;
    std::string sourceFile;
    SimulationSettings simulation;
    ContactSettings contact;
    Camera camera;
    std::vector<Body> bodies;
    std::vector<Joint> joints;
    std::vector<Robot> robots;
    std::vector<Actuator> actuators; // at most one per joint coordinate
    std::vector<Load> loads;

    // The index of the first body of that name, -2 when there is none. A linear search (the model
    // keeps no index that every edit of `bodies` would have to maintain): for a single look-up;
    // the scene loaders resolve names through a name -> index map (io's SceneBuilder).
    int findBody(const std::string& bodyName) const;
};

// The ranges of a scene's lengths and starting motion: beyond them a value is a typo or a corrupt
// file, and the collision detection (FCL's bounding-volume trees) breaks down long before doubles
// overflow. A scene's positions (bodies, shapes, joint anchors, URDF origins, model placements) lie
// within cMaxDistance of the origin, its sizes (box sides, radii, lengths, a scaled mesh's reach)
// are positive and at most cMaxDistance, its starting speeds at most cMaxSpeed and
// cMaxAngularSpeed. A trajectory row (io/trajectory.h) obeys the same distance, and a run stops
// (a blow-up, docs/method.md §7) when a body passes one of them.
inline constexpr double cMaxDistance = 1e6;     // m
inline constexpr double cMaxSpeed = 1e5;        // m/s
inline constexpr double cMaxAngularSpeed = 1e6; // rad/s
// How messages say them.
inline constexpr const char* cPositionRange = "a point within 1e6 m of the origin";
inline constexpr const char* cLengthRange = "a length in (0, 1e6] m";
inline constexpr const char* cSpeedRange = "a velocity of at most 1e5 m/s";
inline constexpr const char* cAngularSpeedRange = "an angular velocity of at most 1e6 rad/s";
// Each is false for NaN and infinities.
inline bool isPosition(const Vec3& p_W)
{
    return p_W.norm() <= cMaxDistance;
}
inline bool isLength(double m)
{
    return m > 0.0 && m <= cMaxDistance;
}
// The farthest point of a shape from its own origin (m): a box's half diagonal, a sphere's radius, a
// capsule's radius + half length, a cylinder's corner, a mesh's farthest vertex, a plane's |offset|.
double shapeReach(const Shape& shape);

// The friction and restitution of a contact between bodies a and b (b may be cWorld), as Box2D
// mixes materials: friction the geometric mean sqrt(mu_a mu_b) (or the larger, by
// ContactSettings::frictionMix), restitution the larger, each body taking the scene's value
// (Model::contact) when it has none of its own.
double contactFriction(const Model& model, int a, int b);
// The values a material may take: friction >= 0, restitution in [0, 1] (NaN neither).
inline bool isFriction(double mu)
{
    return mu >= 0.0 && mu <= 1e6;
}
inline bool isRestitution(double e)
{
    return e >= 0.0 && e <= 1.0;
}
double contactRestitution(const Model& model, int a, int b);

// True for the index of a moving body (not cWorld, not a static body).
bool isMovingBody(const Model& model, int body);

// What model.h answers about a joint type, from the table of joint types (core/joints/joint_types.h,
// which has the rest: coordinates, limits, axis, row writer).
int jointRowCount(JointType type);
// Whether the joint holds (some of) the relative rotation of its bodies: every type but ball and
// nail, whose rows hold a point only.
bool holdsRotation(JointType type);
const char* jointTypeName(JointType type);
std::optional<JointType> jointTypeFromName(const std::string& name);

// The solvers and integrators a run can choose (docs/method.md §11), as scenes and flags name them,
// each with a line on what it is; solvers() and integrators() list them all, in enum order.
struct SolverInfo
{
    SolverKind kind;
    const char* name;
    const char* description;
};
struct IntegratorInfo
{
    IntegratorKind kind;
    const char* name;
    const char* description;
};
std::span<const SolverInfo> solvers();
std::span<const IntegratorInfo> integrators();
std::vector<std::string> solverNames();     // linear, dense, pgs
std::vector<std::string> integratorNames(); // euler, rattle, rattle4
const char* solverName(SolverKind kind);
std::optional<SolverKind> solverFromName(const std::string& name);
const char* integratorName(IntegratorKind kind);
std::optional<IntegratorKind> integratorFromName(const std::string& name);
// Names as a message lists them: "a, b <conjunction> c" (conjunction "or", "and").
std::string nameList(const std::vector<std::string>& names, const std::string& conjunction);

// An actuator's type and coordinate as scenes name them: position | velocity | effort, rotation | slide.
const char* actuatorTypeName(ActuatorKind kind);
const char* coordinateName(JointCoordinate coordinate);

// rattle4's triple jump (docs/method.md §11): stages of c1 h, c2 h, c1 h with
// c1 = 1 / (2 - 2^(1/3)), c2 = -2^(1/3) / (2 - 2^(1/3)) < 0 (its middle stage runs backward).
struct TripleJump
{
    double c1;
    double c2;
};
TripleJump tripleJumpCoefficients();
// The longest time one stage of a step covers (s): dt, or |c2| dt = 1.70 dt for rattle4.
// Contact margins cover it.
double longestStage(const SimulationSettings& settings);

// Fills a joint's frames from world-space data at the model's initial pose: anchor (m) and unit
// axis in world coordinates. Used by io/ for YAML and URDF alike.
void setJointFrames(const Model& model, Joint& joint, const Vec3& anchor_W, const Vec3& axis_W);

// Mass properties of a shape of the given density (kg/m^3) about its own origin, in its frame.
struct MassProperties
{
    double mass = 0.0;           // kg
    Mat3 inertia = Mat3::Zero(); // kg m^2 about the centre of mass, shape frame
    Vec3 centre = Vec3::Zero();  // centre of mass in the shape frame (m); nonzero for meshes
};
MassProperties shapeMassProperties(const Shape& shape, double density);
double shapeVolume(const Shape& shape);

// Support function: the largest u . x over the points x of the shape (shape frame, m), for a unit
// direction u in the shape frame. Planes (solid n . x <= offset) are unbounded: +infinity unless u is along
// +n.
double shapeSupport(const Shape& shape, const Vec3& u_S);
// The same for a shape posed in a body at a world pose: the largest u . x over world points x.
double shapeSupportWorld(const Shape& shape, const Vec3& bodyPosition_W, const Quat& bodyOrientation_WB,
                         const Vec3& u_W);

} // namespace frontier::core
