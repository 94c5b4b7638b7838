// tests/io/joints_file_test.cpp: the joints CSV (io/joints_file.h): its lines and columns, one row
// per joint coordinate (`none` for a joint without one), the file's own coordinate
// (Joint::initialPosition added), empty effort and force fields before the first step, and the
// numbers of a step read back bit for bit.
#include "core/joints/coordinates.h"
#include "csv_table.h"
#include "io/joints_file.h"
#include "io_test_util.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <gtest/gtest.h>

namespace frontier::io::test
{
namespace
{

using core::Vec3;

// A hinge to the world (its file coordinate 0.25 rad at the start), a ball joint named with a
// comma, and a cylindrical joint: 1 + 1 + 2 rows per state.
core::Model threeJoints()
{
    core::Model model;
    for (const char* name : {"a", "b", "c"})
    {
        core::Body body;
        body.name = name;
        body.mass = 1.0;
        body.inertia_B = core::Mat3::Identity();
        body.position_W = Vec3(static_cast<double>(model.bodies.size()), 0.0, 1.0);
        model.bodies.push_back(body);
    }
    auto add = [&](const char* name, core::JointType type, int parent, int child, const Vec3& anchor)
    {
        core::Joint joint;
        joint.name = name;
        joint.type = type;
        joint.parent = parent;
        joint.child = child;
        core::setJointFrames(model, joint, anchor, Vec3::UnitY());
        model.joints.push_back(joint);
        return &model.joints.back();
    };
    add("hinge", core::JointType::Revolute, core::cWorld, 0, Vec3(-0.5, 0.0, 1.0))->initialPosition = 0.25;
    add("shoulder, left", core::JointType::Ball, 0, 1, Vec3(0.5, 0.0, 1.0));
    add("sleeve", core::JointType::Cylindrical, core::cWorld, 2, Vec3(2.0, 0.0, 1.0));
    return model;
}

TEST(JointsFile, RowsPerCoordinateWithEmptyFieldsBeforeTheFirstStep)
{
    TempDir dir;
    const std::string path = dir.file("joints.csv");
    const core::Model model = threeJoints();
    core::State state = core::initialState(model);
    state.bodies[0].angularVelocity_W = Vec3(0.0, 2.0, 0.0); // the hinge turns at 2 rad/s
    {
        JointsWriter writer(path, {{"scene", "s.yaml"}});
        writer.writeState(model, state, {});
        std::vector<JointStepLoad> loads(3);
        loads[0] = {Vec3(0.1, -2.0 / 3.0, 9.81), Vec3(1e-300, 0.0, -3.5), {1.25, 0.0}};
        loads[1] = {Vec3(-1.0, 0.0, 0.5), Vec3::Zero(), {0.0, 0.0}};
        loads[2] = {Vec3(0.0, 0.0, 1.0), Vec3(0.0, 7.0, 0.0), {0.5, -0.75}};
        state.time = 0.001;
        writer.writeState(model, state, loads);
        EXPECT_EQ(writer.rowsWritten(), 8);
        writer.commit();
    }
    const frontier::test::CsvTable table = frontier::test::readCsvTable(path);
    EXPECT_EQ(table.comment, "# frontier joints: scene=s.yaml");
    EXPECT_EQ(table.columns, frontier::test::splitCsvLine(cJointsHeader));
    EXPECT_EQ(std::string(cJointsHeader), "time,joint,coordinate,position,velocity,effort,fx,fy,fz,tx,ty,tz");
    ASSERT_EQ(table.rows.size(), 8u);
    for (const auto& row : table.rows)
    {
        ASSERT_EQ(row.size(), table.columns.size());
    }
    const char* joints[] = {"hinge", "shoulder, left", "sleeve", "sleeve"};
    const char* coordinates[] = {"angle", "none", "slide", "angle"};
    for (std::size_t r = 0; r < 8; ++r)
    {
        EXPECT_EQ(table.text(r, "joint"), joints[r % 4]) << "row " << r;
        EXPECT_EQ(table.text(r, "coordinate"), coordinates[r % 4]) << "row " << r;
        EXPECT_EQ(table.number(r, "time"), r < 4 ? 0.0 : 0.001);
        EXPECT_EQ(std::isnan(table.number(r, "position")), r % 4 == 1) << "row " << r;
        for (const char* column : {"effort", "fx", "fy", "fz", "tx", "ty", "tz"})
        {
            EXPECT_EQ(table.text(r, column).empty(), r < 4) << "row " << r << ", " << column;
        }
    }
    EXPECT_EQ(table.number(0, "position"), 0.25); // the file's coordinate at the start pose
    EXPECT_DOUBLE_EQ(table.number(0, "velocity"), 2.0);
    EXPECT_EQ(table.number(2, "position"), 0.0);
    // The step's numbers, bit for bit; the joint's force and torque on each of its rows; the
    // effort of each coordinate on its own row, 0 for the ball joint.
    auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
    EXPECT_EQ(bits(table.number(4, "fy")), bits(-2.0 / 3.0));
    EXPECT_EQ(bits(table.number(4, "tx")), bits(1e-300));
    EXPECT_EQ(table.number(4, "effort"), 1.25);
    EXPECT_EQ(table.number(5, "effort"), 0.0);
    EXPECT_EQ(table.number(5, "fx"), -1.0);
    EXPECT_EQ(table.number(6, "effort"), 0.5);
    EXPECT_EQ(table.number(7, "effort"), -0.75);
    EXPECT_EQ(table.number(6, "ty"), 7.0);
    EXPECT_EQ(table.number(7, "ty"), 7.0);
}

TEST(JointsFile, UncommittedWriterLeavesNoFile)
{
    TempDir dir;
    const std::string path = dir.file("joints.csv");
    {
        const core::Model model = threeJoints();
        JointsWriter writer(path, {});
        writer.writeState(model, core::initialState(model), {});
    }
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

} // namespace
} // namespace frontier::io::test
