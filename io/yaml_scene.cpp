// io/yaml_scene.cpp: a YAML scene file: top-level keys, simulation, contact, camera, models.
#include "io/yaml_scene.h"

#include "core/state.h"
#include "io/file_util.h"
#include "io/hold_servos.h"
#include "io/mjcf_model.h"
#include "io/scene.h"
#include "io/suggest.h"
#include "io/urdf_model.h"

#include <algorithm>
#include <exception>
#include <filesystem>
#include <sstream>
#include <tuple>
#include <yaml-cpp/exceptions.h>

namespace frontier::io::detail
{

namespace
{

const std::vector<std::string> cSceneKeys = {"name",   "simulation", "contact",  "bodies",
                                             "joints", "models",     "camera",   "actuators",
                                             "loads",  "reference",  "stability"};
const std::vector<std::string> cReferenceKeys = {"csv", "body"};
const std::vector<std::string> cSimulationKeys = {"dt",     "duration",       "gravity",
                                                  "solver", "pgs_iterations", "integrator"};
const std::vector<std::string> cContactKeys = {"friction",           "restitution",       "tolerance",
                                               "relative_tolerance", "start_penetration", "ignore"};
const std::vector<std::string> cCameraKeys = {"position", "look_at", "fov"};
const std::vector<std::string> cModelKeys = {
    "urdf",   "mjcf",           "position", "orientation", "velocity",        "angular_velocity",
    "prefix", "self_collision", "fixed",    "free_base",   "joint_positions", "drop_height",
    "hold",   "keyframe"};
// Keys that place a URDF only (an MJCF file's <key> chosen by 'keyframe' sets its pose).
const std::vector<std::string> cUrdfOnlyModelKeys = {"fixed", "free_base", "joint_positions"};

// `reference: {csv: FILE, body: NAME}`, after all bodies exist; the CSV is read by `sweep` alone.
SceneReference readReference(const SceneBuilder& builder, const YamlNode& node)
{
    const MapNode map(builder.source, node, "'reference'");
    map.checkKeys(cReferenceKeys);
    SceneReference reference;
    reference.csvPath = resolvePath(builder.source.baseDir, map.string("csv"));
    const int body = resolveBodyName(builder, map.require("body"), map.what("body"), false);
    reference.body = builder.model.bodies[static_cast<std::size_t>(body)].name;
    return reference;
}

void readSimulation(const YamlSource& source, const YamlNode& node, core::SimulationSettings& sim)
{
    const MapNode map(source, node, "'simulation'");
    map.checkKeys(cSimulationKeys);
    sim.dt = map.optPositive("dt").value_or(sim.dt);
    sim.duration = map.optPositive("duration").value_or(sim.duration);
    for (const auto& [key, limit, value] : {std::tuple("dt", core::cMaxTimeStep, sim.dt),
                                            std::tuple("duration", core::cMaxDuration, sim.duration)})
    {
        if (!(value <= limit))
        {
            std::ostringstream message;
            message << "expected a number of seconds in (0, " << limit << "] for " << map.what(key)
                    << ", got " << value;
            map.failAtValue(key, message.str());
        }
    }
    sim.gravity = map.optVec3("gravity").value_or(sim.gravity);
    if (map.has("solver"))
    {
        const std::string name = map.string("solver");
        const std::optional<core::SolverKind> kind = core::solverFromName(name);
        if (!kind)
        {
            map.failAtValue("solver", "unknown solver '" + name + "' for " + map.what("solver") +
                                          "; expected " + core::nameList(core::solverNames(), "or"));
        }
        sim.solver = *kind;
    }
    if (map.has("pgs_iterations"))
    {
        sim.pgsIterations = *map.optInteger("pgs_iterations");
        if (sim.pgsIterations < 1 || sim.pgsIterations > cMaxPgsIterations)
        {
            map.failAtValue("pgs_iterations", "expected an integer from 1 to " +
                                                  std::to_string(cMaxPgsIterations) + " for " +
                                                  map.what("pgs_iterations"));
        }
    }
    if (map.has("integrator"))
    {
        const std::string name = map.string("integrator");
        const std::optional<core::IntegratorKind> kind = core::integratorFromName(name);
        if (!kind)
        {
            map.failAtValue("integrator", "unknown integrator '" + name + "' for " + map.what("integrator") +
                                              "; expected " + core::nameList(core::integratorNames(), "or"));
        }
        sim.integrator = *kind;
    }
}

// Friction, restitution and the solve's tolerances now; the ignore pairs once every body exists.
YamlNode readContact(const YamlSource& source, const YamlNode& node, core::ContactSettings& contact)
{
    const MapNode map(source, node, "'contact'");
    map.checkKeys(cContactKeys);
    contact.friction = readFriction(map).value_or(contact.friction);
    contact.restitution = readRestitution(map).value_or(contact.restitution);
    if (map.has("tolerance"))
    {
        contact.tolerance = map.number("tolerance");
        if (!core::isContactTolerance(contact.tolerance))
        {
            map.failAtValue("tolerance", std::string("expected ") + core::cContactToleranceRange + " for " +
                                             map.what("tolerance") + ", got " +
                                             describeNode(map.get("tolerance")));
        }
    }
    if (map.has("start_penetration"))
    {
        contact.startPenetration = map.number("start_penetration");
        if (!(contact.startPenetration >= 0.0 && contact.startPenetration <= 1e6))
        {
            map.failAtValue("start_penetration",
                            "expected a depth in [0, 1e6] m for " + map.what("start_penetration"));
        }
    }
    if (map.has("relative_tolerance"))
    {
        contact.relativeTolerance = map.number("relative_tolerance");
        if (!core::isRelativeContactTolerance(contact.relativeTolerance))
        {
            map.failAtValue("relative_tolerance", std::string("expected ") +
                                                      core::cRelativeContactToleranceRange + " for " +
                                                      map.what("relative_tolerance") + ", got " +
                                                      describeNode(map.get("relative_tolerance")));
        }
    }
    return map.get("ignore");
}

void readIgnorePairs(const SceneBuilder& builder, const YamlNode& node, core::ContactSettings& contact)
{
    const std::string what = "'ignore' in 'contact'";
    requireSequence(builder.source, node, what);
    for (std::size_t i = 0; i < node.size(); ++i)
    {
        const YamlNode pair = node[i];
        if (!pair.isSequence() || pair.size() != 2)
        {
            failAt(builder.source, pair,
                   "expected a pair of body names [a, b] for entry " + std::to_string(i + 1) + " of " + what +
                       ", got " + describeNode(pair));
        }
        const std::string entry = "entry " + std::to_string(i + 1) + " of " + what;
        const int a = resolveBodyName(builder, pair[0], entry, false);
        const int b = resolveBodyName(builder, pair[1], entry, false);
        if (a == b)
        {
            failAt(builder.source, pair,
                   "a body never collides with itself: " + entry + " names '" + pair[0].scalar() + "' twice");
        }
        contact.ignore.push_back({a, b});
    }
}

void readCamera(const YamlSource& source, const YamlNode& node, core::Camera& camera)
{
    const MapNode map(source, node, "'camera'");
    map.checkKeys(cCameraKeys);
    camera.automatic = false;
    camera.position = map.optPosition("position").value_or(camera.position);
    camera.lookAt = map.optPosition("look_at").value_or(camera.lookAt);
    if (map.has("fov"))
    {
        camera.fovDegrees = map.number("fov");
        if (!(camera.fovDegrees > 0.0 && camera.fovDegrees < 180.0))
        {
            map.failAtValue("fov", "expected a number of degrees in (0, 180) for " + map.what("fov"));
        }
    }
    if ((camera.position - camera.lookAt).norm() < 1e-9)
    {
        map.fail("the camera's 'position' and 'look_at' coincide");
    }
}

// Appends a model's bodies, joints, actuators and ignored contact pairs, shifting its indices.
void appendFragment(SceneBuilder& builder, const MapNode& entry, core::Model fragment,
                    const std::string& urdfPath)
{
    core::Model& model = builder.model;
    const int offset = static_cast<int>(model.bodies.size());
    const int jointOffset = static_cast<int>(model.joints.size());
    for (core::Actuator& actuator : fragment.actuators)
    {
        actuator.joint += jointOffset;
        model.actuators.push_back(std::move(actuator));
    }
    for (const std::array<int, 2>& pair : fragment.contact.ignore)
    {
        model.contact.ignore.push_back({pair[0] + offset, pair[1] + offset});
    }
    for (core::Body& body : fragment.bodies)
    {
        if (builder.findBody(body.name) >= 0)
        {
            entry.fail("the model from '" + urdfPath + "' adds body '" + body.name +
                       "', but a body of that name exists already; give this model another 'prefix'");
        }
        builder.addBody(std::move(body));
    }
    for (core::Joint& joint : fragment.joints)
    {
        if (builder.jointIndex.count(joint.name))
        {
            entry.fail("the model from '" + urdfPath + "' adds joint '" + joint.name +
                       "', but a joint of that name exists already; give this model another 'prefix'");
        }
        joint.parent = joint.parent == core::cWorld ? core::cWorld : joint.parent + offset;
        joint.child += offset;
        builder.addJoint(std::move(joint));
    }
}

// Where a model goes: at its `position`; else a free robot rests its lowest collision point on
// z = 0, or `drop_height` (m) above it, as a bare URDF does. Moves the fragment (its root frame in
// placement.position); returns what was done, for the load report.
std::string placeModel(const MapNode& map, core::Model& fragment, UrdfPlacement& placement)
{
    const std::optional<double> dropHeight = map.optNonNegative("drop_height", "m");
    const bool held = heldByWorld(fragment);
    if (dropHeight && (map.has("position") || held))
    {
        map.failAtKey("drop_height",
                      std::string("'drop_height' places a free robot that has no 'position'; ") +
                          (held ? "this one is held by the world" : "this one has a 'position'"));
    }
    const double lowest = lowestPoint(fragment);
    if (map.has("position") || held || !std::isfinite(lowest))
    {
        return std::string(held ? "fixed to the world" : "placed") + " by the scene, root link frame at (" +
               formatVector(placement.position) + ") m";
    }
    if (map.has("mjcf") && !dropHeight)
    {
        // An MJCF file places its bodies itself (a keyframe's qpos too): dropped only when asked.
        return "where the MJCF file puts it, its world frame at the origin";
    }
    const double height = dropHeight.value_or(0.0); // m
    const core::Vec3 shift(0.0, 0.0, height - lowest);
    translate(fragment, shift);
    placement.position += shift;
    return "free-floating, its lowest collision point " + formatNumber(height) +
           " m above z = 0 (no 'position'), root link frame at (" + formatVector(placement.position) + ") m";
}

// One entry of 'models': its map, its file and where the scene puts it.
struct ModelEntry
{
    MapNode& map;
    bool mjcf = false;
    YamlNode fileNode{}; // the 'urdf' or 'mjcf' value
    std::string path{};  // the file, resolved against the scene's folder
    UrdfPlacement placement{};
    YamlNode positions{}; // 'joint_positions', if given
};

// A model entry names one file, and only the keys for its kind; true for an MJCF file.
bool checkModelKind(const MapNode& map)
{
    const bool mjcf = map.has("mjcf");
    if (mjcf && map.has("urdf"))
    {
        map.failAtKey("mjcf", "a model entry names one file: 'urdf' or 'mjcf'");
    }
    for (const std::string& key : mjcf ? cUrdfOnlyModelKeys : std::vector<std::string>{"keyframe"})
    {
        if (map.has(key))
        {
            map.failAtKey(key, "'" + key + "' is for " + (mjcf ? "a 'urdf' model" : "an 'mjcf' model"));
        }
    }
    return mjcf;
}

UrdfPlacement readPlacement(const SceneBuilder& builder, const MapNode& map)
{
    UrdfPlacement placement;
    placement.position = map.optPosition("position").value_or(core::Vec3::Zero());
    placement.orientation = map.optQuaternion("orientation").value_or(core::Quat::Identity());
    placement.prefix = map.optString("prefix").value_or("");
    placement.selfCollision =
        builder.urdf.selfCollision.value_or(map.optBool("self_collision").value_or(true));
    placement.fixedRoot = map.optBool("fixed").value_or(false);
    placement.freeRoot = map.optBool("free_base").value_or(false);
    if (placement.fixedRoot && placement.freeRoot)
    {
        map.failAtKey("free_base", "'fixed' and 'free_base' of " + map.context() + " exclude each other");
    }
    if (map.has("prefix") && placement.prefix.find_first_of(",\"") != std::string::npos)
    {
        map.failAtValue("prefix", "a prefix cannot contain commas or double quotes");
    }
    return placement;
}

// 'joint_positions': a map of joint names to positions (rad or m), into the placement.
void readJointPositions(const YamlSource& source, ModelEntry& entry)
{
    const YamlNode& positions = entry.positions;
    if (!positions.isDefined() || positions.isNull())
    {
        return;
    }
    if (!positions.isMap())
    {
        failAt(source, positions,
               "expected a map of URDF joint names to positions (rad or m) for 'joint_positions' in " +
                   entry.map.context());
    }
    for (std::size_t k = 0; k < positions.size(); ++k)
    {
        const std::string name = toString(source, positions.key(k), "a joint name in 'joint_positions'");
        entry.placement.jointPositions[name] =
            toNumber(source, positions.value(k),
                     "the position (rad or m) of joint '" + name + "' in 'joint_positions'");
    }
}

// The entry's file as a fragment; its errors at the scene's line where the file is not to blame.
ModelFragment loadModelFile(SceneBuilder& builder, const ModelEntry& entry)
{
    const YamlSource& source = builder.source;
    const UrdfPlacement& placement = entry.placement;
    if (!builder.packages)
    {
        builder.packages.emplace(builder.urdf.packagePaths);
    }
    try
    {
        return entry.mjcf ? loadMjcfFragment(entry.path,
                                             {placement.position, placement.orientation, placement.prefix,
                                              placement.selfCollision, entry.map.optString("keyframe")})
                          : loadUrdfFragment(entry.path, placement, *builder.packages);
    }
    catch (const JointPositionError& e)
    {
        for (std::size_t k = 0; k < entry.positions.size(); ++k)
        {
            if (entry.positions.key(k).scalar() == e.joint())
            {
                failAt(source, entry.positions.value(k), e.what());
            }
        }
        failAt(source, entry.positions, e.what());
    }
    catch (const InputError& e)
    {
        // A file that cannot be read at all is named at the scene's line.
        if (e.file() == entry.path && e.line() == 0)
        {
            failAt(source, entry.fileNode,
                   (e.message().starts_with("cannot open file") ? "cannot open " : "cannot read ") +
                       (entry.mjcf ? std::string("MJCF") : std::string("URDF")) + " file '" + entry.path +
                       "': " + e.message());
        }
        throw;
    }
}

// A rigid motion of the whole model: v at the root link origin, w about it, added to the motion it
// starts with (an MJCF keyframe's qvel).
void addStartingMotion(const MapNode& map, core::Model& fragment, const core::Vec3& rootPosition)
{
    const core::Vec3 velocity = map.optVelocity("velocity").value_or(core::Vec3::Zero());
    const core::Vec3 angularVelocity =
        map.optAngularVelocity("angular_velocity").value_or(core::Vec3::Zero());
    for (core::Body& body : fragment.bodies)
    {
        if (!body.isStatic)
        {
            body.velocity_W += velocity + angularVelocity.cross(body.position_W - rootPosition);
            body.angularVelocity_W += angularVelocity;
        }
    }
}

// The placed fragment into the scene: its welded links, its robot, held joints, and the report.
void addModel(SceneBuilder& builder, const ModelEntry& entry, ModelFragment loaded,
              const std::string& placedAt)
{
    core::Model& fragment = loaded.model;
    const UrdfPlacement& placement = entry.placement;
    const int firstBody = static_cast<int>(builder.model.bodies.size());
    for (const auto& [linkName, bodyName] : loaded.report.welded)
    {
        builder.weldedLinks[placement.prefix + linkName] = firstBody + fragment.findBody(bodyName);
    }
    builder.model.robots.push_back({loaded.report.name, entry.path, firstBody,
                                    static_cast<int>(fragment.bodies.size()), placement.selfCollision});
    builder.robotMarks.push_back(entry.map.mark());
    if (builder.urdf.hold || entry.map.optBool("hold").value_or(false))
    {
        const int firstJoint = static_cast<int>(builder.model.joints.size());
        builder.heldJoints.push_back({firstJoint, firstJoint + static_cast<int>(fragment.joints.size())});
    }
    appendFragment(builder, entry.map, std::move(fragment), entry.path);
    if (builder.report)
    {
        loaded.report.placement = placedAt;
        builder.report->robots.push_back(std::move(loaded.report));
        builder.report->warnings.insert(builder.report->warnings.end(), loaded.warnings.begin(),
                                        loaded.warnings.end());
    }
}

void readModels(SceneBuilder& builder, const YamlNode& node)
{
    const YamlSource& source = builder.source;
    requireSequence(source, node, "'models'");
    for (std::size_t i = 0; i < node.size(); ++i)
    {
        MapNode map(source, node[i], "model #" + std::to_string(i + 1));
        map.checkKeys(cModelKeys);
        ModelEntry entry{map};
        entry.mjcf = checkModelKind(map);
        const std::string fileKey = entry.mjcf ? "mjcf" : "urdf";
        entry.fileNode = map.require(fileKey);
        const std::string file = toString(source, entry.fileNode, map.what(fileKey));
        map.setContext("model '" + file + "'");
        entry.placement = readPlacement(builder, map);
        entry.positions = map.get("joint_positions");
        readJointPositions(source, entry);
        entry.path = resolvePath(source.baseDir, file);
        ModelFragment loaded = loadModelFile(builder, entry);
        const std::string placedAt = placeModel(map, loaded.model, entry.placement);
        addStartingMotion(map, loaded.model, entry.placement.position);
        addModel(builder, entry, std::move(loaded), placedAt);
    }
}

// YAML forbids tabs in indentation, and yaml-cpp's message does not say so.
std::string tabHint(const std::string& text, const YAML::Mark& mark)
{
    if (mark.line < 0)
    {
        return {};
    }
    std::size_t pos = 0;
    for (int line = 0; line < mark.line && pos != std::string::npos; ++line)
    {
        pos = text.find('\n', pos);
        pos = pos == std::string::npos ? pos : pos + 1;
    }
    if (pos == std::string::npos)
    {
        return {};
    }
    const std::size_t end = text.find_first_not_of(" \t", pos);
    const std::string indent = text.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
    return indent.find('\t') != std::string::npos ? " (tabs are not allowed in YAML indentation; use spaces)"
                                                  : "";
}

// Every body's starting state within the ranges of core/model.h, its energy finite
// (core::startingStateDefect), at the line of the body, or of the model that brought it.
void checkStartingStates(const SceneBuilder& builder)
{
    const core::Model& model = builder.model;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        const std::string defect = core::startingStateDefect(model, i);
        if (defect.empty())
        {
            continue;
        }
        const std::string& name = model.bodies[i].name;
        YAML::Mark mark = YAML::Mark::null_mark();
        if (const auto it = builder.bodyMarks.find(name); it != builder.bodyMarks.end())
        {
            mark = it->second;
        }
        for (std::size_t r = 0; r < model.robots.size() && r < builder.robotMarks.size(); ++r)
        {
            const int first = model.robots[r].firstBody;
            const int body = static_cast<int>(i);
            mark = body >= first && body < first + model.robots[r].bodyCount ? builder.robotMarks[r] : mark;
        }
        failAt(builder.source, mark, "body '" + name + "': " + defect);
    }
}

// Line breaks as '\n' only: yaml-cpp counts lines at '\n', so a file with old Mac line endings
// (a lone '\r') would read as one line and every message would name line 1. (Called on text that
// has a '\r'.)
std::string withUnixLineBreaks(const std::string& text)
{
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i)
    {
        if (text[i] != '\r')
        {
            out += text[i];
        }
        else if (i + 1 >= text.size() || text[i + 1] != '\n')
        {
            out += '\n';
        }
    }
    return out;
}

