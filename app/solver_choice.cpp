// app/solver_choice.cpp: parsing `linear`, `dense`, `pgs`, `pgs:K`.
#include "app/solver_choice.h"

#include <charconv>

namespace frontier::app
{

std::optional<SolverChoice> parseSolverChoice(const std::string& entry, int defaultPgsIterations)
{
    SolverChoice choice;
    choice.pgsIterations = defaultPgsIterations;
    if (entry.rfind("pgs:", 0) == 0)
    {
        const std::string count = entry.substr(4);
        int iterations = 0;
        const auto [end, error] = std::from_chars(count.data(), count.data() + count.size(), iterations);
        if (count.empty() || error != std::errc() || end != count.data() + count.size() || iterations < 1 ||
            iterations > cMaxPgsIterations)
        {
            return std::nullopt;
        }
        choice.solver = core::SolverKind::Pgs;
        choice.pgsIterations = iterations;
        return choice;
    }
    const std::optional<core::SolverKind> kind = core::solverFromName(entry);
    if (!kind)
    {
        return std::nullopt;
    }
    choice.solver = *kind;
    return choice;
}

} // namespace frontier::app
