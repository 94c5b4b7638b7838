// io/yaml_util.h: typed, located reading of YAML nodes (io/yaml_tree.h), for io/'s readers and the
// batch plan reader (app/batch/plan.cpp); not part of the installed API.
//
// Every error is an InputError with the file and the 1-based line:column of the offending node
// (yaml-cpp's marks are 0-based). Missing keys have no node, so they are reported at the parent
// map. Maps are checked for duplicate and unknown keys (with a "did you mean" suggestion).
#pragma once

#include "core/model.h"
#include "io/yaml_tree.h"

#include <initializer_list>
#include <optional>
#include <string>
#include <vector>
#include <yaml-cpp/mark.h>

namespace frontier::io::detail
{

// Where the nodes come from: the file name used in messages, and the directory for relative paths.
struct YamlSource
{
    std::string file;
    std::string baseDir;
};

[[noreturn]] void failAt(const YamlSource& source, const YAML::Mark& mark, const std::string& message);
[[noreturn]] void failAt(const YamlSource& source, const YamlNode& node, const std::string& message);

// How a node looks in a message: "'heavy'", "a list", "a map", "null".
std::string describeNode(const YamlNode& node);

// Conversions of one node; `what` names it in messages ("'mass' in body 'pelvis'").
double toNumber(const YamlSource& source, const YamlNode& node, const std::string& what);
double toPositive(const YamlSource& source, const YamlNode& node, const std::string& what);
int toInteger(const YamlSource& source, const YamlNode& node, const std::string& what);
bool toBool(const YamlSource& source, const YamlNode& node, const std::string& what);
std::string toString(const YamlSource& source, const YamlNode& node, const std::string& what);
// A list of exactly `count` finite numbers.
std::vector<double> toNumbers(const YamlSource& source, const YamlNode& node, const std::string& what,
                              std::size_t count);
core::Vec3 toVec3(const YamlSource& source, const YamlNode& node, const std::string& what);
// Non-zero 3-vector, normalised.
core::Vec3 toDirection(const YamlSource& source, const YamlNode& node, const std::string& what);
// Quaternion [w, x, y, z], non-zero, normalised.
core::Quat toQuaternion(const YamlSource& source, const YamlNode& node, const std::string& what);
// The ranges of core/model.h. A 3-vector of norm at most `bound`, `range` saying what was expected
// (core::cPositionRange, ...); a position (m) within core::cMaxDistance of the origin; a length (m),
// core::isLength.
core::Vec3 toBoundedVec3(const YamlSource& source, const YamlNode& node, const std::string& what,
                         double bound, const char* range);
core::Vec3 toPosition(const YamlSource& source, const YamlNode& node, const std::string& what);
double toLength(const YamlSource& source, const YamlNode& node, const std::string& what);
const YamlNode& requireSequence(const YamlSource& source, const YamlNode& node, const std::string& what);

// A YAML map with a context for messages ("body 'pelvis'").
class MapNode
{
  public:
    // Throws unless `node` is a map.
    MapNode(const YamlSource& source, const YamlNode& node, std::string context);

    const YamlSource& source() const { return *mSource; }
    const YamlNode& node() const { return mNode; }
    const YAML::Mark& mark() const { return mMark; }
    const std::string& context() const { return mContext; }
    void setContext(std::string context) { mContext = std::move(context); }

    // Duplicate keys and keys not in `known` are errors (at the key), with a suggestion.
    void checkKeys(const std::vector<std::string>& known) const;

    bool has(const std::string& key) const;
    // The value of `key` (the first one when duplicated), or no node (YamlNode()) when absent.
    YamlNode get(const std::string& key) const;
    // The value; "missing key 'key' in <context>" at the map's mark when absent.
    YamlNode require(const std::string& key) const;
    // Mark of the key itself (the map's mark when absent).
    YAML::Mark keyMark(const std::string& key) const;
    // "'key' in <context>"
    std::string what(const std::string& key) const;
    [[noreturn]] void fail(const std::string& message) const;
    [[noreturn]] void failAtKey(const std::string& key, const std::string& message) const;
    [[noreturn]] void failAtValue(const std::string& key, const std::string& message) const;

    // Typed values of present keys (required) or std::nullopt when absent (optional).
    double number(const std::string& key) const { return toNumber(*mSource, require(key), what(key)); }
    std::optional<double> optNumber(const std::string& key) const;
    std::optional<double> optPositive(const std::string& key) const;
    // A finite number >= 0; `unit` ends the message ("(N m s/rad)"), may be empty.
    std::optional<double> optNonNegative(const std::string& key, const std::string& unit = "") const;
    std::optional<int> optInteger(const std::string& key) const;
    std::optional<bool> optBool(const std::string& key) const;
    std::string string(const std::string& key) const { return toString(*mSource, require(key), what(key)); }
    std::optional<std::string> optString(const std::string& key) const;
    std::optional<core::Vec3> optVec3(const std::string& key) const;
    std::optional<core::Vec3> optDirection(const std::string& key) const;
    // Within the ranges of core/model.h: a position (m), a velocity (m/s), an angular velocity (rad/s).
    std::optional<core::Vec3> optPosition(const std::string& key) const;
    std::optional<core::Vec3> optVelocity(const std::string& key) const;
    std::optional<core::Vec3> optAngularVelocity(const std::string& key) const;
    std::optional<core::Quat> optQuaternion(const std::string& key) const;

  private:
    struct Entry
    {
        std::string key;
        YAML::Mark keyMark;
        YamlNode value;
    };
    const Entry* find(const std::string& key) const;

    const YamlSource* mSource;
    YamlNode mNode;
    YAML::Mark mMark;
    std::string mContext;
    std::vector<Entry> mEntries;
};

// A map's `friction` (a Coulomb coefficient, core::isFriction) and `restitution` (core::isRestitution),
// when given: the scene's contact settings and a body's material.
std::optional<double> readFriction(const MapNode& map);
std::optional<double> readRestitution(const MapNode& map);

} // namespace frontier::io::detail