std::string defaultName(const std::string& sourceName)
{
    const std::string stem = std::filesystem::path(sourceName).stem().string();
    return stem.empty() ? sourceName : stem;
}

// The scene's `bodies:` and `joints:` lists read item by item while the text is parsed, so that
// neither is ever held whole (a scene of 10^5 bodies is mostly these two lists). What is read keeps
// the order of the scene's rules (loadYamlScene): YAML bodies, then the `models:` (their bodies
// after the YAML ones, their joints before the YAML ones), then the YAML joints. So the joints are
// read during the parse only once the bodies are in and the models either read or absent so far;
// a `models:` that follows them takes them back out (their items are gone), and joints that could
// not be read in the first parse are read in a second parse of the text. An error is kept, not
// thrown, until loadYamlScene reaches the part it belongs to: the error the scene's rules meet
// first is the one reported, whatever the order of the keys in the file (and a YAML syntax error
// anywhere before any of them, as the whole text is parsed first).
class SceneLists final : public YamlListHandler
{
  public:
    enum class Part
    {
        Bodies,
        Models,
        Joints,
    };

    // jointsOnly: the second parse, for joints that the first could not read.
    SceneLists(SceneBuilder& builder, bool jointsOnly) : mBuilder(builder), mJointsOnly(jointsOnly) {}

