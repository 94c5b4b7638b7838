// tests/core/random_model.h: Models built in code for the core tests: random trees and forests
// (every joint type, masses log-uniform, random poses and velocities) and simple chains. Joints
// are built with core::setJointFrames at the initial pose, so every joint is satisfied there.
#pragma once

#include "core/impulse_solver.h"
#include "core/model.h"
#include "core/state.h"

#include <memory>
#include <random>
#include <string>
#include <vector>

namespace frontier::test
{

using core::Mat3;
using core::Quat;
using core::Vec3;
using core::Vec6;

// Deterministic (std::mt19937 only; never std::rand, which Eigen's Random() uses).
class Rng
{
  public:
    explicit Rng(unsigned seed) : mEngine(seed) {}
    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(mEngine); }
    double logUniform(double lo, double hi);
    double normal() { return std::normal_distribution<double>(0.0, 1.0)(mEngine); }
    int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(mEngine); } // [lo, hi]
    bool coin(double p = 0.5) { return uniform(0.0, 1.0) < p; }
    // Draws come one per statement, z first: a compiler's order for the arguments of one call is
    // unspecified (g++ goes right to left, clang left to right), and the models must not depend on it.
    Vec3 gaussianVec()
    {
        const double z = normal(), y = normal(), x = normal();
        return Vec3(x, y, z);
    }
    Vec3 unitVec();
    Quat rotation();
    std::mt19937& engine() { return mEngine; }

  private:
    std::mt19937 mEngine;
};

// A box body of the given full extents and mass at a pose (inertia of the solid box).
core::Body boxBody(const std::string& name, double mass, const Vec3& size, const Vec3& position,
                   const Quat& orientation = Quat::Identity());

// Appends a joint built with setJointFrames at the model's initial pose; returns its index.
int addJoint(core::Model& model, const std::string& name, core::JointType type, int parent, int child,
             const Vec3& anchor_W, const Vec3& axis_W);

// The body-body joint types (all but Nail).
const std::vector<core::JointType>& bodyJointTypes();

struct RandomTreeOptions
{
    int bodies = 10;
    bool attachToWorld = false; // the root is joined to the world
    double minMass = 1e-3;      // kg, log-uniform between min and max
    double maxMass = 1e3;
    std::vector<core::JointType> types; // body-body types to draw from; empty: all of them
    double branching = 1.0;             // 1: parent uniform among earlier bodies; 0: a chain
};

// Appends one random tree to the model (bodies, joints; random poses and velocities).
void appendRandomTree(core::Model& model, Rng& rng, const RandomTreeOptions& options);

core::Model randomTree(unsigned seed, const RandomTreeOptions& options);

// Several trees in one model, each attached to the world or free at random.
core::Model randomForest(unsigned seed, int trees, int maxBodiesPerTree);

// A straight chain along +x of n thin boxes (length `length`, mass masses[i]) joined at their ends
// by joints of `type` (axis z for revolute and the like); optionally nailed to the world at the
// first body's free end. Velocities zero.
core::Model straightChain(const std::vector<double>& masses, core::JointType type, bool nailToWorld,
                          double length = 1.0);

// Helpers to build and read right-hand sides.
struct Problem
{
    core::FrontierLayout layout;
    core::State state;
    core::RowSystem system;
};
// Builds the layout, the state and the rows (system points into the returned object: keep it
// where it is, i.e. use the result via std::unique_ptr).
std::unique_ptr<Problem> makeProblem(const core::Model& model);

// p = M u for the state's velocities (joint rhs c = 0).
core::BlockVector momentumRhs(const core::Model& model, const core::State& state,
                              const core::RowSystem& system);

// Velocity residual of every tree joint J_a u_a + J_b u_b - c, and a scale: the largest
// |J_a u_a| + |J_b u_b| over the joints (m/s or rad/s).
struct JointResidual
{
    double maxResidual = 0.0;
    double scale = 0.0;
};
JointResidual jointResidual(const core::Model& model, const core::RowSystem& system,
                            const core::BlockVector& x);

// Max-norm of a BlockVector's body part and of its joint part (tree joints, used rows only).
double bodyNorm(const core::BlockVector& x);
double jointNorm(const core::RowSystem& system, const core::BlockVector& x);
double bodyDiff(const core::BlockVector& x, const core::BlockVector& y);
double jointDiff(const core::RowSystem& system, const core::BlockVector& x, const core::BlockVector& y);

} // namespace frontier::test
