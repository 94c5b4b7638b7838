// core/step_options.h: the settings of a step (tolerances, restitution, penetration bounds).
#pragma once

#include "core/extra_rows.h"

namespace frontier::core
{

struct StepOptions
{
    double stabilizationTolerance = 1e-10; // m (rad for angular rows)
    int stabilizationIterations = 40;
    // The step's velocities ask J u = -D_pred / h, the drift the position update is predicted to
    // leave (docs/method.md §7, eq. (11a)), so the projection starts near C = 0 (on steps with
    // extra rows, solved after their impulses); false asks J u = 0 (the same result within
    // stabilizationTolerance, more iterations).
    bool predictDrift = true;
    double restitutionSpeed = 0.1; // m/s: slower impacts do not bounce, so things come to rest
    double penetrationSlop = 5e-4; // m: overlap left to the next steps' contacts, not projected
    // Bounds of the penetration projection (core/penetration.h): a step displaces no body by more
    // than penetrationMaxSpeed * dt nor turns it by more than penetrationMaxAngularSpeed * dt, so
    // deep overlaps come out over several steps (at 1 ms: 5 mm and 0.02 rad a step; the bundled
    // scenes' projections stay below 1 m/s and 4.7 rad/s at 1 ms, 2 m/s and 13.4 rad/s at 1/30 s).
    // A row whose Delassus diagonal is below penetrationHeldRatio of its bodies' free-body value is
    // held by the joints (round-off: a row they leave free is above 0.03 in those scenes) and left
    // alone.
    double penetrationMaxSpeed = 5.0;         // m/s
    double penetrationMaxAngularSpeed = 20.0; // rad/s
    double penetrationHeldRatio = 1e-9;
    double limitMargin = 0.02; // rad or m: limit rows appear this close to a limit
    // The Gauss-Seidel of the contact problem: its sweep cap, stall rule and impulse-change test; its
    // velocity tolerance comes from the model (ContactSettings::tolerance, relativeTolerance).
    ExtraSolveSettings contactSolve;
    // Resting contact may solve with the Delassus matrix of a recent step with the same rows, the
    // result checked exactly against this step's (core/step/contact_problem.h); false always
    // builds this step's matrix when the carried-over impulses do not hold.
    bool reuseDelassus = true;
};

} // namespace frontier::core
