// run/names.cpp: look-ups by name with the nearest name in the error.
#include "run/names.h"

#include "io/suggest.h"

#include <string>
#include <vector>

namespace frontier::run
{

namespace
{

template <typename Item>
int indexByName(const std::vector<Item>& items, std::string_view name, const char* what)
{
    std::vector<std::string> names;
    names.reserve(items.size());
    for (std::size_t i = 0; i < items.size(); ++i)
    {
        if (items[i].name == name)
        {
            return static_cast<int>(i);
        }
        names.push_back(items[i].name);
    }
    throw NameError("no " + std::string(what) + " " + io::detail::quotedName(name) + " in the model" +
                    io::detail::suggestionSuffix(name, names, names.size() <= 12));
}

core::JointCoordinate coordinateOf(const core::Joint& joint, std::optional<core::JointCoordinate> coordinate)
{
    const auto coordinates = core::jointCoordinates(joint.type);
    if (coordinates.empty())
    {
        throw NameError("joint '" + joint.name + "' (" + core::jointTypeName(joint.type) +
                        ") has no coordinate to drive or read");
    }
    if (!coordinate)
    {
        if (coordinates.size() > 1)
        {
            throw NameError("joint '" + joint.name + "' has two coordinates; say which (rotation or slide)");
        }
        return coordinates[0];
    }
    for (core::JointCoordinate c : coordinates)
    {
        if (c == *coordinate)
        {
            return c;
        }
    }
    throw NameError("joint '" + joint.name + "' (" + core::jointTypeName(joint.type) + ") has no " +
                    (*coordinate == core::JointCoordinate::Slide ? "slide" : "rotation") + " coordinate");
}

} // namespace

int bodyIndex(const core::Model& model, std::string_view name)
{
    return indexByName(model.bodies, name, "body");
}

int jointIndex(const core::Model& model, std::string_view name)
{
    return indexByName(model.joints, name, "joint");
}

int actuatorIndex(const core::Model& model, std::string_view jointName,
                  std::optional<core::JointCoordinate> coordinate)
{
    const int joint = jointIndex(model, jointName);
    const core::JointCoordinate c = coordinateOf(model.joints[static_cast<std::size_t>(joint)], coordinate);
    for (std::size_t a = 0; a < model.actuators.size(); ++a)
    {
        if (model.actuators[a].joint == joint && model.actuators[a].coordinate == c)
        {
            return static_cast<int>(a);
        }
    }
    throw NameError("joint '" + std::string(jointName) + "' has no actuator" +
                    (coordinate ? " on that coordinate" : ""));
}

double jointPosition(const core::Model& model, const core::State& state, std::string_view jointName,
                     std::optional<core::JointCoordinate> coordinate)
{
    const int joint = jointIndex(model, jointName);
    return core::fileCoordinate(model, state, joint,
                                coordinateOf(model.joints[static_cast<std::size_t>(joint)], coordinate));
}

} // namespace frontier::run