    void onRootValueBegin(const std::string& key) override
    {
        mFirst = std::find(mSeen.begin(), mSeen.end(), key) == mSeen.end();
        if (!mFirst)
        {
            return;
        }
        mSeen.push_back(key);
        if (mJointsOnly)
        {
            return;
        }
        if (key == "models" && mJoints == Reading::Now)
        {
            // The joints read so far would come before the models' joints: take them out again.
            mJoints = Reading::Later;
            forgetJoints();
        }
        if (key == "joints")
        {
            mJoints = readJointsNow() ? Reading::Now : Reading::Later;
            mJointsBefore = mBuilder.model.joints.size();
        }
    }

    // The first `bodies` and `joints`, when lists (another value, or a second one of these keys,
    // an error of the scene, stays in the tree). The second parse takes the bodies only to drop them.
    bool takeItems(const std::string& key) override
    {
        if (!mFirst || (key != "bodies" && key != "joints"))
        {
            return false;
        }
        (key == "bodies" ? mBodiesTaken : mJointsTaken) = true;
        return true;
    }

    void onItem(const std::string& key, std::size_t index, const YamlNode& item) override
    {
        const bool bodies = key == "bodies";
        if (mError || (bodies && mJointsOnly) || (!bodies && !mJointsOnly && mJoints != Reading::Now))
        {
            return;
        }
        try
        {
            if (bodies)
            {
                readBody(mBuilder, item, index);
            }
            else
            {
                readJoint(mBuilder, item, index);
            }
        }
        catch (...)
        {
            keepError(bodies ? Part::Bodies : Part::Joints);
        }
    }

