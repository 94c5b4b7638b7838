// core/extra_rows.h: rows beyond the joint tree, solved in constraint space on top of the O(n)
// tree factorization (docs/method.md §5): contacts (one-sided normal, Coulomb friction cone), joints
// that close a loop (bilateral), joint limits (one-sided), and bounded drive rows (Coulomb joint
// friction, core/joints/drive.h; actuators at their effort limit, core/actuation.h).
//
// Each block couples at most two moving bodies: rows J_A u_A + J_B u_B. After the tree solve
// gives u_free, the block impulses lambda solve a small complementarity problem in
//     v = J_x u_free + G lambda,    G = J_x H^-1 J_x^T (the Delassus matrix)
// and the final velocities are u_free + H^-1 J_x^T lambda: one more O(n) solve.
#pragma once

#include "core/contact.h"
#include "core/joints/joint_rows.h"

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace frontier::core
{

class DelassusMatrix; // core/delassus.h

struct ExtraBlock
{
    enum class Kind
    {
        Contact, // row 0 normal (lambda >= 0), rows 1-2 friction (|lambda_t| <= mu lambda_n) when mu > 0
        Loop,    // a loop-closing joint: all rows bilateral (its drive rows compliant)
        Limit,   // a joint limit: one row, lambda >= 0
        Drive,   // a bounded drive row of a joint: one row, |lambda| <= bound
    };
    Kind kind = Kind::Contact;
    int count = 0;  // rows, 1..6
    int bodyA = -1; // moving body or -1 (world / static)
    int bodyB = -1; // moving body or -1
    Mat6 J_A = Mat6::Zero();
    Mat6 J_B = Mat6::Zero();
    Vec6 target = Vec6::Zero(); // lower bound (one-sided rows) or value (bilateral) of J u (m/s, rad/s)
    Vec6 error = Vec6::Zero();  // position-level violation to remove (m or rad): contacts and limits > 0
    // Loops and drives: row r is J u + E_r lambda = target (core/joints/drive.h), E_r > 0 only for
    // a drive row ((m/s)/(N s) or (rad/s)/(N m s)).
    Vec6 compliance = Vec6::Zero();
    double friction = 0.0; // mu (contacts)
    double bound = 0.0;    // drives: |lambda| <= bound (N s or N m s)
    int source = -1;       // contact index, or joint index (loops, limits, drives)
    int actuator = -1;     // drives: the actuator at its effort limit (Model::actuators), -1 joint friction
    int offset = 0;        // first row of the block in G
};

// Rows for one contact (normal, and two tangents when mu > 0), docs/method.md §1, "One collision",
// appended to `out` as a new block; returns it.
ExtraBlock& appendContactBlock(const Model& model, const State& state, const Contact& contact,
                               double friction, int source, std::vector<ExtraBlock>& out);

// Joint-limit rows for a revolute (angle about its axis, rad) or prismatic joint (slide along its
// axis, m) when the position is within `margin` of a limit; appends 0 or 1 block.
void appendLimitBlocks(const Model& model, const State& state, int jointIndex, double margin,
                       std::vector<ExtraBlock>& out);

// A drive row on one coordinate of a joint (the row of dq/dt between its bodies at the state's
// pose), appended as a new block of kind Drive with target, compliance and bound 0 for the caller
// to set; returns it.
ExtraBlock& appendDriveBlock(const Model& model, const State& state, int jointIndex,
                             JointCoordinate coordinate, std::vector<ExtraBlock>& out);

// Coulomb friction f of a joint (N m or N; core::Joint::friction) over a solve of duration h (s):
// one drive row per coordinate of the joint, J u = 0 with |lambda| <= f h (stick, or slip against
// the motion with the whole bound). Appends nothing for a joint without friction.
void appendFrictionBlocks(const Model& model, const State& state, int jointIndex, double h,
                          std::vector<ExtraBlock>& out);

// Sets offsets; returns the number of rows in all.
int layoutExtraRows(std::vector<ExtraBlock>& blocks);

// When the block Gauss-Seidel stops: after a sweep that leaves every row's condition met to
// velocityTolerance (conditionResidual below); or that changed no impulse by more than
// `tolerance` of the largest; or when it has stalled: the largest residual of the last stallSweeps
// sweeps is not below stallRatio of the smallest before them (a fixed point or cycle of the friction
// updates, where two sliding contacts of one body trade their load, that more sweeps do not leave);
// or after maxSweeps.
struct ExtraSolveSettings
{
    double velocityTolerance = 3e-5; // m/s (rad/s for angular rows): 30 nm of motion in a 1 ms step
    double tolerance = 1e-6;         // relative impulse change (or 1e-14 N s absolute)
    int maxSweeps = 100;
    int stallSweeps = 10;    // 0: never stalls
    double stallRatio = 0.9; // the residual must fall below this fraction within stallSweeps sweeps
    // A sweep leaves a block alone while its residual is at most settledRatio x velocityTolerance
    // (its update would move it within the tolerance while costing a column update of G); 0
    // updates every block. At 0.5 a pendulum resting on its limit cycles at the tolerance's edge
    // and its carried impulse stops holding; at 0.25 it settles.
    double settledRatio = 0.25;
};

struct ExtraSolveStats
{
    int sweeps = 0;
    bool converged = false; // every condition met to velocityTolerance after the last sweep
    bool stalled = false;   // stopped by the stall rule
    double residual = 0.0;  // conditionResidual after the last sweep (m/s)
};

// Working storage of solveExtraRows, kept by the caller so that stepping does not allocate once
// sizes have settled.
// What the Gauss-Seidel update of one contact block with friction reads, side by side: a sweep
// reads one of these per block instead of the block and its 6 x 6 pivot storage.
struct ContactPivots
{
    double normal = 0.0;                                  // 1 / G_nn (inverse pivot of the normal row)
    Eigen::Matrix2d tangential = Eigen::Matrix2d::Zero(); // G_tt^-1
    Eigen::Matrix3d whole = Eigen::Matrix3d::Zero();      // G_bb^-1, the sticking trial
    Eigen::Vector2d tangentialOfNormal = Eigen::Vector2d::Zero(); // G_tn
    double isotropic = 0.0;                                       // 2 / trace G_tt, the sliding step
    double target = 0.0;                                          // the normal row's target (m/s)
    double friction = 0.0;                                        // mu
};

struct ExtraSolveScratch
{
    std::vector<Mat6> inverse;           // inverse pivots per block
    std::vector<ContactPivots> contacts; // per block, filled for contacts with friction
    std::vector<Mat6> diagonal;          // per block, its diagonal block of G (count x count)
    std::vector<double> regularization;  // per block, added to its pivots (1e-9 of its free scale)
    std::uint64_t pivotsVersion = 0;     // the DelassusMatrix::version the pivots were computed for (0 none)
    Eigen::VectorXd velocity;            // J u with the current impulses (every row)
    std::vector<Eigen::VectorXd> partVelocity; // per part of G: its rows' velocity change within a solve
    // Per island of G, how its last solve ended (islands it did not solve: Skipped).
    enum class IslandEnd : std::uint8_t
    {
        Skipped,
        Converged, // conditions met to its tolerance
        Stalled,   // the stall rule stopped it
        Stopped,   // no impulse moved, or the sweep cap
    };
    std::vector<IslandEnd> islandEnd;
    std::vector<double> islandResidual; // per island: its residual after its last sweep (m/s)
    Eigen::VectorXd product;            // scratch of solveExtraRows
};

// How far velocities v = J u and impulses are from the conditions of their rows (m/s; rad/s for
// angular rows): bilateral rows |v - target|; a one-sided row |v - target| while it pushes, else
// how far v is below its target; friction inside the cone the slip, on the cone's edge the slip
// not opposite to the friction.
double conditionResidual(const std::vector<ExtraBlock>& blocks, const Eigen::VectorXd& velocity,
                         const Eigen::VectorXd& lambda);
// The same over the listed blocks only.
double conditionResidual(const std::vector<ExtraBlock>& blocks, std::span<const int> which,
                         const Eigen::VectorXd& velocity, const Eigen::VectorXd& lambda);

// conditionResidual(blocks, velocity, lambda) <= tolerance, stopping at the first block that is
// not (NaN counts as not met): the Gauss-Seidel's test after each sweep. A drive row: its
// condition J u + E lambda = target while inside its bound, on the bound the side it pushes from.
bool conditionsMet(const std::vector<ExtraBlock>& blocks, const Eigen::VectorXd& velocity,
                   const Eigen::VectorXd& lambda, double tolerance);

// Block projected Gauss-Seidel on the Delassus system, G stored by tree (core/delassus.h), each
// island of G swept to its own stopping test: bilateral (loop) blocks solved exactly given the
// others; a contact's block first as sticking (its three rows to their targets), else its normal
// row clamped at zero, then its two tangential rows solved together and projected radially onto
// the friction cone |lambda_t| <= mu lambda_n; limit rows clamped at zero; drive rows clamped to
// their bound. Compliance adds to a row's pivot. `lambda` is the warm start on entry (size = rows)
// and the result on exit. Stats: sweeps summed over the islands, converged when every island
// converged, the largest final residual.
ExtraSolveStats solveExtraRows(const std::vector<ExtraBlock>& blocks, const DelassusMatrix& G,
                               const Eigen::VectorXd& freeVelocity, const ExtraSolveSettings& settings,
                               Eigen::VectorXd& lambda, ExtraSolveScratch& scratch);

// The same sweeps from known row velocities: scratch.velocity holds J u at `lambda` on entry
// (for instance computed exactly by an O(n) solve), so no product with G is formed first; on exit
// it holds J u at the result by G. `islandTolerance` (optional, one per island of G) gives each
// island its own velocity tolerance (m/s) in place of settings.velocityTolerance; an island with a
// negative one is not solved. The pivots are computed once per DelassusMatrix::version, so repeated
// solves on one G (the reuse route of core/step/contact_problem.h) share them.
ExtraSolveStats solveExtraRowsFrom(const std::vector<ExtraBlock>& blocks, const DelassusMatrix& G,
                                   const ExtraSolveSettings& settings, Eigen::VectorXd& lambda,
                                   ExtraSolveScratch& scratch, std::span<const double> islandTolerance = {});

} // namespace frontier::core
