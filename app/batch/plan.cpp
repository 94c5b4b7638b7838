// app/batch/plan.cpp: reading a batch plan (io/yaml_tree.h, located errors of io/yaml_util.h) and
// expanding it into jobs.
#include "app/batch/plan.h"

#include "app/batch/scene.h"
#include "app/model_overrides.h"
#include "core/model.h"
#include "io/file_util.h"
#include "io/scene.h"
#include "io/yaml_util.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <glob.h>
#include <limits>
#include <map>
#include <yaml-cpp/yaml.h>

namespace frontier::app
{

namespace
{
namespace fs = std::filesystem;
using io::detail::failAt;
using io::detail::MapNode;
using io::detail::YamlNode;
using io::detail::YamlSource;

const std::vector<std::string> cPlanKeys = {
    "scenes", "duration", "dt",           "solver", "integrator", "pgs_iterations", "seed",   "set",
    "vary",   "outputs",  "record_every", "fps",    "width",      "height",         "shards", "perturb"};
const std::vector<std::string> cRunSettings = {"dt",         "duration",       "solver",
                                               "integrator", "pgs_iterations", "seed"};
const std::vector<std::string> cOutputs = {"stats", "trajectory", "frames", "joints", "contacts"};

// The node as yaml-cpp's tree, for its emitter and for the scene paths (app/batch/scene.h): the
// same kinds, scalars, tags, collection styles and shared nodes (an alias) as the text gave.
YAML::Node yamlCppNode(const YamlNode& node, std::map<std::uint32_t, YAML::Node>& made)
{
    if (const auto it = made.find(node.id()); it != made.end())
    {
        return it->second;
    }
    YAML::Node out(node.isMap()        ? YAML::NodeType::Map
                   : node.isSequence() ? YAML::NodeType::Sequence
                   : node.isScalar()   ? YAML::NodeType::Scalar
                                       : YAML::NodeType::Null);
    made.emplace(node.id(), out);
    if (node.isScalar())
    {
        out = node.scalar();
        out.SetTag(node.tag());
    }
    else if (node.isSequence() || node.isMap())
    {
        out.SetTag(node.tag());
        out.SetStyle(node.style());
        for (std::size_t i = 0; i < node.size(); ++i)
        {
            if (node.isSequence())
            {
                out.push_back(yamlCppNode(node[i], made));
            }
            else
            {
                out.force_insert(yamlCppNode(node.key(i), made), yamlCppNode(node.value(i), made));
            }
        }
    }
    return out;
}

YAML::Node yamlCppNode(const YamlNode& node)
{
    std::map<std::uint32_t, YAML::Node> made;
    return yamlCppNode(node, made);
}

// One value's YAML text on one line: "0.001", "pgs", "[0, 0, 2]".
std::string flowText(const YamlNode& node)
{
    YAML::Emitter out;
    out.SetSeqFormat(YAML::Flow);
    out.SetMapFormat(YAML::Flow);
    out << yamlCppNode(node);
    return out.c_str();
}

// Checks one value of a run setting (the same ranges as the flags of `frontier run`; a time is a
// normal double: a subnormal one has lost its precision, and no run takes that many steps).
void checkRunValue(const YamlSource& source, const std::string& key, const YamlNode& value)
{
    const std::string what = "'" + key + "'";
    if (key == "dt" || key == "duration")
    {
        const double seconds = io::detail::toPositive(source, value, what + " (s)");
        const double most = key == "dt" ? cMaxTimeStepS : cMaxDurationS;
        if (!(seconds >= std::numeric_limits<double>::min() && seconds <= most))
        {
            char range[96];
            std::snprintf(range, sizeof range, "a number from %.17g to %.6g",
                          std::numeric_limits<double>::min(), most);
            failAt(source, value,
                   "expected " + std::string(range) + " for " + what + " (s), got " +
                       io::detail::describeNode(value));
        }
    }
    else if (key == "solver" || key == "integrator")
    {
        const std::string name = io::detail::toString(source, value, what);
        const std::vector<std::string> names =
            key == "solver" ? core::solverNames() : core::integratorNames();
        if (std::find(names.begin(), names.end(), name) == names.end())
        {
            failAt(source, value,
                   "unknown " + key + " '" + name + "'; expected " + core::nameList(names, "or"));
        }
    }
    else if (key == "pgs_iterations" || key == "seed")
    {
        const int n = io::detail::toInteger(source, value, what);
        if (n < (key == "seed" ? 0 : 1) || n > 1000000)
        {
            failAt(source, value,
                   "expected a whole number from " + std::string(key == "seed" ? "0" : "1") +
                       " to 1000000 for " + what);
        }
    }
}

// The entries of `scenes:`: a list, or one entry.
std::vector<YamlNode> sceneEntries(const YamlSource& source, const YamlNode& node)
{
    if (!node.isSequence() && !node.isScalar())
    {
        failAt(source, node,
               "expected a scene file, a glob or a list of them for 'scenes', got " +
                   io::detail::describeNode(node));
    }
    std::vector<YamlNode> entries;
    if (node.isSequence())
    {
        for (std::size_t i = 0; i < node.size(); ++i)
        {
            entries.push_back(node[i]);
        }
    }
    else
    {
        entries.push_back(node);
    }
    if (entries.empty())
    {
        failAt(source, node, "expected at least one scene in 'scenes'");
    }
    return entries;
}

// The files of one entry of `scenes:` (label, path): a file, or a glob's matches in sorted order.
std::vector<std::pair<std::string, std::string>> entryScenes(const YamlSource& source, const YamlNode& entry)
{
    const std::string pattern = io::detail::toString(source, entry, "an entry of 'scenes'");
    const bool isGlob = pattern.find_first_of("*?[") != std::string::npos;
    const std::string full = io::detail::resolvePath(source.baseDir, pattern);
    if (!isGlob)
    {
        std::error_code error;
        if (!fs::is_regular_file(full, error))
        {
            failAt(source, entry,
                   "no scene file '" + full +
                       "'; expected a .yaml scene, a .urdf model, an MJCF .xml model or an SDF file");
        }
        return {{pattern, full}};
    }
    glob_t matches{};
    const int code = ::glob(full.c_str(), 0, nullptr, &matches);
    std::vector<std::string> paths;
    for (std::size_t i = 0; code == 0 && i < matches.gl_pathc; ++i)
    {
        paths.emplace_back(matches.gl_pathv[i]);
    }
    ::globfree(&matches);
    if (paths.empty())
    {
        failAt(source, entry, "the glob '" + pattern + "' matches no file (relative to the plan's folder)");
    }
    std::vector<std::pair<std::string, std::string>> scenes;
    for (const std::string& path : paths) // glob(3) sorts them
    {
        const std::string label =
            source.baseDir.empty() ? path : fs::path(path).lexically_relative(source.baseDir).string();
        scenes.emplace_back(label, path);
    }
    return scenes;
}

// The scene files of `scenes:`: each entry a file or a glob (*, ?, [...]) relative to the plan's
// folder; labels are the paths as the plan spells them, globs expanded in sorted order.
std::vector<std::pair<std::string, std::string>> expandScenes(const YamlSource& source, const YamlNode& node)
{
    std::vector<std::pair<std::string, std::string>> scenes; // label, path
    for (const YamlNode& entry : sceneEntries(source, node))
    {
        const auto files = entryScenes(source, entry);
        scenes.insert(scenes.end(), files.begin(), files.end());
    }
    std::vector<const std::string*> labels; // sorted: a label named twice sits next to itself
    labels.reserve(scenes.size());
    for (const auto& scene : scenes)
    {
        labels.push_back(&scene.first);
    }
    std::sort(labels.begin(), labels.end(),
              [](const std::string* a, const std::string* b) { return *a < *b; });
    const auto twice = std::adjacent_find(
        labels.begin(), labels.end(), [](const std::string* a, const std::string* b) { return *a == *b; });
    if (twice != labels.end())
    {
        failAt(source, node, "the scene '" + **twice + "' is named twice in 'scenes'");
    }
    return scenes;
}

// Numbers for values such that equal values share one: a number by its value (0.001 and 1e-3, 2
// and 2.0), another scalar by its text (and tag), a list by its items' numbers, a map by its pairs'
// in any order. Each distinct value is numbered once, so a value built of aliases costs its node
// count, not its size; a value that contains itself equals only itself.
class ValueNumbers
{
  public:
    std::size_t of(const YamlNode& node)
    {
        if (const auto known = mOfNode.find(node.id()); known != mOfNode.end())
        {
            return known->second;
        }
        mOfNode[node.id()] = mNext++; // while its items are numbered: a value of its own
        const std::string& tag = node.tag();
        std::string key;
        if (node.isScalar())
        {
            const bool numeric = tag == "?" || tag == "!" || tag == "tag:yaml.org,2002:int" ||
                                 tag == "tag:yaml.org,2002:float";
            const std::optional<double> number =
                numeric ? io::detail::parseFiniteNumber(node.scalar()) : std::nullopt;
            if (number)
            {
                char text[32];
                const double value = *number == 0.0 ? 0.0 : *number; // -0 is 0
                key = "n" + std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
            }
            else
            {
                const bool plain = tag == "?" || tag == "!" || tag == "tag:yaml.org,2002:str";
                key = "s" + (plain ? std::string() : tag) + "\n" + node.scalar();
            }
        }
        else if (node.isSequence() || node.isMap())
        {
            std::vector<std::string> items;
            for (std::size_t i = 0; i < node.size(); ++i)
            {
                items.push_back(node.isSequence() ? std::to_string(of(node[i]))
                                                  : std::to_string(of(node.key(i))) + ":" +
                                                        std::to_string(of(node.value(i))));
            }
            if (node.isMap())
            {
                std::sort(items.begin(), items.end());
            }
            key = (node.isSequence() ? "l" : "m") + tag + "\n";
            for (const std::string& item : items)
            {
                key += item + ",";
            }
        }
        else
        {
            key = "~";
        }
        const std::size_t number = mOfKey.emplace(key, mNext++).first->second;
        mOfNode[node.id()] = number;
        return number;
    }