    void onRootValueEnd(const std::string& key, const YamlNode& value) override
    {
        if (key == "bodies" && mBodiesTaken && !mBodiesDone)
        {
            mBodiesDone = true;
        }
        if (key == "models" && !mModels.isDefined())
        {
            mModels = value; // read once the bodies are in (readJointsNow, or loadYamlScene)
        }
    }

    // Whether the first parse read the bodies (the first `bodies:`, a list), the models, the joints.
    bool bodiesRead() const { return mBodiesTaken; }
    bool modelsRead() const { return mModelsRead; }
    bool jointsRead() const { return mJoints == Reading::Now; }
    bool tookJoints() const { return mJointsTaken; }
    // The error kept for that part, thrown now.
    void throwErrorOf(Part part) const
    {
        if (mError && mErrorPart == part)
        {
            std::rethrow_exception(mError);
        }
    }

  private:
    enum class Reading
    {
        NotYet,
        Now,   // joints read as they are parsed
        Later, // by the second parse
    };

    bool readJointsNow()
    {
        if (mError || !mBodiesDone)
        {
            return false;
        }
        if (mModels.isDefined() && !mModelsRead)
        {
            mModelsRead = true;
            try
            {
                readModels(mBuilder, mModels);
            }
            catch (...)
            {
                keepError(Part::Models);
                return false;
            }
        }
        // No bodies yet: perhaps a later `models:` brings some; else an error before any joint.
        return !mBuilder.model.bodies.empty();
    }

