// run/run_stats.cpp: the stats file of a run from its summary.
#include "run/run_stats.h"

#include "core/impulse_solver.h"

namespace frontier::run
{

namespace
{

// Counts of how the steps went: lower-order steps, the contact solve's routes, limits that held.
void addStepCounts(const core::Model& model, const RunSummary& s, io::RunStats& stats)
{
    if (model.simulation.integrator != core::IntegratorKind::Euler)
    {
        stats.extra["first_order_steps"] = static_cast<double>(s.firstOrderSteps);
    }
    if (model.simulation.integrator == core::IntegratorKind::Rattle4)
    {
        stats.extra["second_order_steps"] = static_cast<double>(s.secondOrderSteps); // retaken by rattle
    }
    // How the contact problem was solved (core::ContactRoute): steps that kept the last impulses,
    // that finished on a recent step's Delassus matrix, that built their own; sweeps in all.
    stats.extra["contact_steps_carried"] =
        static_cast<double>(s.contactRoutes[core::routeIndex(core::ContactRoute::Carried)]);
    stats.extra["contact_steps_reused"] =
        static_cast<double>(s.contactRoutes[core::routeIndex(core::ContactRoute::Reused)]);
    stats.extra["contact_steps_built"] =
        static_cast<double>(s.contactRoutes[core::routeIndex(core::ContactRoute::Built)]);
    stats.extra["contact_sweeps"] = static_cast<double>(s.contactSweeps);
    // How often a limit held: joint limits that pushed, actuators at their effort limit (steps).
    stats.extra["limit_steps"] = static_cast<double>(s.limitSteps);
    stats.extra["max_actuator_effort"] = s.maxActuatorEffort;
    stats.extra["actuator_limit_steps"] = static_cast<double>(s.actuatorLimitSteps);
}

// Each actuator over the run (ActuatorSummary), named as the scene names it.
void addActuatorStats(const core::Model& model, const RunSummary& s, io::RunStats& stats)
{
    for (std::size_t a = 0; a < s.actuators.size() && a < model.actuators.size(); ++a)
    {
        const core::Actuator& actuator = model.actuators[a];
        const ActuatorSummary& summary = s.actuators[a];
        stats.actuators.push_back({model.joints[static_cast<std::size_t>(actuator.joint)].name,
                                   core::coordinateName(actuator.coordinate),
                                   core::actuatorTypeName(actuator.kind), summary.trackingRms,
                                   summary.trackingMax, summary.effortRms, summary.effortMax,
                                   summary.limitSteps});
    }
}

// Time per step of each stage (s): detection, factorization, impulse and contact solve, integration.
void addStageTimes(const RunSummary& s, io::RunStats& stats)
{
    const char* stageKeys[core::cStepStages] = {"seconds_per_step_detect", "seconds_per_step_factor",
                                                "seconds_per_step_solve", "seconds_per_step_integrate"};
    for (std::size_t stage = 0; stage < core::cStepStages; ++stage)
    {
        stats.extra[stageKeys[stage]] =
            s.steps > 0 ? s.stageSeconds[stage] / static_cast<double>(s.steps) : 0.0;
    }
}

} // namespace

io::RunStats runStats(const std::string& scene, const core::Model& model, const RunSummary& s)
{
    io::RunStats stats;
    io::fillModelCounts(stats, model);
    stats.scene = scene;
    stats.solver = core::solverName(model.simulation.solver);
    stats.integrator = core::integratorName(model.simulation.integrator);
    stats.dt = model.simulation.dt;
    stats.steps = s.steps;
    stats.wallSeconds = s.wallSeconds;
    stats.secondsPerStep = s.steps > 0 ? s.wallSeconds / static_cast<double>(s.steps) : 0.0;
    stats.maxJointErrorM = s.maxJointErrorM;
    stats.pgsIterations = model.simulation.pgsIterations;
    stats.simulatedSeconds = static_cast<double>(s.steps) * model.simulation.dt;
    stats.extra["max_joint_error_rad"] = s.maxJointErrorRad;
    stats.extra["energy_max_j"] = s.energyMaxJ;
    addStepCounts(model, s, stats);
    addActuatorStats(model, s, stats);
    // Steps in which tensioned light bodies took their geometric stiffness (docs/method.md §7a).
    stats.extra["geometric_stiffness_steps"] = static_cast<double>(s.stiffenedSteps);
    addStageTimes(s, stats);
    stats.maxPenetrationM = s.maxPenetrationM;
    stats.energyInitialJ = s.energyInitialJ;
    stats.energyFinalJ = s.energyFinalJ;
    stats.maxContacts = s.maxContacts;
    stats.finite = s.finite;
    if (isPassive(model))
    {
        stats.extra["energy_rise_fraction"] = passiveEnergyRise(model, s); // of energy_scale_j
        stats.extra["energy_scale_j"] = s.energyScaleJ;
    }
    return stats;
}

} // namespace frontier::run
