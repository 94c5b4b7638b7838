// app/batch/scene.cpp: scene paths set in the scene's YAML, and the seeded perturbation.
#include "app/batch/scene.h"

#include "io/file_util.h"
#include "io/input_digest.h"
#include "io/scene.h"
#include "io/trajectory.h"

#include <array>
#include <charconv>
#include <cstdio>
#include <numeric>
#include <optional>

namespace frontier::app
{

namespace
{
std::vector<std::string> splitPath(const std::string& path)
{
    std::vector<std::string> parts;
    std::size_t begin = 0;
    while (begin <= path.size())
    {
        const std::size_t end = std::min(path.find('.', begin), path.size());
        parts.push_back(path.substr(begin, end - begin));
        begin = end + 1;
    }
    return parts;
}

// The entry of a list named `part`: the map whose `name` is `part`, else the entry at index `part`.
YAML::Node listEntry(const YAML::Node& list, const std::string& part, std::size_t& index)
{
    for (std::size_t i = 0; i < list.size(); ++i)
    {
        const YAML::Node entry = list[i];
        if (entry.IsMap() && entry["name"] && entry["name"].IsScalar() && entry["name"].Scalar() == part)
        {
            index = i;
            return entry;
        }
    }
    std::size_t n = 0;
    const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), n);
    if (error == std::errc() && end == part.data() + part.size() && n < list.size())
    {
        index = n;
        return list[n];
    }
    return YAML::Node(YAML::NodeType::Undefined);
}

