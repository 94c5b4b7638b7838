// io/yaml_bodies.cpp: the `bodies:` list of a YAML scene: shapes, mass properties, initial state.
//
// Mass properties of a moving body (scenes/README.md, "Mass properties"):
//   mass + inertia   as given; the body frame is the frame given by position/orientation;
//   mass only        inertia of the shapes scaled to that mass;
//   density only     mass and inertia of the shapes at that density (kg/m^3);
//   neither          density 1000 kg/m^3 (water) when the body has a solid shape, else an error.
// When the mass comes from the shapes, the body's position is shifted to their centre of mass and
// the shapes are moved by the opposite amount, so they stay where the scene put them (this matters
// for meshes and for shapes placed off the body origin).
#include "core/interrupt.h"
#include "io/file_util.h"
#include "io/mass_properties.h"
#include "io/mesh_file.h"
#include "io/scene.h"
#include "io/suggest.h"
#include "io/yaml_scene.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace frontier::io::detail
{

namespace
{

constexpr double cDefaultDensity = 1000.0; // kg/m^3

const std::vector<std::string> cBodyKeys = {
    "name",       "static",      "shape",    "shapes",           "mass",  "density", "inertia",
    "position",   "orientation", "velocity", "angular_velocity", "color", "group",   "friction",
    "restitution"};

// Each shape type's YAML name and the keys its map may hold: one row per core::ShapeType.
struct ShapeSyntax
{
    core::ShapeType type;
    std::string name;
    std::vector<std::string> keys;
};
const std::vector<ShapeSyntax> cShapeSyntax = {
    {core::ShapeType::Box, "box", {"type", "size", "position", "orientation"}},
    {core::ShapeType::Sphere, "sphere", {"type", "radius", "position", "orientation"}},
    {core::ShapeType::Capsule, "capsule", {"type", "radius", "length", "position", "orientation"}},
    {core::ShapeType::Cylinder, "cylinder", {"type", "radius", "length", "position", "orientation"}},
    {core::ShapeType::Plane, "plane", {"type", "normal", "offset"}},
    {core::ShapeType::Mesh, "mesh", {"type", "file", "scale", "position", "orientation"}},
};
const std::vector<std::string> cShapeTypes = []
{
    std::vector<std::string> names;
    for (const ShapeSyntax& syntax : cShapeSyntax)
        names.push_back(syntax.name);
    return names;
}();
const std::vector<std::string> cAllShapeKeys = {"type",   "size", "radius", "length",   "normal",
                                                "offset", "file", "scale",  "position", "orientation"};

struct ShapeEntry
{
    core::Shape shape;
    YamlNode typeNode; // for messages about the shape as a whole
    YamlNode fileNode; // meshes
};

core::Shape readMesh(const MapNode& map)
{
    const YamlNode fileNode = map.require("file");
    const std::string file = toString(map.source(), fileNode, map.what("file"));
    core::Vec3 scale = core::Vec3::Ones();
    if (map.has("scale"))
    {
        const YamlNode scaleNode = map.get("scale");
        if (scaleNode.isSequence())
        {
            scale = toVec3(map.source(), scaleNode, map.what("scale"));
            if (!(scale.minCoeff() > 0.0))
            {
                failAt(map.source(), scaleNode, "expected positive numbers for " + map.what("scale"));
            }
        }
        else
        {
            scale.setConstant(toPositive(map.source(), scaleNode, map.what("scale")));
        }
    }
    const std::string path = resolvePath(map.source().baseDir, file);
    core::Shape mesh;
    try
    {
        mesh = loadMeshFile(path, scale);
    }
    catch (const InputError& e)
    {
        if (e.line() > 0)
        {
            throw; // inside the mesh file: keep its location
        }
        failAt(map.source(), fileNode, "cannot read mesh file '" + path + "': " + e.message());
    }
    if (!(core::shapeReach(mesh) <= core::cMaxDistance))
    {
        std::ostringstream message;
        message << "mesh '" << file << "' of " << map.context() << " reaches " << core::shapeReach(mesh)
                << " m from its origin" << (map.has("scale") ? " at this scale" : "") << "; expected "
                << core::cLengthRange;
        failAt(map.source(), map.has("scale") ? map.get("scale") : fileNode, message.str());
    }
    return mesh;
}

// The index in cShapeTypes of the `type:` named; failing with a suggestion for an unknown one.
std::size_t readShapeType(const MapNode& map, const YamlNode& typeNode, const std::string& context)
{
    const YamlSource& source = map.source();
    const std::string typeName = toString(source, typeNode, map.what("type"));
    const std::size_t typeIndex = static_cast<std::size_t>(
        std::find(cShapeTypes.begin(), cShapeTypes.end(), typeName) - cShapeTypes.begin());
    if (typeIndex == cShapeTypes.size())
    {
        const std::string match = closestMatch(typeName, cShapeTypes);
        failAt(source, typeNode,
               "unknown shape type '" + typeName + "' in " + context +
                   (match.empty() ? "" : "; did you mean '" + match + "'?") +
                   " (known: " + joinNames(cShapeTypes) + ")");
    }
    return typeIndex;
}

// The keys giving the size of a shape of entry.shape.type (m), or its mesh file.
void readShapeSize(const MapNode& map, ShapeEntry& entry)
{
    const YamlSource& source = map.source();
    core::Shape& shape = entry.shape;
    switch (shape.type)
    {
    case core::ShapeType::Box:
    {
        const YamlNode size = map.require("size");
        shape.size = toVec3(source, size, map.what("size"));
        for (std::size_t i = 0; i < 3; ++i)
        {
            toLength(source, size[i], "the full extents of " + map.what("size"));
        }
        break;
    }
    case core::ShapeType::Sphere:
        shape.radius = toLength(source, map.require("radius"), map.what("radius"));
        break;
    case core::ShapeType::Capsule:
    case core::ShapeType::Cylinder:
        shape.radius = toLength(source, map.require("radius"), map.what("radius"));
        shape.length = toLength(source, map.require("length"), map.what("length"));
        break;
    case core::ShapeType::Plane:
        shape.normal = toDirection(source, map.require("normal"), map.what("normal"));
        shape.offset = map.optNumber("offset").value_or(0.0);
        if (!(std::abs(shape.offset) <= core::cMaxDistance))
        {
            map.failAtValue("offset", std::string("expected an offset (m) of ") + core::cPositionRange +
                                          " for " + map.what("offset") + ", got " +
                                          describeNode(map.get("offset")));
        }
        break;
    case core::ShapeType::Mesh:
        entry.fileNode = map.get("file");
        shape = readMesh(map);
        break;
    }
}

ShapeEntry readShape(const YamlSource& source, const YamlNode& node, const std::string& context)
{
    MapNode map(source, node, context);
    if (!map.has("type"))
    {
        map.checkKeys(cAllShapeKeys);
    }
    ShapeEntry entry;
    entry.typeNode = map.require("type");
    const std::size_t typeIndex = readShapeType(map, entry.typeNode, context);
    core::Shape& shape = entry.shape;
    shape.type = cShapeSyntax[typeIndex].type;
    map.setContext(cShapeTypes[typeIndex] + " " + context);
    map.checkKeys(cShapeSyntax[typeIndex].keys);
    readShapeSize(map, entry);
    shape.position_BS = map.optPosition("position").value_or(core::Vec3::Zero());
    shape.rotation_BS = map.optQuaternion("orientation").value_or(core::Quat::Identity());
    return entry;
}

std::vector<ShapeEntry> readShapes(const MapNode& body)
{
    std::vector<ShapeEntry> out;
    const std::string bodyContext = body.context();
    if (body.has("shape") && body.has("shapes"))
    {
        body.failAtKey("shapes", "give either 'shape' or 'shapes' in " + bodyContext + ", not both");
    }
    if (body.has("shape"))
    {
        out.push_back(readShape(body.source(), body.get("shape"), "shape of " + bodyContext));
    }
    if (body.has("shapes"))
    {
        const YamlNode list = requireSequence(body.source(), body.get("shapes"), body.what("shapes"));
        for (std::size_t i = 0; i < list.size(); ++i)
        {
            out.push_back(
                readShape(body.source(), list[i], "shape #" + std::to_string(i + 1) + " of " + bodyContext));
        }
    }
    return out;
}

// [ixx, iyy, izz], [ixx, iyy, izz, ixy, ixz, iyz] or a 3x3 matrix (kg m^2); positive-definite.
core::Mat3 readInertia(const MapNode& body)
{
    const YamlNode node = body.get("inertia");
    const std::string what = body.what("inertia");
    core::Mat3 inertia = core::Mat3::Zero();
    if (node.isSequence() && node.size() == 3 && node[0].isSequence())
    {
        for (std::size_t r = 0; r < 3; ++r)
        {
            const std::vector<double> row =
                toNumbers(body.source(), node[r], "row " + std::to_string(r + 1) + " of " + what, 3);
            for (std::size_t c = 0; c < 3; ++c)
            {
                inertia(static_cast<int>(r), static_cast<int>(c)) = row[c];
            }
        }
        if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > 1e-12 * inertia.norm())
        {
            failAt(body.source(), node, "expected a symmetric matrix for " + what);
        }
    }
    else if (node.isSequence() && node.size() == 6)
    {
        const std::vector<double> v = toNumbers(body.source(), node, what, 6);
        inertia << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
    }
    else if (node.isSequence() && node.size() == 3)
    {
        const std::vector<double> v = toNumbers(body.source(), node, what, 3);
        inertia.diagonal() = core::Vec3(v[0], v[1], v[2]);
    }
    else
    {
        failAt(body.source(), node,
               "expected [ixx, iyy, izz], [ixx, iyy, izz, ixy, ixz, iyz] or a 3x3 matrix for " + what +
                   ", got " + describeNode(node));
    }
    const std::string defect = inertiaDefect(inertia, 0.0); // the size check is for URDF repairs only
    if (!defect.empty())
    {
        failAt(body.source(), node,
               "expected a positive-definite inertia for " + what + " (kg m^2); this one " + defect);
    }
    return inertia;
}

void readMassProperties(const MapNode& map, std::vector<ShapeEntry>& shapes, core::Body& body,
                        core::Vec3& centre_D)
{
    const std::string& context = map.context();
    const std::optional<double> mass = map.optPositive("mass");
    const std::optional<double> density = map.optPositive("density");
    if (mass && density)
    {
        map.failAtKey("density", "give either 'mass' or 'density' in " + context + ", not both");
    }
    if (map.has("inertia") && !mass)
    {
        map.failAtKey("inertia",
                      "'inertia' in " + context +
                          " needs 'mass' (with 'density' or neither, the inertia comes from the shapes)");
    }
    centre_D.setZero();
    if (mass && map.has("inertia"))
    {
        body.mass = *mass;
        body.inertia_B = readInertia(map);
        return;
    }
    std::vector<core::Shape> solids;
    for (const ShapeEntry& entry : shapes)
    {
        if (entry.shape.type == core::ShapeType::Mesh && !(core::shapeVolume(entry.shape) > 0.0))
        {
            failAt(
                map.source(), entry.fileNode,
                "mesh '" + entry.shape.meshFile + "' of " + context +
                    " encloses no positive volume (is it closed, with triangles counter-clockwise seen from "
                    "outside?); give 'mass' and 'inertia' instead");
        }
        solids.push_back(entry.shape);
    }
    if (solids.empty())
    {
        if (mass)
        {
            map.failAtKey("mass", context +
                                      " has 'mass' but no solid shape to compute its inertia from; give "
                                      "'inertia' too");
        }
        map.fail("missing key 'mass' in " + context +
                 " (a moving body without a solid shape needs 'mass' and 'inertia')");
    }
    const CompositeMass composite = compositeMassProperties(solids, density.value_or(cDefaultDensity));
    body.mass = mass.value_or(composite.mass);
    body.inertia_B = composite.inertia * (body.mass / composite.mass);
    centre_D = composite.centre;
    if (!isPositiveDefinite(body.inertia_B))
    {
        map.fail("the shapes of " + context +
                 " give an inertia that is not positive-definite; give 'inertia'");
    }
}

core::Vec3 readColor(const MapNode& map)
{
    const YamlNode node = map.get("color");
    const std::vector<double> v = toNumbers(map.source(), node, map.what("color") + " (r, g, b)", 3);
    for (std::size_t i = 0; i < 3; ++i)
    {
        if (v[i] < 0.0 || v[i] > 1.0)
        {
            failAt(map.source(), node[i],
                   "expected a number in [0, 1] for " + map.what("color") + ", got " + describeNode(node[i]));
        }
    }
    return {v[0], v[1], v[2]};
}

// A static body has none of the keys of motion and mass.
void checkStaticKeys(const MapNode& map)
{
    for (const char* key : {"mass", "density", "inertia", "velocity", "angular_velocity"})
    {
        if (map.has(key))
        {
            map.failAtKey(key, "static " + map.context() + " cannot have '" + key +
                                   "' (static bodies do not move)");
        }
    }
}

// Colour, collision group, friction and restitution.
void readAppearanceAndContact(const MapNode& map, core::Body& body)
{
    if (map.has("color"))
    {
        body.color = readColor(map);
    }
    if (map.has("group"))
    {
        body.group = map.string("group");
        if (body.group.empty())
        {
            map.failAtValue("group", "expected a non-empty name for " + map.what("group"));
        }
    }
    body.friction = readFriction(map);
    body.restitution = readRestitution(map);
}

// The shapes into the body, posed about its centre of mass (centre_D, in the frame given by
// position/orientation); a plane keeps the world frame.
void addShapes(std::vector<ShapeEntry>& shapes, const core::Quat& orientation, const core::Vec3& centre_D,
               core::Body& body)
{
    for (ShapeEntry& entry : shapes)
    {
        core::Shape& shape = entry.shape;
        if (shape.type == core::ShapeType::Plane)
        {
            // normal and offset are world quantities: give the plane the world frame as its frame.
            shape.rotation_BS = orientation.conjugate();
            shape.position_BS = -(orientation.conjugate() * body.position_W);
        }
        else
        {
            shape.position_BS -= centre_D;
        }
        body.shapes.push_back(std::move(shape));
    }
}

} // namespace

