// tests/io/actuator_yaml_test.cpp: `actuators:` and `loads:` of a YAML scene (io/yaml_actuators.cpp,
// io/yaml_loads.cpp, io/yaml_targets.cpp, io/target_table.cpp) and `hold` (io/hold_servos.h):
// what they load to, and every kind of bad input at its file:line:column.
#include "core/joints/coordinate_inertia.h"
#include "io/scene.h"
#include "io_test_util.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

namespace frontier::io::test
{
namespace
{

// Five bodies on four joints (12 lines); `actuators:` or `loads:` follow on line 13.
const char* const cBase = R"(
bodies:
  - {name: base, static: true, shape: {type: box, size: [0.2, 0.2, 0.2]}}
  - {name: arm, shape: {type: box, size: [0.4, 0.05, 0.05]}, position: [0.2, 0, 1]}
  - {name: cart, shape: {type: box, size: [0.2, 0.1, 0.1]}, position: [0, 0, 0.5]}
  - {name: tube, shape: {type: cylinder, radius: 0.05, length: 0.3}, position: [0, 1, 1]}
  - {name: ball, shape: {type: sphere, radius: 0.1}, position: [0, 2, 1]}
joints:
  - {name: hinge, type: revolute, parent: base, child: arm, anchor: [0, 0, 1], axis: [0, 1, 0]}
  - {name: slider, type: prismatic, parent: world, child: cart, anchor: [0, 0, 0.5], axis: [1, 0, 0],
     damping: 2}
  - {name: sleeve, type: cylindrical, parent: world, child: tube, anchor: [0, 1, 1], axis: [0, 0, 1]}
  - {name: socket, type: ball, parent: world, child: ball, anchor: [0, 2, 1.1]}
)";

std::string scene(const char* more)
{
    return text(cBase) + text(more);
}

core::Model load(const std::string& yaml, const std::string& name = "scene.yaml")
{
    return loadSceneFromString(yaml, name);
}

TEST(ActuatorYaml, ReadsEachKindWithItsGainsLimitAndTarget)
{
    const core::Model model = load(scene(R"(
actuators:
  - {joint: hinge, type: position, kp: 400, kd: 20, target: 0.3, effort_limit: 80}
  - {joint: slider, type: velocity, target: 5.0, effort_limit: 2}
  - {joint: sleeve, type: effort, coordinate: rotation, target: {sine: {amplitude: 3, frequency: 0.5}}}
  - {joint: sleeve, type: position, coordinate: slide, kp: 200, kd: 10, target: {keyframes: [[0, 0], [1, 1.2]]}}
)"));
    ASSERT_EQ(model.actuators.size(), 4u);
    const core::Actuator& servo = model.actuators[0];
    EXPECT_EQ(servo.joint, 0);
    EXPECT_EQ(servo.kind, core::ActuatorKind::Position);
    EXPECT_EQ(servo.coordinate, core::JointCoordinate::Rotation);
    EXPECT_EQ(servo.kp, 400.0);
    EXPECT_EQ(servo.kd, 20.0);
    EXPECT_EQ(servo.effortLimit, 80.0);
    EXPECT_EQ(core::valueAt(servo.target, 7.0), 0.3);
    const core::Actuator& motor = model.actuators[1];
    EXPECT_EQ(motor.kind, core::ActuatorKind::Velocity);
    EXPECT_EQ(motor.coordinate, core::JointCoordinate::Slide);
    EXPECT_EQ(motor.kd, 0.0); // rigid
    EXPECT_EQ(motor.effortLimit, 2.0);
    const core::Actuator& effort = model.actuators[2];
    EXPECT_EQ(effort.kind, core::ActuatorKind::Effort);
    EXPECT_TRUE(std::isinf(effort.effortLimit));                // none given, none on the joint
    EXPECT_NEAR(core::valueAt(effort.target, 0.5), 3.0, 1e-15); // 3 sin(2 pi 0.5 0.5)
    const core::Actuator& slide = model.actuators[3];
    EXPECT_EQ(slide.coordinate, core::JointCoordinate::Slide);
    EXPECT_NEAR(core::valueAt(slide.target, 0.5), 0.6, 1e-15);
}

TEST(ActuatorYaml, CsvTargetEqualsTheSameKeyframes)
{
    TempDir dir;
    dir.write("targets.csv", "# written by hand\ntime, hinge, other\n0, 0, 9\n0.5, 0.2, 9\n2, 1.0, 9\n");
    const std::string yaml = scene(R"(
actuators:
  - {joint: hinge, type: position, kp: 100, target: {csv: {file: targets.csv}, smooth: true}}
  - {joint: slider, type: position, kp: 100, target: {keyframes: [[0, 0], [0.5, 0.2], [2, 1.0]], smooth: true}}
)");
    const core::Model model = load(yaml, dir.write("scene.yaml", yaml));
    for (double t : {0.1, 0.5, 0.7, 1.9, 3.0})
    {
        EXPECT_EQ(core::valueAt(model.actuators[0].target, t), core::valueAt(model.actuators[1].target, t));
    }
}

TEST(ActuatorYaml, UrdfEffortLimitAndHoldServos)
{
    const std::string arm =
        std::string(FRONTIER_SOURCE_DIR) + "/scenes/robots/arm6_description/urdf/arm6.urdf";
    const core::Model model = load(text(R"(
models:
  - {urdf: )") + arm + text(R"(, prefix: r_, hold: true}
actuators:
  - {joint: r_elbow_joint, type: position, kp: 1000, target: 0.5}
)"));
    // The scene's servo on the elbow, then hold servos on the five other joints.
    ASSERT_EQ(model.actuators.size(), 6u);
    EXPECT_EQ(model.joints[static_cast<std::size_t>(model.actuators[0].joint)].name, "r_elbow_joint");
    EXPECT_EQ(model.actuators[0].effortLimit, 100.0); // the URDF's <limit effort>
    for (std::size_t a = 1; a < model.actuators.size(); ++a)
    {
        const core::Actuator& hold = model.actuators[a];
        EXPECT_NE(hold.joint, model.actuators[0].joint);
        EXPECT_EQ(hold.effortLimit, 100.0);
        // Critically damped at 10 Hz on the joint's inertia, or stiffer to reach the limit at 0.05 rad.
        const double inertia = core::coordinateInertia(model, hold.joint, hold.coordinate);
        const double omega = 2.0 * std::numbers::pi * 10.0;
        EXPECT_NEAR(hold.kp, std::max(inertia * omega * omega, 100.0 / 0.05), 1e-9 * hold.kp);
        EXPECT_NEAR(hold.kd, 2.0 * std::sqrt(hold.kp * inertia), 1e-9 * hold.kd);
        EXPECT_EQ(core::valueAt(hold.target, 1.0), 0.0);
    }
}

TEST(ActuatorYaml, ReadsLoads)
{
    const core::Model model = load(scene(R"(
loads:
  - {body: arm, force: [50, 0, 0], at: [0, 0, 0.1], frame: body, from: 1.0, to: 1.1}
  - {body: cart, impulse: [5, 0, 0], time: 2.0}
  - {body: tube, torque: [0, 0, 1]}
)"));
    ASSERT_EQ(model.loads.size(), 3u);
    EXPECT_EQ(model.loads[0].body, 1);
    EXPECT_EQ(model.loads[0].frame, core::LoadFrame::Body);
    EXPECT_EQ(*model.loads[0].point, core::Vec3(0, 0, 0.1));
    EXPECT_EQ(model.loads[0].from, 1.0);
    EXPECT_EQ(model.loads[0].to, 1.1);
    EXPECT_EQ(*model.loads[1].instant, 2.0);
    EXPECT_EQ(model.loads[1].force, core::Vec3(5, 0, 0));
    EXPECT_EQ(model.loads[1].frame, core::LoadFrame::World);
    EXPECT_TRUE(std::isinf(model.loads[2].to));
    EXPECT_FALSE(model.loads[2].point.has_value());
}

struct BadInput
{
    const char* name;
    const char* yaml; // after cBase
    int line;
    int column;
    const char* message;
};

class ActuatorYamlError : public ::testing::TestWithParam<BadInput>
{
};

TEST_P(ActuatorYamlError, NamesFileLineAndWhatWasExpected)
{
    const BadInput& bad = GetParam();
    EXPECT_INPUT_ERROR_AT(yamlError(scene(bad.yaml)), "scene.yaml", bad.line, bad.column, bad.message);
}

const BadInput cBadInputs[] = {
    {"UnknownJointWithSuggestion", "actuators:\n  - {joint: hinj, type: position, kp: 1, target: 0}\n", 14,
     13, "unknown joint 'hinj' for 'joint' in actuator #1; did you mean 'hinge'?"},
    {"JointTypeItCannotDrive", "actuators:\n  - {joint: socket, type: effort, target: 1}\n", 14, 13,
     "joint 'socket' is a ball joint; an actuator drives a revolute, cylindrical or prismatic joint"},
    {"UnknownType", "actuators:\n  - {joint: hinge, type: positoin, kp: 1, target: 0}\n", 14, 26,
     "unknown actuator type 'positoin'"},
    {"NegativeGain", "actuators:\n  - {joint: hinge, type: position, kp: 10, kd: -1, target: 0}\n", 14, 48,
     "expected a number >= 0 for 'kd' in the actuator on joint 'hinge' (N m s/rad), got '-1'"},
    {"ZeroStiffness", "actuators:\n  - {joint: hinge, type: position, kp: 0, target: 0}\n", 14, 40,
     "expected a positive number for 'kp'"},
    {"MissingStiffness", "actuators:\n  - {joint: hinge, type: position, target: 0}\n", 14, 5,
     "missing key 'kp' in the actuator on joint 'hinge'"},
    {"StiffnessOnAMotor", "actuators:\n  - {joint: hinge, type: velocity, kp: 3, target: 0}\n", 14, 36,
     "'kp' (stiffness) is for position actuators only"},
    {"NegativeEffortLimit", "actuators:\n  - {joint: hinge, type: velocity, target: 1, effort_limit: -2}\n",
     14, 61, "expected a positive number for 'effort_limit'"},
    {"TwoOnOneCoordinate",
     "actuators:\n  - {joint: hinge, type: effort, target: 1}\n  - {joint: hinge, type: position, kp: 2, "
     "target: 0}\n",
     15, 13, "a second actuator on the rotation of joint 'hinge' (the first is on line 14)"},
    {"CylindricalWithoutCoordinate", "actuators:\n  - {joint: sleeve, type: effort, target: 1}\n", 14, 5,
     "has 2 coordinates; give 'coordinate: slide' or 'coordinate: rotation'"},
    {"CoordinateTheJointLacks",
     "actuators:\n  - {joint: slider, type: effort, coordinate: rotation, target: 1}\n", 14, 47,
     "joint 'slider' (prismatic) has no coordinate 'rotation'; expected slide"},
    {"KeyframeTimesNotIncreasing",
     "actuators:\n  - joint: hinge\n    type: position\n    kp: 5\n    target: {keyframes: [[0, 0], [1, 1], "
     "[1, 2]]}\n",
     17, 42,
     "keyframe times must increase: keyframe 3 of 'keyframes' of 'target' in the actuator on joint "
     "'hinge' is at t = 1 s, after t = 1 s"},
    {"KeyframeNotAPair", "actuators:\n  - {joint: hinge, type: effort, target: {keyframes: [[0, 0], [1]]}}\n",
     14, 63, "expected a list of 2 numbers"},
    {"TwoTargetForms",
     "actuators:\n  - {joint: hinge, type: effort, target: {sine: {amplitude: 1, frequency: 1}, keyframes: "
     "[[0, 1]]}}\n",
     14, 42, "expected exactly one of 'sine', 'keyframes' or 'csv'"},
    {"SineWithoutFrequency", "actuators:\n  - {joint: hinge, type: effort, target: {sine: {amplitude: 1}}}\n",
     14, 49, "missing key 'frequency'"},
    {"MissingTarget", "actuators:\n  - {joint: hinge, type: effort}\n", 14, 5, "missing key 'target'"},
    {"CsvFileMissing", "actuators:\n  - {joint: hinge, type: effort, target: {csv: {file: nowhere.csv}}}\n",
     14, 55, "cannot read the target table"},
    {"LoadOnUnknownBody", "loads:\n  - {body: armm, force: [1, 0, 0]}\n", 14, 12,
     "unknown body 'armm' for 'body' in load #1; did you mean 'arm'?"},
    {"LoadOnStaticBody", "loads:\n  - {body: base, force: [1, 0, 0]}\n", 14, 12,
     "body 'base' is static; a load acts on a moving body"},
    {"LoadWithoutForce", "loads:\n  - {body: arm, from: 1}\n", 14, 5,
     "needs a 'force' and/or a 'torque' (N, N m), or an 'impulse' (N s) at a 'time'"},
    {"ImpulseWithAWindow", "loads:\n  - {body: arm, impulse: [1, 0, 0], time: 1, to: 2}\n", 14, 46,
     "an 'impulse' acts at one instant ('time')"},
    {"ImpulseWithoutTime", "loads:\n  - {body: arm, impulse: [1, 0, 0]}\n", 14, 5, "missing key 'time'"},
    {"EmptyWindow", "loads:\n  - {body: arm, force: [1, 0, 0], from: 2, to: 1}\n", 14, 48,
     "expected 'to' > 'from' for the load on body 'arm', got from = 2 s, to = 1 s"},
    {"UnknownFrame", "loads:\n  - {body: arm, force: [1, 0, 0], frame: local}\n", 14, 42,
     "expected 'world' or 'body' for 'frame'"},
    // Finite parameters whose values or rates are not: refused at their line, not at step 1.
    {"SineWhoseRateOverflows",
     "actuators:\n  - {joint: hinge, type: effort, target: {sine: {amplitude: 1, frequency: 1.0e308}}}\n", 14,
     49, "2 pi x frequency x t overflows within a run (t up to 1e+12 s)"},
    {"KeyframesWhoseSpanOverflows",
     "actuators:\n  - {joint: hinge, type: effort, target: {smooth: true, keyframes: [[-1.0e308, 0], "
     "[1.0e308, "
     "1]]}}\n",
     14, 84,
     "keyframe 2 of 'keyframes' of 'target' in the actuator on joint 'hinge': the time from the keyframe "
     "before overflows"},
    // A load cannot act before the run starts (it used to be ignored without a word).
    {"ImpulseBeforeTheStart", "loads:\n  - {body: arm, impulse: [1, 0, 0], time: -1}\n", 14, 43,
     "expected a number >= 0 for 'time' in the load on body 'arm' (s; the run starts at t = 0), got '-1'"},
    {"WindowBeforeTheStart", "loads:\n  - {body: arm, force: [1, 0, 0], from: -0.5, to: 1}\n", 14, 41,
     "expected a number >= 0 for 'from' in the load on body 'arm'"},
    {"LoadPointFarAway", "loads:\n  - {body: arm, force: [1, 0, 0], at: [0, 0, 2.0e6]}\n", 14, 39,
     "expected a point within 1e6 m of the origin for 'at' in the load on body 'arm', got [0, 0, 2e+06]"},
};

INSTANTIATE_TEST_SUITE_P(Cases, ActuatorYamlError, ::testing::ValuesIn(cBadInputs),
                         [](const ::testing::TestParamInfo<BadInput>& param)
                         { return std::string(param.param.name); });

// Errors inside a target CSV name the CSV file and its line.
TEST(ActuatorYaml, CsvErrorsNameTheCsvFileAndLine)
{
    struct BadCsv
    {
        const char* column; // the actuator's `column:` ("": the joint's name, hinge)
        const char* csv;
        int line;
        const char* message;
    };
    const BadCsv cases[] = {
        {"hnge", "time,hinge\n0,0\n", 1,
         "no column 'hnge' in the header (columns: time, hinge); did you mean 'hinge'?"},
        {"", "time,hinge\n0,0\n1,x\n", 3, "expected a finite number in column 'hinge', got 'x'"},
        {"", "time,hinge\n0,0\n1,1\n1,2\n", 4, "times must increase: time 1 after 1"},
        {"", "hinge\n0\n", 1, "the header has no 'time' column"},
        {"", "time,hinge\n0,1,2\n", 2, "expected 2 comma-separated values"},
        {"", "time,hinge,hinge\n0,0,1\n", 1,
         "column 'hinge' appears twice in the header (fields 2 and 3); expected each column name once"},
        {"", "time,hinge\n-1e308,0\n1e308,1\n", 3,
         "the row of column 'hinge' for 'target' in the actuator on joint 'hinge': the time from the "
         "keyframe "
         "before overflows"},
    };
    TempDir dir;
    for (const BadCsv& bad : cases)
    {
        const std::string column = *bad.column ? std::string(", column: ") + bad.column : "";
        const std::string yaml =
            scene("actuators:\n  - {joint: hinge, type: position, kp: 1, target: {csv: {file: t.csv") +
            column + "}}}\n";
        const std::string scenePath = dir.write("scene.yaml", yaml);
        const std::string csv = dir.write("t.csv", bad.csv);
        EXPECT_INPUT_ERROR_AT(captureInputError([&] { load(yaml, scenePath); }), csv, bad.line, 1,
                              bad.message);
    }
}

// A message that quotes a file's bytes (here a binary CSV header) escapes those that would not print
// (\xNN), so that nothing reaches the terminal raw; well-formed UTF-8 is kept.
TEST(ActuatorYaml, BinaryBytesInAQuotedHeaderAreEscaped)
{
    TempDir dir;
    const std::string yaml =
        scene("actuators:\n  - {joint: hinge, type: position, kp: 1, target: {csv: {file: t.csv}}}\n");
    const std::string scenePath = dir.write("scene.yaml", yaml);
    dir.write("t.csv", std::string("time,\x1b]0;pwned\x07\xff\xfe,r\xc3\xa9glage\r\n0,0,0\n"));
    const InputError e = captureInputError([&] { load(yaml, scenePath); });
    const std::string what = e.what();
    EXPECT_NE(what.find("\\x1b]0;pwned\\x07\\xff\\xfe, r\xc3\xa9glage"), std::string::npos) << what;
    for (const char c : what)
    {
        EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20 || c == 0x7f) << what;
    }
}

} // namespace
} // namespace frontier::io::test