// splitmix64 (Steele, Lea and Flood, 2014): a fixed sequence for a seed on every platform.
std::uint64_t splitmix64(std::uint64_t& state)
{
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

// Uniform in [-1, 1): the top 53 bits as a double.
double symmetricUniform(std::uint64_t& state)
{
    return 2.0 * static_cast<double>(splitmix64(state) >> 11) * 0x1.0p-53 - 1.0;
}

// The scene file's YAML tree; throws io::InputError (with the line and column of a syntax error).
YAML::Node parseScene(const std::string& path)
{
    try
    {
        return YAML::Load(io::detail::readTextFile(path, "scene file"));
    }
    catch (const YAML::Exception& e)
    {
        const bool at = !e.mark.is_null();
        throw io::InputError(path, at ? e.mark.line + 1 : 0, at ? e.mark.column + 1 : 0,
                             "invalid YAML: " + e.msg);
    }
}

// What a job runs besides its files and its id's settings: the scene text as run (the YAML written
// after the plan's scene paths are set; empty when there are none: the scene file is then among
// the files), the loader's options (--package-path, --self-collision, ...) and, with a seed, the
// plan's perturbation sizes.
std::string jobRunText(const BatchPlan& plan, const PlanJob& job, const std::string& sceneText,
                       const io::UrdfOptions& urdf)
{
    std::string text = "scene text:\n" + sceneText + "\nloader options:\n";
    io::TrajectoryMetadata options;
    io::addUrdfOptions(options, urdf);
    for (const auto& [key, value] : options)
    {
        text += key + "=" + value + "\n";
    }
    if (findSetting(job, "seed") != nullptr)
    {
        char perturbation[96]; // m and m/s per axis, exactly (17 digits)
        std::snprintf(perturbation, sizeof perturbation, "perturb position=%.17g velocity=%.17g\n",
                      plan.perturbPositionM, plan.perturbVelocityMps);
        text += perturbation;
    }
    return text;
}

// A scene path's value as set in the scene's tree (its nodes; the setting of the plan).
struct AppliedSetting
{
    YAML::Node value;
    const BatchSetting* setting;
};

// Where a node of the scene as written after setting the scene paths comes from.
struct NodeOrigin
{
    YAML::Mark written;                // its place in the written text
    YAML::Mark original;               // its place in the scene file (null: not from the file)
    const BatchSetting* set = nullptr; // the setting whose value it is part of
};

// Pairs the nodes of `made` (the scene's tree with the settings applied: the file's nodes keep the
// marks of its parse, the values set are `applied`) with those of `read` (the written text parsed
// again: the same tree), in document order. A node seen before (an alias) is not entered again.
void collectOrigins(const YAML::Node& made, const YAML::Node& read,
                    const std::vector<AppliedSetting>& applied, const BatchSetting* set,
                    std::vector<NodeOrigin>& out)
{
    for (const AppliedSetting& a : applied)
    {
        set = made.is(a.value) ? a.setting : set;
    }
    const YAML::Mark written = read.Mark();
    if (!out.empty() && written.pos < out.back().written.pos)
    {
        return; // an alias of a node of the text before
    }
    out.push_back({written, set != nullptr ? YAML::Mark::null_mark() : made.Mark(), set});
    if (made.Type() != read.Type() || made.size() != read.size())
    {
        return;
    }
    if (made.IsSequence())
    {
        for (std::size_t i = 0; i < made.size(); ++i)
        {
            collectOrigins(made[i], read[i], applied, set, out);
        }
    }
    else if (made.IsMap())
    {
        for (auto m = made.begin(), r = read.begin(); m != made.end() && r != read.end(); ++m, ++r)
        {
            collectOrigins(m->first, r->first, applied, set, out);
            collectOrigins(m->second, r->second, applied, set, out);
        }
    }
}

// The scene loader's error `e` about the scene as written after setting the job's scene paths
// (`text`, from `made`), at the place it names in the user's files instead: in the scene file, or,
// for a value the plan set, at that value in the plan.
io::InputError relocatedError(const io::InputError& e, const BatchPlan& plan, const PlanJob& job,
                              const YAML::Node& made, const std::vector<AppliedSetting>& applied,
                              const std::string& text)
{
    if (e.file() != job.scenePath || e.line() <= 0)
    {
        return e;
    }
    std::vector<NodeOrigin> origins;
    try
    {
        collectOrigins(made, YAML::Load(text), applied, nullptr, origins);
    }
    catch (const YAML::Exception&)
    {
        return io::InputError(job.scenePath, 0, 0, e.message()); // (text written by yaml-cpp: not expected)
    }
    // The node the error names: the last one that starts at or before its place; a node the
    // settings made (a new key) counts as the next one (its value).
    const int line = e.line() - 1, column = std::max(0, e.column() - 1);
    std::size_t at = origins.size();
    for (std::size_t i = 0; i < origins.size(); ++i)
    {
        const YAML::Mark& w = origins[i].written;
        if (w.line > line || (w.line == line && w.column > column))
        {
            break;
        }
        at = i;
    }
    while (at < origins.size() && origins[at].set == nullptr && origins[at].original.is_null())
    {
        ++at;
    }
    if (at == origins.size())
    {
        return io::InputError(job.scenePath, 0, 0, e.message());
    }
    if (const BatchSetting* s = origins[at].set)
    {
        return io::InputError(plan.file, s->line, s->column,
                              "'" + s->key + "' set for " + job.scene + ": " + e.message());
    }
    return io::InputError(job.scenePath, origins[at].original.line + 1, origins[at].original.column + 1,
                          e.message());
}
} // namespace

std::string applySceneSetting(YAML::Node root, const std::string& path, const YAML::Node& value)
{
    const std::vector<std::string> parts = splitPath(path);
    YAML::Node node = root;
    std::string at = "the scene";
    for (std::size_t k = 0; k < parts.size(); ++k)
    {
        const std::string& part = parts[k];
        const bool last = k + 1 == parts.size();
        if (part.empty())
        {
            return "an empty key in the path";
        }
        if (node.IsMap())
        {
            if (last)
            {
                node[part] = value;
                return {};
            }
            YAML::Node child = node[part];
            if ((!child.IsDefined() || child.IsNull()) && k == 0 && io::isSettingsMapKey(part))
            {
                node[part] = YAML::Node(YAML::NodeType::Map); // its defaults, given as an empty map
                child = node[part];
            }
            if (!child.IsDefined() || child.IsNull())
            {
                return "no key '" + part + "' in " + at;
            }
            node.reset(child);
        }
        else if (node.IsSequence())
        {
            std::size_t index = 0;
            YAML::Node entry = listEntry(node, part, index);
            if (!entry.IsDefined())
            {
                return "no entry named '" + part + "' (nor index " + part + ") in " + at;
            }
            if (last)
            {
                node[index] = value;
                return {};
            }
            node.reset(entry);
        }
        else
        {
            return at + " is not a map or a list, so it has no '" + part + "'";
        }
        at = "'" + part + "'";
    }
    return {};
}

