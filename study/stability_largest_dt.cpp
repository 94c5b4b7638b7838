// study/stability_largest_dt.cpp: where a method ends on a scene, the largest time step (halving
// from 1/30 s) at which the scene still holds (study/stability.h, largestHoldingDt).
#include "study/stability.h"

#include <algorithm>
#include <cmath>

namespace frontier::study
{

namespace
{
constexpr int cMaxHalvings = 30; // 1/30 s / 2^30 = 3e-11 s: far below any scene's step
}

LargestDtCell largestHoldingDt(const core::Model& model, const std::string& sceneName,
                               const run::Method& method, const StabilityLimits& limits,
                               const io::SceneStabilityCriteria& criteria, const LargestDtOptions& options)
{
    LargestDtCell result;
    result.scene = sceneName;
    result.method = method.label();
    const double sceneDt = limits.dt.value_or(model.simulation.dt);
    result.duration = std::min(limits.duration.value_or(model.simulation.duration), options.duration);
    StabilityLimits run = limits;
    run.duration = result.duration;
    for (int k = 0; k <= cMaxHalvings; ++k)
    {
        run.dt = std::ldexp(options.start, -k); // exactly start / 2^k
        const StabilityCell cell = runStabilityCell(model, sceneName, method, run, criteria);
        if (cell.outcome == StabilityOutcome::Skipped || cell.outcome == StabilityOutcome::Unavailable)
        {
            result.outcome = cell.outcome;
            result.note = cell.note;
            return result;
        }
        ++result.runs;
        result.wallSeconds += cell.wallSeconds;
        result.smallestTriedDt = *run.dt;
        if (cell.survived())
        {
            result.outcome = StabilityOutcome::Survived;
            result.dt = *run.dt;
            result.note.clear();
            return result;
        }
        result.outcome = StabilityOutcome::Failed;
        result.note = cell.note;
        if (*run.dt < sceneDt)
        {
            break; // one halving below the scene's own step and still failing: it ends further down
        }
    }
    return result;
}

} // namespace frontier::study