    void forgetJoints()
    {
        for (std::size_t k = mJointsBefore; k < mBuilder.model.joints.size(); ++k)
        {
            const std::string& name = mBuilder.model.joints[k].name;
            mBuilder.jointIndex.erase(name);
            mBuilder.jointMarks.erase(name);
        }
        mBuilder.model.joints.resize(mJointsBefore);
        if (mError && mErrorPart == Part::Joints)
        {
            mError = nullptr;
        }
    }

    void keepError(Part part)
    {
        mError = std::current_exception();
        mErrorPart = part;
    }

    SceneBuilder& mBuilder;
    bool mJointsOnly;
    std::vector<std::string> mSeen; // root keys whose (first) value began
    bool mFirst = false;            // the value beginning is its key's first
    bool mBodiesTaken = false;
    bool mBodiesDone = false;
    bool mJointsTaken = false;
    YamlNode mModels; // the first `models:` value, in the tree
    bool mModelsRead = false;
    Reading mJoints = Reading::NotYet;
    std::size_t mJointsBefore = 0; // joints before the YAML ones (the models')
    std::exception_ptr mError;
    Part mErrorPart = Part::Bodies;
};

// The text holds one scene document with content.
void checkOneScene(const YamlSource& source, const std::string& text, const YamlDocuments& documents)
{
    if (documents.count > 1)
    {
        failAt(source, documents.second,
               "the file holds " + std::to_string(documents.count) + " YAML documents; expected one scene");
    }
    if (documents.first.root().isNull())
    {
        throw InputError(source.file, 1, 1,
                         std::string(text.find_first_not_of(" \t\n") == std::string::npos
                                         ? "the file is empty"
                                         : "the file holds no YAML content (only comments or an "
                                           "empty document)") +
                             "; expected a scene: a map with 'bodies' (and 'joints', ...)");
    }
}

