// io/trajectory.cpp: trajectory CSV writer (atomic) and reader (located errors).
#include "io/trajectory.h"

#include "io/file_util.h"
#include "io/scene.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>

namespace frontier::io
{

namespace
{

const std::string cMetadataPrefix = metadataPrefix("trajectory");
constexpr std::array<const char*, 15> cColumns = {"time", "body", "px", "py", "pz", "qw", "qx", "qy",
                                                  "qz",   "vx",   "vy", "vz", "wx", "wy", "wz"};

std::string formatNumber(double value)
{
    std::string out;
    appendNumber(out, value);
    return out;
}

struct Field
{
    std::string_view text;
    int column; // 1-based
};

std::vector<Field> splitFields(std::string_view line, char separator)
{
    std::vector<Field> out;
    std::size_t start = 0;
    while (true)
    {
        const std::size_t end = line.find(separator, start);
        out.push_back(
            {line.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start),
             static_cast<int>(start) + 1});
        if (end == std::string_view::npos)
        {
            return out;
        }
        start = end + 1;
    }
}

constexpr double cQuaternionTolerance = 1e-6; // |q| - 1 the writer's normalised quaternions stay within

// What is wrong with the value of a known pair of the comment line ("" when nothing is, or the key
// is not one of the settings).
std::string settingProblem(const std::string& key, const std::string& value)
{
    if (key == "dt")
    {
        const std::optional<double> dt = detail::parseFiniteNumber(value);
        return dt && *dt > 0.0 ? "" : "expected a positive number of seconds";
    }
    if (key == "duration")
    {
        const std::optional<double> duration = detail::parseFiniteNumber(value);
        return duration && *duration >= 0.0 ? "" : "expected a non-negative number of seconds";
    }
    if (key == "pgs_iterations")
    {
        return detail::parseWholeNumber(value, 1, detail::cMaxPgsIterations)
                   ? ""
                   : "expected a whole number from 1 to " + std::to_string(detail::cMaxPgsIterations);
    }
    if (key == "steps")
    {
        return detail::parseWholeNumber(value, 0, std::numeric_limits<long>::max())
                   ? ""
                   : "expected a whole number of steps >= 0";
    }
    if (key == "record_every")
    {
        return detail::parseWholeNumber(value, 1, std::numeric_limits<int>::max())
                   ? ""
                   : "expected a whole number of steps >= 1";
    }
    return {};
}

} // namespace

TrajectoryMetadata makeTrajectoryMetadata(const std::string& scenePath,
                                          const core::SimulationSettings& settings, long steps,
                                          int recordEvery)
{
    return {
        {"scene", scenePath},
        {"dt", formatNumber(settings.dt)},
        {"solver", core::solverName(settings.solver)},
        {"pgs_iterations", std::to_string(settings.pgsIterations)},
        {"integrator", core::integratorName(settings.integrator)},
        {"steps", std::to_string(steps)},
        {"record_every", std::to_string(recordEvery)},
        {"duration", formatNumber(settings.duration)},
    };
}

TrajectoryWriter::TrajectoryWriter(const std::string& path, const TrajectoryMetadata& metadata)
    : CsvWriter(path, "trajectory", metadata, cTrajectoryHeader)
{
}

void TrajectoryWriter::writeState(const core::Model& model, const core::State& state)
{
    std::string& buffer = mLine;
    for (std::size_t i = 0; i < model.bodies.size() && i < state.bodies.size(); ++i)
    {
        const core::Body& body = model.bodies[i];
        if (body.isStatic)
        {
            continue;
        }
        const core::BodyState& s = state.bodies[i];
        buffer.clear();
        appendNumber(buffer, state.time);
        buffer += ',';
        buffer += body.name;
        const double values[13] = {s.position_W.x(),       s.position_W.y(),        s.position_W.z(),
                                   s.orientation_WB.w(),   s.orientation_WB.x(),    s.orientation_WB.y(),
                                   s.orientation_WB.z(),   s.velocity_W.x(),        s.velocity_W.y(),
                                   s.velocity_W.z(),       s.angularVelocity_W.x(), s.angularVelocity_W.y(),
                                   s.angularVelocity_W.z()};
        for (const double v : values)
        {
            buffer += ',';
            appendNumber(buffer, v);
        }
        mFile.writeRow(buffer);
    }
}

