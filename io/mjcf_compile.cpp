// io/mjcf_compile.cpp: MJCF text to MuJoCo's compiled model (io/mjcf_compile.h).
#include "io/mjcf_compile.h"

#include "io/file_util.h"
#include "io/scene.h"
#include "io/xml_scan.h"

#include <cstring>
#include <filesystem>
#include <mujoco/mujoco.h>
#include <mutex>
#include <regex>
#include <set>

namespace frontier::io::detail
{

namespace
{

// Elements whose meaning Frontier does not model (io/mjcf_model.cpp warns when the compiled
// model holds any).
const std::set<std::string, std::less<>> cUnsupportedElements = {"tendon", "equality", "sensor", "pair",
                                                                 "hfield"};

// One XML text of the model: the file, or a file it includes.
struct MjcfText
{
    std::string path;
    std::string text;
    std::vector<std::size_t> compilerEnds; // offsets just past "<compiler" of each <compiler> tag
    bool setsAutolimits = false;
    std::size_t rootEnd = std::string::npos; // offset just past the root start tag's '>'
    std::string root;                        // the root element's name
    std::vector<std::string> meshFiles;      // the `file` of each <mesh>
    std::optional<std::string> meshdir;      // <compiler meshdir>
};

void scanText(MjcfText& source, std::vector<std::string>& includes,
              std::map<std::string, MjcfUnsupported>& unsupported)
{
    XmlDepthCheck depth(source.path, source.text, "an MJCF file needs a few dozen");
    scanXmlTags(
        source.path, source.text, "MJCF file", "the <mujoco> element",
        [&](const XmlTag& tag)
        {
            depth.visit(tag);
            if (tag.end)
            {
                return;
            }
            if (source.root.empty())
            {
                source.root = std::string(tag.name);
                const std::size_t after = static_cast<std::size_t>(
                    tag.attributes.data() + tag.attributes.size() - source.text.data());
                source.rootEnd = tag.empty ? std::string::npos : source.text.find('>', after);
                source.rootEnd = source.rootEnd == std::string::npos ? source.rootEnd : source.rootEnd + 1;
            }
            if (tag.name == "compiler")
            {
                source.compilerEnds.push_back(tag.offset + std::strlen("<compiler"));
                source.setsAutolimits = source.setsAutolimits || xmlAttribute(tag.attributes, "autolimits");
                if (std::optional<std::string> meshdir = xmlAttribute(tag.attributes, "meshdir"))
                {
                    source.meshdir = std::move(meshdir);
                }
            }
            if (tag.name == "mesh")
            {
                if (std::optional<std::string> file = xmlAttribute(tag.attributes, "file"))
                {
                    source.meshFiles.push_back(std::move(*file));
                }
            }
            if (tag.name == "include")
            {
                if (const std::optional<std::string> file = xmlAttribute(tag.attributes, "file"))
                {
                    includes.push_back(*file);
                }
            }
            if (cUnsupportedElements.count(tag.name) && !unsupported.count(std::string(tag.name)))
            {
                unsupported[std::string(tag.name)] = {source.path, positionOf(source.text, tag.offset).line};
            }
        });
}

// The file and the files it includes (MuJoCo resolves an include against the model's folder).
std::vector<MjcfText> readTexts(const std::string& path, std::map<std::string, MjcfUnsupported>& unsupported)
{
    std::vector<MjcfText> texts;
    std::vector<std::string> pending;
    texts.push_back(
        {path, readTextFile(path, "MJCF file"), {}, false, std::string::npos, {}, {}, std::nullopt});
    scanText(texts.back(), pending, unsupported);
    std::set<std::string> seen = {path};
    while (!pending.empty())
    {
        const std::string file = resolvePath(directoryOf(path), pending.back());
        pending.pop_back();
        if (!seen.insert(file).second || !std::filesystem::exists(file))
        {
            continue; // the compiler names a missing include with its line
        }
        texts.push_back({file,
                         readTextFile(file, "MJCF include file"),
                         {},
                         false,
                         std::string::npos,
                         {},
                         {},
                         std::nullopt});
        scanText(texts.back(), pending, unsupported);
    }
    return texts;
}

// autolimits="true" where the model does not choose (io/mjcf_compile.h): inserted into its first
// <compiler> tag, or as a <compiler> element on the root element's line, so no line number moves.
void defaultAutolimits(std::vector<MjcfText>& texts)
{
    for (const MjcfText& source : texts)
    {
        if (source.setsAutolimits)
        {
            return;
        }
    }
    for (MjcfText& source : texts)
    {
        if (!source.compilerEnds.empty())
        {
            source.text.insert(source.compilerEnds.front(), " autolimits=\"true\"");
            return;
        }
    }
    MjcfText& main = texts.front();
    if (main.rootEnd != std::string::npos)
    {
        main.text.insert(main.rootEnd, "<compiler autolimits=\"true\"/>");
    }
}

// The line a compiler message names ("line = 25", "line 23", the XML parser's "Line number=4"), 0
// when it names none. A message about an included file names the line of the <include> last.
int messageLine(const std::string& message)
{
    static const std::regex cLine("[Ll]ine(?: number)? ?=? ?([0-9]+)");
    int line = 0;
    for (auto match = std::sregex_iterator(message.begin(), message.end(), cLine);
         match != std::sregex_iterator(); ++match)
    {
        const int named = std::stoi((*match)[1].str());
        line = named > 0 ? named : line;
    }
    return line;
}

// The compiler's message on one line: its parts joined by "; ".
std::string oneLine(const std::string& message)
{
    std::string joined;
    std::size_t start = 0;
    while (start < message.size())
    {
        std::size_t end = message.find('\n', start);
        end = end == std::string::npos ? message.size() : end;
        const std::string part = message.substr(start, end - start);
        if (part.find_first_not_of(" \t\r") != std::string::npos)
        {
            joined += (joined.empty() ? "" : "; ") + part;
        }
        start = end + 1;
    }
    return joined;
}

// The mesh files the compiler read, as inputs of the load (io/file_util.h's InputFileLog): each in
// the model's folder + meshdir, as MuJoCo finds it.
void recordMeshFiles(const std::vector<MjcfText>& texts)
{
    std::string meshdir;
    for (const MjcfText& source : texts)
    {
        meshdir = source.meshdir.value_or(meshdir);
    }
    const std::string folder = resolvePath(directoryOf(texts.front().path), meshdir);
    for (const MjcfText& source : texts)
    {
        for (const std::string& file : source.meshFiles)
        {
            const std::string path = resolvePath(folder, file);
            if (std::filesystem::is_regular_file(path))
            {
                checkInputFile(path, "mesh file");
            }
        }
    }
}

} // namespace

namespace
{
std::mutex gMujocoMessagesMutex;
// The load holding MuJoCo's handlers (MujocoMessages).
const std::string* gPath = nullptr;
std::vector<std::string>* gWarnings = nullptr;

void onMujocoWarning(const char* message)
{
    gWarnings->push_back(diagnostic(*gPath, {}, "warning", std::string("MuJoCo: ") + message));
}

[[noreturn]] void onMujocoError(const char* message)
{
    throw InputError(*gPath, 0, 0, std::string("MuJoCo cannot use this model: ") + message);
}
} // namespace

MujocoMessages::MujocoMessages(const std::string& path, std::vector<std::string>& warnings)
{
    gMujocoMessagesMutex.lock();
    gPath = &path;
    gWarnings = &warnings;
    mWarning = mju_user_warning;
    mError = mju_user_error;
    mju_user_warning = onMujocoWarning;
    mju_user_error = onMujocoError;
}

MujocoMessages::~MujocoMessages()
{
    mju_user_warning = mWarning;
    mju_user_error = mError;
    gPath = nullptr;
    gWarnings = nullptr;
    gMujocoMessagesMutex.unlock();
}

bool isUrdfText(const std::string& path, const std::string& text)
{
    std::string root;
    scanXmlTags(path, text, "XML file", "a <mujoco> or <robot> element",
                [&](const XmlTag& tag)
                {
                    if (root.empty() && !tag.end)
                    {
                        root = std::string(tag.name);
                    }
                });
    return root == "robot";
}

CompiledMjcf compileMjcf(const std::string& path)
{
    CompiledMjcf compiled;
    std::vector<MjcfText> texts = readTexts(path, compiled.unsupported);
    if (texts.front().root != "mujoco")
    {
        throw InputError(path, 1, 0,
                         "expected an MJCF file, whose root element is <mujoco>, got <" + texts.front().root +
                             ">" + (texts.front().root == "robot" ? " (a URDF: name it .urdf)" : ""));
    }
    defaultAutolimits(texts);
    // The texts go to the compiler through its virtual file system, which names files without their
    // folder: a second file of the same name is left for the compiler to read from disk.
    const MujocoVfs vfs(new mjVFS);
    mj_defaultVFS(vfs.get());
    for (const MjcfText& source : texts)
    {
        if (mj_makeEmptyFileVFS(vfs.get(), source.path.c_str(), static_cast<int>(source.text.size())) == 0)
        {
            const int index = mj_findFileVFS(vfs.get(), source.path.c_str());
            std::memcpy(vfs->filedata[index], source.text.data(), source.text.size());
        }
    }
    std::string message(4096, '\0');
    compiled.model.reset(
        mj_loadXML(path.c_str(), vfs.get(), message.data(), static_cast<int>(message.size())));
    message.resize(std::strlen(message.c_str()));
    if (!compiled.model)
    {
        throw InputError(path, messageLine(message), 0,
                         "MuJoCo's MJCF compiler (libmujoco " + std::string(mj_versionString()) +
                             ") refused it: " + oneLine(message));
    }
    recordMeshFiles(texts);
    if (!message.empty())
    {
        compiled.warnings.push_back(
            diagnostic(path, {messageLine(message), 0}, "warning", "MuJoCo's compiler: " + oneLine(message)));
    }
    return compiled;
}

} // namespace frontier::io::detail
