// bench/peers/engines.cpp: the harness's engines by name.
#include "bench/peers/engine.h"

#include <stdexcept>

namespace frontier::peers
{

std::vector<std::string> engineNames()
{
    return {"frontier-euler", "frontier-rattle", "frontier-rattle4", "bullet-multibody", "bullet-si",
            "ode-quick",      "ode-direct",      "mujoco",           "mujoco-rk4"};
}

std::unique_ptr<Engine> makeEngine(const std::string& name, const core::Model& model)
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
        return makeMujoco(model, MujocoIntegrator::Euler);
    if (name == "mujoco-rk4")
        return makeMujoco(model, MujocoIntegrator::Rk4);
    throw std::invalid_argument("unknown engine '" + name + "'");
}

} // namespace frontier::peers
