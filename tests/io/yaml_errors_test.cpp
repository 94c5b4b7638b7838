// tests/io/yaml_errors_test.cpp: every kind of bad scene input gives an InputError at the right
// line:column, saying what was expected.
#include "io/scene.h"
#include "io_test_util.h"

#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <utility>

namespace frontier::io::test
{
namespace
{

// Three bodies for the joint cases; joints start at line 12, block style, so that a value's
// column is the length of its key + 7.
const char* const cJointBase = R"(
bodies:
  - name: upper
    shape: {type: sphere, radius: 0.1}
    position: [0, 0, 1]
  - name: lower
    shape: {type: sphere, radius: 0.1}
    position: [0, 0, 0.5]
  - name: floor
    static: true
    shape: {type: plane, normal: [0, 0, 1]}
joints:
)";

std::string withJoints(const char* joints)
{
    return text(cJointBase) + text(joints);
}

TEST(YamlErrors, NumberThatIsNotANumber)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 0.1}
    mass: heavy
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 11, "expected a number for 'mass' in body 'a', got 'heavy'");
    EXPECT_EQ(std::string(e.what()).rfind("scene.yaml:4:11: error: ", 0), 0u) << e.what();
}

// The contact solve's tolerances: a velocity in [0, 1] m/s and a finite fraction in [0, 1).
TEST(YamlErrors, ContactTolerancesOutOfRange)
{
    const std::pair<const char*, const char*> cases[] = {
        {"contact: {tolerance: -1.0e-5}",
         "expected a velocity in [0, 1] m/s for 'tolerance' in 'contact', got '-1.0e-5'"},
        {"contact: {tolerance: 5}",
         "expected a velocity in [0, 1] m/s for 'tolerance' in 'contact', got '5'"},
        {"contact: {relative_tolerance: 1}",
         "expected a fraction in [0, 1) for 'relative_tolerance' in 'contact', got '1'"},
        {"contact: {relative_tolerance: .nan}",
         "expected a finite number for 'relative_tolerance' in 'contact', got '.nan'"},
    };
    for (const auto& [line, message] : cases)
    {
        const InputError e = yamlError(std::string(line) + "\n");
        EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 1, static_cast<int>(std::string(line).find(':', 10)) + 3,
                              message);
    }
}

TEST(YamlErrors, UnknownKeySuggestsClosest)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: pelvis
    shape: {type: sphere, radius: 0.1}
    mas: 8.0
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 5, "unknown key 'mas' in body 'pelvis'; did you mean 'mass'?");
}

TEST(YamlErrors, UnknownTopLevelKeySuggestsClosest)
{
    const InputError e = yamlError(text(R"(
name: x
bodys:
  - name: a
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 2, 1, "unknown key 'bodys' in the scene; did you mean 'bodies'?");
}

TEST(YamlErrors, UnknownKeyFarFromAnyListsKnownKeys)
{
    const InputError e = yamlError(text(R"(
simulation:
  zzzzzzzz: 1
bodies: []
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 2, 3,
                          "(known: dt, duration, gravity, solver, pgs_iterations, integrator)");
}

TEST(YamlErrors, MissingKeyIsReportedAtTheParentMap)
{
    const InputError e = yamlError(text(R"(
bodies:
  - shape: {type: sphere, radius: 0.1}
    mass: 1
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 2, 5, "missing key 'name' in body #1");
}

TEST(YamlErrors, DuplicateKeyInAMap)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    mass: 1
    shape: {type: sphere, radius: 0.1}
    mass: 2
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 5, 5, "duplicate key 'mass' in body 'a' (first given at line 3)");
}

TEST(YamlErrors, DuplicateBodyName)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 0.1}
  - name: a
    shape: {type: sphere, radius: 0.1}
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 11, "duplicate body name 'a' (first defined at line 2)");
}