void readBody(SceneBuilder& builder, const YamlNode& node, std::size_t index)
{
    core::throwIfInterrupted(); // a checkpoint between bodies (core/interrupt.h)
    const YamlSource& source = builder.source;
    MapNode map(source, node, "body #" + std::to_string(index + 1));
    if (map.get("name").isScalar())
    {
        map.setContext("body '" + map.get("name").scalar() + "'");
    }
    map.checkKeys(cBodyKeys);
    const std::string& context = map.context();
    core::Body body;
    const YamlNode nameNode = map.require("name");
    body.name = toString(source, nameNode, map.what("name"));
    checkNewName(builder, nameNode, "body");
    body.isStatic = map.optBool("static").value_or(false);
    if (body.isStatic)
    {
        checkStaticKeys(map);
    }
    const core::Vec3 position = map.optPosition("position").value_or(core::Vec3::Zero());
    const core::Quat orientation = map.optQuaternion("orientation").value_or(core::Quat::Identity());
    body.velocity_W = map.optVelocity("velocity").value_or(core::Vec3::Zero());
    body.angularVelocity_W = map.optAngularVelocity("angular_velocity").value_or(core::Vec3::Zero());
    readAppearanceAndContact(map, body);
    std::vector<ShapeEntry> shapes = readShapes(map);
    core::Vec3 centre_D = core::Vec3::Zero(); // centre of mass in the frame given by position/orientation
    if (!body.isStatic)
    {
        for (const ShapeEntry& entry : shapes)
        {
            if (entry.shape.type == core::ShapeType::Plane)
            {
                failAt(source, entry.typeNode,
                       "a plane shape needs a static body, but " + context +
                           " is moving (add 'static: true', or use a box)");
            }
        }
        readMassProperties(map, shapes, body, centre_D);
    }
    body.position_W = position + orientation * centre_D;
    body.orientation_WB = orientation;
    addShapes(shapes, orientation, centre_D, body);
    builder.bodyMarks[body.name] = nameNode.mark();
    builder.addBody(std::move(body));
}

