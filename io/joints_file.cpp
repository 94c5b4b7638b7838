// io/joints_file.cpp: the joints CSV writer.
#include "io/joints_file.h"

#include "core/joints/coordinates.h"

#include <algorithm>

namespace frontier::io
{

namespace
{
// The joints file's name of a coordinate: angle (rad) or slide (m).
const char* columnCoordinateName(core::JointCoordinate coordinate)
{
    return coordinate == core::JointCoordinate::Rotation ? "angle" : "slide";
}
} // namespace

JointsWriter::JointsWriter(const std::string& path, const FileMetadata& metadata)
    : CsvWriter(path, "joints", metadata, cJointsHeader)
{
}

void JointsWriter::writeState(const core::Model& model, const core::State& state,
                              std::span<const JointStepLoad> loads)
{
    const bool stepped = !loads.empty();
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        const core::Joint& joint = model.joints[k];
        const std::span<const core::JointCoordinate> coordinates = core::jointCoordinates(joint.type);
        // A joint without a coordinate still passes force and torque: one row, `none`.
        const std::size_t rows = std::max<std::size_t>(1, coordinates.size());
        for (std::size_t c = 0; c < rows; ++c)
        {
            std::string& line = mLine;
            line.clear();
            appendNumber(line, state.time);
            line += ',';
            appendName(line, joint.name);
            line += ',';
            if (coordinates.empty())
            {
                line += "none,,";
            }
            else
            {
                const int index = static_cast<int>(k);
                line += columnCoordinateName(coordinates[c]);
                line += ',';
                appendNumber(line, core::fileCoordinate(model, state, index, coordinates[c]));
                line += ',';
                appendNumber(line, core::jointCoordinateVelocity(model, state, index, coordinates[c]));
            }
            if (!stepped)
            {
                line += ",,,,,,,"; // effort and fx..tz: no step yet
                mFile.writeRow(line);
                continue;
            }
            const JointStepLoad& load = loads[k];
            line += ',';
            appendNumber(line, coordinates.empty() ? 0.0 : load.effort[c]);
            for (const core::Vec3* v : {&load.force_W, &load.torque_W})
            {
                for (int i = 0; i < 3; ++i)
                {
                    line += ',';
                    appendNumber(line, (*v)(i));
                }
            }
            mFile.writeRow(line);
        }
    }
}

} // namespace frontier::io
