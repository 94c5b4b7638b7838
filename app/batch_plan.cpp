// app/batch_plan.cpp: reading a batch plan (io/yaml_tree.h, located errors of io/yaml_util.h) and
// expanding it into jobs.
#include "app/batch_plan.h"

#include "app/batch_scene.h"
#include "io/file_util.h"
#include "io/scene.h"
#include "io/yaml_util.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <glob.h>
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

// The node as yaml-cpp's tree, for its emitter and for the scene paths (app/batch_scene.h): the
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

// Checks one value of a run setting (the same ranges as the flags of `frontier run`).
void checkRunValue(const YamlSource& source, const std::string& key, const YamlNode& value)
{
    const std::string what = "'" + key + "'";
    if (key == "dt" || key == "duration")
    {
        io::detail::toPositive(source, value, what + " (s)");
    }
    else if (key == "solver" || key == "integrator")
    {
        const std::string name = io::detail::toString(source, value, what);
        const std::vector<std::string> names = key == "solver"
                                                   ? std::vector<std::string>{"linear", "dense", "pgs"}
                                                   : std::vector<std::string>{"euler", "rattle", "rattle4"};
        if (std::find(names.begin(), names.end(), name) == names.end())
        {
            failAt(source, value,
                   "unknown " + key + " '" + name + "'; expected " + names[0] + ", " + names[1] + " or " +
                       names[2]);
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

// The scene files of `scenes:`: each entry a file or a glob (*, ?, [...]) relative to the plan's
// folder; labels are the paths as the plan spells them, globs expanded in sorted order.
std::vector<std::pair<std::string, std::string>> expandScenes(const YamlSource& source, const YamlNode& node)
{
    std::vector<std::pair<std::string, std::string>> scenes; // label, path
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
    for (const YamlNode& entry : entries)
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
                       "no scene file '" + full + "'; expected a .yaml scene or a .urdf model");
            }
            scenes.emplace_back(pattern, full);
            continue;
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
            failAt(source, entry,
                   "the glob '" + pattern + "' matches no file (relative to the plan's folder)");
        }
        for (const std::string& path : paths) // glob(3) sorts them
        {
            const std::string label =
                source.baseDir.empty() ? path : fs::path(path).lexically_relative(source.baseDir).string();
            scenes.emplace_back(label, path);
        }
    }
    for (std::size_t i = 0; i < scenes.size(); ++i)
    {
        for (std::size_t j = 0; j < i; ++j)
        {
            if (scenes[i].first == scenes[j].first)
            {
                failAt(source, node, "the scene '" + scenes[i].first + "' is named twice in 'scenes'");
            }
        }
    }
    return scenes;
}

struct Axis
{
    std::string key;
    std::vector<YamlNode> values;
};

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

