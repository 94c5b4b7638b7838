// bench/peers/jitter.h: jittered starts of a scene (frontier_peers --variants). A variant moves
// every free tree of the model (moving bodies joined by joints, not joined to the world or to a
// static body; a free body alone is a tree of its own) rigidly by a small pseudo-random offset:
// up to +-horizontalM in x and in y, up to upM upwards, and a yaw of up to +-yawRad about the
// vertical through the tree's centre of mass, each uniform. A rigid move keeps every joint of the
// tree exactly as closed as before (their frames are in the bodies' frames), and turns a tree's
// starting velocity with it. Trees joined to the world or to a static body stay where they are.
// The draws come from one std::mt19937_64 seeded with `seed` (its output, and so every variant,
// is the same on every platform), tree after tree in the order of their first body; a variant
// whose start overlaps (by Frontier's contact detection) more deeply than the model's own start is
// rejected and drawn again from the next numbers.
#pragma once

#include "core/model.h"

#include <cstdint>
#include <vector>

namespace frontier::peers
{

struct JitterBounds
{
    double horizontalM = 0.02; // m, in x and in y each
    double upM = 0.005;        // m, upwards only
    double yawRad = 0.05;      // rad, about the vertical through the tree's centre of mass
};

// `count` variants of the model, drawn in turn from one generator seeded with `seed`. Throws
// std::runtime_error when 100 draws in a row start in overlap.
std::vector<core::Model> jitteredVariants(const core::Model& model, int count, std::uint64_t seed,
                                          const JitterBounds& bounds = {});

// The free trees of the model: per tree its bodies (indices, in increasing order).
std::vector<std::vector<int>> freeTrees(const core::Model& model);

} // namespace frontier::peers
