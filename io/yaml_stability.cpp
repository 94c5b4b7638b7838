// io/yaml_stability.cpp: a YAML scene's `stability:` map (io::SceneStabilityCriteria): the pass
// criteria the stability suite checks in this scene beyond its own.
#include "io/scene.h"
#include "io/yaml_scene.h"

namespace frontier::io::detail
{

namespace
{

const std::vector<std::string> cStabilityKeys = {"max_speed", "max_energy_rise", "joints"};
const std::vector<std::string> cJointCheckKeys = {"joint", "max_tracking_error", "range", "reach"};

StabilityJointCheck readJointCheck(const SceneBuilder& builder, const YamlNode& node, std::size_t index)
{
    MapNode map(builder.source, node, "stability joint check #" + std::to_string(index + 1));
    map.checkKeys(cJointCheckKeys);
    const YamlNode jointNode = map.require("joint");
    StabilityJointCheck check;
    check.joint = resolveJointName(builder, jointNode, map.what("joint"));
    const core::Joint& joint = builder.model.joints[static_cast<std::size_t>(check.joint)];
    map.setContext("the stability check of joint '" + joint.name + "'");
    if (joint.type != core::JointType::Revolute)
    {
        failAt(builder.source, jointNode,
               "joint '" + joint.name + "' is a " + core::jointTypeName(joint.type) +
                   " joint; a stability check watches the angle of a revolute joint");
    }
    check.maxTrackingError = map.optPositive("max_tracking_error");
    if (check.maxTrackingError)
    {
        bool servo = false;
        for (const core::Actuator& actuator : builder.model.actuators)
        {
            servo = servo || (actuator.joint == check.joint && actuator.kind == core::ActuatorKind::Position);
        }
        if (!servo)
        {
            map.failAtKey("max_tracking_error", "joint '" + joint.name +
                                                    "' has no position actuator; 'max_tracking_error' is "
                                                    "measured from a position servo's target");
        }
    }
    if (map.has("range"))
    {
        const YamlNode rangeNode = map.get("range");
        const std::vector<double> range =
            toNumbers(builder.source, rangeNode, map.what("range") + " [lower, upper]", 2);
        if (range[0] > range[1])
        {
            failAt(builder.source, rangeNode,
                   "expected lower <= upper for " + map.what("range") + ", got [" + rangeNode[0].scalar() +
                       ", " + rangeNode[1].scalar() + "]");
        }
        check.range = std::array<double, 2>{range[0], range[1]};
    }
    check.reach = map.optPositive("reach");
    if (!check.maxTrackingError && !check.range && !check.reach)
    {
        map.fail(map.context() + " checks nothing; expected 'max_tracking_error', 'range' or 'reach'");
    }
    return check;
}

} // namespace

SceneStabilityCriteria readStabilityCriteria(const SceneBuilder& builder, const YamlNode& node)
{
    const MapNode map(builder.source, node, "'stability'");
    map.checkKeys(cStabilityKeys);
    SceneStabilityCriteria criteria;
    criteria.maxSpeed = map.optPositive("max_speed");
    criteria.maxEnergyRise = map.optNonNegative("max_energy_rise", "(J)");
    if (map.has("joints"))
    {
        const YamlNode joints = map.get("joints");
        requireSequence(builder.source, joints, map.what("joints"));
        for (std::size_t i = 0; i < joints.size(); ++i)
        {
            criteria.joints.push_back(readJointCheck(builder, joints[i], i));
        }
    }
    return criteria;
}

} // namespace frontier::io::detail
