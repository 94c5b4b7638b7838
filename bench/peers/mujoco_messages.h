// bench/peers/mujoco_messages.h: MuJoCo's message handlers taken over (engine_mujoco.cpp,
// mjcf_peers.cpp): a warning is not printed (nor written to MUJOCO_LOG.TXT) but kept, an error (by
// default: print and exit) is thrown as an EngineError.
#pragma once

#include "bench/peers/engine.h"

#include <string>
#include <vector>

namespace frontier::peers
{

// Sends MuJoCo's warnings on this thread to `messages` while it lives.
class MessageScope
{
  public:
    explicit MessageScope(std::vector<std::string>& messages);
    ~MessageScope();
    MessageScope(const MessageScope&) = delete;
    MessageScope& operator=(const MessageScope&) = delete;
};

} // namespace frontier::peers
