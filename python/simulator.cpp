// python/simulator.cpp: a scene stepped, read and driven from Python.
#include "python/simulator.h"

#include "core/joints/coordinates.h"
#include "io/atomic_file.h"
#include "io/input_digest.h"
#include "render/renderer.h"
#include "run/names.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace frontier::python
{

namespace
{
// Wall time between calls of the signal check (Ctrl-C in a long sim.step(n)).
constexpr std::chrono::milliseconds cSignalCheckInterval{50};

std::vector<Coordinate> coordinatesOf(const core::Model& model)
{
    std::vector<Coordinate> out;
    for (std::size_t j = 0; j < model.joints.size(); ++j)
    {
        const std::span<const core::JointCoordinate> coordinates =
            core::jointCoordinates(model.joints[j].type);
        for (const core::JointCoordinate c : coordinates)
        {
            std::string name = model.joints[j].name;
            if (coordinates.size() > 1)
            {
                name += std::string(":") + core::coordinateName(c);
            }
            out.push_back({static_cast<int>(j), c, std::move(name)});
        }
    }
    return out;
}
} // namespace

class Simulator::Busy
{
  public:
    explicit Busy(const Simulator& sim) : mSim(sim)
    {
        if (mSim.mBusy.exchange(true))
        {
            throw std::runtime_error("this simulator is busy in another thread (step or render): use a "
                                     "simulator from one thread at a time");
        }
    }
    ~Busy() { mSim.mBusy.store(false); }
    Busy(const Busy&) = delete;
    Busy& operator=(const Busy&) = delete;

  private:
    const Simulator& mSim;
};

void Simulator::checkIdle() const
{
    if (mBusy.load())
    {
        throw std::runtime_error("this simulator is busy in another thread (step or render): use a "
                                 "simulator from one thread at a time");
    }
}

Simulator::Simulator(const std::string& path, const LoadOptions& options)
    : mPath(path), mOptions(options),
      mScene(std::make_unique<run::LoadedScene>(run::loadScene(path, options.urdf)))
{
    try
    {
        run::applySettingOverrides(options.overrides, mScene->model);
    }
    catch (const io::InputError& e) // a keyword, not the file: say so
    {
        throw io::InputError(e.file(), 0, 0, "a keyword of load(): " + e.message());
    }
    run::printLoadWarnings(mScene->report);
    mInputs = io::inputPaths(mScene->report.inputFiles);
    std::error_code error;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(path, error);
    mSource = error ? path : canonical.string();
    mSimulation = std::make_unique<run::Simulation>(mScene->model);
    mCoordinates = coordinatesOf(mScene->model);
}

Simulator::~Simulator() = default;

void Simulator::step(long steps, const std::function<void()>& checkSignals)
{
    const Busy busy(*this);
    auto lastCheck = std::chrono::steady_clock::now();
    for (long k = 0; k < steps; ++k)
    {
        if (checkSignals && k > 0 && std::chrono::steady_clock::now() - lastCheck >= cSignalCheckInterval)
        {
            checkSignals();
            lastCheck = std::chrono::steady_clock::now();
        }
        try
        {
            mSimulation->step();
        }
        catch (const core::SimulationError& error)
        {
            if (mRecording)
            {
                mRecording->fail(error, mSimulation->simulator());
            }
            throw;
        }
        mHasLastStep = true;
        if (mRecording)
        {
            mRecording->addStep(mSimulation->simulator(), mSimulation->state());
        }
    }
}

std::string Simulator::actuatorName(std::size_t actuator) const
{
    const core::Actuator& a = model().actuators.at(actuator);
    for (const Coordinate& c : mCoordinates)
    {
        if (c.joint == a.joint && c.coordinate == a.coordinate)
        {
            return c.name;
        }
    }
    return model().joints[static_cast<std::size_t>(a.joint)].name;
}

void Simulator::setGravity(const core::Vec3& gravity_mps2)
{
    checkIdle();
    if (!gravity_mps2.allFinite())
    {
        throw std::invalid_argument("gravity must be three finite numbers (m/s^2)");
    }
    mScene->model.simulation.gravity = gravity_mps2;
}

void Simulator::applyForce(int body, const core::Vec3& force_N, const core::Vec3& torque_Nm,
                           const std::optional<core::Vec3>& point_W)
{
    checkIdle();
    core::Simulator& simulator = mSimulation->simulator();
    if (point_W)
    {
        simulator.applyForceAtPoint(state(), body, force_N, *point_W);
        simulator.applyWrench(body, core::Vec3::Zero(), torque_Nm);
    }
    else
    {
        simulator.applyWrench(body, force_N, torque_Nm);
    }
}

SavedState Simulator::getState() const
{
    checkIdle();
    return {mSimulation->snapshot(), mSource};
}

void Simulator::setState(const SavedState& saved)
{
    checkIdle();
    if (saved.source != mSource)
    {
        throw std::invalid_argument("set_state: a state of " + saved.source + ", not of " + mSource);
    }
    if (mRecording)
    {
        throw std::logic_error("set_state while recording: close the recording first (its rows would "
                               "run back in time)");
    }
    mSimulation->restore(saved.snapshot);
    mHasLastStep = false;
}

int Simulator::bodyIndex(const std::string& name) const
{
    return run::bodyIndex(model(), name);
}

int Simulator::actuatorIndex(const std::string& name) const
{
    for (std::size_t a = 0; a < model().actuators.size(); ++a)
    {
        if (actuatorName(a) == name)
        {
            return static_cast<int>(a);
        }
    }
    return run::actuatorIndex(model(), name); // the message: no such joint, or no actuator on it
}

void Simulator::setActuatorTarget(int actuator, double value)
{
    checkIdle();
    if (actuator < 0 || static_cast<std::size_t>(actuator) >= model().actuators.size())
    {
        throw std::out_of_range("actuator index " + std::to_string(actuator) +
                                " out of range (the model has " + std::to_string(model().actuators.size()) +
                                " actuators)");
    }
    if (!std::isfinite(value))
    {
        throw std::invalid_argument("the target of actuator '" +
                                    actuatorName(static_cast<std::size_t>(actuator)) + "' must be finite");
    }
    mSimulation->simulator().setActuatorTarget(static_cast<std::size_t>(actuator), value);
}

render::Image Simulator::render(int width, int height, const std::optional<core::Camera>& camera)
{
    const Busy busy(*this);
    const core::State& now = mSimulation->state();
    if (width < 1 || height < 1 || width > 8192 || height > 8192)
    {
        throw std::invalid_argument("image size " + std::to_string(width) + " x " + std::to_string(height) +
                                    ": expected 1 to 8192 pixels each way");
    }
    const auto sameCamera = [](const std::optional<core::Camera>& a, const std::optional<core::Camera>& b)
    {
        return a.has_value() == b.has_value() &&
               (!a ||
                (a->position == b->position && a->lookAt == b->lookAt && a->fovDegrees == b->fovDegrees));
    };
    if (!mRenderer || width != mRenderWidth || height != mRenderHeight || !sameCamera(camera, mRenderCamera))
    {
        const core::Camera sceneCamera = mScene->model.camera;
        if (camera)
        {
            mScene->model.camera = *camera; // read while framing, at the first render
        }
        mRenderer.reset();
        render::RenderOptions options;
        options.width = width;
        options.height = height;
        mRenderer = std::make_unique<render::Renderer>(mScene->model, options);
        // The automatic camera is framed once, around the state of the first render, and kept.
        if (!camera && !mFramedAt)
        {
            mFramedAt = now;
        }
        mRenderer->frameFrom(camera ? now : *mFramedAt);
        mScene->model.camera = sceneCamera;
        mRenderWidth = width;
        mRenderHeight = height;
        mRenderCamera = camera;
    }
    return mRenderer->render(now);
}

void Simulator::startRecording(RecordingOptions options)
{
    checkIdle();
    if (mRecording)
    {
        throw std::logic_error("a recording is already under way: close it first");
    }
    // Written where the names point now, whatever the working folder is when the recording closes.
    for (std::string* path : {&options.trajectory, &options.stats})
    {
        if (!path->empty())
        {
            *path = std::filesystem::absolute(*path).lexically_normal().string();
        }
    }
    if (!options.trajectory.empty() && options.trajectory == options.stats)
    {
        throw std::invalid_argument("record(): trajectory and stats name the same file " + options.stats);
    }
    const std::string failedTrajectory = options.trajectory.empty() ? "" : io::failedPath(options.trajectory);
    for (const std::string& path : {options.trajectory, failedTrajectory, options.stats})
    {
        if (const std::string input = path.empty() ? "" : io::replacedInput(path, mInputs); !input.empty())
        {
            throw std::invalid_argument("record(): " + path + " is the input " + input +
                                        ": the recording would replace a file the load read");
        }
    }
    options.urdf = mOptions.urdf;
    options.contact = mOptions.overrides.contact;
    mRecording = std::make_unique<Recording>(options, mPath, mScene->model, mSimulation->simulator(),
                                             mSimulation->state());
}

std::vector<std::string> Simulator::closeRecording(const std::optional<std::string>& failure)
{
    checkIdle();
    if (!mRecording)
    {
        return {};
    }
    std::unique_ptr<Recording> recording = std::move(mRecording);
    if (failure)
    {
        recording->abandon(*failure);
    }
    return recording->close(mSimulation->state());
}

} // namespace frontier::python