// The scene's name, simulation, contact and camera maps; gives back the contact's 'ignore' list,
// read once the bodies and joints are in.
YamlNode readSettings(SceneBuilder& builder, const MapNode& root)
{
    const YamlSource& source = builder.source;
    core::Model& model = builder.model;
    if (root.has("name"))
    {
        model.name = root.string("name");
    }
    if (root.has("simulation"))
    {
        readSimulation(source, root.get("simulation"), model.simulation);
    }
    YamlNode ignore;
    if (root.has("contact"))
    {
        ignore = readContact(source, root.get("contact"), model.contact);
    }
    if (root.has("camera"))
    {
        readCamera(source, root.get("camera"), model.camera);
    }
    return ignore;
}

// Bodies, models and joints: those the parse handed to `lists` as it went, the others from the tree.
void readLists(SceneBuilder& builder, SceneLists& lists, const MapNode& root, const std::string& text)
{
    lists.throwErrorOf(SceneLists::Part::Bodies);
    if (root.has("bodies") && !lists.bodiesRead())
    {
        readBodies(builder, root.get("bodies"));
    }
    lists.throwErrorOf(SceneLists::Part::Models);
    if (root.has("models") && !lists.modelsRead())
    {
        readModels(builder, root.get("models"));
    }
    if (builder.model.bodies.empty())
    {
        root.fail("the scene has no bodies; expected 'bodies' or 'models'");
    }
    lists.throwErrorOf(SceneLists::Part::Joints);
    if (root.has("joints") && !lists.jointsRead())
    {
        if (lists.tookJoints())
        {
            // Its items were not kept: read them in a second parse, bodies and models now in.
            SceneLists second(builder, true);
            YamlDocuments again;
            parseYaml(text, builder.source.file, again, &second);
            second.throwErrorOf(SceneLists::Part::Joints);
        }
        else
        {
            readJoints(builder, root.get("joints")); // not a list: the error
        }
    }
}

