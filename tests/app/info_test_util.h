// tests/app/info_test_util.h: reading `frontier info --json`.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace frontier::app::test
{

// True when the list of body-name pairs holds {a, b} in either order.
inline bool hasPair(const nlohmann::json& pairs, const std::string& a, const std::string& b)
{
    for (const auto& pair : pairs)
    {
        const std::string x = pair.at(0).get<std::string>();
        const std::string y = pair.at(1).get<std::string>();
        if ((x == a && y == b) || (x == b && y == a))
        {
            return true;
        }
    }
    return false;
}

} // namespace frontier::app::test
