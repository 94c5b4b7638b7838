// core/impulse_solver.h: the impulse problem of docs/method.md §1-3 and the three ways to solve it.
//
// Unknowns: post-impulse velocities u_i = [v_i; w_i] of every moving body and the multipliers
// lambda_k of every tree joint. Equations (docs/method.md eqs. (1)-(4)):
//     M_i u_i - sum_k J_ki^T lambda_k = p_i      (momentum: p = M u* + external impulses)
//     J_ka u_a + J_kb u_b + E_k lambda_k = c_k   (joint velocity conditions; c = 0 in a plain solve;
//                                              compliance E_k = 0 but on drive rows, core/joints/drive.h)
// In KKT form [M J^T; J -E][u; -lambda] = [p; c], symmetric and quasi-definite when the joint rows
// are independent. `linear` eliminates it in frontier order in O(n) (docs/method.md §3); `dense` is
// Moore's dense Gaussian elimination of the same matrix, O(n^3); `pgs` is projected Gauss-Seidel
// over the same rows with a fixed iteration count (what game engines do: O(n) per sweep, inexact).
#pragma once

#include "core/delassus.h"
#include "core/extra_rows.h"
#include "core/frontier_order.h"
#include "core/joints/drive.h"
#include "core/joints/joint_rows.h"
#include "core/large_vector.h"
#include "core/simulation_error.h"
#include "core/state.h"