TEST(YamlErrors, ReservedAndInvalidBodyNames)
{
    EXPECT_INPUT_ERROR_AT(yamlError(text(R"(
bodies:
  - name: world
    shape: {type: sphere, radius: 0.1}
)")),
                          "scene.yaml", 2, 11, "'world' is reserved");
    EXPECT_INPUT_ERROR_AT(yamlError(text(R"(
bodies:
  - name: "a,b"
    shape: {type: sphere, radius: 0.1}
)")),
                          "scene.yaml", 2, 11, "cannot contain commas");
}

TEST(YamlErrors, DuplicateJointName)
{
    const InputError e = yamlError(withJoints(R"(
  - {name: j, type: ball, parent: world, child: upper, anchor: [0, 0, 1.5]}
  - {name: j, type: ball, parent: upper, child: lower, anchor: [0, 0, 0.75]}
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 13, 12, "duplicate joint name 'j' (first defined at line 12)");
}

TEST(YamlErrors, JointReferencesMissingBody)
{
    const InputError e = yamlError(withJoints(R"(
  - name: j
    type: ball
    parent: world
    child: lowr
    anchor: [0, 0, 1]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 15, 12,
                          "unknown body 'lowr' for the child of joint 'j'; did you mean 'lower'?");
}

// A name of 4 MB is reported at once (no edit distance over megabytes) and quoted cut short.
TEST(YamlErrors, HugeUnknownBodyNameIsQuotedShort)
{
    const std::string joints = R"(
  - name: j
    type: ball
    parent: world
    child: )" + std::string(4 << 20, 'q') +
                               R"(
    anchor: [0, 0, 1]
)";
    const InputError e = yamlError(withJoints(joints.c_str()));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 15, 12, "unknown body 'qqqq");
    EXPECT_NE(e.message().find("...' (4194304 bytes) for the child of joint 'j'"), std::string::npos)
        << e.message().substr(0, 200);
    EXPECT_LT(e.message().size(), 200u);
}

TEST(YamlErrors, UnknownJointTypeListsKnownTypes)
{
    const InputError e = yamlError(withJoints(R"(
  - name: j
    type: hinge
    parent: world
    child: lower
    anchor: [0, 0, 1]
)"));
    EXPECT_INPUT_ERROR_AT(
        e, "scene.yaml", 13, 11,
        "unknown joint type 'hinge' in joint 'j' (known: ball, nail, revolute, angle, cylindrical, "
        "prismatic, fixed, planar)");
}

TEST(YamlErrors, MisspelledJointTypeSuggests)
{
    const InputError e = yamlError(withJoints(R"(
  - name: j
    type: revolut
    parent: world
    child: lower
    anchor: [0, 0, 1]
    axis: [0, 1, 0]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 13, 11, "did you mean 'revolute'?");
}

TEST(YamlErrors, JointChildIsStatic)
{
    const InputError e = yamlError(withJoints(R"(
  - name: j
    type: ball
    parent: upper
    child: floor
    anchor: [0, 0, 1]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 15, 12, "the child of joint 'j', body 'floor', is static");
}

TEST(YamlErrors, JointChildIsWorld)
{
    const InputError e = yamlError(withJoints(R"(
  - name: j
    type: ball
    parent: upper
    child: world
    anchor: [0, 0, 1]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 15, 12, "the world cannot be the child of joint 'j'");
}

TEST(YamlErrors, JointParentEqualsChild)
{
    const InputError e = yamlError(withJoints(R"(
  - name: j
    type: ball
    parent: upper
    child: upper
    anchor: [0, 0, 1]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 15, 12, "joins body 'upper' to itself");
}

// Limits, damping and friction act on a joint's one coordinate: a ball joint has none.
TEST(YamlErrors, LimitsDampingOrFrictionOnAJointTypeWithoutACoordinate)
{
    for (const std::string line : {"limits: [-1, 1]", "damping: 0.1", "friction: 0.1"})
    {
        const std::string key = line.substr(0, line.find(':'));
        const std::string joint = "  - name: j\n    type: ball\n    parent: world\n    child: upper\n"
                                  "    anchor: [0, 0, 1.5]\n    " +
                                  line + "\n";
        const InputError e = yamlError(text(cJointBase) + joint);
        EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 17, 5,
                              "joint 'j' of type ball takes no '" + key +
                                  "' (only revolute and prismatic joints do)");
    }
}

// A hinge or a rail with one bad `damping:` or `friction:` line (line 18, the value at the key's
// length + 7): the message names the key, the joint, the unit and what was found.
TEST(YamlErrors, NegativeOrNonNumericDampingAndFriction)
{
    struct Case
    {
        const char* type;
        const char* line;
        int column;
        const char* message;
    };
    const Case cases[] = {
        {"revolute", "damping: -0.5", 14,
         "expected a number >= 0 for 'damping' in joint 'j' (N m s/rad), got '-0.5'"},
        {"revolute", "friction: -1", 15,
         "expected a number >= 0 for 'friction' in joint 'j' (N m), got '-1'"},
        {"prismatic", "damping: -3", 14,
         "expected a number >= 0 for 'damping' in joint 'j' (N s/m), got '-3'"},
        {"prismatic", "friction: -2", 15, "expected a number >= 0 for 'friction' in joint 'j' (N), got '-2'"},
        {"prismatic", "damping: lots", 14, "expected a number for 'damping' in joint 'j', got 'lots'"},
    };
    for (const Case& c : cases)
    {
        const std::string joint = std::string("  - name: j\n    type: ") + c.type +
                                  "\n    parent: world\n    child: upper\n    anchor: [0, 0, 1.5]\n"
                                  "    axis: [0, 1, 0]\n    " +
                                  c.line + "\n";
        const InputError e = yamlError(text(cJointBase) + joint);
        EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 18, c.column, c.message);
    }
}

TEST(YamlErrors, LimitsLowerAboveUpper)
{
    const InputError e = yamlError(withJoints(R"(
  - name: j
    type: revolute
    parent: world
    child: upper
    anchor: [0, 0, 1.5]
    axis: [0, 1, 0]
    limits: [1, -1]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 18, 13,
                          "expected lower <= upper for 'limits' in joint 'j', got [1, -1]");
}

TEST(YamlErrors, AxisMissingForRevolute)
{
    const InputError e = yamlError(withJoints(R"(
  - name: j
    type: revolute
    parent: world
    child: upper
    anchor: [0, 0, 1.5]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 12, 5, "missing key 'axis' in joint 'j'");
}

TEST(YamlErrors, AxisZero)
{
    const InputError e = yamlError(withJoints(R"(
  - name: j
    type: prismatic
    parent: world
    child: upper
    anchor: [0, 0, 1.5]
    axis: [0, 0, 0]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 17, 11, "expected a non-zero direction for 'axis' in joint 'j'");
}

TEST(YamlErrors, AxisOnABallJoint)
{
    const InputError e = yamlError(withJoints(R"(
  - name: j
    type: ball
    parent: world
    child: upper
    anchor: [0, 0, 1.5]
    axis: [0, 0, 1]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 17, 5, "joint 'j' of type ball takes no 'axis'");
}

TEST(YamlErrors, NailParentMustBeWorldLike)
{
    const InputError e = yamlError(withJoints(R"(
  - name: j
    type: nail
    parent: upper
    child: lower
    anchor: [0, 0, 0.75]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 14, 13,
                          "the parent of nail joint 'j' must be 'world' or a static body");
}

TEST(YamlErrors, AnchorMissing)
{
    const InputError e = yamlError(withJoints(R"(
  - name: j
    type: ball
    parent: world
    child: upper
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 12, 5, "missing key 'anchor' in joint 'j'");
}

TEST(YamlErrors, MisspelledJointKey)
{
    const InputError e = yamlError(withJoints(R"(
  - name: j
    type: ball
    parent: world
    child: upper
    achor: [0, 0, 1.5]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 16, 5, "unknown key 'achor' in joint 'j'; did you mean 'anchor'?");
}

TEST(YamlErrors, NonPositiveMass)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 0.1}
    mass: 0
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 11,
                          "expected a positive number for 'mass' in body 'a', got '0'");
}

TEST(YamlErrors, NonPositiveDensity)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 0.1}
    density: -5
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 14,
                          "expected a positive number for 'density' in body 'a', got '-5'");
}

TEST(YamlErrors, NonPositiveRadius)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape:
      type: sphere
      radius: 0
)"));
    EXPECT_INPUT_ERROR_AT(
        e, "scene.yaml", 5, 15,
        "expected a length in (0, 1e6] m for 'radius' in sphere shape of body 'a', got '0'");
}

TEST(YamlErrors, NonPositiveBoxSize)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape:
      type: box
      size: [1, 0, 1]
)"));
    EXPECT_INPUT_ERROR_AT(
        e, "scene.yaml", 5, 17,
        "expected a length in (0, 1e6] m for the full extents of 'size' in box shape of body "
        "'a', got '0'");
}

TEST(YamlErrors, BoxSizeWithTwoNumbers)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape:
      type: box
      size: [1, 1]
)"));
    EXPECT_INPUT_ERROR_AT(
        e, "scene.yaml", 5, 13,
        "expected a list of 3 numbers for 'size' in box shape of body 'a', got a list of 2 items");
}