// What needs the bodies and joints in: ignored pairs, actuators, held joints, the starting states'
// check, loads, the reference and the stability criteria.
void readAfterLists(SceneBuilder& builder, const MapNode& root, const YamlNode& ignore)
{
    core::Model& model = builder.model;
    if (ignore.isDefined() && !ignore.isNull())
    {
        readIgnorePairs(builder, ignore, model.contact);
    }
    if (root.has("actuators"))
    {
        readActuators(builder, root.get("actuators"));
    }
    for (const auto& [first, end] : builder.heldJoints)
    {
        addHoldServos(model, first, end); // where the scene's actuators leave a joint free
    }
    checkStartingStates(builder);
    if (root.has("loads"))
    {
        readLoads(builder, root.get("loads"));
    }
    if (root.has("reference"))
    {
        SceneReference reference = readReference(builder, root.get("reference"));
        if (builder.report != nullptr)
        {
            builder.report->reference = std::move(reference);
        }
    }
    if (root.has("stability"))
    {
        SceneStabilityCriteria criteria = readStabilityCriteria(builder, root.get("stability"));
        if (builder.report != nullptr)
        {
            builder.report->stability = std::move(criteria);
        }
    }
}

void readScene(SceneBuilder& builder, const std::string& text)
{
    SceneLists lists(builder, false);
    YamlDocuments documents;
    parseYaml(text, builder.source.file, documents, &lists);
    checkOneScene(builder.source, text, documents);
    const MapNode root(builder.source, documents.first.root(), "the scene");
    root.checkKeys(cSceneKeys);
    const YamlNode ignore = readSettings(builder, root);
    readLists(builder, lists, root, text);
    readAfterLists(builder, root, ignore);
}

} // namespace

