// core/extra_rows_solve.cpp: block projected Gauss-Seidel on the Delassus system of the extra
// rows (docs/method.md §5): v = v_free + G lambda with the complementarity conditions of each block.
//
// G is stored by tree (core/delassus.h): a block's impulse moves the rows of the parts it is in,
// so each part keeps the velocity its blocks' impulse changes have made on its rows, and a sweep
// updates only those: a pile of separate articulated bodies costs the sum of its trees' squares
// per sweep, not the square of the whole. Islands (parts joined by shared rows) are solved one
// after another, each swept until its own conditions are met or it stops progressing.
#include "core/column_update.h"
#include "core/delassus.h"
#include "core/extra_rows.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace frontier::core
{

namespace
{

// part velocity += G_part(:, o .. o + n - 1) delta over the part's rows (core/column_update.h:
// vectorized kernels, four wide where the processor has AVX2).
void addColumns(const Eigen::MatrixXd& G, int o, int n, const double* delta, double* velocity)
{
    static const ColumnKernels& kernels = columnKernels();
    const Eigen::Index ld = G.rows(); // column-major: column k starts at G.data() + k ld
    const double* column = G.data() + o * ld;
    if (n == 3)
    {
        kernels.three(velocity, column, column + ld, column + 2 * ld, delta[0], delta[1], delta[2], ld);
        return;
    }
    for (int q = 0; q < n; ++q)
    {
        kernels.one(velocity, column + q * ld, delta[q], ld);
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
// conditionResidual. v and lambda point at the block's rows. NaN when one of them is not finite.
inline double blockResidual(const ExtraBlock& block, const double* v, const double* lambda)
{
    const int n = block.count;
    double sum = 0.0; // finite exactly when every value is (NaN and infinities propagate)
    for (int q = 0; q < n; ++q)
    {
        sum += v[q] * 0.0 + lambda[q] * 0.0;
    }
    if (sum != 0.0)
    {
        return std::numeric_limits<double>::quiet_NaN();
    }
    if (block.kind == ExtraBlock::Kind::Loop)
    {
        double worst = 0.0;
        for (int q = 0; q < n; ++q)
        {
            worst = std::max(worst, std::abs(v[q] + block.compliance(q) * lambda[q] - block.target(q)));
        }
        return worst;
    }
    if (block.kind == ExtraBlock::Kind::Drive)
    {
        // Inside its bound the row holds; on the bound it may only fall short of the side it
        // pushes from (on +bound the row would take more, w <= 0; on -bound less, w >= 0).
        const double w = v[0] + block.compliance(0) * lambda[0] - block.target(0);
        const bool upper = lambda[0] >= block.bound;
        const bool lower = lambda[0] <= -block.bound;
        return upper && lower ? 0.0 : upper ? std::max(0.0, w) : lower ? std::max(0.0, -w) : std::abs(w);
    }
    // One-sided row: at its target while it pushes, at or above it otherwise.
    const double gap = v[0] - block.target(0);
    double worst = lambda[0] > 0.0 ? std::abs(gap) : std::max(0.0, -gap);
    if (n == 3)
    {
        // Friction inside the cone: no slip. On its edge: slip opposite to the friction.
        const double limit = block.friction * lambda[0];
        if (!(limit > 0.0))
        {
            return worst; // no normal impulse, no friction: any slip
        }
        const double magnitude = std::sqrt(lambda[1] * lambda[1] + lambda[2] * lambda[2]);
        if (magnitude < (1.0 - 1e-9) * limit)
        {
            return std::max({worst, std::abs(v[1]), std::abs(v[2])});
        }
        const double scale = std::sqrt(v[1] * v[1] + v[2] * v[2]) / magnitude;
        return std::max({worst, std::abs(v[1] + scale * lambda[1]), std::abs(v[2] + scale * lambda[2])});
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
        const double residual =
            blockResidual(block, velocity.data() + block.offset, lambda.data() + block.offset);
        if (std::isnan(residual))
        {
            return residual; // std::max would pass over it
        }
        worst = std::max(worst, residual);
    }
    return worst;
}

double conditionResidual(const std::vector<ExtraBlock>& blocks, std::span<const int> which,
                         const Eigen::VectorXd& velocity, const Eigen::VectorXd& lambda)
{
    double worst = 0.0;
    for (int b : which)
    {
        const ExtraBlock& block = blocks[static_cast<std::size_t>(b)];
        const double residual =
            blockResidual(block, velocity.data() + block.offset, lambda.data() + block.offset);
        if (std::isnan(residual))
        {
            return residual;
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
        if (!(blockResidual(block, velocity.data() + block.offset, lambda.data() + block.offset) <=
              tolerance))
        {
            return false; // the first unmet block decides: a sweep far from converged stops here
        }
    }
    return true;
}

ExtraSolveStats solveExtraRows(const std::vector<ExtraBlock>& blocks, const DelassusMatrix& G,
                               const Eigen::VectorXd& freeVelocity, const ExtraSolveSettings& settings,
                               Eigen::VectorXd& lambda, ExtraSolveScratch& scratch)
{
    scratch.velocity = freeVelocity;
    if (lambda.size() > 0 && lambda.cwiseAbs().maxCoeff() > 0.0)
    {
        G.multiply(lambda, scratch.product);
        scratch.velocity += scratch.product; // J u with the current impulses
    }
    return solveExtraRowsFrom(blocks, G, settings, lambda, scratch);
}

namespace
{

// Inverse pivots, once per matrix version: loops by their whole block, contacts normal row alone
// and the 2x2 tangential block, limits and drives their one row (compliance on the diagonal). With
// pivotsKnown only the contacts' targets and friction, which change from step to step.
void computePivots(const std::vector<ExtraBlock>& blocks, const DelassusMatrix& G, bool pivotsKnown,
                   ExtraSolveScratch& scratch)
{
    std::vector<Mat6>& inverse = scratch.inverse;
    if (!pivotsKnown)
    {
        // A row that can barely move (a point pinned by joints) has a tiny pivot: regularize it by
        // a relative 1e-9 of what it would be on free bodies (DelassusMatrix::freeScale), so the
        // update stays bounded whatever the other rows are.
        scratch.diagonal.resize(blocks.size());
        scratch.regularization.resize(blocks.size());
        for (std::size_t b = 0; b < blocks.size(); ++b)
        {
            G.diagonalBlock(static_cast<int>(b), blocks[b].count, scratch.diagonal[b]);
            scratch.regularization[b] = 1e-9 * G.freeScale(static_cast<int>(b), blocks[b].count) + 1e-300;
        }
    }
    for (std::size_t b = 0; b < blocks.size(); ++b)
    {
        const int n = blocks[b].count;
        const double regularization = scratch.regularization[b];
        if (pivotsKnown)
        {
            if (n == 3 && blocks[b].kind == ExtraBlock::Kind::Contact)
            {
                scratch.contacts[b].target = blocks[b].target(0); // targets change from step to step
                scratch.contacts[b].friction = blocks[b].friction;
            }
            continue;
        }
        const Mat6& D = scratch.diagonal[b]; // the block's diagonal block of G
        if (blocks[b].kind == ExtraBlock::Kind::Loop)
        {
            Eigen::MatrixXd block = D.topLeftCorner(n, n) + regularization * Eigen::MatrixXd::Identity(n, n);
            block.diagonal() += blocks[b].compliance.head(n);
            inverse[b].topLeftCorner(n, n) = block.inverse();
            continue;
        }
        if (blocks[b].kind == ExtraBlock::Kind::Drive)
        {
            // A drive row's impulse is bounded, so a small pivot cannot make it run away; the
            // regularization would leave a relative 1e-9 slip in a sticking joint every step,
            // which the carried-over impulses of later steps would add up.
            const double pivot = D(0, 0) + blocks[b].compliance(0);
            inverse[b](0, 0) = 1.0 / (pivot > regularization ? pivot : pivot + regularization);
            continue;
        }
        inverse[b](0, 0) = 1.0 / (D(0, 0) + regularization);
        if (n == 3)
        {
            ContactPivots& p = scratch.contacts[b];
            p.normal = inverse[b](0, 0);
            const Eigen::Matrix2d tt = D.block<2, 2>(1, 1) + regularization * Eigen::Matrix2d::Identity();
            p.tangential = tt.inverse();
            const Eigen::Matrix3d whole =
                D.topLeftCorner<3, 3>() + regularization * Eigen::Matrix3d::Identity();
            p.whole = whole.inverse(); // the sticking trial
            p.tangentialOfNormal = D.block<2, 1>(1, 0);
            p.isotropic = 2.0 / (D(1, 1) + D(2, 2) + 2.0 * regularization);
            p.target = blocks[b].target(0);
            p.friction = blocks[b].friction;
        }
    }
}

using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

// A loop, drive, limit or frictionless contact block's new impulses, the others held; v points at
// its row velocities.
SmallVec nextImpulses(const ExtraBlock& block, const Mat6& inverse, const double* v, const SmallVec& old)
{
    const int n = block.count;
    SmallVec next = old;
    if (block.kind == ExtraBlock::Kind::Loop)
    {
        const SmallVec target = block.target.head(n);
        next += inverse.topLeftCorner(n, n) *
                (target - Eigen::Map<const SmallVec>(v, n) - block.compliance.head(n).cwiseProduct(old));
    }
    else if (block.kind == ExtraBlock::Kind::Drive)
    {
        const double free = old(0) + inverse(0, 0) * (block.target(0) - v[0] - block.compliance(0) * old(0));
        next(0) = std::clamp(free, -block.bound, block.bound);
    }
    else
    {
        // Normal (frictionless contact) or limit row: one-sided.
        next(0) = std::max(0.0, old(0) + inverse(0, 0) * (block.target(0) - v[0]));
    }
    return next;
}

// The largest impulse change of a sweep and the largest impulse (N s); the largest residual of a
// block before its update (m/s; NaN when one is not finite) and how many blocks were updated.
struct SweepChange
{
    double change = 0.0;
    double largest = 0.0;
    double residualBefore = 0.0;
    int updated = 0;
};

// One island's working view: the base velocities (exact at the impulses on entry) plus what each
// of its parts' impulse changes have done since.
class IslandSweeper
{
  public:
    IslandSweeper(const std::vector<ExtraBlock>& blocks, const DelassusMatrix& G, ExtraSolveScratch& scratch,
                  Eigen::VectorXd& lambda)
        : mBlocks(blocks), mG(G), mScratch(scratch), mLambda(lambda)
    {
    }

    // Zeroes the accumulators of the island's parts.
    void start(int island)
    {
        mIsland = island;
        for (int p : mG.islandParts(island))
        {
            mScratch.partVelocity[static_cast<std::size_t>(p)].setZero(mG.part(p).rows);
        }
    }

    // The velocities of block b's rows now (count values into v).
    void velocity(int b, double* v) const
    {
        const ExtraBlock& block = mBlocks[static_cast<std::size_t>(b)];
        const DelassusMatrix::Place& place = mG.place(b);
        const double* base = mScratch.velocity.data() + block.offset;
        const double* first =
            mScratch.partVelocity[static_cast<std::size_t>(place.part[0])].data() + place.offset[0];
        if (place.part[1] < 0)
        {
            for (int q = 0; q < block.count; ++q)
            {
                v[q] = base[q] + first[q];
            }
            return;
        }
        const double* second =
            mScratch.partVelocity[static_cast<std::size_t>(place.part[1])].data() + place.offset[1];
        for (int q = 0; q < block.count; ++q)
        {
            v[q] = base[q] + first[q] + second[q];
        }
    }

    // One Gauss-Seidel sweep over the island's blocks, in order; a block whose residual is at most
    // skipBelow (m/s) is settled and left as it is.
    SweepChange sweep(double skipBelow)
    {
        SweepChange sweep;
        double v[6];
        for (int b : mG.islandBlocks(mIsland))
        {
            const ExtraBlock& block = mBlocks[static_cast<std::size_t>(b)];
            const int o = block.offset;
            velocity(b, v);
            const double before = blockResidual(block, v, mLambda.data() + o);
            sweep.residualBefore = std::isnan(before) || std::isnan(sweep.residualBefore)
                                       ? std::numeric_limits<double>::quiet_NaN()
                                       : std::max(sweep.residualBefore, before);
            if (before <= skipBelow)
            {
                continue;
            }
            if (block.kind == ExtraBlock::Kind::Contact && block.count == 3)
            {
                const Eigen::Vector3d old = mLambda.segment<3>(o);
                const ContactPivots& pivots = mScratch.contacts[static_cast<std::size_t>(b)];
                if (old(0) == 0.0 && old(1) == 0.0 && old(2) == 0.0 && v[0] >= pivots.target)
                {
                    // Apart and not pushing: no impulse solves the block (a quarter of the updates
                    // in the pileup; the full update left them at zero every time).
                    continue;
                }
                commit(b, old, updateContact(pivots, v, old), sweep);
                continue;
            }
            const SmallVec old = mLambda.segment(o, block.count);
            commit(b, old, nextImpulses(block, mScratch.inverse[static_cast<std::size_t>(b)], v, old), sweep);
        }
        return sweep;
    }

    // The largest residual of the island's blocks (conditionResidual), NaN when one is not finite.
    double residual() const
    {
        double worst = 0.0;
        double v[6];
        for (int b : mG.islandBlocks(mIsland))
        {
            const ExtraBlock& block = mBlocks[static_cast<std::size_t>(b)];
            velocity(b, v);
            const double r = blockResidual(block, v, mLambda.data() + block.offset);
            if (std::isnan(r))
            {
                return r;
            }
            worst = std::max(worst, r);
        }
        return worst;
    }

    // The accumulated changes into the base velocities (scratch.velocity: J u at the impulses now).
    void finish()
    {
        for (int p : mG.islandParts(mIsland))
        {
            const DelassusMatrix::Part& part = mG.part(p);
            const Eigen::VectorXd& accumulated = mScratch.partVelocity[static_cast<std::size_t>(p)];
            for (int l = 0; l < part.rows; ++l)
            {
                mScratch.velocity(part.global[static_cast<std::size_t>(l)]) += accumulated(l);
            }
        }
    }

  private:
    // The block's new impulses replace the old ones; the rows of its parts follow
    // (velocity += G(:, block) (next - old) in each part). Fixed-size vectors (a contact's three
    // rows) keep the running maxima in registers.
    template <typename Vec>
    [[gnu::always_inline]] inline void commit(int b, const Vec& old, const Vec& next, SweepChange& sweep)
    {
        const ExtraBlock& block = mBlocks[static_cast<std::size_t>(b)];
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
            ++sweep.updated;
            if constexpr (Vec::RowsAtCompileTime == Eigen::Dynamic)
                mLambda.segment(block.offset, n) = next;
            else
                mLambda.template segment<Vec::RowsAtCompileTime>(block.offset) = next;
            const DelassusMatrix::Place& place = mG.place(b);
            for (int side = 0; side < 2 && place.part[side] >= 0; ++side)
            {
                const std::size_t p = static_cast<std::size_t>(place.part[side]);
                addColumns(mG.part(place.part[side]).G, place.offset[side], n, delta,
                           mScratch.partVelocity[p].data());
            }
        }
        sweep.largest = std::max(sweep.largest, next.cwiseAbs().maxCoeff());
        sweep.change = std::max(sweep.change, step);
    }

    const std::vector<ExtraBlock>& mBlocks;
    const DelassusMatrix& mG;
    ExtraSolveScratch& mScratch;
    Eigen::VectorXd& mLambda;
    int mIsland = 0;
};

// The stall rule of ExtraSolveSettings: the residuals of the last stallSweeps sweeps against the
// smallest one before them.
class StallWatch
{
  public:
    explicit StallWatch(const ExtraSolveSettings& settings)
        : mWindow(std::clamp(settings.stallSweeps, 0, cMaxWindow)), mRatio(settings.stallRatio)
    {
    }

    // Takes the residual after a sweep; true when the sweeps have stalled.
    bool stalled(double residual)
    {
        if (mWindow == 0)
        {
            return false;
        }
        if (mCount >= mWindow)
        {
            mBestBefore = std::min(mBestBefore, mRecent[static_cast<std::size_t>(mCount % mWindow)]);
        }
        mRecent[static_cast<std::size_t>(mCount % mWindow)] = residual;
        ++mCount;
        if (mCount <= mWindow)
        {
            return false;
        }
        const double bestRecent = *std::min_element(mRecent.begin(), mRecent.begin() + mWindow);
        return bestRecent > mRatio * mBestBefore; // NaN: not stalled (the sweeps run to the cap)
    }

  private:
    static constexpr int cMaxWindow = 64;
    int mWindow;
    double mRatio;
    int mCount = 0;
    double mBestBefore = std::numeric_limits<double>::infinity();
    std::array<double, cMaxWindow> mRecent{};
};

} // namespace

// Above this many tolerances, a sweep's residuals before the updates (SweepChange) stand for the
// residual after it.
constexpr double cMeasureBelow = 4.0;

namespace
{

// Gauss-Seidel sweeps over one island until its residual (m/s, left in `residual`) is within
// `tolerance`, the sweeps stop moving it, it stalls, or settings.maxSweeps; `sweeps` counts them.
inline ExtraSolveScratch::IslandEnd sweepIsland(IslandSweeper& sweeper, const DelassusMatrix& G,
                                                const ExtraSolveSettings& settings, int island,
                                                double tolerance, int& sweeps, double& residual)
{
    using IslandEnd = ExtraSolveScratch::IslandEnd;
    sweeper.start(island);
    StallWatch stall(settings);
    IslandEnd end = IslandEnd::Stopped;
    for (int sweep = 0; sweep < settings.maxSweeps; ++sweep)
    {
        const SweepChange moved = sweeper.sweep(settings.settledRatio * tolerance);
        ++sweeps;
        // The blocks' residuals before their updates bound nothing once a block moved, but far
        // above the tolerance they say the sweeps go on: the residual after the sweep (a second
        // pass over the blocks) is measured only near it, or for a lone block (whose update may
        // be exact).
        const bool measure = moved.updated > 0 && (!(moved.residualBefore > cMeasureBelow * tolerance) ||
                                                   G.islandBlocks(island).size() == 1);
        residual = measure ? sweeper.residual() : moved.residualBefore;
        if (residual <= tolerance)
        {
            end = IslandEnd::Converged;
            break;
        }
        if (moved.change <= settings.tolerance * moved.largest || moved.change < 1e-14)
        {
            break;
        }
        if (stall.stalled(residual))
        {
            end = IslandEnd::Stalled;
            break;
        }
    }
    sweeper.finish();
    return end;
}

} // namespace

ExtraSolveStats solveExtraRowsFrom(const std::vector<ExtraBlock>& blocks, const DelassusMatrix& G,
                                   const ExtraSolveSettings& settings, Eigen::VectorXd& lambda,
                                   ExtraSolveScratch& scratch, std::span<const double> islandTolerance)
{
    using IslandEnd = ExtraSolveScratch::IslandEnd;
    ExtraSolveStats stats;
    stats.converged = true;
    scratch.islandEnd.assign(static_cast<std::size_t>(G.islands()), IslandEnd::Skipped);
    scratch.islandResidual.assign(static_cast<std::size_t>(G.islands()), 0.0);
    if (G.rows() == 0)
    {
        return stats;
    }
    const bool pivotsKnown = G.version() == scratch.pivotsVersion && scratch.inverse.size() == blocks.size();
    scratch.pivotsVersion = G.version();
    if (!pivotsKnown)
    {
        scratch.inverse.assign(blocks.size(), Mat6::Zero());
    }
    scratch.contacts.resize(blocks.size());
    computePivots(blocks, G, pivotsKnown, scratch);
    if (scratch.partVelocity.size() < static_cast<std::size_t>(G.parts()))
    {
        scratch.partVelocity.resize(static_cast<std::size_t>(G.parts()));
    }

    IslandSweeper sweeper(blocks, G, scratch, lambda);
    for (int island = 0; island < G.islands(); ++island)
    {
        const double tolerance = islandTolerance.empty() ? settings.velocityTolerance
                                                         : islandTolerance[static_cast<std::size_t>(island)];
        if (tolerance < 0.0)
        {
            continue;
        }
        double residual = 0.0;
        const IslandEnd end = sweepIsland(sweeper, G, settings, island, tolerance, stats.sweeps, residual);
        scratch.islandEnd[static_cast<std::size_t>(island)] = end;
        scratch.islandResidual[static_cast<std::size_t>(island)] = residual;
        stats.converged = stats.converged && end == IslandEnd::Converged;
        stats.stalled = stats.stalled || end == IslandEnd::Stalled;
        stats.residual = std::isnan(residual) || std::isnan(stats.residual)
                             ? std::numeric_limits<double>::quiet_NaN()
                             : std::max(stats.residual, residual);
    }
    return stats;
}

} // namespace frontier::core