const std::string* findSetting(const PlanJob& job, const std::string& key)
{
    for (const BatchSetting& s : job.settings)
    {
        if (s.key == key)
        {
            return &s.value;
        }
    }
    return nullptr;
}

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
    const auto scenes = expandScenes(source, map.require("scenes"));

    // Fixed settings: run settings at the top level, scene paths under `set:`.
    std::vector<BatchSetting> fixed;
    std::vector<YamlNode> fixedNodes;
    for (const std::string& key : cRunSettings)
    {
        if (map.has(key))
        {
            checkRunValue(source, key, map.get(key));
            fixed.push_back({key, flowText(map.get(key))});
            fixedNodes.push_back(map.get(key));
        }
    }
    std::map<std::string, YAML::Mark> seen; // every setting key, where it was given
    for (const BatchSetting& s : fixed)
    {
        seen[s.key] = map.keyMark(s.key);
    }
    if (map.has("set"))
    {
        const MapNode set(source, map.get("set"), "'set'");
        for (std::size_t i = 0; i < set.node().size(); ++i)
        {
            const YamlNode keyNode = set.node().key(i);
            const std::string key = keyNode.scalar();
            checkSettingKey(source, keyNode.mark(), key, "'set'");
            if (isRunSetting(key))
            {
                failAt(source, keyNode,
                       "'" + key + "' is a run setting: give it at the top level of the plan");
            }
            if (!seen.emplace(key, keyNode.mark()).second)
            {
                failAt(source, keyNode, "'" + key + "' is given twice");
            }
            fixed.push_back({key, flowText(set.node().value(i))});
            fixedNodes.push_back(set.node().value(i));
        }
    }

    std::vector<Axis> axes;
    if (map.has("vary"))
    {
        const YamlNode vary = map.get("vary");
        MapNode(source, vary, "'vary'"); // a map
        for (std::size_t i = 0; i < vary.size(); ++i)
        {
            const YamlNode keyNode = vary.key(i);
            const YamlNode values = vary.value(i);
            const std::string key = keyNode.scalar();
            checkSettingKey(source, keyNode.mark(), key, "'vary'");
            if (const auto at = seen.find(key); at != seen.end())
            {
                failAt(source, keyNode,
                       "'" + key + "' is also given at line " + std::to_string(at->second.line + 1) +
                           "; a setting is either fixed or varied");
            }
            seen.emplace(key, keyNode.mark());
            const std::string what = "'" + key + "' in 'vary'";
            io::detail::requireSequence(source, values, what);
            if (values.size() == 0)
            {
                failAt(source, values, "expected a non-empty list of values for " + what);
            }
            Axis axis{key, {}};
            std::vector<std::string> texts;
            for (std::size_t v = 0; v < values.size(); ++v)
            {
                const YamlNode value = values[v];
                if (isRunSetting(key))
                {
                    checkRunValue(source, key, value);
                }
                const std::string valueText = flowText(value);
                if (std::find(texts.begin(), texts.end(), valueText) != texts.end())
                {
                    failAt(source, value, "the value " + valueText + " is given twice for " + what);
                }
                texts.push_back(valueText);
                axis.values.push_back(value);
            }
            plan.varyKeys.push_back(key);
            axes.push_back(std::move(axis));
        }
    }

    if (map.has("outputs"))
    {
        const YamlNode outputs = map.get("outputs");
        io::detail::requireSequence(source, outputs, "'outputs'");
        for (std::size_t i = 0; i < outputs.size(); ++i)
        {
            const YamlNode entry = outputs[i];
            const std::string name = io::detail::toString(source, entry, "an entry of 'outputs'");
            if (std::find(cOutputs.begin(), cOutputs.end(), name) == cOutputs.end())
            {
                failAt(source, entry,
                       "unknown output '" + name +
                           "'; expected stats, trajectory, frames, joints or contacts");
            }
            plan.outputs.trajectory = plan.outputs.trajectory || name == "trajectory";
            plan.outputs.frames = plan.outputs.frames || name == "frames";
            plan.outputs.joints = plan.outputs.joints || name == "joints";
            plan.outputs.contacts = plan.outputs.contacts || name == "contacts";
        }
    }
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

    // Scene paths are checked against every scene: a path no scene has is a mistake of the plan.
    for (const auto& scene : scenes)
    {
        const std::string& label = scene.first; // named copies: a lambda below uses them (clang 14
        const std::string& file = scene.second; // cannot capture structured bindings)
        std::optional<YAML::Node> sceneRoot;
        auto checkPath = [&](const std::string& key, const YamlNode& value)
        {
            if (isRunSetting(key))
            {
                return;
            }
            if (io::detail::lowerExtension(file) == ".urdf")
            {
                failAt(source, value,
                       "'" + key + "' is a scene path, and " + label + " is a .urdf model, not a scene");
            }
            if (!sceneRoot)
            {
                try
                {
                    sceneRoot = YAML::Load(io::detail::readTextFile(file, "scene file"));
                }
                catch (const YAML::Exception& e)
                {
                    failAt(source, value, label + " is not valid YAML: " + e.msg);
                }
            }
            const std::string problem = applySceneSetting(YAML::Clone(*sceneRoot), key, yamlCppNode(value));
            if (!problem.empty())
            {
                failAt(source, value, "'" + key + "' does not fit " + label + ": " + problem);
            }
        };
        for (std::size_t k = 0; k < fixed.size(); ++k)
        {
            checkPath(fixed[k].key, fixedNodes[k]);
        }
        for (const Axis& axis : axes)
        {
            for (const YamlNode& value : axis.values)
            {
                checkPath(axis.key, value);
            }
        }
    }

    // The grid: scenes outer, then the vary keys in the plan's order, the last one fastest.
    std::size_t cells = 1;
    for (const Axis& axis : axes)
    {
        cells *= axis.values.size();
        if (cells * scenes.size() > 1000000)
        {
            failAt(source, map.keyMark("vary"), "the plan makes more than 1000000 jobs");
        }
    }
    for (const auto& [label, file] : scenes)
    {
        for (std::size_t cell = 0; cell < cells; ++cell)
        {
            PlanJob job;
            job.index = plan.jobs.size();
            job.scene = label;
            job.scenePath = file;
            job.settings = fixed;
            std::size_t rest = cell;
            std::vector<BatchSetting> variation(axes.size());
            for (std::size_t a = axes.size(); a-- > 0;)
            {
                const std::size_t n = axes[a].values.size();
                variation[a] = {axes[a].key, flowText(axes[a].values[rest % n])};
                rest /= n;
            }
            job.variation = variation;
            job.settings.insert(job.settings.end(), variation.begin(), variation.end());
            job.id = jobId(job.index, label, job.settings);
            plan.jobs.push_back(std::move(job));
        }
    }
    return plan;
}

} // namespace frontier::app
