// core/failure_hint.h: the likely cause of a run that blew up, for the SimulationError message.
//
// A smaller time step helps when bodies turn so far within one step that the joint correction's
// linearization fails; it does not help a scene that starts with bodies deep inside each other
// or a joint beyond its limit. The first step's contacts and limit rows say whether the scene
// started so; a failure while the recovery of that start could still be under way names it (the
// bodies and the depth, or the joint, its coordinate and its limits) instead of the time step.
#pragma once

#include "core/contact.h"
#include "core/extra_rows.h"

#include <string>
#include <vector>

namespace frontier::core
{

// Overlaps at the start deeper than this count as a deep initial overlap (m); an overlap, or a
// start limit overrun (rad or m), still beyond it when a run fails is still being recovered.
inline constexpr double cDeepOverlap = 0.01;
// A body turning more than this within one step (rad) is fast for the step.
inline constexpr double cFastRotationPerStep = 0.1;

// What the first step found wrong with the scene's start.
struct StartDefects
{
    int deepOverlaps = 0;  // contacts overlapping more than cDeepOverlap
    double overlapM = 0.0; // the deepest of them (m)
    int overlapBodyA = -1; // its bodies (overlapBodyB may be static)
    int overlapBodyB = -1;
    int limitJoint = -1;          // the joint furthest beyond a limit, -1 none
    double limitExcess = 0.0;     // by how much (rad or m)
    double limitCoordinate = 0.0; // its coordinate at the start (rad or m)
};

// From the first step's contacts and extra rows (limit blocks carry their overrun in error(0)).
StartDefects findStartDefects(const std::vector<Contact>& contacts, const std::vector<ExtraBlock>& extra,
                              const Model& model, const State& state);

// What to append to a failure message ("; ..." or empty). `recovering`: the failure came while
// the recovery of the start defects could still be under way; rotationPerStep (rad) of
// fastestBody: the largest |w| dt at the start of the failing step.
std::string failureHint(const Model& model, const StartDefects& start, bool recovering,
                        double rotationPerStep, int fastestBody);

} // namespace frontier::core
