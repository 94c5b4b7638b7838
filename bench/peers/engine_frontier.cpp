// bench/peers/engine_frontier.cpp: Frontier itself, the `linear` (exact, O(n)) solver, with its
// contact detection (collision::ContactDetector at the frontier program's margin) when the scene's
// bodies can collide; a spelling's tolerance and relative set the model's contact tolerances.
#include "bench/peers/contacts.h"
#include "bench/peers/engine.h"
#include "core/simulator.h"
#include "core/state.h"

namespace frontier::peers
{
namespace
{

class FrontierEngine final : public Engine
{
  public:
    FrontierEngine(const core::Model& model, core::IntegratorKind integrator, const EngineSettings& settings)
        : mModel(withIntegrator(model, integrator, settings)),
          mDetector(hasContacts(mModel) ? std::make_unique<collision::ContactDetector>(
                                              mModel, collision::contactMargin(mModel.simulation.dt))
                                        : nullptr),
          mSimulator(mModel, {}, mDetector.get()), mState(core::initialState(mModel))
    {
    }

    void step() override { mSimulator.step(mState); }

    void poses(std::vector<Pose>& out) override
    {
        out.resize(mState.bodies.size());
        for (std::size_t b = 0; b < out.size(); ++b)
            out[b] = {mState.bodies[b].position_W, mState.bodies[b].orientation_WB};
    }

  private:
    static core::Model withIntegrator(core::Model model, core::IntegratorKind integrator,
                                      const EngineSettings& settings)
    {
        model.simulation.integrator = integrator;
        model.simulation.solver = core::SolverKind::Linear;
        model.contact.tolerance = settings.tolerance.value_or(model.contact.tolerance);
        model.contact.relativeTolerance = settings.relative.value_or(model.contact.relativeTolerance);
        return model;
    }

    core::Model mModel;
    std::unique_ptr<collision::ContactDetector> mDetector; // null: no contacts
    core::Simulator mSimulator;
    core::State mState;
};

} // namespace

std::unique_ptr<Engine> makeFrontier(const core::Model& model, core::IntegratorKind integrator,
                                     const EngineSettings& settings)
{
    return std::make_unique<FrontierEngine>(model, integrator, settings);
}

} // namespace frontier::peers
