// python/simulator.h: what frontier.Simulator wraps: a scene loaded as `frontier run` loads it, the
// run::Simulation that steps it, and what Python reads and sets between steps. No Python here
// (python/module.cpp binds it), so the physics and the bindings stay apart.
#pragma once

#include "python/recording.h"
#include "run/overrides.h"
#include "run/scene_loading.h"
#include "run/simulation.h"

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace frontier::render
{
class Renderer;
struct Image;
} // namespace frontier::render

namespace frontier::python
{

struct LoadOptions
{
    io::UrdfOptions urdf;
    run::SettingOverrides overrides;
};

// A saved state (Simulator::getState) with the file it is a state of.
struct SavedState
{
    run::Simulation::Snapshot snapshot;
    std::string source; // the model file's canonical path
};

// One joint coordinate Python addresses (Simulator::coordinates()).
struct Coordinate
{
    int joint = 0;
    core::JointCoordinate coordinate = core::JointCoordinate::Rotation;
    std::string name; // the joint's name; "NAME:slide" / "NAME:rotation" for a cylindrical joint
};

class Simulator
{
  public:
    // Loads `path` as `frontier run PATH` with the flags in `options` loads it. Throws io::InputError.
    Simulator(const std::string& path, const LoadOptions& options);
    ~Simulator();

    // `steps` steps. `checkSignals` is called every few steps (with the GIL taken, by the binding)
    // and may throw to stop. Throws core::SimulationError (recorded first by an open recording).
    void step(long steps, const std::function<void()>& checkSignals);

    const core::Model& model() const { return mScene->model; }
    // The state and the simulator between steps: throw std::runtime_error while another thread
    // is in step() or render() (a simulator is used by one thread at a time; the reader would race).
    const core::State& state() const
    {
        checkIdle();
        return mSimulation->state();
    }
    const core::Simulator& simulator() const
    {
        checkIdle();
        return mSimulation->simulator();
    }
    void checkIdle() const;
    const std::string& path() const { return mPath; }
    const std::vector<Coordinate>& coordinates() const { return mCoordinates; }
    // "NAME" for an actuator on a one-coordinate joint, "NAME:slide"/"NAME:rotation" on a cylindrical one.
    std::string actuatorName(std::size_t actuator) const;

    // Whether the state is one a step produced (contacts, joint loads and efforts are that step's);
    // false after loading and after a state was set.
    bool hasLastStep() const { return mHasLastStep; }
    // Joint violations of the current state (m, rad).
    std::pair<double, double> jointErrors() { return mSimulation->simulator().jointErrors(state()); }

    void setGravity(const core::Vec3& gravity_mps2);
    // A force (N) and torque (N m), world frame, on a moving body during the next step; with a
    // point (m, world) the force acts there. Throws std::invalid_argument / std::out_of_range.
    void applyForce(int body, const core::Vec3& force_N, const core::Vec3& torque_Nm,
                    const std::optional<core::Vec3>& point_W);

    // What the next steps depend on (run::Simulation::Snapshot), and back. set_state refuses
    // while a recording is under way (its rows would run back in time).
    SavedState getState() const;
    // Throws std::invalid_argument for a state of another file.
    void setState(const SavedState& saved);
    // Index of a body by name or of the actuator on a coordinate ("NAME" or "NAME:slide"); throw
    // run::NameError naming the nearest.
    int bodyIndex(const std::string& name) const;
    int actuatorIndex(const std::string& name) const;
    // Throws std::out_of_range for an index beyond Model::actuators, std::invalid_argument for a
    // value that is not finite.
    void setActuatorTarget(int actuator, double value);

    // The image of the current state, width x height pixels; the camera: the scene's, or `camera`
    // when given. Throws std::runtime_error when no OSMesa context can be made.
    render::Image render(int width, int height, const std::optional<core::Camera>& camera);

    // Starts recording (io::OutputError when a file cannot be written); one at a time.
    void startRecording(RecordingOptions options);
    // Writes the files of the recording under way; returns them. Nothing when none is under way.
    // `failure`: the loop stopped on an exception, the files say the run failed and why.
    std::vector<std::string> closeRecording(const std::optional<std::string>& failure = std::nullopt);
    bool recording() const { return mRecording != nullptr; }
    // Ends the recording under way writing nothing (its handle was dropped unclosed).
    void discardRecording() { mRecording.reset(); }

  private:
    // Marks the simulator busy for the scope (step, render): a second entry throws std::runtime_error.
    class Busy;

    std::string mPath;
    std::string mSource; // canonical mPath: a saved state's origin
    LoadOptions mOptions;
    std::vector<std::string> mInputs; // every file the load read (io::LoadReport::inputFiles)
    mutable std::atomic<bool> mBusy{false};
    std::unique_ptr<run::LoadedScene> mScene; // its model stays where the simulation references it
    std::unique_ptr<run::Simulation> mSimulation;
    std::vector<Coordinate> mCoordinates;
    std::unique_ptr<render::Renderer> mRenderer;
    int mRenderWidth = 0, mRenderHeight = 0;
    std::optional<core::Camera> mRenderCamera;
    std::optional<core::State> mFramedAt; // the state the automatic camera was framed around
    std::unique_ptr<Recording> mRecording;
    bool mHasLastStep = false;
};

} // namespace frontier::python
