// core/extra_rows_solve.cpp: block projected Gauss-Seidel on the Delassus system of the extra
// rows (docs/method.md §5): v = v_free + G lambda with the complementarity conditions of each block.
//
// G couples two rows only when their bodies share a tree (rows of different trees are exact
// zeros, see TreeSolver::delassus), so each block keeps the runs of rows where its columns are
// nonzero and a sweep updates velocities only there: a pile of separate articulated bodies costs
// the sum of its trees' squares per sweep, not the square of the whole.
#include "core/column_update.h"
#include "core/extra_rows.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>

namespace frontier::core
{

namespace
{

// Appends [begin, end) to sorted runs, merged with the last run when they touch or nearly do
// (a gap of a few rows costs less than starting a new run).
constexpr int cRunGap = 8; // rows

void appendRun(std::vector<std::pair<int, int>>& runs, int begin, int end)
{
    if (!runs.empty() && begin - runs.back().second <= cRunGap)
    {
        runs.back().second = std::max(runs.back().second, end);
        return;
    }
    runs.emplace_back(begin, end);
}

// velocity(rows in runs) += G(rows, o .. o + n - 1) delta (core/column_update.h: vectorized
// kernels, four wide where the processor has AVX2).
void addColumns(const Eigen::MatrixXd& G, int o, int n, const double* delta, const std::pair<int, int>* first,
                const std::pair<int, int>* last, Eigen::VectorXd& velocity)
{
    static const ColumnKernels& kernels = columnKernels();
    const Eigen::Index ld = G.rows(); // column-major: column k starts at G.data() + k ld
    for (const std::pair<int, int>* run = first; run != last; ++run)
    {
        const Eigen::Index start = run->first;
        const Eigen::Index length = run->second - run->first;
        double* v = velocity.data() + start;
        const double* column = G.data() + o * ld + start;
        if (n == 3)
        {
            kernels.three(v, column, column + ld, column + 2 * ld, delta[0], delta[1], delta[2], length);
            continue;
        }
        for (int q = 0; q < n; ++q)
        {
            kernels.one(v, column + q * ld, delta[q], length);
        }
    }
}

// One contact block with friction (rows normal, t1, t2), the others held: the new impulses. v
// points at the block's row velocities.
Eigen::Vector3d updateContact(const ContactPivots& p, const double* v, const Eigen::Vector3d& old)
{
    // Sticking first (docs/method.md §1): the whole block's velocity to its target; kept when the
    // normal impulse pushes and the friction stays inside the cone.
    const Eigen::Vector3d gap(p.target - v[0], -v[1], -v[2]);
    const Eigen::Vector3d trial = old + p.whole * gap;
    // |trial_t| from the two scalars: the same sum and root as Eigen's norm(), without reloading
    // 16 bytes across the vector's two stores (a store-forwarding stall here).
    const double t1 = trial(1);
    const double t2 = trial(2);
    if (trial(0) >= 0.0 && std::sqrt(t1 * t1 + t2 * t2) <= p.friction * trial(0))
    {
        return trial;
    }
    // Normal row: one-sided.
    Eigen::Vector3d next;
    next(0) = std::max(0.0, old(0) + p.normal * (p.target - v[0]));
    // Tangential rows after the normal change, then the friction cone |lambda_t| <= mu lambda_n
    // by radial projection.
    const Eigen::Vector2d vt = Eigen::Vector2d(v[1], v[2]) + p.tangentialOfNormal * (next(0) - old(0));
    Eigen::Vector2d lt = old.tail<2>() - p.tangential * vt;
    const double limit = p.friction * next(0);
    const double tangential = lt.norm();
    if (tangential > limit)
    {
        // Sliding: the anisotropic 2x2 step would leave the friction off the slip direction at
        // the fixed point; an isotropic step (k = 2 / trace) followed by the radial projection
        // converges to friction opposing the slip.
        lt = old.tail<2>() - p.isotropic * vt;
        const double slide = lt.norm();
        if (slide > limit)
        {
            lt *= slide > 0.0 ? limit / slide : 0.0;
        }
    }
    next.tail<2>() = lt;
    return next;
}

// How far one block's velocities and impulses are from its conditions (m/s or rad/s): see
// conditionResidual. NaN when one of them is not finite.
double blockResidual(const ExtraBlock& block, const Eigen::VectorXd& velocity, const Eigen::VectorXd& lambda)
{
    const int o = block.offset;
    if (!velocity.segment(o, block.count).allFinite() || !lambda.segment(o, block.count).allFinite())
    {
        return std::numeric_limits<double>::quiet_NaN();
    }
    if (block.kind == ExtraBlock::Kind::Loop)
    {
        return (velocity.segment(o, block.count) +
                block.compliance.head(block.count).cwiseProduct(lambda.segment(o, block.count)) -
                block.target.head(block.count))
            .cwiseAbs()
            .maxCoeff();
    }
    if (block.kind == ExtraBlock::Kind::Drive)
    {
        // Inside its bound the row holds; on the bound it may only fall short of the side it
        // pushes from (on +bound the row would take more, w <= 0; on -bound less, w >= 0).
        const double w = velocity(o) + block.compliance(0) * lambda(o) - block.target(0);
        const bool upper = lambda(o) >= block.bound;
        const bool lower = lambda(o) <= -block.bound;
        return upper && lower ? 0.0 : upper ? std::max(0.0, w) : lower ? std::max(0.0, -w) : std::abs(w);
    }
    // One-sided row: at its target while it pushes, at or above it otherwise.
    const double gap = velocity(o) - block.target(0);
    double worst = lambda(o) > 0.0 ? std::abs(gap) : std::max(0.0, -gap);
    if (block.count == 3)
    {
        // Friction inside the cone: no slip. On its edge: slip opposite to the friction.
        const Eigen::Vector2d slip = velocity.segment<2>(o + 1);
        const Eigen::Vector2d friction = lambda.segment<2>(o + 1);
        const double limit = block.friction * lambda(o);
        const double magnitude = friction.norm();
        if (!(limit > 0.0))
        {
            return worst; // no normal impulse, no friction: any slip
        }
        if (magnitude < (1.0 - 1e-9) * limit)
        {
            worst = std::max(worst, slip.cwiseAbs().maxCoeff());
        }
        else
        {
            worst = std::max(worst, (slip + slip.norm() / magnitude * friction).cwiseAbs().maxCoeff());
        }
    }
    return worst;
}

} // namespace

double conditionResidual(const std::vector<ExtraBlock>& blocks, const Eigen::VectorXd& velocity,
                         const Eigen::VectorXd& lambda)
{
    double worst = 0.0;
    for (const ExtraBlock& block : blocks)
    {
        const double residual = blockResidual(block, velocity, lambda);
        if (std::isnan(residual))
        {
            return residual; // std::max would pass over it
        }
        worst = std::max(worst, residual);
    }
    return worst;
}

bool conditionsMet(const std::vector<ExtraBlock>& blocks, const Eigen::VectorXd& velocity,
                   const Eigen::VectorXd& lambda, double tolerance)
{
    for (const ExtraBlock& block : blocks)
    {
        if (!(blockResidual(block, velocity, lambda) <= tolerance))
        {
            return false; // the first unmet block decides: a sweep far from converged stops here
        }
    }
    return true;
}

void coupleRowsByTree(const std::vector<ExtraBlock>& blocks, const std::vector<int>& treeOfBody,
                      RowCoupling& coupling, std::vector<std::vector<std::pair<int, int>>>& scratch)
{
    auto treeOf = [&](int body) { return body >= 0 ? treeOfBody[static_cast<std::size_t>(body)] : -1; };
    for (std::vector<std::pair<int, int>>& runs : scratch)
    {
        runs.clear();
    }
    for (const ExtraBlock& block : blocks) // blocks are in row order, so each tree's runs are sorted
    {
        const int a = treeOf(block.bodyA);
        const int b = treeOf(block.bodyB);
        for (int tree : {a, b})
        {
            if (tree >= 0 && (tree == a || b != a))
            {
                if (static_cast<std::size_t>(tree) >= scratch.size())
                {
                    scratch.resize(static_cast<std::size_t>(tree) + 1);
                }
                appendRun(scratch[static_cast<std::size_t>(tree)], block.offset, block.offset + block.count);
            }
            if (a == b)
            {
                break;
            }
        }
    }
    coupling.runs.clear();
    coupling.firstRun.clear();
    for (const ExtraBlock& block : blocks)
    {
        coupling.firstRun.push_back(static_cast<int>(coupling.runs.size()));
        const int a = treeOf(block.bodyA);
        const int b = treeOf(block.bodyB);
        const std::vector<std::pair<int, int>>* first =
            a >= 0 ? &scratch[static_cast<std::size_t>(a)] : nullptr;
        const std::vector<std::pair<int, int>>* second =
            b >= 0 && b != a ? &scratch[static_cast<std::size_t>(b)] : nullptr;
        if (first == nullptr)
        {
            std::swap(first, second);
        }
        if (second == nullptr)
        {
            coupling.runs.insert(coupling.runs.end(), first->begin(), first->end());
            continue;
        }
        // The union of two sorted run lists, overlapping runs joined in place (no allocation
        // once the vector has grown).
        const std::size_t start = coupling.runs.size();
        std::merge(first->begin(), first->end(), second->begin(), second->end(),
                   std::back_inserter(coupling.runs));
        std::size_t kept = start;
        for (std::size_t r = start; r < coupling.runs.size(); ++r)
        {
            const std::pair<int, int> run = coupling.runs[r];
            if (kept > start && run.first - coupling.runs[kept - 1].second <= cRunGap)
            {
                coupling.runs[kept - 1].second = std::max(coupling.runs[kept - 1].second, run.second);
            }
            else
            {
                coupling.runs[kept++] = run;
            }
        }
        coupling.runs.resize(kept);
    }
    coupling.firstRun.push_back(static_cast<int>(coupling.runs.size()));
}

ExtraSolveStats solveExtraRows(const std::vector<ExtraBlock>& blocks, const Eigen::MatrixXd& G,
                               const Eigen::VectorXd& freeVelocity, const ExtraSolveSettings& settings,
                               Eigen::VectorXd& lambda, ExtraSolveScratch& scratch,
                               const RowCoupling* coupling)
{
    scratch.velocity.noalias() = freeVelocity;
    if (lambda.size() > 0 && lambda.cwiseAbs().maxCoeff() > 0.0)
    {
        scratch.velocity.noalias() += G * lambda; // J u with the current impulses
    }
    return solveExtraRowsFrom(blocks, G, settings, lambda, scratch, coupling);
}

namespace
{

// The coupling that lets every block move every row, when the caller has none.
const RowCoupling* denseCoupling(std::size_t blockCount, Eigen::Index m, RowCoupling& dense)
{
    dense.runs.assign(blockCount, {0, static_cast<int>(m)});
    dense.firstRun.resize(blockCount + 1);
    for (std::size_t b = 0; b <= blockCount; ++b)
    {
        dense.firstRun[b] = static_cast<int>(b);
    }
    return &dense;
}

// Inverse pivots, once per matrix: loops by their whole block, contacts normal row alone and the
// 2x2 tangential block, limits and drives their one row (compliance on the diagonal). With
// pivotsKnown only the contacts' targets and friction, which change from step to step.
void computePivots(const std::vector<ExtraBlock>& blocks, const Eigen::MatrixXd& G, bool pivotsKnown,
                   ExtraSolveScratch& scratch)
{
    // A row that can barely move (a point pinned by joints) has a tiny pivot: regularize it by a
    // relative 1e-9 of the largest diagonal so the update stays bounded.
    const double regularization = 1e-9 * G.diagonal().cwiseAbs().maxCoeff() + 1e-300;
    std::vector<Mat6>& inverse = scratch.inverse;
    for (std::size_t b = 0; b < blocks.size(); ++b)
    {
        const int o = blocks[b].offset;
        const int n = blocks[b].count;
        if (pivotsKnown)
        {
            if (n == 3 && blocks[b].kind == ExtraBlock::Kind::Contact)
            {
                scratch.contacts[b].target = blocks[b].target(0); // targets change from step to step
                scratch.contacts[b].friction = blocks[b].friction;
            }
            continue;
        }
        if (blocks[b].kind == ExtraBlock::Kind::Loop)
        {
            Eigen::MatrixXd block = G.block(o, o, n, n) + regularization * Eigen::MatrixXd::Identity(n, n);
            block.diagonal() += blocks[b].compliance.head(n);
            inverse[b].topLeftCorner(n, n) = block.inverse();
            continue;
        }
        if (blocks[b].kind == ExtraBlock::Kind::Drive)
        {
            // A drive row's impulse is bounded, so a small pivot cannot make it run away; the
            // regularization would leave a relative 1e-9 slip in a sticking joint every step,
            // which the carried-over impulses of later steps would add up.
            const double pivot = G(o, o) + blocks[b].compliance(0);
            inverse[b](0, 0) = 1.0 / (pivot > regularization ? pivot : pivot + regularization);
            continue;
        }
        inverse[b](0, 0) = 1.0 / (G(o, o) + regularization);
        if (n == 3)
        {
            ContactPivots& p = scratch.contacts[b];
            p.normal = inverse[b](0, 0);
            const Eigen::Matrix2d tt =
                G.block<2, 2>(o + 1, o + 1) + regularization * Eigen::Matrix2d::Identity();
            p.tangential = tt.inverse();
            const Eigen::Matrix3d whole = G.block<3, 3>(o, o) + regularization * Eigen::Matrix3d::Identity();
            p.whole = whole.inverse(); // the sticking trial
            p.tangentialOfNormal = G.block<2, 1>(o + 1, o);
            p.isotropic = 2.0 / (G(o + 1, o + 1) + G(o + 2, o + 2) + 2.0 * regularization);
            p.target = blocks[b].target(0);
            p.friction = blocks[b].friction;
        }
    }
}

using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

// A loop, drive, limit or frictionless contact block's new impulses, the others held.
SmallVec nextImpulses(const ExtraBlock& block, const Mat6& inverse, const Eigen::VectorXd& velocity,
                      const SmallVec& old)
{
    const int o = block.offset;
    const int n = block.count;
    SmallVec next = old;
    if (block.kind == ExtraBlock::Kind::Loop)
    {
        const SmallVec target = block.target.head(n);
        next += inverse.topLeftCorner(n, n) *
                (target - velocity.segment(o, n) - block.compliance.head(n).cwiseProduct(old));
    }
    else if (block.kind == ExtraBlock::Kind::Drive)
    {
        const double free =
            old(0) + inverse(0, 0) * (block.target(0) - velocity[o] - block.compliance(0) * old(0));
        next(0) = std::clamp(free, -block.bound, block.bound);
    }
    else
    {
        // Normal (frictionless contact) or limit row: one-sided.
        next(0) = std::max(0.0, old(0) + inverse(0, 0) * (block.target(0) - velocity[o]));
    }
    return next;
}

// The largest impulse change of a sweep and the largest impulse (N s).
struct SweepChange
{
    double change = 0.0;
    double largest = 0.0;
};

// The commit step: the block's new impulses replace the old ones at rows o ..; the rows it moves
// follow (velocity += G(:, o ..) (next - old) over the block's runs). Fixed-size vectors (a
// contact's three rows) keep the running maxima in registers.
template <typename Vec>
[[gnu::always_inline]] inline void commitBlock(const Eigen::MatrixXd& G, int o, const Vec& old,
                                               const Vec& next, const std::pair<int, int>* firstRun,
                                               const std::pair<int, int>* lastRun, Eigen::VectorXd& lambda,
                                               Eigen::VectorXd& velocity, SweepChange& sweep)
{
    const int n = static_cast<int>(next.size());
    double delta[6];
    double step = 0.0; // largest impulse change of this block (N s)
    for (int q = 0; q < n; ++q)
    {
        delta[q] = next(q) - old(q);
        step = std::max(step, std::abs(delta[q]));
    }
    if (step > 0.0)
    {
        if constexpr (Vec::RowsAtCompileTime == Eigen::Dynamic)
            lambda.segment(o, n) = next;
        else
            lambda.template segment<Vec::RowsAtCompileTime>(o) = next;
        addColumns(G, o, n, delta, firstRun, lastRun, velocity);
    }
    sweep.largest = std::max(sweep.largest, next.cwiseAbs().maxCoeff());
    sweep.change = std::max(sweep.change, step);
}

// One Gauss-Seidel sweep over the blocks, in order.
SweepChange sweepBlocks(const std::vector<ExtraBlock>& blocks, const Eigen::MatrixXd& G,
                        const RowCoupling& coupling, ExtraSolveScratch& scratch, Eigen::VectorXd& lambda)
{
    SweepChange sweep;
    Eigen::VectorXd& velocity = scratch.velocity;
    const double* v = velocity.data();
    for (std::size_t b = 0; b < blocks.size(); ++b)
    {
        const ExtraBlock& block = blocks[b];
        const int o = block.offset;
        const std::pair<int, int>* firstRun = coupling.runs.data() + coupling.firstRun[b];
        const std::pair<int, int>* lastRun = coupling.runs.data() + coupling.firstRun[b + 1];
        if (block.kind == ExtraBlock::Kind::Contact && block.count == 3)
        {
            const Eigen::Vector3d old = lambda.segment<3>(o);
            if (old(0) == 0.0 && old(1) == 0.0 && old(2) == 0.0 && v[o] >= scratch.contacts[b].target)
            {
                // Apart and not pushing: no impulse solves the block (a quarter of the updates
                // in the pileup; the full update left them at zero every time).
                continue;
            }
            const Eigen::Vector3d next = updateContact(scratch.contacts[b], v + o, old);
            commitBlock(G, o, old, next, firstRun, lastRun, lambda, velocity, sweep);
            continue;
        }
        const SmallVec old = lambda.segment(o, block.count);
        const SmallVec next = nextImpulses(block, scratch.inverse[b], velocity, old);
        commitBlock(G, o, old, next, firstRun, lastRun, lambda, velocity, sweep);
    }
    return sweep;
}

} // namespace

ExtraSolveStats solveExtraRowsFrom(const std::vector<ExtraBlock>& blocks, const Eigen::MatrixXd& G,
                                   const ExtraSolveSettings& settings, Eigen::VectorXd& lambda,
                                   ExtraSolveScratch& scratch, const RowCoupling* coupling,
                                   std::uint64_t matrixVersion)
{
    ExtraSolveStats stats;
    const Eigen::Index m = G.rows();
    if (m == 0)
    {
        return stats;
    }
    const bool pivotsKnown = matrixVersion != 0 && matrixVersion == scratch.pivotsVersion &&
                             scratch.inverse.size() == blocks.size() && scratch.pivotsRows == m;
    scratch.pivotsVersion = matrixVersion;
    scratch.pivotsRows = m;
    if (!pivotsKnown)
    {
        scratch.inverse.assign(blocks.size(), Mat6::Zero());
    }
    scratch.contacts.resize(blocks.size());
    if (coupling == nullptr)
    {
        coupling = denseCoupling(blocks.size(), m, scratch.dense);
    }
    computePivots(blocks, G, pivotsKnown, scratch);

    for (int sweep = 0; sweep < settings.maxSweeps; ++sweep)
    {
        const SweepChange moved = sweepBlocks(blocks, G, *coupling, scratch, lambda);
        stats.sweeps = sweep + 1;
        stats.converged = conditionsMet(blocks, scratch.velocity, lambda, settings.velocityTolerance);
        if (stats.converged || moved.change <= settings.tolerance * moved.largest || moved.change < 1e-14)
        {
            break;
        }
    }
    return stats;
}

} // namespace frontier::core