TEST(YamlErrors, UnknownShapeTypeSuggests)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape:
      type: bx
      size: [1, 1, 1]
)"));
    EXPECT_INPUT_ERROR_AT(
        e, "scene.yaml", 4, 13,
        "unknown shape type 'bx' in shape of body 'a'; did you mean 'box'? (known: box, sphere, "
        "capsule, cylinder, plane, mesh)");
}

TEST(YamlErrors, KeyOfAnotherShapeType)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape:
      type: box
      radius: 1
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 5, 7, "unknown key 'radius' in box shape of body 'a'");
}

TEST(YamlErrors, InertiaNotPositiveDefinite)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    mass: 1
    inertia: [1, 1, -1]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 14,
                          "expected a positive-definite inertia for 'inertia' in body 'a'");
}

TEST(YamlErrors, InertiaMatrixNotSymmetric)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    mass: 1
    inertia: [[1, 0.1, 0], [0, 1, 0], [0, 0, 1]]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 14, "expected a symmetric matrix");
}

TEST(YamlErrors, NanInAVector)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 0.1}
    position: [0, .nan, 0]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 19,
                          "expected a finite number for element 2 of 'position' in body 'a', got '.nan'");
}

TEST(YamlErrors, InfiniteMass)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 0.1}
    mass: .inf
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 11,
                          "expected a finite number for 'mass' in body 'a', got '.inf'");
}