core::BodyState TrajectoryRow::state() const
{
    core::BodyState s;
    s.position_W = core::Vec3(values[0], values[1], values[2]);
    s.orientation_WB = core::Quat(values[3], values[4], values[5], values[6]);
    s.velocity_W = core::Vec3(values[7], values[8], values[9]);
    s.angularVelocity_W = core::Vec3(values[10], values[11], values[12]);
    return s;
}

namespace
{

// One line of the file at a time; the state its steps share.
struct TrajectoryReader
{
    const std::string& path;
    const std::string& text;
    Trajectory out{};
    std::map<std::string, double> lastTime{}; // s, of each body's latest row
    bool haveHeader = false;
    int lineNumber = 0;
    std::size_t pos = 0;

    // The next line without its line ending; false at the end of the text.
    bool nextLine(std::string_view& line)
    {
        if (pos >= text.size())
        {
            return false;
        }
        const std::size_t end = text.find('\n', pos);
        line = std::string_view(text.data() + pos, (end == std::string::npos ? text.size() : end) - pos);
        pos = end == std::string::npos ? text.size() : end + 1;
        ++lineNumber;
        if (!line.empty() && line.back() == '\r')
        {
            line.remove_suffix(1);
        }
        return true;
    }

    // A comment before the header: the settings of the metadata line, any other comment skipped.
    void readComment(std::string_view line)
    {
        if (!line.starts_with(cMetadataPrefix))
        {
            return;
        }
        const std::size_t offset = cMetadataPrefix.size();
        for (const Field& pair : splitFields(line.substr(offset), ' '))
        {
            if (pair.text.empty())
            {
                continue;
            }
            const std::size_t eq = pair.text.find('=');
            if (eq == std::string_view::npos)
            {
                throw InputError(path, lineNumber, static_cast<int>(offset) + pair.column,
                                 "expected key=value in the trajectory comment, got '" +
                                     std::string(pair.text) + "'");
            }
            const std::string key = decodeMetadataField(pair.text.substr(0, eq));
            const std::string value = decodeMetadataField(pair.text.substr(eq + 1));
            const std::string problem = settingProblem(key, value);
            if (!problem.empty())
            {
                throw InputError(path, lineNumber,
                                 static_cast<int>(offset) + pair.column + static_cast<int>(eq) + 1,
                                 "'" + key + "' in the trajectory comment is '" + value + "'; " + problem);
            }
            out.metadata[key] = value;
        }
        out.metadataLine = lineNumber;
    }

    void readHeader(std::string_view line, const std::vector<Field>& fields)
    {
        for (std::size_t i = 0; i < cColumns.size(); ++i)
        {
            if (i >= fields.size())
            {
                throw InputError(path, lineNumber, static_cast<int>(line.size()) + 1,
                                 std::string("missing column '") + cColumns[i] +
                                     "' in the header; expected '" + cTrajectoryHeader + "'");
            }
            if (fields[i].text != cColumns[i])
            {
                throw InputError(path, lineNumber, fields[i].column,
                                 std::string("expected column '") + cColumns[i] + "' in the header, got '" +
                                     std::string(fields[i].text) + "' (a trajectory CSV, as `frontier run " +
                                     "--trajectory` writes, has the header '" + cTrajectoryHeader + "')");
            }
        }
        if (fields.size() > cColumns.size())
        {
            throw InputError(path, lineNumber, fields[cColumns.size()].column,
                             "unexpected column '" + std::string(fields[cColumns.size()].text) +
                                 "' in the header; expected '" + cTrajectoryHeader + "'");
        }
        haveHeader = true;
    }

