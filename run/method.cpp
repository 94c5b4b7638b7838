// run/method.cpp: printing and parsing `solver[:K]/integrator`.
#include "run/method.h"

#include <charconv>

namespace frontier::run
{

std::string Method::solverLabel() const
{
    if (solver == core::SolverKind::Pgs)
    {
        return "pgs:" + std::to_string(pgsIterations);
    }
    return core::solverName(solver);
}

std::string Method::label() const
{
    return solverLabel() + "/" + core::integratorName(integrator);
}

bool Method::sameSolver(const Method& other) const
{
    return solver == other.solver &&
           (solver != core::SolverKind::Pgs || pgsIterations == other.pgsIterations);
}

Method Method::of(const core::SimulationSettings& settings)
{
    return {settings.solver, settings.pgsIterations, settings.integrator};
}

void Method::applyTo(core::SimulationSettings& settings) const
{
    settings.solver = solver;
    settings.pgsIterations = pgsIterations;
    settings.integrator = integrator;
}

namespace
{
// `linear`, `dense`, `pgs`, `pgs:K` into method's solver and sweeps.
bool parseSolverPart(const std::string& entry, Method& method)
{
    if (entry.rfind("pgs:", 0) == 0)
    {
        const std::string count = entry.substr(4);
        int iterations = 0;
        const auto [end, error] = std::from_chars(count.data(), count.data() + count.size(), iterations);
        if (count.empty() || error != std::errc() || end != count.data() + count.size() || iterations < 1 ||
            iterations > cMaxPgsIterations)
        {
            return false;
        }
        method.solver = core::SolverKind::Pgs;
        method.pgsIterations = iterations;
        return true;
    }
    const std::optional<core::SolverKind> kind = core::solverFromName(entry);
    if (!kind)
    {
        return false;
    }
    method.solver = *kind;
    return true;
}
} // namespace

std::optional<Method> parseMethod(const std::string& text, int defaultPgsIterations, bool* hasIntegrator)
{
    Method method;
    method.pgsIterations = defaultPgsIterations;
    std::string solver = text;
    std::string integrator;
    if (const std::size_t slash = text.find('/'); slash != std::string::npos)
    {
        solver = text.substr(0, slash);
        integrator = text.substr(slash + 1);
    }
    else if (const std::size_t space = text.find(' '); space != std::string::npos)
    {
        integrator = text.substr(0, space);
        solver = text.substr(space + 1);
    }
    const bool named = text.find_first_of("/ ") != std::string::npos;
    if (named)
    {
        const auto kind = core::integratorFromName(integrator);
        if (!kind)
        {
            return std::nullopt;
        }
        method.integrator = *kind;
    }
    if (!parseSolverPart(solver, method))
    {
        return std::nullopt;
    }
    if (hasIntegrator)
    {
        *hasIntegrator = named;
    }
    return method;
}

} // namespace frontier::run