TEST(YamlErrors, NanGravity)
{
    const InputError e = yamlError(text(R"(
simulation:
  gravity: [0, 0, .NaN]
bodies:
  - name: a
    shape: {type: sphere, radius: 0.1}
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 2, 19, "expected a finite number for element 3 of 'gravity'");
}

TEST(YamlErrors, StaticBodyWithVelocity)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: floor
    static: true
    shape: {type: plane, normal: [0, 0, 1]}
    velocity: [1, 0, 0]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 5, 5, "static body 'floor' cannot have 'velocity'");
}

TEST(YamlErrors, StaticBodyWithMass)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: floor
    static: true
    mass: 3
    shape: {type: plane, normal: [0, 0, 1]}
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 5, "static body 'floor' cannot have 'mass'");
}

TEST(YamlErrors, PlaneOnAMovingBody)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape:
      type: plane
      normal: [0, 0, 1]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 13,
                          "a plane shape needs a static body, but body 'a' is moving");
}

TEST(YamlErrors, BrokenSyntax)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 0.1
    mass: 1
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 9, "invalid YAML: end of map flow not found");
}

TEST(YamlErrors, TabIndentation)
{
    const InputError e = yamlError("bodies:\n\t- name: a\n");
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 2, 2, "tabs are not allowed in YAML indentation");
}

TEST(YamlErrors, BrokenSyntaxBadIndentation)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
     mass: 1
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 3, 10, "invalid YAML: illegal map value");
}

TEST(YamlErrors, FileDoesNotExist)
{
    const InputError e = captureInputError([] { loadScene("/nonexistent/dir/scene.yaml"); });
    EXPECT_INPUT_ERROR_AT(e, "/nonexistent/dir/scene.yaml", 0, 0, "cannot open file");
}

TEST(YamlErrors, UnknownFileExtension)
{
    const InputError e = captureInputError([] { loadScene("scene.txt"); });
    EXPECT_INPUT_ERROR_AT(e, "scene.txt", 0, 0,
                          "expected a .yaml or .yml scene, a .urdf model, an MJCF .xml model or an SDF");
}

TEST(YamlErrors, ZeroQuaternion)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 0.1}
    orientation: [0, 0, 0, 0]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 18,
                          "expected a non-zero quaternion [w, x, y, z] for 'orientation'");
}

TEST(YamlErrors, UnknownSolverAndBadIterations)
{
    EXPECT_INPUT_ERROR_AT(
        yamlError(text(R"(
simulation:
  solver: fast
bodies: []
)")),
        "scene.yaml", 2, 11,
        "unknown solver 'fast' for 'solver' in 'simulation'; expected linear, dense or pgs");
    EXPECT_INPUT_ERROR_AT(yamlError(text(R"(
simulation:
  pgs_iterations: 2.5
bodies: []
)")),
                          "scene.yaml", 2, 19,
                          "expected an integer for 'pgs_iterations' in 'simulation', got '2.5'");
    EXPECT_INPUT_ERROR_AT(yamlError(text(R"(
simulation:
  integrator: rk4
bodies: []
)")),
                          "scene.yaml", 2, 15, "expected euler, rattle or rattle4");
    EXPECT_INPUT_ERROR_AT(yamlError(text(R"(
simulation:
  dt: -0.001
bodies: []
)")),
                          "scene.yaml", 2, 7, "expected a positive number for 'dt' in 'simulation'");
}

TEST(YamlErrors, MassAndDensityTogether)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 0.1}
    mass: 1
    density: 1000
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 5, 5, "give either 'mass' or 'density' in body 'a', not both");
}

TEST(YamlErrors, InertiaWithoutMass)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 0.1}
    inertia: [1, 1, 1]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 5, "'inertia' in body 'a' needs 'mass'");
}

