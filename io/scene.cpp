// io/scene.cpp: loadScene dispatches on the file extension.
#include "io/scene.h"

#include "io/file_util.h"
#include "io/mjcf_compile.h"
#include "io/mjcf_model.h"
#include "io/sdf_model.h"
#include "io/urdf_model.h"
#include "io/yaml_scene.h"

namespace frontier::io
{

namespace
{
// Runs load() with the files it reads recorded in report->inputFiles (when a report is given).
template <typename Load> core::Model recordingInputs(LoadReport* report, const Load& load)
{
    const detail::InputFileLog reads;
    core::Model model = load();
    if (report != nullptr)
    {
        report->inputFiles = reads.files();
    }
    return model;
}

core::Model loadSceneFile(const std::string& path, const UrdfOptions& options, LoadReport* report)
{
    const std::string ext = detail::lowerExtension(path);
    if (options.keyframe && ext != ".xml")
    {
        throw InputError(path, 0, 0, "--keyframe chooses a <key> of a bare MJCF file (.xml)");
    }
    if (ext == ".urdf" ||
        (ext == ".xml" && detail::isUrdfText(path, detail::readTextFile(path, "model file"))))
    {
        if (options.keyframe)
        {
            throw InputError(path, 0, 0, "--keyframe chooses a <key> of an MJCF file; this .xml is a URDF");
        }
        return detail::loadUrdfScene(path, options, report);
    }
    if (ext == ".xml")
    {
        return detail::loadMjcfScene(path, options, report);
    }
    if (ext == ".sdf" || ext == ".world" || ext == ".model")
    {
        return detail::loadSdfScene(path, options, report);
    }
    if (ext == ".yaml" || ext == ".yml")
    {
        if (options.fixedBase || options.freeBase || options.dropHeight || !options.jointPositions.empty())
        {
            throw InputError(
                path, 0, 0,
                "--fixed-base, --free-base, --drop-height and --joint-position place a bare .urdf; a "
                "scene places its models itself (keys 'fixed', 'free_base', 'position' and "
                "'joint_positions' of each entry of 'models')");
        }
        return detail::loadYamlScene(detail::readTextFile(path, "scene file"), path, options, report);
    }
    throw InputError(
        path, 0, 0,
        "unknown scene file type '" + ext +
            "'; expected a .yaml or .yml scene, a .urdf model, an MJCF .xml model or an SDF .sdf, "
            ".world or .model file");
}
} // namespace

core::Model loadScene(const std::string& path, const UrdfOptions& options, LoadReport* report)
{
    return recordingInputs(report, [&]() { return loadSceneFile(path, options, report); });
}

core::Model loadSceneFromString(const std::string& yamlText, const std::string& sourceName,
                                const UrdfOptions& options, LoadReport* report)
{
    return recordingInputs(report,
                           [&]() { return detail::loadYamlScene(yamlText, sourceName, options, report); });
}

} // namespace frontier::io