  private:
    std::map<std::string, std::size_t> mOfKey;
    std::map<std::uint32_t, std::size_t> mOfNode;
    std::size_t mNext = 0;
};

// A setting with its value as a job keeps it: a run setting's plain text (checked by
// checkRunValue: a tag or quotes are not part of it), a scene path's YAML flow text (its tags too:
// the scene loader reads them).
BatchSetting makeSetting(const std::string& key, const YamlNode& value)
{
    const YAML::Mark at = value.mark();
    return {key, isRunSetting(key) ? value.scalar() : flowText(value), at.line + 1, at.column + 1};
}

struct Axis
{
    std::string key;
    std::vector<YamlNode> values;
    std::vector<BatchSetting> settings; // one per value
};

// When the plan gives both dt and duration: the most steps it asks for is a number a run takes
// (checkedStepCount), else an error at the smallest dt.
void checkStepCount(const YamlSource& source, const std::vector<YamlNode>& dts,
                    const std::vector<YamlNode>& durations)
{
    if (dts.empty() || durations.empty())
    {
        return;
    }
    auto value = [](const YamlNode& node) { return *io::detail::parseFiniteNumber(node.scalar()); };
    auto smaller = [&](const YamlNode& a, const YamlNode& b) { return value(a) < value(b); };
    const YamlNode& dt = *std::min_element(dts.begin(), dts.end(), smaller);
    const YamlNode& duration = *std::max_element(durations.begin(), durations.end(), smaller);
    try
    {
        checkedStepCount(value(duration), value(dt), source.file);
    }
    catch (const io::InputError& e)
    {
        failAt(source, dt, "'dt' " + dt.scalar() + " is too small: " + e.message());
    }
}

// A key of `vary:` or `set:`: a run setting, or a scene path (at least two parts joined by '.').
void checkSettingKey(const YamlSource& source, const YAML::Mark& mark, const std::string& key,
                     const std::string& where)
{
    if (isRunSetting(key) || (key.find('.') != std::string::npos && key.front() != '.' && key.back() != '.'))
    {
        return;
    }
    failAt(source, mark,
           "unknown key '" + key + "' in " + where +
               "; expected dt, duration, solver, integrator, pgs_iterations, seed or a scene path such as "
               "bodies.NAME.mass or contact.friction");
}

std::string hex8(std::uint64_t hash)
{
    char text[16];
    std::snprintf(text, sizeof text, "%08x", static_cast<unsigned>((hash ^ (hash >> 32)) & 0xffffffffU));
    return text;
}

// "0007-pendulum-3f2a9c1b": the hash covers the scene as the plan names it and every setting (not
// the index, not the outputs), so a job keeps its folder when the plan is read again.
std::string jobId(std::size_t index, const std::string& scene, std::vector<BatchSetting> settings)
{
    std::sort(settings.begin(), settings.end(),
              [](const BatchSetting& a, const BatchSetting& b) { return a.key < b.key; });
    std::string text = "scene=" + scene + "\n";
    for (const BatchSetting& s : settings)
    {
        text += s.key + "=" + s.value + "\n";
    }
    char number[32];
    std::snprintf(number, sizeof number, "%04zu", index);
    std::string name = fs::path(scene).stem().string();
    for (char& c : name)
    {
        const bool plain =
            (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
        c = plain ? c : '_';
    }
    return std::string(number) + "-" + name + "-" + hex8(fnv1a64(text));
}
} // namespace

std::uint64_t fnv1a64(const std::string& text)
{
    std::uint64_t hash = 14695981039346656037ULL;
    for (const char c : text)
    {
        hash ^= static_cast<unsigned char>(c);
        hash *= 1099511628211ULL;
    }
    return hash;
}

bool isRunSetting(const std::string& key)
{
    return std::find(cRunSettings.begin(), cRunSettings.end(), key) != cRunSettings.end();
}

std::string describeVariation(const PlanJob& job)
{
    std::string text;
    for (const BatchSetting& s : job.variation)
    {
        text += (text.empty() ? "" : " ") + s.key + "=" + s.value;
    }
    return text;
}

const BatchSetting* findSetting(const PlanJob& job, const std::string& key)
{
    for (const BatchSetting& s : job.settings)
    {
        if (s.key == key)
        {
            return &s;
        }
    }
    return nullptr;
}

std::optional<double> numberSetting(const BatchPlan& plan, const PlanJob& job, const std::string& key)
{
    const BatchSetting* s = findSetting(job, key);
    if (s == nullptr)
    {
        return std::nullopt;
    }
    const std::optional<double> value = io::detail::parseFiniteNumber(s->value);
    if (!value)
    {
        throw io::InputError(plan.file, s->line, s->column,
                             "expected a number for '" + key + "', got '" + s->value + "'");
    }
    return value;
}

namespace
{
using SceneFiles = std::vector<std::pair<std::string, std::string>>; // label, path (expandScenes)

// The settings every job has: run settings at the top level, scene paths under `set:`; with the
// nodes of their values. `seen`: every setting key, where it was given.
struct FixedSettings
{
    std::vector<BatchSetting> settings;
    std::vector<YamlNode> nodes;
};

FixedSettings readFixedSettings(const YamlSource& source, const MapNode& map,
                                std::map<std::string, YAML::Mark>& seen)
{
    FixedSettings fixed;
    for (const std::string& key : cRunSettings)
    {
        if (map.has(key))
        {
            checkRunValue(source, key, map.get(key));
            fixed.settings.push_back(makeSetting(key, map.get(key)));
            fixed.nodes.push_back(map.get(key));
        }
    }
    for (const BatchSetting& s : fixed.settings)
    {
        seen[s.key] = map.keyMark(s.key);
    }
    if (!map.has("set"))
    {
        return fixed;
    }
    const MapNode set(source, map.get("set"), "'set'");
    for (std::size_t i = 0; i < set.node().size(); ++i)
    {
        const YamlNode keyNode = set.node().key(i);
        const std::string key = keyNode.scalar();
        checkSettingKey(source, keyNode.mark(), key, "'set'");
        if (isRunSetting(key))
        {
            failAt(source, keyNode, "'" + key + "' is a run setting: give it at the top level of the plan");
        }
        if (!seen.emplace(key, keyNode.mark()).second)
        {
            failAt(source, keyNode, "'" + key + "' is given twice");
        }
        fixed.settings.push_back(makeSetting(key, set.node().value(i)));
        fixed.nodes.push_back(set.node().value(i));
    }
    return fixed;
}

// One key of `vary:` and its values, each checked and given once.
Axis readAxis(const YamlSource& source, const YamlNode& keyNode, const YamlNode& values,
              ValueNumbers& numbers)
{
    const std::string key = keyNode.scalar();
    const std::string what = "'" + key + "' in 'vary'";
    io::detail::requireSequence(source, values, what);
    if (values.size() == 0)
    {
        failAt(source, values, "expected a non-empty list of values for " + what);
    }
    Axis axis{key, {}, {}};
    std::map<std::size_t, YamlNode> given; // by ValueNumbers: equal values are given twice
    for (std::size_t v = 0; v < values.size(); ++v)
    {
        const YamlNode value = values[v];
        if (isRunSetting(key))
        {
            checkRunValue(source, key, value);
        }
        axis.values.push_back(value);
        axis.settings.push_back(makeSetting(key, value));
        const auto [first, fresh] = given.emplace(numbers.of(value), value);
        if (!fresh)
        {
            const YAML::Mark at = first->second.mark();
            failAt(source, value,
                   "the value " + axis.settings.back().value + " is given twice for " + what +
                       " (equal to the one at line " + std::to_string(at.line + 1) + ", column " +
                       std::to_string(at.column + 1) + ")");
        }
    }
    return axis;
}

// The axes of `vary:`, in the plan's key order; a key also fixed (in `seen`) is an error.
std::vector<Axis> readVary(const YamlSource& source, const MapNode& map,
                           std::map<std::string, YAML::Mark>& seen)
{
    std::vector<Axis> axes;
    if (!map.has("vary"))
    {
        return axes;
    }
    ValueNumbers numbers;
    const YamlNode vary = map.get("vary");
    MapNode(source, vary, "'vary'"); // a map
    for (std::size_t i = 0; i < vary.size(); ++i)
    {
        const YamlNode keyNode = vary.key(i);
        const std::string key = keyNode.scalar();
        checkSettingKey(source, keyNode.mark(), key, "'vary'");
        if (const auto at = seen.find(key); at != seen.end())
        {
            failAt(source, keyNode,
                   "'" + key + "' is also given at line " + std::to_string(at->second.line + 1) +
                       "; a setting is either fixed or varied");
        }
        seen.emplace(key, keyNode.mark());
        axes.push_back(readAxis(source, keyNode, vary.value(i), numbers));
    }
    return axes;
}

// The values a run setting takes in the plan: fixed, or varied.
std::vector<YamlNode> givenValues(const MapNode& map, const std::vector<Axis>& axes, const std::string& key)
{
    std::vector<YamlNode> given;
    if (map.has(key))
    {
        given.push_back(map.get(key));
    }
    for (const Axis& axis : axes)
    {
        if (axis.key == key)
        {
            given = axis.values;
        }
    }
    return given;
}

// `outputs:`: the files each job writes besides its stats.
BatchOutputs readOutputs(const YamlSource& source, const MapNode& map)
{
    BatchOutputs wanted;
    if (!map.has("outputs"))
    {
        return wanted;
    }
    const YamlNode outputs = map.get("outputs");
    io::detail::requireSequence(source, outputs, "'outputs'");
    for (std::size_t i = 0; i < outputs.size(); ++i)
    {
        const YamlNode entry = outputs[i];
        const std::string name = io::detail::toString(source, entry, "an entry of 'outputs'");
        if (std::find(cOutputs.begin(), cOutputs.end(), name) == cOutputs.end())
        {
            failAt(source, entry,
                   "unknown output '" + name + "'; expected stats, trajectory, frames, joints or contacts");
        }
        wanted.trajectory = wanted.trajectory || name == "trajectory";
        wanted.frames = wanted.frames || name == "frames";
        wanted.joints = wanted.joints || name == "joints";
        wanted.contacts = wanted.contacts || name == "contacts";
    }
    return wanted;
}

// record_every, width, height, fps, shards, perturb.
void readJobShape(const YamlSource& source, const MapNode& map, BatchPlan& plan)
{
    auto wholeIn = [&](const std::string& key, int low, int high, int fallback)
    {
        const std::optional<int> value = map.optInteger(key);
        if (value && (*value < low || *value > high))
        {
            map.failAtValue(key, "expected a whole number from " + std::to_string(low) + " to " +
                                     std::to_string(high) + " for " + map.what(key));
        }
        return value.value_or(fallback);
    };
    plan.recordEvery = wholeIn("record_every", 1, 2147483647, 1);
    plan.width = wholeIn("width", 16, 16384, plan.width);
    plan.height = wholeIn("height", 16, 16384, plan.height);
    plan.fps = map.optPositive("fps").value_or(plan.fps);
    if (map.has("shards"))
    {
        plan.shards = wholeIn("shards", 1, 100000, 1);
    }
    if (map.has("perturb"))
    {
        const MapNode perturb(source, map.get("perturb"), "'perturb'");
        perturb.checkKeys({"position", "velocity"});
        plan.perturbPositionM = perturb.optNonNegative("position", "(m)").value_or(plan.perturbPositionM);
        plan.perturbVelocityMps =
            perturb.optNonNegative("velocity", "(m/s)").value_or(plan.perturbVelocityMps);
    }
}

// The cells of the grid of `vary`; at most 1000000 jobs with the scenes.
std::size_t gridCells(const YamlSource& source, const MapNode& map, std::size_t sceneCount,
                      const std::vector<Axis>& axes)
{
    if (sceneCount > 1000000)
    {
        failAt(source, map.keyMark("scenes"), "the plan makes more than 1000000 jobs");
    }
    std::size_t cells = 1;
    for (const Axis& axis : axes)
    {
        cells *= axis.values.size();
        if (cells * sceneCount > 1000000)
        {
            failAt(source, map.keyMark("vary"), "the plan makes more than 1000000 jobs");
        }
    }
    return cells;
}

// Scene paths are checked against every scene: a path no scene has is a mistake of the plan.
class ScenePathCheck
{
  public:
    ScenePathCheck(const YamlSource& source, const std::string& label, const std::string& file)
        : mSource(source), mLabel(label), mFile(file)
    {
    }