core::Model loadYamlScene(const std::string& rawText, const std::string& sourceName, const UrdfOptions& urdf,
                          LoadReport* report)
{
    std::string converted;
    const std::string& text =
        rawText.find('\r') == std::string::npos ? rawText : (converted = withUnixLineBreaks(rawText));
    SceneBuilder builder;
    builder.urdf = urdf;
    builder.report = report;
    builder.source = YamlSource{sourceName, directoryOf(sourceName)};
    const YamlSource& source = builder.source;
    core::Model& model = builder.model;
    model.sourceFile = sourceName;
    model.name = defaultName(sourceName);
    try
    {
        readScene(builder, text);
    }
    catch (const YAML::ParserException& e)

    {
        failAt(source, e.mark, "invalid YAML: " + e.msg + tabHint(text, e.mark));
    }
    catch (const YAML::Exception& e)
    {
        // Not expected (every access is checked), but keep the location if there is one.
        failAt(source, e.mark, "cannot read the scene: " + e.msg);
    }
    if (urdf.selfCollision && model.robots.empty() && report != nullptr)
    {
        report->warnings.push_back(diagnostic(
            sourceName, {}, "warning",
            "--self-collision applies to URDF robots (a bare .urdf or the scene's 'models'); this scene "
            "has none, so it changes nothing (its bodies' collisions are set by 'group', 'contact: "
            "ignore' and the joints' 'collide')"));
    }
    // The lists grew one item at a time: give back their spare capacity (up to half of them).
    model.bodies.shrink_to_fit();
    model.joints.shrink_to_fit();
    return std::move(builder.model);
}

} // namespace frontier::io::detail

namespace frontier::io
{
bool isSettingsMapKey(std::string_view key)
{
    return key == "simulation" || key == "contact"; // not `camera`: given, it turns off the automatic one
}
} // namespace frontier::io