void readBodies(SceneBuilder& builder, const YamlNode& bodies)
{
    requireSequence(builder.source, bodies, "'bodies'");
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
        readBody(builder, bodies[i], i);
    }
}

void checkNewName(const SceneBuilder& builder, const YamlNode& nameNode, const std::string& kind)
{
    const std::string name = nameNode.scalar();
    const std::string reason = invalidNameReason(name);
    if (!reason.empty())
    {
        failAt(builder.source, nameNode, "invalid " + kind + " name '" + name + "': " + reason);
    }
    const auto& marks = kind == "body" ? builder.bodyMarks : builder.jointMarks;
    const bool taken = kind == "body" ? builder.findBody(name) >= 0 : builder.jointIndex.count(name) > 0;
    if (taken)
    {
        const auto it = marks.find(name);
        failAt(builder.source, nameNode,
               "duplicate " + kind + " name '" + name + "'" +
                   (it != marks.end() ? " (first defined at line " + std::to_string(it->second.line + 1) + ")"
                                      : " (already defined by a URDF model)"));
    }
}

int resolveBodyName(const SceneBuilder& builder, const YamlNode& node, const std::string& what,
                    bool allowWorld)
{
    const std::string name = toString(builder.source, node, what);
    if (name == "world")
    {
        if (!allowWorld)
        {
            failAt(builder.source, node, "the world cannot be " + what);
        }
        return core::cWorld;
    }
    int index = builder.findBody(name);
    if (const auto welded = builder.weldedLinks.find(name); index < 0 && welded != builder.weldedLinks.end())
    {
        index = welded->second;
    }
    if (index < 0)
    {
        std::vector<std::string> names;
        for (const core::Body& body : builder.model.bodies)
        {
            names.push_back(body.name);
        }
        if (allowWorld)
        {
            names.emplace_back("world");
        }
        failAt(builder.source, node,
               "unknown body " + quotedName(name) + " for " + what + suggestionSuffix(name, names, false));
    }
    return index;
}

} // namespace frontier::io::detail