TEST(YamlErrors, MovingBodyWithoutShapeOrMass)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    position: [0, 0, 1]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 2, 5, "missing key 'mass' in body 'a'");
}

TEST(YamlErrors, MassWithoutShapeNeedsInertia)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    mass: 2
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 3, 5, "body 'a' has 'mass' but no solid shape");
}

TEST(YamlErrors, BadBoolean)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    static: maybe
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 3, 13,
                          "expected true or false for 'static' in body 'a', got 'maybe'");
}

TEST(YamlErrors, ColorOutOfRange)
{
    const InputError e = yamlError(text(R"(
bodies:
  - name: a
    shape: {type: sphere, radius: 0.1}
    color: [0.5, 2, 0]
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 18,
                          "expected a number in [0, 1] for 'color' in body 'a', got '2'");
}

TEST(YamlErrors, IgnorePairWithUnknownBody)
{
    const InputError e = yamlError(text(R"(
contact:
  ignore:
    - [a, bb]
bodies:
  - name: a
    shape: {type: sphere, radius: 0.1}
  - name: b
    shape: {type: sphere, radius: 0.1}
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 3, 11, "unknown body 'bb' for entry 1 of 'ignore' in 'contact'");
}

TEST(YamlErrors, WrongNodeKinds)
{
    EXPECT_INPUT_ERROR_AT(yamlError("bodies: 3\n"), "scene.yaml", 1, 9,
                          "expected a list for 'bodies', got '3'");
    EXPECT_INPUT_ERROR_AT(yamlError("- a\n- b\n"), "scene.yaml", 1, 1,
                          "expected a map for the scene, got a list");
    EXPECT_INPUT_ERROR_AT(yamlError("bodies:\n  - 7\n"), "scene.yaml", 2, 5,
                          "expected a map for body #1, got '7'");
}

TEST(YamlErrors, EmptySceneAndNoBodies)
{
    EXPECT_INPUT_ERROR_AT(yamlError(""), "scene.yaml", 1, 1, "the file is empty; expected a scene");
    EXPECT_INPUT_ERROR_AT(yamlError("\n# only a comment\n"), "scene.yaml", 1, 1,
                          "the file holds no YAML content (only comments or an empty document)");
    EXPECT_INPUT_ERROR_AT(yamlError("name: nothing\n"), "scene.yaml", 1, 1, "the scene has no bodies");
}

TEST(YamlErrors, SeveralDocuments)
{
    const InputError e = yamlError(text(R"(
bodies:
  - {name: a, shape: {type: sphere, radius: 0.1}}
---
bodies: []
)"));
    EXPECT_INPUT_ERROR_AT(e, "scene.yaml", 4, 1, "the file holds 2 YAML documents");
}

// A ',' where a value or document should start made yaml-cpp return empty documents without end
// (memory grew until the process was killed; found by fuzz/yaml_scene_fuzz.cpp): refused at once.
TEST(YamlErrors, StrayCommaAtTheTopLevel)
{
    EXPECT_INPUT_ERROR_AT(yamlError(","), "scene.yaml", 1, 1, "invalid YAML: unexpected ',' here");
    EXPECT_INPUT_ERROR_AT(yamlError(", duration: 3.0, gravity: [0, 0, -9.81]}\n"), "scene.yaml", 1, 1,
                          "unexpected ','");
    EXPECT_INPUT_ERROR_AT(yamlError("- x\n,\n"), "scene.yaml", 2, 1, "unexpected ','");
    EXPECT_INPUT_ERROR_AT(yamlError("# comment\n  ,\n"), "scene.yaml", 2, 3, "unexpected ','");
    EXPECT_INPUT_ERROR_AT(yamlError("bodies: []\n---\n,\n"), "scene.yaml", 3, 1, "unexpected ','");
}

TEST(YamlErrors, MissingMeshFileIsReportedAtTheSceneNode)
{
    TempDir dir;
    const std::string scene = dir.write("scene.yaml", text(R"(
bodies:
  - name: a
    shape:
      type: mesh
      file: nope.obj
)"));
    const InputError e = captureInputError([&] { loadScene(scene); });
    EXPECT_INPUT_ERROR_AT(e, scene, 5, 13, "cannot read mesh file '" + dir.file("nope.obj") + "'");
}

TEST(YamlErrors, MissingUrdfFileIsReportedAtTheSceneNode)
{
    TempDir dir;
    const std::string scene = dir.write("scene.yaml", text(R"(
models:
  - urdf: robot.urdf
)"));
    const InputError e = captureInputError([&] { loadScene(scene); });
    EXPECT_INPUT_ERROR_AT(e, scene, 2, 11, "cannot open URDF file");
}

// assimp reports no line inside the mesh file: the error is placed at the scene's `file:` node and
// names the mesh file and assimp's reason (its OBJ reader skips the bad vertex, so face 3 is
// out of range).
TEST(YamlErrors, BadMeshContentNamesTheMeshFileAtTheSceneNode)
{
    TempDir dir;
    dir.write("cube.obj", "v 0 0 0\nv 1 0 0\nv 0 one 0\nf 1 2 3\n");
    const std::string scene = dir.write("scene.yaml", text(R"(
bodies:
  - name: a
    shape: {type: mesh, file: cube.obj}
)"));
    const InputError e = captureInputError([&] { loadScene(scene); });
    EXPECT_INPUT_ERROR_AT(e, scene, 3, 31,
                          "cannot read mesh file '" + dir.file("cube.obj") +
                              "': the mesh importer (assimp) failed: OBJ: vertex index out of range");
}

// Old Mac line endings (a lone CR): yaml-cpp counts lines at LF only, so the scene is read with
// CR and CR LF turned into LF and messages name the right line.
TEST(YamlErrors, CarriageReturnLineEndingsKeepLineNumbers)
{
    const std::string ball = "  - {name: ball, mass: 1, shape: {type: sphere, radius: 0.1}}";
    EXPECT_INPUT_ERROR_AT(yamlError("bodies:\r" + ball + "\r  - bad\r"), "scene.yaml", 3, 5,
                          "expected a map for body #2, got 'bad'");
    EXPECT_INPUT_ERROR_AT(yamlError("bodies:\r\n" + ball + "\r\n  - bad\r\n"), "scene.yaml", 3, 5,
                          "expected a map for body #2, got 'bad'");
}

// A local tag would change what the number means to some other reader: refused, not dropped.
TEST(YamlErrors, TaggedNumbersAreRefused)
{
    EXPECT_INPUT_ERROR_AT(yamlError("bodies:\n  - name: ball\n    mass: !tag 3\n"
                                    "    shape: {type: sphere, radius: 0.1}\n"),
                          "scene.yaml", 3, 11, "got one tagged '!tag'");
    EXPECT_INPUT_ERROR_AT(yamlError("simulation: {dt: 0.01, pgs_iterations: !n 5}\nbodies:\n"
                                    "  - {name: ball, mass: 1, shape: {type: sphere, radius: 0.1}}\n"),
                          "scene.yaml", 1, 40, "got one tagged '!n'");
    // The standard tags are numbers.
    EXPECT_NO_THROW(loadSceneFromString("bodies:\n  - name: ball\n    mass: !!float 3\n"
                                        "    shape: {type: sphere, radius: 0.1}\n",
                                        "scene.yaml"));
}

// Principal moments obey I1 + I2 >= I3: [1, 1, 3] is no rigid body.
TEST(YamlErrors, InertiaBreakingTheTriangleInequalityIsRefused)
{
    EXPECT_INPUT_ERROR_AT(yamlError("bodies:\n  - name: ball\n    mass: 1\n    inertia: [1, 1, 3]\n"
                                    "    shape: {type: sphere, radius: 0.1}\n"),
                          "scene.yaml", 4, 14, "the two smaller must add up to the largest");
    EXPECT_NO_THROW(loadSceneFromString("bodies:\n  - name: plate\n    mass: 1\n    inertia: [1, 1, 2]\n"
                                        "    shape: {type: sphere, radius: 0.1}\n",
                                        "scene.yaml"));
}

// Only regular files are read: a FIFO would block, /dev/zero and /dev/urandom never end. A URDF
// model that cannot be read at all is named at the scene's line.
TEST(YamlErrors, OnlyRegularFilesAreRead)
{
    TempDir dir;
    const std::string fifo = dir.file("pipe.yaml");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_INPUT_ERROR_AT(captureInputError([&] { loadScene(fifo); }), fifo, 0, 0,
                          "is not a regular file (a FIFO), expected a scene file");
    for (const char* device : {"/dev/zero", "/dev/urandom"})
    {
        const std::string link = dir.file(std::string("device") + (device[5] == 'z' ? "0" : "1") + ".yaml");
        std::filesystem::create_symlink(device, link);
        EXPECT_INPUT_ERROR_AT(captureInputError([&] { loadScene(link); }), link, 0, 0,
                              "is not a regular file (a device), expected a scene file");
    }
    std::filesystem::create_directory(dir.file("folder.urdf"));
    std::filesystem::create_symlink("/dev/zero", dir.file("zero.urdf"));
    ASSERT_EQ(::mkfifo(dir.file("pipe.urdf").c_str(), 0600), 0);
    const std::pair<const char*, const char*> models[] = {
        {"folder.urdf", "is a directory, expected a URDF file"},
        {"zero.urdf", "is not a regular file (a device), expected a URDF file"},
        {"pipe.urdf", "is not a regular file (a FIFO), expected a URDF file"}};
    for (const auto& [model, needle] : models)
    {
        const std::string scene =
            dir.write("scene.yaml", std::string("\nmodels:\n  - urdf: ") + model + "\n");
        EXPECT_INPUT_ERROR_AT(captureInputError([&] { loadScene(scene); }), scene, 3, 11,
                              "cannot read URDF file '" + dir.file(model) + "': " + needle);
    }
}

// Input files are read up to FRONTIER_MAX_INPUT_BYTES (256 MiB when unset).
TEST(YamlErrors, InputFilesAboveTheSizeLimitAreRefused)
{
    TempDir dir;
    const std::string scene =
        dir.write("scene.yaml", "bodies:\n  - {name: ball, mass: 1, shape: {type: sphere, radius: 0.1}}\n");
    ASSERT_EQ(::setenv("FRONTIER_MAX_INPUT_BYTES", "40", 1), 0);
    const InputError big = captureInputError([&] { loadScene(scene); });
    ASSERT_EQ(::setenv("FRONTIER_MAX_INPUT_BYTES", "forty", 1), 0);
    const InputError bad = captureInputError([&] { loadScene(scene); });
    ASSERT_EQ(::unsetenv("FRONTIER_MAX_INPUT_BYTES"), 0);
    EXPECT_INPUT_ERROR_AT(
        big, scene, 0, 0,
        "scene file has 70 bytes, above the limit of 40 bytes (set FRONTIER_MAX_INPUT_BYTES");
    EXPECT_INPUT_ERROR_AT(bad, "FRONTIER_MAX_INPUT_BYTES", 0, 0,
                          "expected a positive whole number of bytes, got 'forty'");
    EXPECT_NO_THROW(loadScene(scene));
}

// One rule for numbers in every input file (io/file_util.h): counts are whole numbers in range.
TEST(YamlErrors, CountsAreWholeNumbersInRange)
{
    const std::string ball = "bodies:\n  - {name: ball, mass: 1, shape: {type: sphere, radius: 0.1}}\n";
    EXPECT_INPUT_ERROR_AT(yamlError("simulation: {pgs_iterations: 2.5}\n" + ball), "scene.yaml", 1, 30,
                          "expected an integer for 'pgs_iterations' in 'simulation', got '2.5'");
    EXPECT_INPUT_ERROR_AT(yamlError("simulation: {pgs_iterations: 99999999999}\n" + ball), "scene.yaml", 1,
                          30, "expected an integer for 'pgs_iterations'");
    EXPECT_INPUT_ERROR_AT(yamlError("simulation: {pgs_iterations: 2000000}\n" + ball), "scene.yaml", 1, 30,
                          "expected an integer from 1 to 1000000 for 'pgs_iterations'");
    EXPECT_INPUT_ERROR_AT(yamlError("simulation: {dt: .inf}\n" + ball), "scene.yaml", 1, 18,
                          "expected a finite number for 'dt' in 'simulation', got '.inf'");
}

} // namespace
} // namespace frontier::io::test
