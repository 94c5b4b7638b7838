// io/yaml_loads.cpp: the `loads:` list of a YAML scene (core::Load): a force and/or torque on a
// body over a time window, or an impulse at one instant.
#include "io/scene.h"
#include "io/yaml_scene.h"

#include <sstream>

namespace frontier::io::detail
{

namespace
{

const std::vector<std::string> cLoadKeys = {"body",  "force", "torque", "impulse", "at",
                                            "frame", "from",  "to",     "time"};

// `frame:` world (the default) or body: the frame the force and torque are given in.
void readLoadFrame(const MapNode& map, core::Load& load)
{
    if (map.has("frame"))
    {
        const std::string frame = map.string("frame");
        if (frame != "world" && frame != "body")
        {
            map.failAtValue("frame",
                            "expected 'world' or 'body' for " + map.what("frame") + ", got '" + frame + "'");
        }
        load.frame = frame == "body" ? core::LoadFrame::Body : core::LoadFrame::World;
    }
}

// `impulse:` (N s) at `time:` (s); no force, torque or window.
void readImpulse(const MapNode& map, core::Load& load)
{
    for (const char* key : {"force", "torque", "from", "to"})
    {
        if (map.has(key))
        {
            map.failAtKey(key, "an 'impulse' acts at one instant ('time'); '" + std::string(key) +
                                   "' is for a force over a window [from, to)");
        }
    }
    load.force = *map.optVec3("impulse");
    map.require("time");
    load.instant = map.optNonNegative("time", "(s; the run starts at t = 0)");
}

// `force:` (N) and/or `torque:` (N m) over the window [`from:`, `to:`) (s).
void readForceWindow(const MapNode& map, core::Load& load)
{
    if (map.has("time"))
    {
        map.failAtKey("time", "'time' is the instant of an 'impulse'; a force acts over [from, to)");
    }
    if (!map.has("force") && !map.has("torque"))
    {
        map.fail(map.context() +
                 " needs a 'force' and/or a 'torque' (N, N m), or an 'impulse' (N s) at a 'time'");
    }
    load.force = map.optVec3("force").value_or(core::Vec3::Zero());
    load.torque = map.optVec3("torque").value_or(core::Vec3::Zero());
    load.from = map.optNonNegative("from", "(s; the run starts at t = 0)").value_or(0.0);
    load.to = map.optNumber("to").value_or(load.to);
    if (!(load.to > load.from))
    {
        std::ostringstream message;
        message << "expected 'to' > 'from' for " << map.context() << ", got from = " << load.from
                << " s, to = " << load.to << " s";
        map.failAtValue("to", message.str());
    }
}

void readLoad(SceneBuilder& builder, const YamlNode& node, std::size_t index)
{
    const YamlSource& source = builder.source;
    MapNode map(source, node, "load #" + std::to_string(index + 1));
    map.checkKeys(cLoadKeys);
    const YamlNode bodyNode = map.require("body");
    core::Load load;
    load.body = resolveBodyName(builder, bodyNode, map.what("body"), false);
    const core::Body& body = builder.model.bodies[static_cast<std::size_t>(load.body)];
    map.setContext("the load on body '" + body.name + "'");
    if (body.isStatic)
    {
        failAt(source, bodyNode, "body '" + body.name + "' is static; a load acts on a moving body");
    }
    readLoadFrame(map, load);
    load.point = map.optPosition("at");
    if (map.has("impulse"))
    {
        readImpulse(map, load);
    }
    else
    {
        readForceWindow(map, load);
    }
    builder.model.loads.push_back(load);
}

} // namespace

void readLoads(SceneBuilder& builder, const YamlNode& loads)
{
    requireSequence(builder.source, loads, "'loads'");
    for (std::size_t i = 0; i < loads.size(); ++i)
    {
        readLoad(builder, loads[i], i);
    }
}

} // namespace frontier::io::detail
