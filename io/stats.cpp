// io/stats.cpp: stats JSON with nlohmann-json.
#include "io/stats.h"

#include "io/atomic_file.h"
#include "io/file_util.h"
#include "io/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

namespace frontier::io
{

namespace
{

using Json = nlohmann::ordered_json;

Json number(double value)
{
    return std::isfinite(value) ? Json(value) : Json(nullptr);
}

// A value of a stats file for a message: a scalar as JSON, at most 40 characters of it; an array
// or an object by its size (a value of a damaged file may be nested deep or megabytes long).
std::string shown(const nlohmann::json& v)
{
    if (v.is_array())
    {
        return "an array of " + std::to_string(v.size()) + " items";
    }
    if (v.is_object())
    {
        return "an object of " + std::to_string(v.size()) + " keys";
    }
    const std::string text = v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    return text.size() <= 40 ? text : text.substr(0, 40) + "...";
}

// The byte offset of the first '[' or '{' of `text` (JSON) nested deeper than `most`, or npos.
// nlohmann-json parses any depth, but a deep value can overflow the stack of what walks it.
std::size_t tooDeep(const std::string& text, int most)
{
    int depth = 0;
    bool inString = false;
    for (std::size_t i = 0; i < text.size(); ++i)
    {
        const char c = text[i];
        if (inString)
        {
            i += c == '\\' ? 1 : 0;
            inString = c != '"';
        }
        else if (c == '"')
        {
            inString = true;
        }
        else if (c == '[' || c == '{')
        {
            if (++depth > most)
            {
                return i;
            }
        }
        else if (c == ']' || c == '}')
        {
            --depth;
        }
    }
    return std::string::npos;
}

class Reader
{
  public:
    Reader(const std::string& path, const nlohmann::json& json) : mPath(path), mJson(json) {}

    const nlohmann::json& at(const std::string& key) const
    {
        const auto it = mJson.find(key);
        if (it == mJson.end())
        {
            throw InputError(mPath, 0, 0, "missing key '" + key + "' in the stats file");
        }
        return *it;
    }
    std::string string(const std::string& key) const
    {
        const nlohmann::json& v = at(key);
        if (!v.is_string())
        {
            throw InputError(mPath, 0, 0, "expected a string for '" + key + "', got " + shown(v));
        }
        return v.get<std::string>();
    }
    double number(const std::string& key) const
    {
        const nlohmann::json& v = at(key);
        if (v.is_null())
        {
            return std::numeric_limits<double>::quiet_NaN();
        }
        if (!v.is_number())
        {
            throw InputError(mPath, 0, 0, "expected a number for '" + key + "', got " + shown(v));
        }
        return v.get<double>();
    }
    long integer(const std::string& key) const
    {
        const nlohmann::json& v = at(key);
        if (!v.is_number_integer())
        {
            throw InputError(mPath, 0, 0, "expected an integer for '" + key + "', got " + shown(v));
        }
        return v.get<long>();
    }
    std::vector<std::string> strings(const std::string& key) const
    {
        const nlohmann::json& v = at(key);
        if (!v.is_array() ||
            !std::all_of(v.begin(), v.end(), [](const nlohmann::json& item) { return item.is_string(); }))
        {
            throw InputError(mPath, 0, 0, "expected an array of strings for '" + key + "', got " + shown(v));
        }
        std::vector<std::string> out;
        for (const nlohmann::json& item : v)
        {
            out.push_back(item.get<std::string>());
        }
        return out;
    }
    bool boolean(const std::string& key) const
    {
        const nlohmann::json& v = at(key);
        if (!v.is_boolean())
        {
            throw InputError(mPath, 0, 0, "expected true or false for '" + key + "', got " + shown(v));
        }
        return v.get<bool>();
    }

