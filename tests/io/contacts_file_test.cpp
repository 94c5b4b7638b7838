// tests/io/contacts_file_test.cpp: the contacts CSV (io/contacts_file.h): its lines and columns,
// one row per contact, the force (impulse / dt) split into its normal part and the friction
// vector tangential to the contact (a contact of known normal and impulse), numbers bit for bit.
#include "csv_table.h"
#include "io/contacts_file.h"
#include "io_test_util.h"

#include <gtest/gtest.h>

namespace frontier::io::test
{
namespace
{

using core::Vec3;

TEST(ContactsFile, OneRowPerContactWithNormalAndFrictionForce)
{
    TempDir dir;
    const std::string path = dir.file("contacts.csv");
    core::Model model;
    for (const char* name : {"floor", "box", "ball"})
    {
        core::Body body;
        body.name = name;
        model.bodies.push_back(body);
    }
    std::vector<core::ContactImpulse> contacts(2);
    contacts[0].contact = {1, 0, Vec3(0.1, 0.2, 0.0), Vec3(0.0, 0.0, -1.0), 2e-4};
    contacts[0].impulse_W = Vec3(0.003, -0.004, -0.05); // on the floor: pushed down, dragged along
    const Vec3 n = Vec3(0.6, 0.0, 0.8);
    contacts[1].contact = {1, 2, Vec3(0.3, 0.0, 0.5), n, -1e-3};
    contacts[1].impulse_W = 0.02 * n + Vec3(0.0, 0.01, 0.0);
    {
        ContactsWriter writer(path, {{"scene", "s.yaml"}});
        writer.writeStep(model, 0.5, 0.25, contacts); // forces 4x the impulses, exactly
        EXPECT_EQ(writer.rowsWritten(), 2);
        writer.commit();
    }
    const frontier::test::CsvTable table = frontier::test::readCsvTable(path);
    EXPECT_EQ(table.comment, "# frontier contacts: scene=s.yaml");
    EXPECT_EQ(std::string(cContactsHeader), "time,body_a,body_b,px,py,pz,nx,ny,nz,depth,normal_force,"
                                            "friction_force_x,friction_force_y,friction_force_z");
    EXPECT_EQ(table.columns, frontier::test::splitCsvLine(cContactsHeader));
    ASSERT_EQ(table.rows.size(), 2u);
    EXPECT_EQ(table.text(0, "body_a"), "box");
    EXPECT_EQ(table.text(0, "body_b"), "floor");
    EXPECT_EQ(table.text(1, "body_b"), "ball");
    EXPECT_EQ(table.number(0, "time"), 0.5);
    EXPECT_EQ(table.number(0, "nz"), -1.0);
    EXPECT_EQ(table.number(0, "depth"), 2e-4);
    EXPECT_EQ(table.number(1, "depth"), -1e-3);
    EXPECT_EQ(table.number(0, "normal_force"), 4.0 * 0.05); // N
    EXPECT_EQ(table.number(0, "friction_force_x"), 4.0 * 0.003);
    EXPECT_EQ(table.number(0, "friction_force_y"), 4.0 * -0.004);
    EXPECT_EQ(table.number(0, "friction_force_z"), 0.0);
    EXPECT_NEAR(table.number(1, "normal_force"), 4.0 * 0.02, 4e-17);
    const Vec3 friction(table.number(1, "friction_force_x"), table.number(1, "friction_force_y"),
                        table.number(1, "friction_force_z"));
    EXPECT_NEAR((friction - Vec3(0.0, 0.04, 0.0)).norm(), 0.0, 4e-17);
}

} // namespace
} // namespace frontier::io::test