    void operator()(const std::string& key, const YamlNode& value)
    {
        if (isRunSetting(key))
        {
            return;
        }
        if (const std::string ext = io::detail::lowerExtension(mFile); ext != ".yaml" && ext != ".yml")
        {
            failAt(mSource, value,
                   "'" + key + "' is a scene path, and " + mLabel + " is a model file (" + ext +
                       "), not a YAML scene");
        }
        if (!mRoot)
        {
            try
            {
                mRoot = YAML::Load(io::detail::readTextFile(mFile, "scene file"));
            }
            catch (const YAML::Exception& e)
            {
                failAt(mSource, value, mLabel + " is not valid YAML: " + e.msg);
            }
        }
        const std::string problem = applySceneSetting(YAML::Clone(*mRoot), key, yamlCppNode(value));
        if (!problem.empty())
        {
            failAt(mSource, value, "'" + key + "' does not fit " + mLabel + ": " + problem);
        }
    }

  private:
    const YamlSource& mSource;
    const std::string& mLabel;
    const std::string& mFile;
    std::optional<YAML::Node> mRoot; // the scene, read at its first scene path
};

void checkScenePaths(const YamlSource& source, const SceneFiles& scenes, const FixedSettings& fixed,
                     const std::vector<Axis>& axes)
{
    for (const auto& scene : scenes)
    {
        ScenePathCheck checkPath(source, scene.first, scene.second);
        for (std::size_t k = 0; k < fixed.settings.size(); ++k)
        {
            checkPath(fixed.settings[k].key, fixed.nodes[k]);
        }
        for (const Axis& axis : axes)
        {
            for (const YamlNode& value : axis.values)
            {
                checkPath(axis.key, value);
            }
        }
    }
}

// The grid: scenes outer, then the vary keys in the plan's order, the last one fastest.
void expandJobs(BatchPlan& plan, const SceneFiles& scenes, const std::vector<BatchSetting>& fixed,
                const std::vector<Axis>& axes, std::size_t cells)
{
    plan.jobs.reserve(cells * scenes.size());
    for (const auto& [label, file] : scenes)
    {
        for (std::size_t cell = 0; cell < cells; ++cell)
        {
            PlanJob job;
            job.index = plan.jobs.size();
            job.scene = label;
            job.scenePath = file;
            std::size_t rest = cell;
            job.variation.resize(axes.size());
            for (std::size_t a = axes.size(); a-- > 0;)
            {
                const std::size_t n = axes[a].values.size();
                job.variation[a] = axes[a].settings[rest % n];
                rest /= n;
            }
            job.settings.reserve(fixed.size() + axes.size());
            job.settings = fixed;
            job.settings.insert(job.settings.end(), job.variation.begin(), job.variation.end());
            job.id = jobId(job.index, label, job.settings);
            plan.jobs.push_back(std::move(job));
        }
    }
}
} // namespace

BatchPlan readBatchPlan(const std::string& path)
{
    const YamlSource source{path, io::detail::directoryOf(path)};
    BatchPlan plan;
    plan.file = path;
    const std::string text = io::detail::readTextFile(path, "batch plan");
    io::detail::YamlDocuments documents; // the first document (more are ignored)
    try
    {
        io::detail::parseYaml(text, path, documents);
    }
    catch (const YAML::ParserException& e)
    {
        failAt(source, e.mark, "invalid YAML: " + e.msg);
    }
    const YamlNode root = documents.first.root();
    if (!root.isMap())
    {
        failAt(source, root,
               "expected a map with 'scenes' (and 'vary') for the batch plan, got " +
                   io::detail::describeNode(root));
    }
    const MapNode map(source, root, "the batch plan");
    map.checkKeys(cPlanKeys);
    const SceneFiles scenes = expandScenes(source, map.require("scenes"));
    std::map<std::string, YAML::Mark> seen; // every setting key, where it was given
    const FixedSettings fixed = readFixedSettings(source, map, seen);
    const std::vector<Axis> axes = readVary(source, map, seen);
    for (const Axis& axis : axes)
    {
        plan.varyKeys.push_back(axis.key);
    }
    checkStepCount(source, givenValues(map, axes, "dt"), givenValues(map, axes, "duration"));
    plan.outputs = readOutputs(source, map);
    readJobShape(source, map, plan);
    const std::size_t cells = gridCells(source, map, scenes.size(), axes);
    checkScenePaths(source, scenes, fixed, axes);
    expandJobs(plan, scenes, fixed.settings, axes, cells);
    return plan;
}

} // namespace frontier::app