  private:
    const std::string& mPath;
    const nlohmann::json& mJson;
};

std::vector<ActuatorStats> readActuators(const std::string& path, const nlohmann::json& array)
{
    if (!array.is_array())
    {
        throw InputError(path, 0, 0, "expected an array of objects for 'actuators', got " + shown(array));
    }
    std::vector<ActuatorStats> out;
    for (const nlohmann::json& entry : array)
    {
        if (!entry.is_object())
        {
            throw InputError(path, 0, 0, "expected an object in 'actuators', got " + shown(entry));
        }
        const Reader r(path, entry);
        ActuatorStats a;
        a.joint = r.string("joint");
        a.coordinate = r.string("coordinate");
        a.type = r.string("type");
        const bool tracks = entry.contains("tracking_rms");
        a.trackingRms = tracks ? r.number("tracking_rms") : std::numeric_limits<double>::quiet_NaN();
        a.trackingMax = tracks ? r.number("tracking_max") : std::numeric_limits<double>::quiet_NaN();
        a.effortRms = r.number("effort_rms");
        a.effortMax = r.number("effort_max");
        a.limitSteps = r.integer("limit_steps");
        out.push_back(std::move(a));
    }
    return out;
}

} // namespace

const std::vector<std::string>& statsKeys()
{
    static const std::vector<std::string> keys = {"scene",
                                                  "solver",
                                                  "integrator",
                                                  "pgs_iterations",
                                                  "dt",
                                                  "steps",
                                                  "simulated_seconds",
                                                  "bodies",
                                                  "static_bodies",
                                                  "joints",
                                                  "constraint_rows",
                                                  "degrees_of_freedom",
                                                  "wall_seconds",
                                                  "seconds_per_step",
                                                  "max_joint_error_m",
                                                  "max_penetration_m",
                                                  "energy_initial_j",
                                                  "energy_final_j",
                                                  "max_contacts",
                                                  "finite",
                                                  "completed",
                                                  "failure",
                                                  "warnings",
                                                  "inputs_digest",
                                                  "input_files",
                                                  "actuators"};
    return keys;
}

void fillModelCounts(RunStats& stats, const core::Model& model)
{
    stats.bodies = 0;
    stats.staticBodies = 0;
    for (const core::Body& body : model.bodies)
    {
        (body.isStatic ? stats.staticBodies : stats.bodies) += 1;
    }
    stats.joints = static_cast<int>(model.joints.size());
    stats.constraintRows = 0;
    for (const core::Joint& joint : model.joints)
    {
        stats.constraintRows += core::jointRowCount(joint.type);
    }
    stats.degreesOfFreedom = 6 * stats.bodies - stats.constraintRows;
}

namespace
{
// One actuator's entry: its joint, coordinate and type, tracking (not for an effort actuator),
// effort and steps at its limit.
Json actuatorJson(const ActuatorStats& a)
{
    Json entry;
    entry["joint"] = a.joint;
    entry["coordinate"] = a.coordinate;
    entry["type"] = a.type;
    if (a.type != "effort")
    {
        entry["tracking_rms"] = number(a.trackingRms);
        entry["tracking_max"] = number(a.trackingMax);
    }
    entry["effort_rms"] = number(a.effortRms);
    entry["effort_max"] = number(a.effortMax);
    entry["limit_steps"] = a.limitSteps;
    return entry;
}
} // namespace

void writeStats(const std::string& path, const RunStats& stats)
{
    Json json;
    json["scene"] = stats.scene;
    json["solver"] = stats.solver;
    json["integrator"] = stats.integrator;
    json["pgs_iterations"] = stats.pgsIterations;
    json["dt"] = number(stats.dt);
    json["steps"] = stats.steps;
    json["simulated_seconds"] = number(stats.simulatedSeconds);
    json["bodies"] = stats.bodies;
    json["static_bodies"] = stats.staticBodies;
    json["joints"] = stats.joints;
    json["constraint_rows"] = stats.constraintRows;
    json["degrees_of_freedom"] = stats.degreesOfFreedom;
    json["wall_seconds"] = number(stats.wallSeconds);
    json["seconds_per_step"] = number(stats.secondsPerStep);
    json["max_joint_error_m"] = number(stats.maxJointErrorM);
    json["max_penetration_m"] = number(stats.maxPenetrationM);
    json["energy_initial_j"] = number(stats.energyInitialJ);
    json["energy_final_j"] = number(stats.energyFinalJ);
    json["max_contacts"] = stats.maxContacts;
    json["finite"] = stats.finite;
    json["completed"] = stats.completed;
    if (!stats.failure.empty())
    {
        json["failure"] = stats.failure;
    }
    json["warnings"] = stats.warnings;
    if (!stats.inputsDigest.empty())
    {
        json["inputs_digest"] = stats.inputsDigest;
        json["input_files"] = stats.inputFiles;
    }
    json["actuators"] = Json::array();
    for (const ActuatorStats& a : stats.actuators)
    {
        json["actuators"].push_back(actuatorJson(a));
    }
    for (const auto& [key, value] : stats.extra)
    {
        if (!json.contains(key))
        {
            json[key] = number(value);
        }
    }
    AtomicFile file(path);
    file.write(json.dump(2) + "\n");
    file.commit();
}

namespace
{

// The file's text as a JSON object: nested no deeper than a stats file may be, errors located.
nlohmann::json parseStatsJson(const std::string& path, const std::string& text)
{
    if (const std::size_t deep = tooDeep(text, cMaxStatsDepth); deep != std::string::npos)
    {
        const detail::TextPosition at = detail::positionOf(text, deep);
        throw InputError(path, at.line, at.column,
                         "JSON nested deeper than " + std::to_string(cMaxStatsDepth) +
                             " levels; expected a stats file (3 levels)");
    }
    nlohmann::json json;
    try
    {
        json = nlohmann::json::parse(text);
    }
    catch (const nlohmann::json::parse_error& e)
    {
        const detail::TextPosition at = detail::positionOf(text, e.byte > 0 ? e.byte - 1 : 0);
        const std::string what = e.what(); // quotes the token read last: keep a long one short
        throw InputError(path, at.line, at.column,
                         "invalid JSON: " + (what.size() <= 200 ? what : what.substr(0, 200) + "..."));
    }
    if (!json.is_object())
    {
        throw InputError(path, 1, 1, "expected a JSON object");
    }
    return json;
}

// The keys every stats file has.
void readRequired(const Reader& r, RunStats& s)
{
    s.scene = r.string("scene");
    s.solver = r.string("solver");
    s.integrator = r.string("integrator");
    s.pgsIterations = static_cast<int>(r.integer("pgs_iterations"));
    s.dt = r.number("dt");
    s.steps = r.integer("steps");
    s.simulatedSeconds = r.number("simulated_seconds");
    s.bodies = static_cast<int>(r.integer("bodies"));
    s.staticBodies = static_cast<int>(r.integer("static_bodies"));
    s.joints = static_cast<int>(r.integer("joints"));
    s.constraintRows = static_cast<int>(r.integer("constraint_rows"));
    s.degreesOfFreedom = static_cast<int>(r.integer("degrees_of_freedom"));
    s.wallSeconds = r.number("wall_seconds");
    s.secondsPerStep = r.number("seconds_per_step");
    s.maxJointErrorM = r.number("max_joint_error_m");
    s.maxPenetrationM = r.number("max_penetration_m");
    s.energyInitialJ = r.number("energy_initial_j");
    s.energyFinalJ = r.number("energy_final_j");
    s.maxContacts = static_cast<int>(r.integer("max_contacts"));
    s.finite = r.boolean("finite");
}

// The keys a stats file may leave out, and numbers under keys of their own (kept as extras).
void readOptional(const std::string& path, nlohmann::json& json, const Reader& r, RunStats& s)
{
    s.completed = !json.contains("completed") || r.boolean("completed");
    if (json.contains("failure"))
    {
        s.failure = r.string("failure");
    }
    if (json.contains("warnings"))
    {
        s.warnings = r.strings("warnings");
    }
    if (json.contains("inputs_digest"))
    {
        s.inputsDigest = r.string("inputs_digest");
    }
    if (json.contains("input_files"))
    {
        s.inputFiles = r.strings("input_files");
    }
    if (json.contains("actuators"))
    {
        s.actuators = readActuators(path, json["actuators"]);
    }
    for (const auto& [key, value] : json.items())
    {
        const auto& known = statsKeys();
        if (std::find(known.begin(), known.end(), key) == known.end() &&
            (value.is_number() || value.is_null()))
        {
            s.extra[key] = r.number(key);
        }
    }
}

} // namespace

RunStats readStats(const std::string& path)
{
    const std::string text = detail::readTextFile(path);
    nlohmann::json json = parseStatsJson(path, text);
    const Reader r(path, json);
    RunStats s;
    readRequired(r, s);
    readOptional(path, json, r, s);
    return s;
}

} // namespace frontier::io