    double number(const std::vector<Field>& fields, std::size_t index) const
    {
        const Field& field = fields[index];
        const std::optional<double> value = detail::parseFiniteNumber(field.text);
        if (!value)
        {
            throw InputError(path, lineNumber, field.column,
                             std::string("expected a finite number for '") + cColumns[index] + "', got '" +
                                 std::string(field.text) + "'");
        }
        return *value;
    }

    // The row's fields as numbers and a body name, without checking what they say.
    TrajectoryRow parseRow(std::string_view line, const std::vector<Field>& fields) const
    {
        if (fields.size() != cColumns.size())
        {
            const int column = fields.size() > cColumns.size() ? fields[cColumns.size()].column
                                                               : static_cast<int>(line.size()) + 1;
            throw InputError(path, lineNumber, column,
                             "expected " + std::to_string(cColumns.size()) + " fields, got " +
                                 std::to_string(fields.size()));
        }
        TrajectoryRow row;
        row.line = lineNumber;
        row.time = number(fields, 0);
        if (fields[1].text.empty())
        {
            throw InputError(path, lineNumber, fields[1].column, "expected a body name, got an empty field");
        }
        row.body = std::string(fields[1].text);
        for (std::size_t i = 0; i < row.values.size(); ++i)
        {
            row.values[i] = number(fields, i + 2);
        }
        return row;
    }

    // A pose in range with a unit quaternion.
    void checkState(const TrajectoryRow& row, const std::vector<Field>& fields) const
    {
        const core::BodyState state = row.state();
        if (!core::isPosition(state.position_W)) // the scenes' rule: farther is a corrupt row
        {
            throw InputError(path, lineNumber, fields[2].column,
                             "position (" + formatNumber(row.values[0]) + ", " + formatNumber(row.values[1]) +
                                 ", " + formatNumber(row.values[2]) + ") m is farther than " +
                                 formatNumber(core::cMaxDistance) + " m from the origin");
        }
        if (!(std::abs(state.orientation_WB.norm() - 1.0) <= cQuaternionTolerance))
        {
            throw InputError(path, lineNumber, fields[5].column,
                             "orientation quaternion has norm " + formatNumber(state.orientation_WB.norm()) +
                                 "; expected a unit quaternion (norm 1 within 1e-6)");
        }
    }

    // Times increase over the file and strictly for each body.
    void checkTime(const TrajectoryRow& row, const std::vector<Field>& fields)
    {
        if (!out.rows.empty() && row.time < out.rows.back().time)
        {
            throw InputError(path, lineNumber, fields[0].column,
                             "time " + formatNumber(row.time) + " s is earlier than the row before (" +
                                 formatNumber(out.rows.back().time) + " s); times must increase");
        }
        const auto [last, first] = lastTime.try_emplace(row.body, row.time);
        if (!first)
        {
            if (!(row.time > last->second))
            {
                throw InputError(path, lineNumber, fields[0].column,
                                 "body '" + row.body + "' has a second row at time " +
                                     formatNumber(row.time) + " s; each body's times must strictly increase");
            }
            last->second = row.time;
        }
    }

    void readLine(std::string_view line)
    {
        if (line.empty())
        {
            return;
        }
        if (!haveHeader && line.front() == '#')
        {
            readComment(line);
            return;
        }
        const std::vector<Field> fields = splitFields(line, ',');
        if (!haveHeader)
        {
            readHeader(line, fields);
            return;
        }
        TrajectoryRow row = parseRow(line, fields);
        checkState(row, fields);
        checkTime(row, fields);
        out.rows.push_back(std::move(row));
    }
};

} // namespace

