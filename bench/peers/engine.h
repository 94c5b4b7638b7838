// bench/peers/engine.h: one scene (a core::Model) stepped by Frontier or by a peer engine (Bullet,
// ODE, MuJoCo), each translated from the same Model through that engine's own API, so that every
// engine runs the same bodies, joints, gravity and time step.
//
// Scope: moving bodies joined in trees by ball, revolute (with or without limits), angle
// (universal) and fixed joints, each tree's root joined to the world (or to a static body) or
// free, each tree starting at rest or with one rigid velocity; any inertia tensor; contacts
// between box, sphere, capsule, cylinder and mesh shapes (a mesh as its convex hull; several
// shapes per body, posed in the body) and static bodies' shapes (a plane floor, a robot's base),
// on the pairs Frontier's filter allows (contacts.h), with the scene's friction and restitution
// (MuJoCo: friction only). A robot from a URDF fits when its joints have no damping or friction
// (Debian dart-doc's Barrett WAM does; its Atlas has joint damping). A model outside that scope
// (other joints, limits on other joints, joint damping or friction, actuators, loads) is refused
// with a message that says what is missing.
#pragma once

#include "core/model.h"

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace frontier::peers
{

// A body's pose: centre of mass (m) and orientation, world frame.
struct Pose
{
    core::Vec3 position_W = core::Vec3::Zero();
    core::Quat orientation_WB = core::Quat::Identity();
};

// The model cannot be run by an engine (a joint type it lacks, a body off the tree, ...).
class Unsupported : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// What a run asks of an engine beyond the model: the size of its fixed buffers. MuJoCo 2.2 keeps
// its contacts and constraint rows in buffers of fixed size (nconmax, njmax), sized from the scene
// (engine_mujoco.cpp); Bullet and ODE grow theirs as they need. ODE takes a fixed number of contact
// points per pair of geoms (engine_ode.cpp), Bullet at most 4 per pair of bodies by design (its
// contact manifold keeps the 4 that span the largest area).
struct EngineOptions
{
    // The buffers sized from the scene, times this (>= 1): the harness doubles it and reruns when a
    // run reports a full buffer (harness.h).
    int bufferGrowth = 1;
    // Test only: MuJoCo's nconmax and njmax before the growth (0: sized from the scene).
    int mujocoContacts = 0;
    int mujocoRows = 0;
};

// A warning an engine raised: its text (the engine's name first), the step it first came at (1:
// the first step; 0: while the engine was set up) and in how many steps it came.
struct EngineWarning
{
    std::string text;
    long firstStep = 0;
    long steps = 1;
    bool bufferFull = false; // a fixed buffer was full: larger buffers (EngineOptions) may avoid it
};

// The warnings of one engine, each text once.
class WarningLog
{
  public:
    // Records `text` at `step` (see EngineWarning); a text already recorded counts one more step
    // (when `step` is not the step it last came at). Returns its index in all().
    std::size_t raise(const std::string& text, long step, bool bufferFull = false);
    // One more step of the warning at `index`.
    void again(std::size_t index, long step);
    const std::vector<EngineWarning>& all() const { return mWarnings; }

  private:
    std::vector<EngineWarning> mWarnings;
    std::vector<long> mLastStep; // per warning
};

// An engine failed in a way that ends its run (an ODE or MuJoCo error, which by default would end
// the process): the run stops and its note says why.
class EngineError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

class Engine
{
  public:
    virtual ~Engine() = default;
    // Advances one time step of the model's dt (s).
    virtual void step() = 0;
    // The moving bodies' poses, in Model::bodies order (static bodies keep their model pose).
    virtual void poses(std::vector<Pose>& out) = 0;
    // Looks at what the steps so far raised that the engine only counts (MuJoCo's warning
    // counters): called after every step, outside the timed step.
    virtual void checkStep() {}
    // Every warning the engine raised so far, each once (its handlers' messages as they come).
    const std::vector<EngineWarning>& warnings() const { return mLog.all(); }
    // Its fixed buffers as the note of a rerun with larger ones names them ("" when it has none).
    virtual std::string bufferSizes() const { return ""; }

  protected:
    WarningLog mLog;
};

// An engine's accuracy settings (unset: the engine's default), spelled after its name on the
// command line and in the tables, each as `:KEY=VALUE` (parseEngine):
//   frontier-*       tolerance=M/S   the contact tolerance (core::ContactSettings::tolerance; 3e-5)
//                    relative=F      the relative one (ContactSettings::relativeTolerance; 0)
//   bullet-si        iterations=N    the sequential-impulse solver's iterations (10)
//   ode-quick        iterations=N    QuickStep's iterations (20)
//   mujoco, mujoco-rk4  iterations=N  the constraint solver's iterations (100)
//                    tolerance=T     its tolerance (1e-8)
// e.g. `bullet-si:iterations=20`, `frontier-euler:tolerance=1e-3:relative=0.01`.
struct EngineSettings
{
    std::optional<int> iterations;
    std::optional<double> tolerance;
    std::optional<double> relative;
};

// A spelling split into the engine's name and its settings.
struct EngineSpelling
{
    std::string engine; // one of engineNames()
    EngineSettings settings;
};

// Reads NAME[:KEY=VALUE]...; throws std::invalid_argument naming the engine and the key for an
// unknown engine or key, a key given twice, or a value out of the key's range.
EngineSpelling parseEngine(const std::string& spelling);

// Every engine and method of the harness, by the names the command line and the tables use:
//   frontier-euler, frontier-rattle  Frontier, `linear` solver (exact, O(n))
//   bullet-multibody                 Bullet 3 btMultiBody (reduced coordinates, Featherstone)
//   bullet-si                        Bullet 3 rigid bodies and constraints, sequential impulses (10 it.)
//   ode-quick, ode-direct            ODE dWorldQuickStep (20 it.) and dWorldStep (direct LCP)
//   mujoco, mujoco-rk4               MuJoCo (reduced coordinates), its default Euler integrator or RK4
std::vector<std::string> engineNames();
// The engine of a spelling (a name, or a name with settings: parseEngine). Throws Unsupported, or
// std::invalid_argument for a spelling parseEngine refuses.
std::unique_ptr<Engine> makeEngine(const std::string& spelling, const core::Model& model,
                                   const EngineOptions& options = {});

// Per-engine constructors (engine_*.cpp).
std::unique_ptr<Engine> makeFrontier(const core::Model& model, core::IntegratorKind integrator,
                                     const EngineSettings& settings = {});
std::unique_ptr<Engine> makeBulletMultibody(const core::Model& model);
std::unique_ptr<Engine> makeBulletSequentialImpulses(const core::Model& model,
                                                     const EngineSettings& settings = {});
std::unique_ptr<Engine> makeOde(const core::Model& model, bool quickStep,
                                const EngineSettings& settings = {});
enum class MujocoIntegrator
{
    Euler, // MuJoCo's default (semi-implicit Euler)
    Rk4,   // its fourth-order Runge-Kutta
};
std::unique_ptr<Engine> makeMujoco(const core::Model& model, MujocoIntegrator integrator,
                                   const EngineOptions& options = {}, const EngineSettings& settings = {});

} // namespace frontier::peers