#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace frontier::core
{

// The matrices of one impulse problem at one configuration.
struct RowSystem
{
    const Model* model = nullptr;
    const FrontierLayout* layout = nullptr;
    LargeVector<double> mass;      // kg, per body index (0 for static bodies)
    LargeVector<Mat3> inertia_W;   // kg m^2, per body index, world frame
    LargeVector<Mat3> rotation_WB; // per body index: R_WB at the state the rows were evaluated at
    JointRowsTable joints;         // per joint index (loop joints evaluated too, used by later stages)
    int rowCount = 0;              // tree joint rows in all
    // Per body index, kg m^2: geometric stiffness h^2 k added to each diagonal entry of the
    // rotational inertia in the factorization only (docs/method.md §7a; momenta use inertia_W).
    // Empty: none, as assembleRows leaves it.
    LargeVector<double> geometricInertia;
};

// Evaluates masses and joint rows at a state (docs/method.md §1-2), with the drive rows of a solve of
// duration driveStep (s; 0 for an instantaneous impulse: drives give none, core/joints/drive.h).
// `gains`: per joint, the gains of its drive rows (core::Actuation::gains(): damping and the
// actuators in the joints' blocks); empty: the joints' damping alone. `system` keeps its storage.
void assembleRows(const Model& model, const FrontierLayout& layout, const State& state, double driveStep,
                  RowSystem& system, std::span<const JointDriveGains> gains = {});

// Only the joints' conditions C(q) at a state, with the errors of their drive rows zero: what
// measuring the joints' drift needs. Leaves `system` incomplete (masses, inertias, drive rows and
// the Jacobians of some joint types as they were, JointRows::count = constraintRows) until
// assembleRows completes it.
void assembleJointConditions(const Model& model, const State& state, RowSystem& system);

// The rows of one joint's block at a state (its conditions, then its drive rows for a solve of
// duration driveStep with the joint's `gains`, empty as in assembleRows), as assembleRows writes them.
void evaluateJointBlock(const Model& model, const FrontierLayout& layout, const State& state, int jointIndex,
                        double driveStep, std::span<const JointDriveGains> gains, JointRows& out);

// Body i's rotational inertia as the solvers factor it: inertia_W plus its geometric stiffness
// (kg m^2, world frame).
inline Mat3 factoredInertia(const RowSystem& system, std::size_t i)
{
    return system.geometricInertia.empty()
               ? system.inertia_W[i]
               : Mat3(system.inertia_W[i] + system.geometricInertia[i] * Mat3::Identity());
}

// Right-hand side or solution, by body and by joint (joint rows beyond JointRows::count unused). The
// linear solver (core/tree_solver.h) also takes a right-hand side whose body part is empty: zero
// momenta.
struct BlockVector
{
    LargeVector<Vec6> body;  // per body index: p (N s, N m s) in, u (m/s, rad/s) out
    LargeVector<Vec6> joint; // per joint index: c (m/s, rad/s) in, lambda (N s or N m s) out
    void resize(std::size_t bodies, std::size_t joints);
    void setZero();
};

// SingularJointError (a joint block that cannot be eliminated): core/simulation_error.h.

class ImpulseSolver
{
  public:
    virtual ~ImpulseSolver() = default;
    // Prepares for solves at this configuration (throws SingularJointError). `system` must
    // outlive the following solve() calls.
    virtual void factor(const RowSystem& system) = 0;
    // One right-hand side; may be called many times per factor().
    virtual void solve(const BlockVector& rhs, BlockVector& solution) = 0;
    // factor() and the first solve() in one call (the tree solver fuses them).
    virtual void factorAndSolve(const RowSystem& system, const BlockVector& rhs, BlockVector& solution)
    {
        factor(system);
        solve(rhs, solution);
    }
    virtual const char* name() const = 0;

    // The Delassus matrix G = J_x H^-1 J_x^T of extra rows (contacts, loops, limits; docs/method.md
    // §5), after factor(), stored by tree (core/delassus.h): the values of the listed parts of G,
    // laid out for these blocks (DelassusMatrix::layOut). The default takes one solve per row; the
    // tree solver overrides it with forward sweeps that touch only each body's path to its root.
    virtual void delassusParts(const std::vector<ExtraBlock>& blocks, DelassusMatrix& G,
                               std::span<const int> parts);
    // Every part: the layout and all the values.
    void delassus(const std::vector<ExtraBlock>& blocks, DelassusMatrix& G);
    // G dense, rows x rows: for problems factored whole (the loop rows of the drift correction).
    void delassus(const std::vector<ExtraBlock>& blocks, int rows, Eigen::MatrixXd& G);

    // Adds the momentum of extra-row impulses to a right-hand side: rhs.body += J_x^T lambda.
    static void addExtraImpulses(const std::vector<ExtraBlock>& blocks, const Eigen::VectorXd& lambda,
                                 BlockVector& rhs);

    // Adds the response to extra-row impulses: solution += H^-1 [J_x^T lambda; 0] (one solve).
    void applyExtraImpulses(const std::vector<ExtraBlock>& blocks, const Eigen::VectorXd& lambda,
                            BlockVector& solution);

  protected:
    const RowSystem* mSystem = nullptr;    // set by factor()
    BlockVector mExtraRhs, mExtraResponse; // scratch
    DelassusMatrix mDenseScratch;          // delassus(blocks, rows, G)
    std::vector<int> mAllParts;            // scratch: 0 .. parts - 1
};

// One body's term of a row's Delassus value without the joints, J_i M_i^-1 J_i^T for its part J_i
// (linear, angular) of the row ((m/s)/(N s), (rad/s)/(N m s)): the scale the row would have on a
// free body.
double freeDelassus(const RowSystem& system, std::size_t body, const Vec6& row);

// The Part::free values of a part of G laid out for these blocks (core/delassus.h): each row's
// freeDelassus over its bodies on the part's tree.
void setFreeDelassus(const RowSystem& system, const std::vector<ExtraBlock>& blocks,
                     DelassusMatrix::Part& part);

// J_x u for every extra row, at velocities `solution.body`.
void extraRowVelocities(const std::vector<ExtraBlock>& blocks, const BlockVector& solution,
                        Eigen::VectorXd& out);

std::unique_ptr<ImpulseSolver> makeSolver(SolverKind kind, int pgsIterations = 20);

} // namespace frontier::core