Trajectory readTrajectory(const std::string& path)
{
    const std::string text = detail::readTextFile(path, "trajectory file");
    TrajectoryReader reader{path, text};
    for (std::string_view line; reader.nextLine(line);)
    {
        reader.readLine(line);
    }
    if (!reader.haveHeader)
    {
        throw InputError(path, reader.lineNumber, 0,
                         std::string("no header line; expected '") + cTrajectoryHeader + "'");
    }
    return std::move(reader.out);
}

namespace
{
constexpr const char* cContactTolerance = "contact_tolerance";
constexpr const char* cContactRelativeTolerance = "contact_relative_tolerance";
constexpr const char* cFixedBase = "fixed_base";
constexpr const char* cFreeBase = "free_base";
constexpr const char* cDropHeight = "drop_height";
constexpr const char* cJointPositions = "joint_positions"; // NAME=VALUE;NAME=VALUE
constexpr const char* cSelfCollision = "self_collision";
constexpr const char* cPackagePath = "package_path"; // entries joined by ';'
constexpr const char* cHold = "hold";
constexpr const char* cKeyframe = "keyframe";
} // namespace

void addContactTolerances(TrajectoryMetadata& metadata, const core::ContactTolerances& contact)
{
    if (contact.tolerance)
    {
        metadata.emplace_back(cContactTolerance, formatNumber(*contact.tolerance));
    }
    if (contact.relativeTolerance)
    {
        metadata.emplace_back(cContactRelativeTolerance, formatNumber(*contact.relativeTolerance));
    }
}

void addUrdfOptions(TrajectoryMetadata& metadata, const UrdfOptions& options)
{
    if (options.fixedBase)
    {
        metadata.emplace_back(cFixedBase, "1");
    }
    if (options.freeBase)
    {
        metadata.emplace_back(cFreeBase, "1");
    }
    if (options.dropHeight)
    {
        std::ostringstream value;
        value.precision(17);
        value << *options.dropHeight;
        metadata.emplace_back(cDropHeight, value.str());
    }
    if (!options.jointPositions.empty())
    {
        std::ostringstream joined;
        joined.precision(17);
        for (const auto& [name, position] : options.jointPositions)
        {
            joined << (joined.tellp() > 0 ? ";" : "") << name << '=' << position;
        }
        metadata.emplace_back(cJointPositions, joined.str());
    }
    if (options.selfCollision)
    {
        metadata.emplace_back(cSelfCollision, *options.selfCollision ? "on" : "off");
    }
    if (options.hold)
    {
        metadata.emplace_back(cHold, "1");
    }
    if (options.keyframe)
    {
        metadata.emplace_back(cKeyframe, *options.keyframe);
    }
    if (!options.packagePaths.empty())
    {
        std::string joined;
        for (const std::string& entry : options.packagePaths)
        {
            joined += (joined.empty() ? "" : ";") + entry;
        }
        metadata.emplace_back(cPackagePath, joined);
    }
}

UrdfOptions urdfOptionsFrom(const std::map<std::string, std::string>& metadata, const std::string& path)
{
    UrdfOptions options;
    const auto value = [&](const char* key) -> const std::string*
    {
        const auto it = metadata.find(key);
        return it == metadata.end() ? nullptr : &it->second;
    };
    options.fixedBase = value(cFixedBase) && *value(cFixedBase) == "1";
    options.freeBase = value(cFreeBase) && *value(cFreeBase) == "1";
    options.hold = value(cHold) && *value(cHold) == "1";
    if (const std::string* keyframe = value(cKeyframe))
    {
        options.keyframe = *keyframe;
    }
    if (const std::string* height = value(cDropHeight))
    {
        options.dropHeight = detail::parseFiniteNumber(*height);
        if (!options.dropHeight)
        {
            throw InputError(path, 1, 0, "the header's drop_height=" + *height + " is not a finite number");
        }
    }
    if (const std::string* positions = value(cJointPositions))
    {
        std::stringstream in(*positions);
        std::string entry;
        while (std::getline(in, entry, ';'))
        {
            const std::size_t equals = entry.rfind('=');
            const std::optional<double> position = equals == std::string::npos
                                                       ? std::nullopt
                                                       : detail::parseFiniteNumber(entry.substr(equals + 1));
            if (!position || equals == 0)
            {
                throw InputError(path, 1, 0,
                                 "the header's joint_positions entry '" + entry +
                                     "' is not NAME=POSITION with a finite position");
            }
            options.jointPositions[entry.substr(0, equals)] = *position;
        }
    }
    if (const std::string* self = value(cSelfCollision))
    {
        options.selfCollision = *self == "on";
    }
    if (const std::string* paths = value(cPackagePath))
    {
        std::stringstream in(*paths);
        std::string entry;
        while (std::getline(in, entry, ';'))
        {
            if (!entry.empty())
            {
                options.packagePaths.push_back(entry);
            }
        }
    }
    return options;
}

