// bench/peers/engines.cpp: the harness's engines by name, and their warning log.
#include "bench/peers/engine.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

namespace
{

bool isFrontier(const std::string& engine)
{
    return engine.rfind("frontier-", 0) == 0;
}
bool isMujoco(const std::string& engine)
{
    return engine == "mujoco" || engine == "mujoco-rk4";
}

// The keys an engine's spelling may set.
std::vector<std::string> keysOf(const std::string& engine)
{
    if (isFrontier(engine))
        return {"tolerance", "relative"};
    if (engine == "bullet-si" || engine == "ode-quick")
        return {"iterations"};
    if (isMujoco(engine))
        return {"iterations", "tolerance"};
    return {};
}

// The whole of `text` as a number, or NaN.
double numberOf(const std::string& text)
{
    if (text.empty() || text.find_first_of(" \t") != std::string::npos)
        return std::nan("");
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    return end == text.c_str() + text.size() && errno == 0 ? v : std::nan("");
}

// Sets `key` of `settings` from `value`; returns what the key expects when the value is out of
// its range ("" when it was set).
std::string set(EngineSettings& settings, const std::string& engine, const std::string& key,
                const std::string& value)
{
    const double v = numberOf(value);
    if (key == "iterations")
    {
        if (!(v >= 1 && v <= 1e6 && v == std::floor(v)))
            return "a whole number from 1 to 1000000";
        settings.iterations = static_cast<int>(v);
    }
    else if (key == "relative")
    {
        if (!core::isRelativeContactTolerance(v))
            return "a fraction in [0, 1)";
        settings.relative = v;
    }
    else if (isFrontier(engine))
    {
        if (!core::isContactTolerance(v))
        {
            char range[40];
            std::snprintf(range, sizeof range, "m/s in [0, %g]", core::cMaxContactTolerance);
            return range;
        }
        settings.tolerance = v;
    }
    else
    {
        if (!(v >= 0 && std::isfinite(v)))
            return "a number >= 0";
        settings.tolerance = v;
    }
    return "";
}

} // namespace

EngineSpelling parseEngine(const std::string& spelling)
{
    EngineSpelling out;
    const std::size_t colon = spelling.find(':');
    out.engine = spelling.substr(0, colon);
    const std::vector<std::string> names = engineNames();
    if (std::find(names.begin(), names.end(), out.engine) == names.end())
    {
        std::string expected;
        for (const std::string& n : names)
            expected += " " + n;
        throw std::invalid_argument("unknown engine '" + out.engine + "' (expected one of" + expected + ")");
    }
    const std::vector<std::string> keys = keysOf(out.engine);
    std::vector<std::string> seen;
    for (std::size_t at = colon; at != std::string::npos;)
    {
        const std::size_t next = spelling.find(':', at + 1);
        const std::string item = spelling.substr(at + 1, next == std::string::npos ? next : next - at - 1);
        at = next;
        const std::size_t equals = item.find('=');
        const std::string key = item.substr(0, equals);
        const std::string where = "engine '" + out.engine + "'";
        if (std::find(keys.begin(), keys.end(), key) == keys.end())
        {
            std::string expected = keys.empty() ? " (it has no settings)" : " (expected";
            for (const std::string& k : keys)
                expected += " " + k + "=";
            throw std::invalid_argument(where + ": unknown key '" + key + "'" + expected +
                                        (keys.empty() ? "" : ")"));
        }
        if (std::find(seen.begin(), seen.end(), key) != seen.end())
            throw std::invalid_argument(where + ": " + key + " given twice");
        seen.push_back(key);
        const std::string value = equals == std::string::npos ? "" : item.substr(equals + 1);
        const std::string expected = set(out.settings, out.engine, key, value);
        if (!expected.empty())
            throw std::invalid_argument(where + ": bad value '" + value + "' for " + key + " (expected " +
                                        expected + ")");
    }
    return out;
}

std::vector<std::string> engineNames()
{
    return {"frontier-euler", "frontier-rattle", "frontier-rattle4", "bullet-multibody", "bullet-si",
            "ode-quick",      "ode-direct",      "mujoco",           "mujoco-rk4"};
}

std::unique_ptr<Engine> makeEngine(const std::string& spelling, const core::Model& model,
                                   const EngineOptions& options)
{
    const auto [name, settings] = parseEngine(spelling);
    if (name == "frontier-euler")
        return makeFrontier(model, core::IntegratorKind::Euler, settings);
    if (name == "frontier-rattle")
        return makeFrontier(model, core::IntegratorKind::Rattle, settings);
    if (name == "frontier-rattle4")
        return makeFrontier(model, core::IntegratorKind::Rattle4, settings);
    if (name == "bullet-multibody")
        return makeBulletMultibody(model);
    if (name == "bullet-si")
        return makeBulletSequentialImpulses(model, settings);
    if (name == "ode-quick")
        return makeOde(model, true, settings);
    if (name == "ode-direct")
        return makeOde(model, false);
    if (name == "mujoco")
        return makeMujoco(model, MujocoIntegrator::Euler, options, settings);
    return makeMujoco(model, MujocoIntegrator::Rk4, options, settings); // parseEngine knows no other
}

} // namespace frontier::peers
