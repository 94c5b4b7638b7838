// core/step_stats.h: what a step reports about itself (stage timings, joint errors, contacts,
// the contact problem's route), and the clock that times the stages.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>

namespace frontier::core
{

// How a step's contact problem was solved.
enum class ContactRoute
{
    None,    // no extra rows
    Carried, // the last step's impulses still met every condition
    Reused,  // Gauss-Seidel on a recent step's G, checked exactly against this step's rows
    Built,   // this step's G, then Gauss-Seidel
};
inline constexpr std::size_t cContactRoutes = 4;

// Index of a route in per-route counts (arrays of cContactRoutes).
constexpr std::size_t routeIndex(ContactRoute route)
{
    return static_cast<std::size_t>(route);
}

// Stages of a step, timed (wall seconds; the `seconds_per_step_*` keys of the run statistics):
// contact detection; free velocities, rows and the O(n) factorization; the impulse solve with the
// contact problem; positions, penetration and drift correction, momentum carry.
enum class StepStage
{
    Detect,
    Factor,
    Solve,
    Integrate,
};
inline constexpr std::size_t cStepStages = 4;

struct StepStats
{
    std::array<double, cStepStages> seconds{}; // wall time of each StepStage this step (s)
    double maxJointErrorM = 0.0;               // largest positional joint violation after the step (m)
    double maxJointErrorRad = 0.0;             // largest angular joint violation after the step (rad)
    int stabilizationIterations = 0;
    int contacts = 0;        // contact points found this step
    int extraRows = 0;       // contact, loop, limit and joint friction rows this step
    int contactSweeps = 0;   // Gauss-Seidel sweeps of the contact problem
    int stiffenedBodies = 0; // bodies given geometric stiffness this step (docs/method.md §7a)
    ContactRoute contactRoute = ContactRoute::None;
    double maxPenetrationM = 0.0;    // deepest contact overlap at the start of the step (m)
    bool firstOrderFallback = false; // a rattle step that stalled and was taken by euler instead
    // A rattle4 step taken as one rattle step (contact or limit rows, or a stage stalled;
    // docs/method.md §11).
    bool secondOrderFallback = false;
};

// Wall time of consecutive stages of one step, added into StepStats::seconds (zeroed when a step
// starts; a stage timed several times in a step, as by rattle4's three stages, counts each time).
class StageClock
{
  public:
    explicit StageClock(std::array<double, cStepStages>& out)
        : mOut(out), mLast(std::chrono::steady_clock::now())
    {
    }
    void lap(StepStage stage)
    {
        const auto now = std::chrono::steady_clock::now();
        mOut[static_cast<std::size_t>(stage)] += std::chrono::duration<double>(now - mLast).count();
        mLast = now;
    }

  private:
    std::array<double, cStepStages>& mOut;
    std::chrono::steady_clock::time_point mLast;
};

} // namespace frontier::core
