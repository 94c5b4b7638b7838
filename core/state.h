// core/state.h: what changes while stepping: poses and velocities of every body.
#pragma once

#include "core/model.h"

#include <string>
#include <vector>

namespace frontier::core
{

struct BodyState
{
    Vec3 position_W = Vec3::Zero();         // centre of mass (m)
    Quat orientation_WB = Quat::Identity(); // body to world, unit
    Vec3 velocity_W = Vec3::Zero();         // m/s
    Vec3 angularVelocity_W = Vec3::Zero();  // rad/s
};

struct State
{
    double time = 0.0; // s; from 0 at one dt, exactly step * dt (core::Simulator adds no round-off)
    long step = 0;     // steps taken
    std::vector<BodyState> bodies; // one per Model::bodies entry, static ones included (never change)
    // Per Model::joints entry: the rotation of revolute and cylindrical joints about their axis,
    // continuous across +-pi (rad, 0 at the model's initial pose; core/joints/coordinates.h); 0
    // for the other types. Part of the state so that copies and restarts of a step agree.
    std::vector<double> jointAngles;
    // Per Model::joints entry: the violation of its conditions the next step's first solve
    // anticipates (m, rad; docs/method.md §7, eq. (11a)); empty when there is none. Part of the
    // state so that copies and restarts of a step agree.
    std::vector<Eigen::Matrix<double, 6, 1>> jointDrift;
    // Per Model::joints entry: the drift the last step's position update would have left without
    // a prediction (m, rad), from which the next prediction extrapolates (eq. (11a)); empty or
    // zero when there is none.
    std::vector<Eigen::Matrix<double, 6, 1>> jointDriftLast;
    // Two per Model::joints entry (its parent's end, its child's): the tension moments of the last
    // steps (N s m, core/step/geometric_stiffness.h), which set the next step's geometric stiffness
    // (docs/method.md §7a); empty before the first step. Part of the state so that copies and
    // restarts of a step agree.
    std::vector<double> jointLoads;
};

State initialState(const Model& model);

// World-frame inertia R I_B R^T (kg m^2); R_WB: the body's rotation matrix where it is at hand.
Mat3 worldInertia(const Body& body, const BodyState& state);
Mat3 worldInertia(const Body& body, const Mat3& R_WB);

// The kinetic energy and the magnitude of the gravitational potential (zero at the origin) of moving
// body i in `state` (J): what a run's energy scale sums.
double bodyEnergyScale(const Model& model, std::size_t i, const BodyState& state);

// What is wrong with body i's starting state (its fields in the model): a position beyond
// cMaxDistance from the origin, a speed beyond cMaxSpeed or cMaxAngularSpeed (core/model.h), or,
// for a moving body, an energy (bodyEnergyScale) that doubles cannot hold, which no run could
// report. "" when nothing is; the scene loaders name the body and its line.
std::string startingStateDefect(const Model& model, std::size_t i);

// Kinetic energy of the moving bodies, translational plus rotational (J).
double kineticEnergy(const Model& model, const State& state);

// Total mechanical energy: kinetic plus gravitational potential of moving bodies (J).
double totalEnergy(const Model& model, const State& state);

struct Momentum
{
    Vec3 linear = Vec3::Zero();  // kg m/s
    Vec3 angular = Vec3::Zero(); // kg m^2/s, about the world origin
};
Momentum totalMomentum(const Model& model, const State& state);

} // namespace frontier::core
