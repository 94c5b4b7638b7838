// io/package_paths.cpp: package://, model:// and file:// URIs to files (the search order is in
// package_paths.h).
#include "io/package_paths.h"

#include "io/file_util.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace frontier::io::detail
{

namespace fs = std::filesystem;

namespace
{

constexpr int cMaxFoldersVisited = 20000; // bounds the walk below one package-path entry

bool isDirectory(const fs::path& p)
{
    std::error_code ec;
    return fs::is_directory(p, ec);
}

bool pathExists(const fs::path& p)
{
    std::error_code ec;
    return fs::exists(p, ec);
}

// <name>...</name> of a package.xml, trimmed; "" when there is none.
std::string manifestName(const fs::path& dir)
{
    // A regular file only: a FIFO of that name would block the open (io/file_util.h).
    std::error_code ec;
    const fs::path manifest = dir / "package.xml";
    if (!fs::is_regular_file(manifest, ec))
    {
        return {};
    }
    std::ifstream in(manifest);
    if (!in)
    {
        return {};
    }
    std::string text(4096, '\0'); // the name comes first in every manifest format
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
    const std::size_t open = text.find("<name>");
    const std::size_t close = open == std::string::npos ? open : text.find("</name>", open);
    if (close == std::string::npos)
    {
        return {};
    }
    const std::string raw = text.substr(open + 6, close - open - 6);
    const std::size_t first = raw.find_first_not_of(" \t\r\n");
    const std::size_t last = raw.find_last_not_of(" \t\r\n");
    return first == std::string::npos ? std::string() : raw.substr(first, last - first + 1);
}

bool ignoredFolder(const fs::path& dir)
{
    const std::string name = dir.filename().string();
    return name.starts_with('.') || pathExists(dir / "CATKIN_IGNORE") || pathExists(dir / "COLCON_IGNORE") ||
           pathExists(dir / "AMENT_IGNORE");
}

void collectPackages(const fs::path& dir, int depth, int& visited, std::map<std::string, std::string>& out)
{
    if (++visited > cMaxFoldersVisited || ignoredFolder(dir))
    {
        return;
    }
    const std::string name = manifestName(dir);
    if (!name.empty())
    {
        out.try_emplace(name, dir.string()); // a package holds no further packages
        return;
    }
    if (depth == 0)
    {
        return;
    }
    std::error_code ec;
    std::vector<fs::path> children;
    for (fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec), end;
         !ec && it != end; it.increment(ec))
    {
        if (it->is_directory(ec) && !it->is_symlink(ec))
        {
            children.push_back(it->path());
        }
    }
    std::sort(children.begin(), children.end()); // the first of two equal names wins, deterministically
    for (const fs::path& child : children)
    {
        collectPackages(child, depth - 1, visited, out);
    }
}

std::vector<std::string> splitPathList(const char* value)
{
    std::vector<std::string> out;
    if (value == nullptr)
    {
        return out;
    }
    std::stringstream in(value);
    std::string item;
    while (std::getline(in, item, ':'))
    {
        if (!item.empty())
        {
            out.push_back(item);
        }
    }
    return out;
}

// The URDF's folder (absolute) and its parents, nearest first.
std::vector<fs::path> ancestorsOf(const std::string& urdfFile)
{
    std::error_code ec;
    fs::path dir = fs::absolute(fs::path(urdfFile), ec).parent_path().lexically_normal();
    std::vector<fs::path> out;
    while (!dir.empty())
    {
        out.push_back(dir);
        if (dir == dir.root_path() || !dir.has_relative_path())
        {
            break;
        }
        dir = dir.parent_path();
    }
    return out;
}

bool gazeboRoot(const std::string& origin)
{
    return origin == "GAZEBO_MODEL_PATH" || origin == "GZ_SIM_RESOURCE_PATH" ||
           origin == "IGN_GAZEBO_RESOURCE_PATH";
}

} // namespace

