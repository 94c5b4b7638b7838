// io/scene.h: public API of scene loading (YAML scenes with yaml-cpp, URDF models with urdfdom).
#pragma once

#include "core/model.h"

#include <stdexcept>
#include <string>

namespace frontier::io
{

// Bad input: names the file, line and column (1-based, 0 when unknown) and what was expected.
// what() is the full message "FILE:LINE:COL: error: TEXT".
class InputError : public std::runtime_error
{
  public:
    InputError(std::string file, int line, int column, const std::string& message);
    const std::string& file() const { return mFile; }
    int line() const { return mLine; }
    int column() const { return mColumn; }
    // The text without the location prefix.
    const std::string& message() const { return mMessage; }

  private:
    std::string mFile;
    std::string mMessage;
    int mLine;
    int mColumn;
};

// Loads a .yaml/.yml scene or a .urdf model (a URDF alone is dropped onto a floor with defaults).
// Throws InputError on any bad input (scenes/README.md lists the rules).
core::Model loadScene(const std::string& path);
// Parses scene YAML text; sourceName is used in messages and to resolve relative files.
core::Model loadSceneFromString(const std::string& yamlText, const std::string& sourceName);

} // namespace frontier::io
