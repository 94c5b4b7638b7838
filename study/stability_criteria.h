// study/stability_criteria.h: a scene's own pass criteria in the stability suite (its
// `stability:` map, io::SceneStabilityCriteria), watched over a run: the speed of every centre of
// mass, the energy's rise, and the angle of watched revolute joints, continued through whole turns
// here (independently of the simulator's count of turns) and compared with their range and their
// position servo's target.
#pragma once

#include "core/model.h"
#include "core/state.h"
#include "io/scene.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace frontier::study
{

struct StabilityCell;

class CriteriaWatch
{
  public:
    CriteriaWatch(const core::Model& model, const io::SceneStabilityCriteria& criteria);

    // Every recorded state, the initial one first: the largest speed (into the cell) and the
    // watched joints' angles.
    void observe(const core::State& state, StabilityCell& cell);

    // After the run: the watched joints' extremes into the cell, and a cell that survived fails
    // when it broke a criterion (its note says which, and when).
    void judge(StabilityCell& cell) const;

  private:
    struct Watched
    {
        io::StabilityJointCheck check;
        const core::Actuator* servo = nullptr; // the joint's position actuator (tracking)
        double previous = 0.0;                 // continued angle at the last state (rad, from the start)
        double low = 0.0;                      // smallest angle, the model file's convention (rad)
        double high = 0.0;                     // largest
        double worstTracking = 0.0;            // rad
        std::string broke;                     // the first break of its range or tracking
    };

    const core::Model& mModel;
    io::SceneStabilityCriteria mCriteria;
    std::vector<Watched> mWatched;
    bool mFirst = true;
    std::string mTooFast; // the first centre faster than maxSpeed
};

// "max speed 3 m/s; energy rise < 5 J; 'hinge' within [-4.05, 4.05] rad, past 3.5 rad": the
// criteria in words (empty for none).
std::string criteriaText(const core::Model& model, const io::SceneStabilityCriteria& criteria);

} // namespace frontier::study
