// core/joints/joint_types.h: every joint type in one table (docs/method.md §2). What a type is
// (its name, rows, coordinates, whether it takes limits or an axis, its row writer) is read from
// here by the row assembly, the coordinates, the joint limits and the scene readers; adding a type
// is a JointType value, a row in cJointTypeTable (joint_types.cpp) and its row writer.
#pragma once

#include "core/joints/joint_rows.h"

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace frontier::core
{

// Writes a type's condition rows (count, positionRows and the rows; docs/method.md §2) into a
// JointRows or in place into a JointRowsTable (JointRowsSlot).
template <class Rows>
using JointRowWriter = void (*)(const Joint&, const JointPose&, const detail::JointGeometry&, Rows&);

struct JointTypeInfo
{
    JointType type;
    const char* name; // as scenes and messages name it (a YAML joint's `type:`)
    int rows;         // condition rows (the joint's block before its drive rows)
    // Its coordinates, in the order of its drive rows (core/joints/coordinates.h); none: no
    // actuator, damping or friction acts on it.
    std::span<const JointCoordinate> coordinates;
    // The coordinate limits, damping and friction act on; none: the type takes no limits.
    std::optional<JointCoordinate> limitCoordinate;
    bool needsAxis;     // a scene gives its axis d_k
    bool holdsRotation; // its rows hold (some of) the relative rotation, not only a point
    JointRowWriter<JointRows> writeRows;
    JointRowWriter<JointRowsSlot> writeRowsInPlace;
};

// The table, indexed by JointType (joint_types.cpp checks the order).
extern const JointTypeInfo cJointTypeTable[];
inline const JointTypeInfo& jointTypeInfo(JointType type)
{
    return cJointTypeTable[static_cast<std::size_t>(type)];
}
// Every type, in the order of JointType.
std::span<const JointTypeInfo> jointTypes();

// The names of the types for which `has` holds (all of them without it), in table order.
std::vector<std::string> jointTypeNames(bool (*has)(const JointTypeInfo&) = nullptr);

// Whether limits (and damping, friction) act on the type's coordinate.
inline bool hasLimits(JointType type)
{
    return jointTypeInfo(type).limitCoordinate.has_value();
}

// Its row writer for a JointRows or a JointRowsSlot.
template <class Rows> JointRowWriter<Rows> jointRowWriter(const JointTypeInfo& info)
{
    if constexpr (std::is_same_v<Rows, JointRows>)
    {
        return info.writeRows;
    }
    else
    {
        return info.writeRowsInPlace;
    }
}

} // namespace frontier::core
