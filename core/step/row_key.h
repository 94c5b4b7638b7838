// core/step/row_key.h: what identifies an extra block from one step to the next, for carrying
// its impulse (core/step/impulse_memory.h) and for reusing the Delassus matrix built for it
// (core/step/contact_problem.h; docs/method.md §5).
#pragma once

#include "core/contact.h"
#include "core/extra_rows.h"

#include <vector>

namespace frontier::core
{

// An extra block by kind, bodies and source; contacts by point and normal (their indices are not
// stable), loops and limits by joint and the first row of J (a limit's sign flips between its
// lower and upper side).
struct RowKey
{
    ExtraBlock::Kind kind;
    int count, bodyA, bodyB, source;
    int actuator;   // drives: the actuator at its limit, -1 joint friction
    Vec3 point_W;   // contacts (m)
    Vec6 direction; // contacts: the normal; loops, limits: the first row of J
};

// The key of a block of this step; contacts are looked up in the step's contacts.
RowKey rowKey(const ExtraBlock& block, const std::vector<Contact>& contacts);

// Loops and limits: the same kind of block of the same joint, a limit on the same side.
bool sameJointRows(const RowKey& now, const RowKey& then);

} // namespace frontier::core
