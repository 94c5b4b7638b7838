// io/mjcf_compile.h: an MJCF file through MuJoCo's own compiler (private to io/).
//
// Frontier reads MJCF as MuJoCo reads it: defaults and classes, <include>, angle units, fromto,
// euler sequences, inertia from geoms and meshes are all MuJoCo's compiler's work (Debian's
// libmujoco 2.2). The file's text goes to the compiler with one change: autolimits="true" unless
// the file sets it, as MuJoCo 2.3 and later default it (a `range` limits its joint without
// `limited="true"`), so that files written for current MuJoCo load.
#pragma once

#include "io/mujoco_util.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace frontier::io::detail
{

// The elements of an MJCF file Frontier does not model, where each first appears.
struct MjcfUnsupported
{
    std::string file;
    int line = 0;
};

struct CompiledMjcf
{
    MujocoModel model;
    // Element name ("tendon", "equality", ...) -> where it first appears in the file or its includes.
    std::map<std::string, MjcfUnsupported> unsupported;
    std::vector<std::string> warnings; // the compiler's, "FILE: warning: ..."
};

// While it lives, MuJoCo's messages about the model of `path` are this load's: a warning goes to
// `warnings` ("FILE: warning: MuJoCo: ..."), an error (MuJoCo's default handler prints it and ends
// the process; its default warning handler writes MUJOCO_LOG.TXT into the working folder) throws
// InputError naming the file. MuJoCo's handlers are global: one load at a time holds them (a
// mutex), and the ones before are restored.
class MujocoMessages
{
  public:
    MujocoMessages(const std::string& path, std::vector<std::string>& warnings);
    ~MujocoMessages();
    MujocoMessages(const MujocoMessages&) = delete;
    MujocoMessages& operator=(const MujocoMessages&) = delete;

  private:
    void (*mWarning)(const char*);
    void (*mError)(const char*);
};

// Throws InputError naming the file and, where the compiler says it, the line. Call it with a
// MujocoMessages alive.
CompiledMjcf compileMjcf(const std::string& path);

// True when the XML text's root element is <robot> (a URDF saved as .xml).
bool isUrdfText(const std::string& path, const std::string& text);

} // namespace frontier::io::detail
