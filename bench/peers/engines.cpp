// bench/peers/engines.cpp: the harness's engines by name, and their warning log.
#include "bench/peers/engine.h"

#include <algorithm>
#include <stdexcept>

namespace frontier::peers
{

std::size_t WarningLog::raise(const std::string& text, long step, bool bufferFull)
{
    const auto known = std::find_if(mWarnings.begin(), mWarnings.end(),
                                    [&text](const EngineWarning& w) { return w.text == text; });
    if (known != mWarnings.end())
    {
        const auto index = static_cast<std::size_t>(known - mWarnings.begin());
        again(index, step);
        return index;
    }
    mWarnings.push_back({text, step, 1, bufferFull});
    mLastStep.push_back(step);
    return mWarnings.size() - 1;
}

void WarningLog::again(std::size_t index, long step)
{
    if (mLastStep[index] == step)
        return;
    mLastStep[index] = step;
    ++mWarnings[index].steps;
}

std::vector<std::string> engineNames()
{
    return {"frontier-euler", "frontier-rattle", "frontier-rattle4", "bullet-multibody", "bullet-si",
            "ode-quick",      "ode-direct",      "mujoco",           "mujoco-rk4"};
}

std::unique_ptr<Engine> makeEngine(const std::string& name, const core::Model& model,
                                   const EngineOptions& options)
{
    if (name == "frontier-euler")
        return makeFrontier(model, core::IntegratorKind::Euler);
    if (name == "frontier-rattle")
        return makeFrontier(model, core::IntegratorKind::Rattle);
    if (name == "frontier-rattle4")
        return makeFrontier(model, core::IntegratorKind::Rattle4);
    if (name == "bullet-multibody")
        return makeBulletMultibody(model);
    if (name == "bullet-si")
        return makeBulletSequentialImpulses(model);
    if (name == "ode-quick")
        return makeOde(model, true);
    if (name == "ode-direct")
        return makeOde(model, false);
    if (name == "mujoco")
        return makeMujoco(model, MujocoIntegrator::Euler, options);
    if (name == "mujoco-rk4")
        return makeMujoco(model, MujocoIntegrator::Rk4, options);
    throw std::invalid_argument("unknown engine '" + name + "'");
}

} // namespace frontier::peers
