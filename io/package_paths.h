// io/package_paths.h: where a URDF's mesh URIs point (package://, model://, file://, plain paths).
//
// ROS tools find `package://NAME/rest` in the package called NAME: a folder whose package.xml says
// <name>NAME</name>. Frontier looks, in this order:
//   1. each --package-path entry: `NAME=DIR` (DIR is package NAME, whatever its package.xml says),
//      a package folder, or a folder holding packages (searched cPackageSearchDepth levels down);
//   2. each entry of ROS_PACKAGE_PATH (colon-separated), the same way; for `model://` also
//      GAZEBO_MODEL_PATH, GZ_SIM_RESOURCE_PATH and IGN_GAZEBO_RESOURCE_PATH;
//   3. the URDF's own folder and its parents: one whose package.xml names NAME, or whose name is NAME;
//   4. last, `rest` relative to the URDF's folder and its parents (robot files are often shipped
//      without their package.xml, with the meshes beside them); this one is reported as a warning.
// A folder without package.xml counts as package NAME when its own name is NAME (Gazebo's model://
// folders, packages copied without their manifest).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace frontier::io::detail
{

inline constexpr int cPackageSearchDepth = 4; // folder levels searched below a package-path entry

// Where a URI was found (or why not).
struct ResolvedUri
{
    std::string path;     // the file (empty when not found)
    std::string note;     // how a last-resort match was made (step 4 above), for a warning; else ""
    std::string notFound; // when path is empty: what was missing and every place looked in
};

// A --package-path entry as PackagePaths reads it: `NAME=DIR` when a '=' follows a non-empty NAME
// without '/', else a folder (a package or a folder of packages) with an empty name.
struct PackagePathEntry
{
    std::string name;
    std::string dir;
};
PackagePathEntry splitPackagePathEntry(const std::string& entry);

class PackagePaths
{
  public:
    // packagePaths: the --package-path entries in order (DIR or NAME=DIR); the environment
    // variables are read here, once.
    explicit PackagePaths(std::vector<std::string> packagePaths);

    // Resolves `uri` written in the URDF `urdfFile`.
    ResolvedUri resolve(const std::string& uri, const std::string& urdfFile) const;

  private:
    struct Root
    {
        std::string origin; // "--package-path", "ROS_PACKAGE_PATH", ... (for messages)
        std::string name;   // NAME of a NAME=DIR entry, else ""
        std::string dir;
    };
    std::optional<std::string> findPackage(const std::string& name, bool gazeboModel) const;
    const std::map<std::string, std::string>& packagesBelow(const std::string& dir) const;
    std::string placesLooked(const std::string& name, bool gazeboModel, const std::string& urdfFile) const;

    std::vector<Root> mRoots;
    mutable std::map<std::string, std::map<std::string, std::string>> mCache; // dir -> (name -> package dir)
};

// "%20" and friends decoded (URIs in robot files are sometimes percent-encoded).
std::string percentDecoded(const std::string& text);

} // namespace frontier::io::detail