void perturbInitialState(core::Model& model, std::uint64_t seed, double positionM, double velocityMps)
{
    const std::size_t n = model.bodies.size();
    std::vector<std::size_t> group(n);
    std::iota(group.begin(), group.end(), 0);
    auto find = [&](std::size_t b)
    {
        while (group[b] != b)
        {
            b = group[b] = group[group[b]];
        }
        return b;
    };
    std::vector<bool> anchored(n, false);
    for (std::size_t b = 0; b < n; ++b)
    {
        anchored[b] = model.bodies[b].isStatic;
    }
    for (const core::Joint& joint : model.joints)
    {
        const auto child = static_cast<std::size_t>(joint.child);
        if (joint.parent == core::cWorld)
        {
            anchored[find(child)] = true;
            continue;
        }
        const std::size_t a = find(static_cast<std::size_t>(joint.parent));
        const std::size_t c = find(child);
        if (a != c)
        {
            group[c] = a;
            anchored[a] = anchored[a] || anchored[c];
        }
    }
    std::uint64_t state = seed;
    std::vector<std::optional<std::array<double, 6>>> draws(n);
    for (std::size_t b = 0; b < n; ++b) // groups in the order of their first body
    {
        const std::size_t root = find(b);
        if (anchored[root] || model.bodies[b].isStatic)
        {
            continue;
        }
        if (!draws[root])
        {
            std::array<double, 6> u{};
            for (double& x : u)
            {
                x = symmetricUniform(state);
            }
            draws[root] = u;
        }
        const std::array<double, 6>& u = *draws[root];
        model.bodies[b].position_W += positionM * core::Vec3(u[0], u[1], u[2]);
        model.bodies[b].velocity_W += velocityMps * core::Vec3(u[3], u[4], u[5]);
    }
}

BatchScene loadBatchScene(const BatchPlan& plan, const PlanJob& job, const io::UrdfOptions& urdf)
{
    bool scenePaths = false;
    for (const BatchSetting& s : job.settings)
    {
        scenePaths = scenePaths || !isRunSetting(s.key);
    }
    const io::detail::InputFileLog reads; // the scene file too, read here when scene paths are set
    BatchScene scene;
    std::string sceneText; // as run, when it is not the scene file's
    if (!scenePaths)
    {
        scene.loaded = run::loadScene(job.scenePath, urdf);
    }
    else
    {
        YAML::Node root = parseScene(job.scenePath);
        std::vector<AppliedSetting> applied;
        for (const BatchSetting& s : job.settings)
        {
            if (!isRunSetting(s.key))
            {
                applied.push_back({YAML::Load(s.value), &s});
                const std::string problem = applySceneSetting(root, s.key, applied.back().value);
                if (!problem.empty())
                {
                    throw io::InputError(plan.file, s.line, s.column,
                                         "'" + s.key + "' does not fit " + job.scene + ": " + problem);
                }
            }
        }
        YAML::Emitter text;
        text << root;
        sceneText = text.c_str();
        try
        {
            scene.loaded = run::loadSceneText(sceneText, job.scenePath, urdf);
        }
        catch (const io::InputError& e)
        {
            throw relocatedError(e, plan, job, root, applied, sceneText);
        }
    }
    if (const std::optional<double> seed = numberSetting(plan, job, "seed"))
    {
        perturbInitialState(scene.loaded.model, static_cast<std::uint64_t>(*seed), plan.perturbPositionM,
                            plan.perturbVelocityMps); // a whole number from 0 to 1000000 (readBatchPlan)
        run::checkStartingStates(scene.loaded.model, job.scenePath);
    }
    scene.loaded.report.inputFiles = reads.files();
    scene.inputsDigest =
        io::inputsDigest(io::programIdentity(), jobRunText(plan, job, sceneText, urdf), reads.files());
    return scene;
}

} // namespace frontier::app