std::string percentDecoded(const std::string& text)
{
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i)
    {
        if (text[i] == '%' && i + 2 < text.size() && std::isxdigit(static_cast<unsigned char>(text[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(text[i + 2])))
        {
            out += static_cast<char>(std::stoi(text.substr(i + 1, 2), nullptr, 16));
            i += 2;
        }
        else
        {
            out += text[i];
        }
    }
    return out;
}

PackagePathEntry splitPackagePathEntry(const std::string& entry)
{
    const std::size_t eq = entry.find('=');
    if (eq != std::string::npos && eq > 0 && entry.find('/') > eq)
    {
        return {entry.substr(0, eq), entry.substr(eq + 1)};
    }
    return {"", entry};
}

PackagePaths::PackagePaths(std::vector<std::string> packagePaths)
{
    for (const std::string& entry : packagePaths)
    {
        PackagePathEntry split = splitPackagePathEntry(entry);
        mRoots.push_back({"--package-path", std::move(split.name), std::move(split.dir)});
    }
    for (const char* variable :
         {"ROS_PACKAGE_PATH", "GAZEBO_MODEL_PATH", "GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH"})
    {
        for (const std::string& dir : splitPathList(std::getenv(variable)))
        {
            mRoots.push_back({variable, "", dir});
        }
    }
}

const std::map<std::string, std::string>& PackagePaths::packagesBelow(const std::string& dir) const
{
    const auto it = mCache.find(dir);
    if (it != mCache.end())
    {
        return it->second;
    }
    std::map<std::string, std::string>& packages = mCache[dir];
    int visited = 0;
    if (isDirectory(dir))
    {
        collectPackages(fs::path(dir), cPackageSearchDepth, visited, packages);
    }
    return packages;
}

std::optional<std::string> PackagePaths::findPackage(const std::string& name, bool gazeboModel) const
{
    // 1 and 2: the package-path entries and the environment, each first by manifest, then by folder name.
    for (const Root& root : mRoots)
    {
        if (gazeboRoot(root.origin) && !gazeboModel)
        {
            continue;
        }
        if (!root.name.empty())
        {
            if (root.name == name)
            {
                return root.dir;
            }
            continue;
        }
        const std::map<std::string, std::string>& packages = packagesBelow(root.dir);
        if (const auto it = packages.find(name); it != packages.end())
        {
            return it->second;
        }
        const fs::path dir(root.dir);
        if (dir.filename() == name && isDirectory(dir))
        {
            return root.dir;
        }
        if (isDirectory(dir / name))
        {
            return (dir / name).string();
        }
    }
    return std::nullopt;
}

std::string PackagePaths::placesLooked(const std::string& name, bool gazeboModel,
                                       const std::string& urdfFile) const
{
    std::string out;
    for (const Root& root : mRoots)
    {
        if (gazeboRoot(root.origin) && !gazeboModel)
        {
            continue;
        }
        out += (out.empty() ? "" : ", ") + root.origin + " " + (root.name.empty() ? "" : root.name + "=") +
               root.dir;
    }
    if (out.empty())
    {
        out = "no --package-path given, ROS_PACKAGE_PATH unset";
    }
    const std::vector<fs::path> ancestors = ancestorsOf(urdfFile);
    out += "; then the URDF's folder and its parents (" +
           (ancestors.empty() ? "" : ancestors.front().string()) + " up to /) for a package.xml naming '" +
           name + "' or a folder of that name";
    return out;
}

namespace
{

// A plain path or file:// URI, against the URDF's folder.
ResolvedUri resolveFileUri(const std::string& uri, const std::string& baseDir)
{
    ResolvedUri out;
    std::string path = uri;
    if (uri.starts_with("file://"))
    {
        path = percentDecoded(uri.substr(7));
    }
    else if (uri.find("://") != std::string::npos)
    {
        out.notFound =
            "unsupported URI scheme in '" + uri + "'; expected a file path, package://, model:// or file://";
        return out;
    }
    path = resolvePath(baseDir, path);
    if (!pathExists(path))
    {
        out.notFound = "no such file '" + path + "'";
        return out;
    }
    out.path = path;
    return out;
}

// package://NAME/PATH or model://NAME/PATH taken apart; `notFound` says why it names no file
// inside its package.
struct PackageUri
{
    std::string name;
    std::string rest; // PATH
    std::string notFound;
};

PackageUri packageUriParts(const std::string& uri, bool package)
{
    PackageUri out;
    std::string body = percentDecoded(uri.substr(package ? 10 : 8));
    if (body.starts_with('/'))
    {
        body.erase(0, 1); // package:///NAME/PATH, as some exporters write it, is package://NAME/PATH
    }
    const std::size_t slash = body.find('/');
    out.name = body.substr(0, slash);
    out.rest = slash == std::string::npos ? std::string() : body.substr(slash + 1);
    if (out.name.empty() || out.rest.empty())
    {
        out.notFound =
            "'" + uri + "' names no file; expected " + (package ? "package" : "model") + "://NAME/PATH";
        return out;
    }
    const fs::path inside = fs::path(out.rest).lexically_normal();
    if (out.name == "." || out.name == ".." || inside.has_root_path() ||
        (!inside.empty() && *inside.begin() == ".."))
    {
        out.notFound = "'" + uri + "' leads out of its package folder; expected " +
                       (package ? "package" : "model") +
                       "://NAME/PATH with PATH inside the package (no '..' " + "above it, not absolute)";
    }
    return out;
}

// The file in the package's folder `dir`.
ResolvedUri resolveInPackage(const PackageUri& parts, const std::string& dir)
{
    ResolvedUri out;
    const fs::path path = fs::path(dir) / parts.rest;
    if (!pathExists(path))
    {
        out.notFound = "package '" + parts.name + "' is " + dir + ", which has no '" + parts.rest + "'";
        return out;
    }
    out.path = path.lexically_normal().string();
    return out;
}

} // namespace

ResolvedUri PackagePaths::resolve(const std::string& uri, const std::string& urdfFile) const
{
    const bool package = uri.starts_with("package://");
    const bool model = uri.starts_with("model://");
    if (!package && !model)
    {
        return resolveFileUri(uri, directoryOf(urdfFile));
    }
    const PackageUri parts = packageUriParts(uri, package);
    ResolvedUri out;
    if (!parts.notFound.empty())
    {
        out.notFound = parts.notFound;
        return out;
    }
    const std::string& name = parts.name;
    std::optional<std::string> dir = findPackage(name, model);
    const std::vector<fs::path> ancestors = ancestorsOf(urdfFile);
    for (std::size_t i = 0; !dir && i < ancestors.size(); ++i) // 3: the URDF's own package
    {
        if (manifestName(ancestors[i]) == name || ancestors[i].filename() == name)
        {
            dir = ancestors[i].string();
        }
    }
    if (dir)
    {
        return resolveInPackage(parts, *dir);
    }
    for (const fs::path& ancestor : ancestors) // 4: the files beside the URDF
    {
        const fs::path path = ancestor / parts.rest;
        if (pathExists(path))
        {
            out.path = path.lexically_normal().string();
            out.note = "package '" + name + "' was not found (" + placesLooked(name, model, urdfFile) +
                       "); using the files found beside the URDF, in " + ancestor.string();
            return out;
        }
    }
    out.notFound = "package '" + name + "' not found; looked in: " + placesLooked(name, model, urdfFile) +
                   "; and found no '" + parts.rest +
                   "' beside the URDF. Give --package-path DIR (the package, or a folder of packages) or "
                   "--package-path " +
                   name + "=DIR";
    return out;
}

} // namespace frontier::io::detail
