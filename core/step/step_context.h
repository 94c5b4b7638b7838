// core/step/step_context.h: what one step (or one stage of a composed step) needs, shared by the
// units of core/step/ and the steppers of core/steppers/: the model and its settings, the
// factorization, the (sub)step under way, and the rows, right-hand side, solution and poses its
// stages pass from one to the next. A unit takes the context and the few things that vary per
// call, not each of these one by one.
#pragma once

#include "core/actuation.h"
#include "core/extra_rows.h"
#include "core/free_rotation.h"
#include "core/impulse_solver.h"
#include "core/step_options.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace frontier::core
{

// Which scheme the step under way is taken by (docs/method.md §4, §11).
enum class StepScheme
{
    Euler,        // first order: symplectic Euler with the SHAKE-type projection
    Rattle,       // second order: a whole RATTLE step
    Rattle4Stage, // a RATTLE stage of a composed (rattle4) step
};

struct StepContext
{
    StepContext(const Model& model, const StepOptions& options, const FrontierLayout& layout,
                ImpulseSolver& solver, Actuation& actuation);

    // The model, its settings and the factorization: fixed for the simulator's life.
    const Model& model;
    const StepOptions& options;
    const FrontierLayout& layout;
    ImpulseSolver& solver;
    Actuation& actuation; // servos, motors, effort actuators and loads
    double dt;            // the model's time step (s)

    // The (sub)step under way.
    StepScheme scheme = StepScheme::Euler;
    double h = 0.0; // s: dt, or a stage of a composed step (< 0 for rattle4's middle stage)
    // Duration of one impulse solve (s): the step, or half of it for rattle, whose two velocity
    // stages each take half of the joints' damping and friction (core/joints/drive.h); for a
    // rattle4 stage half of its share of the step, always positive (docs/method.md §11).
    double driveStep = 0.0;
    bool rattle() const { return scheme != StepScheme::Euler; } // a RATTLE step or stage
    double stepLength() const { return std::abs(h); }           // s: h without its sign

    // What the stages of a step pass from one to the next.
    RowSystem rows;      // rows at the start of the step (the factored ones)
    RowSystem rowsAfter; // rows re-evaluated after the position update
    BlockVector rhs, solution;
    std::vector<BodyState> start;           // poses at the start of the step
    std::vector<PrincipalAxes> principal;   // principal axes per body (free rotation, momentum carry)
    std::vector<std::uint8_t> freeRotation; // per body: the step turns it by the free rotation (§4)
    std::vector<ExtraBlock> loopBlocks;     // loop joints alone, at the factored rows (§5, §7)
};

} // namespace frontier::core
