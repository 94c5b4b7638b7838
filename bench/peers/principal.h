// bench/peers/principal.h: the model with each moving body's frame turned onto its principal axes,
// for engines that take principal moments only (Bullet). The bodies, joints and shapes are the
// same; only the frames they are written in change.
#pragma once

#include "core/model.h"

#include <vector>

namespace frontier::peers
{

// A copy of `model` in which every moving body whose inertia is not diagonal in its frame has the
// frame of its principal axes instead (origin still the centre of mass): inertia diagonal, and its
// shapes, joint anchors and axes rewritten in that frame. rotation_BP[b] turns the new frame into
// the old (identity where the frame was kept): a pose reported in the new frame becomes the
// model's by orientation_WB = orientation_WP * rotation_BP^-1.
core::Model inPrincipalFrames(const core::Model& model, std::vector<core::Quat>& rotation_BP);

} // namespace frontier::peers
