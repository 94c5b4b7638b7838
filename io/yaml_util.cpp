// io/yaml_util.cpp: typed, located reading of YAML nodes.
#include "io/yaml_util.h"

#include "io/file_util.h"
#include "io/scene.h"
#include "io/suggest.h"

#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <yaml-cpp/yaml.h>

namespace frontier::io::detail
{

void failAt(const YamlSource& source, const YAML::Mark& mark, const std::string& message)
{
    if (mark.is_null() || mark.line < 0)
    {
        throw InputError(source.file, 0, 0, message);
    }
    throw InputError(source.file, mark.line + 1, mark.column + 1, message);
}

void failAt(const YamlSource& source, const YamlNode& node, const std::string& message)
{
    failAt(source, node.isDefined() ? node.mark() : YAML::Mark::null_mark(), message);
}

std::string describeNode(const YamlNode& node)
{
    if (!node.isDefined() || node.isNull())
    {
        return "null";
    }
    if (node.isSequence())
    {
        return node.size() == 1 ? "a list of 1 item" : "a list of " + std::to_string(node.size()) + " items";
    }
    if (node.isMap())
    {
        return "a map";
    }
    return "'" + node.scalar() + "'";
}

namespace
{
// A number may carry no tag, or the standard !!int / !!float: a local tag ("!units 3") means
// something this reader does not know, so it is refused rather than silently dropped.
void checkNumberTag(const YamlSource& source, const YamlNode& node, const std::string& what)
{
    const std::string& tag = node.tag();
    if (tag.empty() || tag == "?" || tag == "!" || tag == "tag:yaml.org,2002:int" ||
        tag == "tag:yaml.org,2002:float")
    {
        return;
    }
    failAt(source, node,
           "expected a number for " + what + ", got one tagged '" + tag +
               "' (only the standard tags !!int and !!float are understood)");
}
} // namespace

double toNumber(const YamlSource& source, const YamlNode& node, const std::string& what)
{
    if (!node.isScalar())
    {
        failAt(source, node, "expected a number for " + what + ", got " + describeNode(node));
    }
    checkNumberTag(source, node, what);
    // The rule of every text input file (io/file_util.h), so that a scene and a trajectory agree on
    // what a number is.
    const std::optional<double> value = parseFiniteNumber(node.scalar());
    if (!value)
    {
        bool nonFinite = false; // YAML's .inf and .nan: say why they are refused
        try
        {
            nonFinite = !std::isfinite(YAML::Node(node.scalar()).as<double>()); // yaml-cpp's reading
        }
        catch (const YAML::Exception&)
        {
        }
        failAt(source, node,
               std::string(nonFinite ? "expected a finite number for " : "expected a number for ") + what +
                   ", got " + describeNode(node));
    }
    return *value;
}

double toPositive(const YamlSource& source, const YamlNode& node, const std::string& what)
{
    const double value = toNumber(source, node, what);
    if (!(value > 0.0))
    {
        failAt(source, node, "expected a positive number for " + what + ", got " + describeNode(node));
    }
    return value;
}

int toInteger(const YamlSource& source, const YamlNode& node, const std::string& what)
{
    if (!node.isScalar())
    {
        failAt(source, node, "expected an integer for " + what + ", got " + describeNode(node));
    }
    checkNumberTag(source, node, what);
    const std::optional<long long> value =
        parseWholeNumber(node.scalar(), std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
    if (!value)
    {
        failAt(source, node, "expected an integer for " + what + ", got " + describeNode(node));
    }
    return static_cast<int>(*value);
}

bool toBool(const YamlSource& source, const YamlNode& node, const std::string& what)
{
    if (!node.isScalar())
    {
        failAt(source, node, "expected true or false for " + what + ", got " + describeNode(node));
    }
    try
    {
        return YAML::Node(node.scalar()).as<bool>(); // yaml-cpp's words: true/false, yes/no, on/off, ...
    }
    catch (const YAML::Exception&)
    {
        failAt(source, node, "expected true or false for " + what + ", got " + describeNode(node));
    }
}

std::string toString(const YamlSource& source, const YamlNode& node, const std::string& what)
{
    if (!node.isScalar())
    {
        failAt(source, node, "expected a string for " + what + ", got " + describeNode(node));
    }
    return node.scalar();
}

std::vector<double> toNumbers(const YamlSource& source, const YamlNode& node, const std::string& what,
                              std::size_t count)
{
    if (!node.isSequence() || node.size() != count)
    {
        failAt(source, node,
               "expected a list of " + std::to_string(count) + " numbers for " + what + ", got " +
                   describeNode(node));
    }
    std::vector<double> out;
    out.reserve(count);
    for (std::size_t i = 0; i < count; ++i)
    {
        out.push_back(toNumber(source, node[i], "element " + std::to_string(i + 1) + " of " + what));
    }
    return out;
}

core::Vec3 toVec3(const YamlSource& source, const YamlNode& node, const std::string& what)
{
    const std::vector<double> v = toNumbers(source, node, what, 3);
    return {v[0], v[1], v[2]};
}

core::Vec3 toDirection(const YamlSource& source, const YamlNode& node, const std::string& what)
{
    const core::Vec3 v = toVec3(source, node, what);
    const double length = v.norm();
    if (!(length > 1e-12) || !std::isfinite(length))
    {
        failAt(source, node, "expected a non-zero direction for " + what + ", got [0, 0, 0]");
    }
    return v / length;
}

core::Quat toQuaternion(const YamlSource& source, const YamlNode& node, const std::string& what)
{
    const std::vector<double> v = toNumbers(source, node, what + " (quaternion w, x, y, z)", 4);
    core::Quat q(v[0], v[1], v[2], v[3]);
    const double length = q.norm();
    if (!(length > 1e-12) || !std::isfinite(length))
    {
        failAt(source, node, "expected a non-zero quaternion [w, x, y, z] for " + what);
    }
    q.coeffs() /= length;
    return q;
}

core::Vec3 toBoundedVec3(const YamlSource& source, const YamlNode& node, const std::string& what,
                         double bound, const char* range)
{
    const core::Vec3 v = toVec3(source, node, what);
    if (!(v.norm() <= bound))
    {
        std::ostringstream message;
        message << "expected " << range << " for " << what << ", got [" << v.x() << ", " << v.y() << ", "
                << v.z() << "] (norm " << v.stableNorm() << ")";
        failAt(source, node, message.str());
    }
    return v;
}

core::Vec3 toPosition(const YamlSource& source, const YamlNode& node, const std::string& what)
{
    return toBoundedVec3(source, node, what, core::cMaxDistance, core::cPositionRange);
}

double toLength(const YamlSource& source, const YamlNode& node, const std::string& what)
{
    const double value = toNumber(source, node, what);
    if (!core::isLength(value))
    {
        failAt(source, node,
               std::string("expected ") + core::cLengthRange + " for " + what + ", got " +
                   describeNode(node));
    }
    return value;
}

const YamlNode& requireSequence(const YamlSource& source, const YamlNode& node, const std::string& what)
{
    if (!node.isSequence())
    {
        failAt(source, node, "expected a list for " + what + ", got " + describeNode(node));
    }
    return node;
}

MapNode::MapNode(const YamlSource& source, const YamlNode& node, std::string context)
    : mSource(&source), mNode(node), mMark(node.isDefined() ? node.mark() : YAML::Mark::null_mark()),
      mContext(std::move(context))
{
    if (!node.isMap())
    {
        failAt(source, node, "expected a map for " + mContext + ", got " + describeNode(node));
    }
    mEntries.reserve(node.size());
    for (std::size_t i = 0; i < node.size(); ++i)
    {
        const YamlNode key = node.key(i);
        if (!key.isScalar())
        {
            failAt(source, key, "expected a key name in " + mContext + ", got " + describeNode(key));
        }
        mEntries.push_back(Entry{key.scalar(), key.mark(), node.value(i)});
    }
}

void MapNode::checkKeys(const std::vector<std::string>& known) const
{
    for (std::size_t i = 0; i < mEntries.size(); ++i)
    {
        const Entry& entry = mEntries[i];
        for (std::size_t j = 0; j < i; ++j)
        {
            if (mEntries[j].key == entry.key)
            {
                failAt(*mSource, entry.keyMark,
                       "duplicate key '" + entry.key + "' in " + mContext + " (first given at line " +
                           std::to_string(mEntries[j].keyMark.line + 1) + ")");
            }
        }
        bool isKnown = false;
        for (const std::string& k : known)
        {
            isKnown = isKnown || k == entry.key;
        }
        if (!isKnown)
        {
            failAt(*mSource, entry.keyMark,
                   "unknown key " + quotedName(entry.key) + " in " + mContext +
                       suggestionSuffix(entry.key, known, true));
        }
    }
}

const MapNode::Entry* MapNode::find(const std::string& key) const
{
    for (const Entry& entry : mEntries)
    {
        if (entry.key == key)
        {
            return &entry;
        }
    }
    return nullptr;
}

bool MapNode::has(const std::string& key) const
{
    return find(key) != nullptr;
}

YamlNode MapNode::get(const std::string& key) const
{
    const Entry* entry = find(key);
    return entry != nullptr ? entry->value : YamlNode();
}

YamlNode MapNode::require(const std::string& key) const
{
    const Entry* entry = find(key);
    if (entry == nullptr)
    {
        fail("missing key '" + key + "' in " + mContext);
    }
    return entry->value;
}

YAML::Mark MapNode::keyMark(const std::string& key) const
{
    const Entry* entry = find(key);
    return entry != nullptr ? entry->keyMark : mMark;
}

std::string MapNode::what(const std::string& key) const
{
    return "'" + key + "' in " + mContext;
}

void MapNode::fail(const std::string& message) const
{
    failAt(*mSource, mMark, message);
}

void MapNode::failAtKey(const std::string& key, const std::string& message) const
{
    failAt(*mSource, keyMark(key), message);
}

void MapNode::failAtValue(const std::string& key, const std::string& message) const
{
    const Entry* entry = find(key);
    if (entry == nullptr)
    {
        fail(message);
    }
    failAt(*mSource, entry->value, message);
}

std::optional<double> MapNode::optNumber(const std::string& key) const
{
    const Entry* entry = find(key);
    return entry ? std::optional(toNumber(*mSource, entry->value, what(key))) : std::nullopt;
}

std::optional<double> MapNode::optPositive(const std::string& key) const
{
    const Entry* entry = find(key);
    return entry ? std::optional(toPositive(*mSource, entry->value, what(key))) : std::nullopt;
}

std::optional<double> MapNode::optNonNegative(const std::string& key, const std::string& unit) const
{
    const std::optional<double> value = optNumber(key);
    if (value && !(*value >= 0.0))
    {
        failAtValue(key, "expected a number >= 0 for " + what(key) + (unit.empty() ? "" : " " + unit) +
                             ", got " + describeNode(get(key)));
    }
    return value;
}

std::optional<int> MapNode::optInteger(const std::string& key) const
{
    const Entry* entry = find(key);
    return entry ? std::optional(toInteger(*mSource, entry->value, what(key))) : std::nullopt;
}

std::optional<bool> MapNode::optBool(const std::string& key) const
{
    const Entry* entry = find(key);
    return entry ? std::optional(toBool(*mSource, entry->value, what(key))) : std::nullopt;
}

std::optional<std::string> MapNode::optString(const std::string& key) const
{
    const Entry* entry = find(key);
    return entry ? std::optional(toString(*mSource, entry->value, what(key))) : std::nullopt;
}

std::optional<core::Vec3> MapNode::optVec3(const std::string& key) const
{
    const Entry* entry = find(key);
    return entry ? std::optional(toVec3(*mSource, entry->value, what(key))) : std::nullopt;
}

std::optional<core::Vec3> MapNode::optDirection(const std::string& key) const
{
    const Entry* entry = find(key);
    return entry ? std::optional(toDirection(*mSource, entry->value, what(key))) : std::nullopt;
}

std::optional<core::Vec3> MapNode::optPosition(const std::string& key) const
{
    const Entry* entry = find(key);
    return entry ? std::optional(toPosition(*mSource, entry->value, what(key))) : std::nullopt;
}

std::optional<core::Vec3> MapNode::optVelocity(const std::string& key) const
{
    const Entry* entry = find(key);
    return entry ? std::optional(
                       toBoundedVec3(*mSource, entry->value, what(key), core::cMaxSpeed, core::cSpeedRange))
                 : std::nullopt;
}

std::optional<core::Vec3> MapNode::optAngularVelocity(const std::string& key) const
{
    const Entry* entry = find(key);
    return entry ? std::optional(toBoundedVec3(*mSource, entry->value, what(key), core::cMaxAngularSpeed,
                                               core::cAngularSpeedRange))
                 : std::nullopt;
}

std::optional<core::Quat> MapNode::optQuaternion(const std::string& key) const
{
    const Entry* entry = find(key);
    return entry ? std::optional(toQuaternion(*mSource, entry->value, what(key))) : std::nullopt;
}

std::optional<double> readFriction(const MapNode& map)
{
    if (!map.has("friction"))
    {
        return std::nullopt;
    }
    const double mu = map.number("friction");
    if (!core::isFriction(mu))
    {
        map.failAtValue("friction", "expected a number in [0, 1e6] for " + map.what("friction"));
    }
    return mu;
}

std::optional<double> readRestitution(const MapNode& map)
{
    if (!map.has("restitution"))
    {
        return std::nullopt;
    }
    const double e = map.number("restitution");
    if (!core::isRestitution(e))
    {
        map.failAtValue("restitution", "expected a number in [0, 1] for " + map.what("restitution"));
    }
    return e;
}

} // namespace frontier::io::detail