namespace
{
// The value of a setting of the comment line, checked by the rule readTrajectory applies.
const std::string& requireKey(const Trajectory& trajectory, const std::string& path, const std::string& key)
{
    const auto found = trajectory.metadata.find(key);
    if (found == trajectory.metadata.end())
    {
        throw InputError(
            path, trajectory.metadataLine, 0,
            "the reference's header line has no '" + key +
                "': record references with `frontier run --trajectory` (it writes the settings)");
    }
    const std::string problem = settingProblem(key, found->second);
    if (!problem.empty())
    {
        throw InputError(path, trajectory.metadataLine, 0,
                         "'" + key + "' in the header line is '" + found->second + "'; " + problem);
    }
    return found->second;
}
} // namespace

TrajectorySettings readTrajectorySettings(const Trajectory& trajectory, const std::string& path)
{
    TrajectorySettings out;
    core::SimulationSettings& sim = out.simulation;
    const int line = trajectory.metadataLine;
    sim.dt = *detail::parseFiniteNumber(requireKey(trajectory, path, "dt"));
    const std::string& solver = requireKey(trajectory, path, "solver");
    if (!core::solverFromName(solver))
    {
        throw InputError(path, line, 0, "unknown solver '" + solver + "' in the header line");
    }
    sim.solver = *core::solverFromName(solver);
    sim.pgsIterations = static_cast<int>(*detail::parseWholeNumber(
        requireKey(trajectory, path, "pgs_iterations"), 1, detail::cMaxPgsIterations));
    const std::string& integrator = requireKey(trajectory, path, "integrator");
    if (!core::integratorFromName(integrator))
    {
        throw InputError(path, line, 0, "unknown integrator '" + integrator + "' in the header line");
    }
    sim.integrator = *core::integratorFromName(integrator);
    out.steps = static_cast<long>(*detail::parseWholeNumber(requireKey(trajectory, path, "steps"), 0,
                                                            std::numeric_limits<long>::max()));
    out.recordEvery = static_cast<int>(*detail::parseWholeNumber(requireKey(trajectory, path, "record_every"),
                                                                 1, std::numeric_limits<int>::max()));
    const auto contactValue = [&](const char* key, bool (*rule)(double), const char* expected)
    {
        std::optional<double> value;
        if (const auto it = trajectory.metadata.find(key); it != trajectory.metadata.end())
        {
            value = detail::parseFiniteNumber(it->second);
            if (!value || !rule(*value))
            {
                throw InputError(path, line, 0,
                                 std::string("the header's ") + key + "=" + it->second + " is not " +
                                     expected);
            }
        }
        return value;
    };
    out.contact.tolerance =
        contactValue(cContactTolerance, core::isContactTolerance, core::cContactToleranceRange);
    out.contact.relativeTolerance = contactValue(cContactRelativeTolerance, core::isRelativeContactTolerance,
                                                 core::cRelativeContactToleranceRange);
    return out;
}

} // namespace frontier::io
