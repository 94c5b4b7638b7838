// core/dense_solver.h: the `dense` baseline, Moore's solve (docs/method.md §3): the whole impulse
// system as one dense matrix, Gaussian elimination with partial pivoting, O(n^3) time and
// O(n^2) memory. The correctness oracle for the linear solver: same equations, same layout.
#pragma once

#include "core/impulse_solver.h"

#include <Eigen/Dense>

namespace frontier::core
{

class DenseSolver final : public ImpulseSolver
{
  public:
    void factor(const RowSystem& system) override;
    void solve(const BlockVector& rhs, BlockVector& solution) override;
    const char* name() const override { return "dense"; }

    // The assembled KKT matrix [M J^T; J -E] in layout order (for tests and the benchmark); E is
    // the compliance of drive rows, zero elsewhere.
    static Eigen::MatrixXd assemble(const RowSystem& system);

  private:
    Eigen::PartialPivLU<Eigen::MatrixXd> mLu;
    Eigen::VectorXd mRhs;
};

} // namespace frontier::core
