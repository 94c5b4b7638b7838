// io/contacts_file.h: the contacts CSV of a run (`frontier run --contacts`, docs/files.md).
//
// Format (io/csv_output.h: comment line, header, 17 significant digits, atomic):
//   # frontier contacts: scene=<path> dt=<s> ... (the trajectory's key=value pairs)
//   time,body_a,body_b,px,py,pz,nx,ny,nz,depth,normal_force,friction_force_x,friction_force_y,friction_force_z
// Per recorded step, one row per contact the step detected (at its start, time - dt), written at
// the time the step ended: the bodies (A moves; B may be static), the point (m) and the unit normal
// from A towards B (world frame), the depth (m; > 0 overlapping, < 0 a gap within the detector's
// margin), and the force the contact passed to B over that one step (N; A received the opposite):
// its impulse over the step divided by dt, the mean force of the step, as the joints file's
// forces. normal_force >= 0 along the normal, and the friction force, a world vector tangential to
// the contact. A contact whose gap the bodies could not close within the step had no row in the
// solve: its forces are 0. The initial state has no rows (no step yet).
#pragma once

#include "core/contact.h"
#include "core/model.h"
#include "io/csv_output.h"

#include <span>
#include <string>

namespace frontier::io
{

inline constexpr const char* cContactsHeader =
    "time,body_a,body_b,px,py,pz,nx,ny,nz,depth,normal_force,friction_force_x,friction_force_y,"
    "friction_force_z";

class ContactsWriter : public CsvWriter
{
  public:
    // Creates PATH.tmp-XXXXXX next to `path` and writes the comment and header lines; without
    // commit() (io/csv_output.h) the temporary file is removed. Throws OutputError
    // (io/atomic_file.h).
    ContactsWriter(const std::string& path, const FileMetadata& metadata);

    // The rows of the step of `dt` (s) that ended at `time` (s): its contacts' impulses (N s) / dt.
    void writeStep(const core::Model& model, double time, double dt,
                   std::span<const core::ContactImpulse> contacts);
};

} // namespace frontier::io
