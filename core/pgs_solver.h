// core/pgs_solver.h: the `pgs` baseline, projected Gauss-Seidel over the same joint rows, one
// scalar row at a time, a fixed number of sweeps (ODE QuickStep, sequential impulses). O(n) per
// sweep but inexact: error remains on long chains and large mass ratios (docs/method.md §3).
// Starts from lambda = 0 (no warm start), so a solve depends only on its right-hand side.
#pragma once

#include "core/impulse_solver.h"

namespace frontier::core
{

class PgsSolver final : public ImpulseSolver
{
  public:
    explicit PgsSolver(int iterations) : mIterations(iterations) {}
    void factor(const RowSystem& system) override;
    void solve(const BlockVector& rhs, BlockVector& solution) override;
    const char* name() const override { return "pgs"; }
    int iterations() const { return mIterations; }

  private:
    struct Row
    {
        int joint = 0;
        int k = 0;      // row within the joint
        int bodyA = -1; // -1: world/static
        int bodyB = 0;
        Vec6 JA, JB;             // the row's Jacobian entries
        Vec6 WA, WB;             // M^-1 J^T: velocity change per unit impulse
        double compliance = 0.0; // E of a drive row (J u + E lambda = c), 0 for conditions
        double invDiag = 0.0;    // 1 / (J M^-1 J^T + E)
    };
    int mIterations;
    std::vector<Row> mRows;
};

} // namespace frontier::core
