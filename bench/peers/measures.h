// bench/peers/measures.h: what the harness measures on any engine's poses, by one rule for all
// engines (so no engine's own bookkeeping enters the comparison).
#pragma once

#include "bench/peers/engine.h"

#include <vector>

namespace frontier::peers
{

// Largest distance (m) between a joint's anchor on its parent and on its child.
double jointGap(const core::Model& model, const std::vector<Pose>& poses);

// Total energy (J): kinetic from central differences of three consecutive poses h apart
// (velocity (x+ - x-) / 2h, angular velocity from the rotation q+ q-^-1 over 2h), potential of
// gravity at the middle pose.
struct Energy
{
    double kinetic = 0.0; // J
    double total = 0.0;   // J, kinetic + potential of gravity
};
Energy energyByDifferences(const core::Model& model, const std::vector<Pose>& before,
                           const std::vector<Pose>& middle, const std::vector<Pose>& after, double h);

// Largest distance (m) between the bodies' centres of mass in two pose sets.
double positionError(const std::vector<Pose>& a, const std::vector<Pose>& b);

} // namespace frontier::peers
