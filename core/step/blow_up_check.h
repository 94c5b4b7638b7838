// core/step/blow_up_check.h: what stops a run that blew up, a body's state non-finite or runaway
// or a joint come apart after the drift correction (docs/method.md §7), with a SimulationError
// that names it and the likely cause (core/failure_hint.h).
#pragma once

#include "core/contact.h"
#include "core/extra_rows.h"
#include "core/failure_hint.h"
#include "core/simulation_error.h"
#include "core/step/drift_correction.h"
#include "core/step_options.h"

#include <string>
#include <vector>

namespace frontier::core
{

class BlowUpCheck
{
  public:
    BlowUpCheck(const Model& model, const StepOptions& options, double dt);

    // The first step's contacts and limit rows tell whether the scene started with bodies deep
    // inside each other or a joint beyond its limit; later calls keep the first.
    void recordStartDefects(const std::vector<Contact>& contacts, const std::vector<ExtraBlock>& blocks,
                            const State& state);

    // What the likely cause reads from the step under way: its deepest overlap (m), its extra
    // rows, and its start-of-step velocities.
    struct StepView
    {
        double maxPenetrationM;
        const std::vector<ExtraBlock>& blocks;
        const std::vector<BodyState>& start;
    };

    // Throws SimulationError when a body's position, orientation, velocity or angular velocity is
    // not finite, or its position or speeds beyond the ranges of core/model.h (cMaxDistance from
    // the origin, cMaxSpeed, cMaxAngularSpeed); `where` in the step.
    void checkState(const State& state, const char* where, const StepView& step) const;

    // Throws the SimulationError of a joint that came apart: the joint of the largest error after
    // the correction, its child and parent, and the gap.
    [[noreturn]] void jointCameApart(const State& state, const JointErrors& errors,
                                     const StepView& step) const;

    // What carries over from one step to the next (core/step_memory.h): the first step's record.
    struct Memory
    {
        StartDefects startDefects;
        bool startRecorded = false;
    };
    const Memory& memory() const { return mMemory; }
    void restore(const Memory& memory) { mMemory = memory; }

  private:
    // "; ..." for a failure message, or empty.
    std::string likelyCause(const State& state, const StepView& step) const;

    const Model& mModel;
    const StepOptions& mOptions;
    double mDt;
    Memory mMemory; // what the first step found wrong with the start
};

} // namespace frontier::core
