// io/yaml_targets.cpp: an actuator's `target:` as a function of time (core/time_function.h): a
// number, `sine`, `keyframes` or `csv`.
#include "io/file_util.h"
#include "io/scene.h"
#include "io/target_table.h"
#include "io/yaml_scene.h"

#include <sstream>

namespace frontier::io::detail
{

namespace
{

const std::vector<std::string> cTargetKeys = {"sine", "keyframes", "csv", "smooth"};
const std::vector<std::string> cSineKeys = {"amplitude", "frequency", "phase", "offset"};
const std::vector<std::string> cCsvKeys = {"file", "column"};

core::TimeFunction readSine(const YamlSource& source, const YamlNode& node, const std::string& what)
{
    const MapNode map(source, node, "'sine' of " + what);
    map.checkKeys(cSineKeys);
    const double amplitude = map.number("amplitude");
    map.require("frequency");
    const double frequency = *map.optNonNegative("frequency", "(Hz)");
    core::TimeFunction sine = core::sineFunction(amplitude, frequency, map.optNumber("phase").value_or(0.0),
                                                 map.optNumber("offset").value_or(0.0));
    const std::string defect = core::overflowDefect(sine, core::cMaxDuration);
    if (!defect.empty())
    {
        map.fail("the " + map.context() + " gives values that doubles cannot hold: " + defect +
                 "; expected an amplitude, frequency and offset whose value and rate stay finite");
    }
    return sine;
}

core::TimeFunction readKeyframes(const YamlSource& source, const YamlNode& node, const std::string& what,
                                 bool smooth)
{
    const std::string list = "'keyframes' of " + what;
    requireSequence(source, node, list);
    if (node.size() == 0)
    {
        failAt(source, node, "expected at least one [time, value] pair in " + list);
    }
    std::vector<double> times;
    std::vector<double> values;
    for (std::size_t k = 0; k < node.size(); ++k)
    {
        const YamlNode pair = node[k];
        const std::vector<double> tv = toNumbers(
            source, pair, "keyframe " + std::to_string(k + 1) + " of " + list + " [time, value]", 2);
        if (!times.empty() && !(tv[0] > times.back()))
        {
            std::ostringstream message;
            message << "keyframe times must increase: keyframe " << k + 1 << " of " << list
                    << " is at t = " << tv[0] << " s, after t = " << times.back() << " s";
            failAt(source, pair, message.str());
        }
        times.push_back(tv[0]);
        values.push_back(tv[1]);
    }
    core::TimeFunction keyframes = core::keyframeFunction(std::move(times), std::move(values), smooth);
    std::size_t k = 0;
    const std::string defect = core::overflowDefect(keyframes, core::cMaxDuration, &k);
    if (!defect.empty())
    {
        failAt(source, node[k],
               "keyframe " + std::to_string(k + 1) + " of " + list + ": " + defect +
                   "; expected keyframes whose values and rates stay finite");
    }
    return keyframes;
}

core::TimeFunction readCsv(const YamlSource& source, const YamlNode& node, const std::string& what,
                           const std::string& defaultColumn, bool smooth)
{
    const MapNode map(source, node, "'csv' of " + what);
    map.checkKeys(cCsvKeys);
    const YamlNode fileNode = map.require("file");
    const std::string path = resolvePath(source.baseDir, toString(source, fileNode, map.what("file")));
    const std::string column = map.optString("column").value_or(defaultColumn);
    TargetColumn table;
    try
    {
        table = readTargetColumn(path, column);
    }
    catch (const InputError& e)
    {
        if (e.line() == 0 && e.message().starts_with("cannot"))
        {
            failAt(source, fileNode, "cannot read the target table '" + path + "' of " + what);
        }
        throw;
    }
    core::TimeFunction keyframes =
        core::keyframeFunction(std::move(table.times), std::move(table.values), smooth);
    std::size_t k = 0;
    const std::string defect = core::overflowDefect(keyframes, core::cMaxDuration, &k);
    if (!defect.empty())
    {
        throw InputError(path, table.lines[k], 1,
                         "the row of column '" + column + "' for " + what + ": " + defect +
                             "; expected rows whose values and rates stay finite");
    }
    return keyframes;
}

} // namespace

core::TimeFunction readTarget(const YamlSource& source, const YamlNode& node, const std::string& what,
                              const std::string& defaultColumn)
{
    if (node.isScalar())
    {
        return core::constantFunction(toNumber(source, node, what));
    }
    if (!node.isMap())
    {
        failAt(source, node,
               "expected a number or a map with 'sine', 'keyframes' or 'csv' for " + what + ", got " +
                   describeNode(node));
    }
    const MapNode map(source, node, what);
    map.checkKeys(cTargetKeys);
    int forms = 0;
    for (const char* key : {"sine", "keyframes", "csv"})
    {
        forms += map.has(key) ? 1 : 0;
    }
    if (forms != 1)
    {
        map.fail("expected exactly one of 'sine', 'keyframes' or 'csv' in " + what);
    }
    if (map.has("smooth") && map.has("sine"))
    {
        map.failAtKey("smooth", "'smooth' is for 'keyframes' and 'csv' targets (a sine is smooth already)");
    }
    const bool smooth = map.optBool("smooth").value_or(false);
    if (map.has("sine"))
    {
        return readSine(source, map.get("sine"), what);
    }
    if (map.has("keyframes"))
    {
        return readKeyframes(source, map.get("keyframes"), what, smooth);
    }
    return readCsv(source, map.get("csv"), what, defaultColumn, smooth);
}

} // namespace frontier::io::detail
