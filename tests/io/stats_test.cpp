// tests/io/stats_test.cpp: stats JSON keys, round trip, non-finite values, errors.
#include "io/atomic_file.h"
#include "io/scene.h"
#include "io/stats.h"
#include "io_test_util.h"

#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <nlohmann/json.hpp>

namespace frontier::io::test
{
namespace
{

RunStats sample()
{
    RunStats s;
    s.scene = "scenes/doll.yaml";
    s.solver = "linear";
    s.integrator = "rattle";
    s.pgsIterations = 20;
    s.dt = 0.001;
    s.steps = 3000;
    s.simulatedSeconds = 3.0;
    s.bodies = 15;
    s.staticBodies = 1;
    s.joints = 14;
    s.constraintRows = 60;
    s.degreesOfFreedom = 30;
    s.wallSeconds = 0.25;
    s.secondsPerStep = 0.25 / 3000;
    s.maxJointErrorM = 1e-9;
    s.maxPenetrationM = 0.002;
    s.energyInitialJ = 123.456;
    s.energyFinalJ = 120.0;
    s.maxContacts = 12;
    s.finite = true;
    s.extra["momentum_drift"] = 1e-12;
    return s;
}

TEST(Stats, HasEveryContractKey)
{
    TempDir dir;
    const std::string path = dir.file("stats.json");
    writeStats(path, sample());
    const nlohmann::json json = nlohmann::json::parse(readTextOf(path));
    for (const char* key :
         {"scene", "solver", "dt", "steps", "bodies", "joints", "constraint_rows", "wall_seconds",
          "seconds_per_step", "max_joint_error_m", "max_penetration_m", "energy_initial_j", "energy_final_j",
          "max_contacts", "finite", "integrator", "momentum_drift"})
    {
        EXPECT_TRUE(json.contains(key)) << key;
    }
    EXPECT_EQ(json["steps"], 3000);
    EXPECT_EQ(json["finite"], true);
}

TEST(Stats, RoundTrip)
{
    TempDir dir;
    const std::string path = dir.file("stats.json");
    const RunStats s = sample();
    writeStats(path, s);
    const RunStats r = readStats(path);
    EXPECT_EQ(r.scene, s.scene);
    EXPECT_EQ(r.solver, s.solver);
    EXPECT_EQ(r.integrator, s.integrator);
    EXPECT_EQ(r.steps, s.steps);
    EXPECT_EQ(r.dt, s.dt);
    EXPECT_EQ(r.secondsPerStep, s.secondsPerStep); // nlohmann writes doubles so they read back exactly
    EXPECT_EQ(r.energyInitialJ, s.energyInitialJ);
    EXPECT_EQ(r.maxContacts, s.maxContacts);
    EXPECT_EQ(r.constraintRows, s.constraintRows);
    EXPECT_EQ(r.extra.at("momentum_drift"), 1e-12);
}

TEST(Stats, NonFiniteBecomesNullAndReadsAsNan)
{
    TempDir dir;
    const std::string path = dir.file("stats.json");
    RunStats s = sample();
    s.energyFinalJ = std::numeric_limits<double>::quiet_NaN();
    s.maxPenetrationM = std::numeric_limits<double>::infinity();
    s.finite = false;
    writeStats(path, s);
    const nlohmann::json json = nlohmann::json::parse(readTextOf(path));
    EXPECT_TRUE(json["energy_final_j"].is_null());
    const RunStats r = readStats(path);
    EXPECT_TRUE(std::isnan(r.energyFinalJ));
    EXPECT_FALSE(r.finite);
}

TEST(Stats, ReadErrors)
{
    TempDir dir;
    const std::string bad = dir.write("bad.json", "{\n  \"scene\": \"x\",\n  \"solver\": ]\n}\n");
    const InputError e = captureInputError([&] { readStats(bad); });
    EXPECT_EQ(e.line(), 3) << e.what();
    EXPECT_NE(std::string(e.what()).find("invalid JSON"), std::string::npos);
    const std::string missing = dir.write("missing.json", "{\"scene\": \"x\"}");
    EXPECT_NE(std::string(captureInputError([&] { readStats(missing); }).what()).find("missing key 'solver'"),
              std::string::npos);
}

TEST(Stats, ModelCounts)
{
    const core::Model model = loadSceneFromString(text(R"(
bodies:
  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1]}}
  - {name: a, shape: {type: sphere, radius: 0.1}}
  - {name: b, shape: {type: sphere, radius: 0.1}}
joints:
  - {name: j1, type: revolute, parent: floor, child: a, anchor: [0, 0, 0], axis: [0, 1, 0]}
  - {name: j2, type: ball, parent: a, child: b, anchor: [0, 0, 0]}
)"),
                                                  "s.yaml");
    RunStats s;
    fillModelCounts(s, model);
    EXPECT_EQ(s.bodies, 2);
    EXPECT_EQ(s.staticBodies, 1);
    EXPECT_EQ(s.joints, 2);
    EXPECT_EQ(s.constraintRows, 8);
    EXPECT_EQ(s.degreesOfFreedom, 4);
}

TEST(Stats, UnwritableDirectoryIsAnOutputError)
{
    EXPECT_THROW(writeStats("/nonexistent/dir/stats.json", sample()), OutputError);
}

} // namespace
} // namespace frontier::io::test
