// io/contacts_file.cpp: the contacts CSV writer.
#include "io/contacts_file.h"

namespace frontier::io
{

ContactsWriter::ContactsWriter(const std::string& path, const FileMetadata& metadata)
    : CsvWriter(path, "contacts", metadata, cContactsHeader)
{
}

void ContactsWriter::writeStep(const core::Model& model, double time, double dt,
                               std::span<const core::ContactImpulse> contacts)
{
    for (const core::ContactImpulse& c : contacts)
    {
        std::string& line = mLine;
        line.clear();
        appendNumber(line, time);
        for (const int body : {c.contact.bodyA, c.contact.bodyB})
        {
            line += ',';
            appendName(line, model.bodies[static_cast<std::size_t>(body)].name);
        }
        const core::Vec3 friction = c.frictionImpulse_W() / dt; // N
        const double values[] = {
            c.contact.point_W.x(),  c.contact.point_W.y(),  c.contact.point_W.z(), c.contact.normal_W.x(),
            c.contact.normal_W.y(), c.contact.normal_W.z(), c.contact.depth,       c.normalImpulse() / dt,
            friction.x(),           friction.y(),           friction.z()};
        for (const double v : values)
        {
            line += ',';
            appendNumber(line, v);
        }
        mFile.writeRow(line);
    }
}

} // namespace frontier::io
