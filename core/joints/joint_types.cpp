// core/joints/joint_types.cpp: the table of joint types, and what model.h answers from it.
#include "core/joints/joint_types.h"

#include <array>

namespace frontier::core
{

namespace
{
constexpr std::array<JointCoordinate, 0> cNone = {};
constexpr std::array<JointCoordinate, 1> cRotation = {JointCoordinate::Rotation};
constexpr std::array<JointCoordinate, 1> cSlide = {JointCoordinate::Slide};
constexpr std::array<JointCoordinate, 2> cSlideRotation = {JointCoordinate::Slide, JointCoordinate::Rotation};
constexpr std::optional<JointCoordinate> cNoLimits = std::nullopt;

} // namespace

// Rows per type as docs/method.md §2 derives them; the writers are in core/joints/<type>.cpp.
// name, rows, coordinates, limit coordinate, needs axis, holds rotation, row writers
constexpr JointTypeInfo cJointTypeTable[] = {
    {JointType::Ball, "ball", 3, cNone, cNoLimits, false, false, detail::writeBallJoint<JointRows>,
     detail::writeBallJoint<JointRowsSlot>},
    // A ball joint whose parent is the world or a static body.
    {JointType::Nail, "nail", 3, cNone, cNoLimits, false, false, detail::writeBallJoint<JointRows>,
     detail::writeBallJoint<JointRowsSlot>},
    {JointType::Revolute, "revolute", 5, cRotation, JointCoordinate::Rotation, true, true,
     detail::writeRevoluteJoint<JointRows>, detail::writeRevoluteJoint<JointRowsSlot>},
    {JointType::Angle, "angle", 4, cNone, cNoLimits, true, true, detail::writeAngleJoint<JointRows>,
     detail::writeAngleJoint<JointRowsSlot>},
    {JointType::Cylindrical, "cylindrical", 4, cSlideRotation, cNoLimits, true, true,
     detail::writeCylindricalJoint<JointRows>, detail::writeCylindricalJoint<JointRowsSlot>},
    {JointType::Prismatic, "prismatic", 5, cSlide, JointCoordinate::Slide, true, true,
     detail::writePrismaticJoint<JointRows>, detail::writePrismaticJoint<JointRowsSlot>},
    {JointType::Fixed, "fixed", 6, cNone, cNoLimits, false, true, detail::writeFixedJoint<JointRows>,
     detail::writeFixedJoint<JointRowsSlot>},
    {JointType::Planar, "planar", 3, cNone, cNoLimits, true, true, detail::writePlanarJoint<JointRows>,
     detail::writePlanarJoint<JointRowsSlot>},
};

namespace
{
constexpr bool tableInOrder()
{
    std::size_t k = 0;
    for (const JointTypeInfo& info : cJointTypeTable)
    {
        const bool limitsOwnCoordinate =
            !info.limitCoordinate ||
            (info.coordinates.size() == 1 && info.coordinates[0] == *info.limitCoordinate);
        if (static_cast<std::size_t>(info.type) != k++ || info.rows < 1 || info.rows > 6 ||
            !limitsOwnCoordinate)
        {
            return false;
        }
    }
    return true;
}
static_assert(tableInOrder(), "cJointTypeTable: one row per JointType, in its order, of 1 to 6 rows; a "
                              "limited type has that one coordinate");

// Names every JointType and has no default, so a value added to the enum is a compile error
// (-Wswitch, warnings are errors) here until it has its case, and a row: tableInOrder checks the order.
constexpr bool hasRow(JointType type)
{
    switch (type)
    {
    case JointType::Ball:
    case JointType::Nail:
    case JointType::Revolute:
    case JointType::Angle:
    case JointType::Cylindrical:
    case JointType::Prismatic:
    case JointType::Fixed:
    case JointType::Planar:
        return static_cast<std::size_t>(type) < std::size(cJointTypeTable);
    }
    return false;
}
static_assert(hasRow(JointType::Planar), "cJointTypeTable: a row for every JointType");
} // namespace

std::span<const JointTypeInfo> jointTypes()
{
    return cJointTypeTable;
}

std::vector<std::string> jointTypeNames(bool (*has)(const JointTypeInfo&))
{
    std::vector<std::string> names;
    for (const JointTypeInfo& info : cJointTypeTable)
    {
        if (!has || has(info))
        {
            names.emplace_back(info.name);
        }
    }
    return names;
}

int jointRowCount(JointType type)
{
    return jointTypeInfo(type).rows;
}

bool holdsRotation(JointType type)
{
    return jointTypeInfo(type).holdsRotation;
}

const char* jointTypeName(JointType type)
{
    return jointTypeInfo(type).name;
}

std::optional<JointType> jointTypeFromName(const std::string& name)
{
    for (const JointTypeInfo& info : cJointTypeTable)
    {
        if (name == info.name)
        {
            return info.type;
        }
    }
    return std::nullopt;
}

} // namespace frontier::core
