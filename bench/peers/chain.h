// bench/peers/chain.h: the harness's generated scene, a chain of n boxes on ball joints hanging
// from the world, released horizontal so it swings down under gravity.
#pragma once

#include "core/model.h"

namespace frontier::peers
{

// Links of 0.1 x 0.02 x 0.02 m and 0.1 kg along +x at z = 2 m, joined end to end, the first to the
// world at (0, 0, 2); the last link's mass (and inertia) times tipMassRatio. dt = 1 ms.
core::Model chainOfBoxes(int n, double tipMassRatio = 1.0);

} // namespace frontier::peers
