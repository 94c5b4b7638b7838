// app/outputs.cpp: output paths of single and batch jobs.
#include "app/outputs.h"

#include "app/frames.h"
#include "io/atomic_file.h"
#include "io/scene.h"

#include <filesystem>
#include <map>
#include <set>
#include <utility>

namespace frontier::app
{

namespace
{
namespace fs = std::filesystem;

// The path an output will have, for comparing: symbolic links of its folders resolved, "." and
// ".." removed, so two spellings of one file compare equal.
fs::path canonicalOutput(const std::string& path)
{
    std::error_code error;
    const fs::path absolute = fs::absolute(fs::path(path), error);
    const fs::path canonical = fs::weakly_canonical(absolute, error);
    return error ? absolute.lexically_normal() : canonical;
}

} // namespace

void checkOutputPath(const std::string& flag, const std::string& path, const std::vector<std::string>& inputs,
                     bool folder)
{
    std::error_code error;
    if (folder)
    {
        if (fs::exists(fs::symlink_status(path, error)) && !fs::is_directory(path, error))
        {
            throw io::InputError(path, 0, 0, flag + " names a folder, and this is not one");
        }
    }
    else if (const std::string problem = io::outputPathProblem(path); !problem.empty())
    {
        throw io::InputError(path, 0, 0, flag + ": " + problem);
    }
    checkInputsKept({{flag, path, folder, ""}}, inputs);
}

std::vector<OutputPath> outputPathsOf(const JobOutputs& out)
{
    std::vector<OutputPath> paths;
    const std::pair<const char*, const std::string*> files[] = {
        {"--trajectory", &out.trajectory}, {"--stats", &out.stats}, {"--joints", &out.joints},
        {"--contacts", &out.contacts},     {"--video", &out.video}, {"--frames", &out.frames}};
    for (const auto& [flag, path] : files)
    {
        if (!path->empty())
        {
            paths.push_back({flag, *path, path == &out.frames, ""});
        }
    }
    for (const auto& [flag, path] : {files[0], files[2], files[3]})
    {
        if (!path->empty())
        {
            paths.push_back({flag, failedPath(*path), false, "a failed run's rows"});
        }
    }
    return paths;
}

void checkInputsKept(const std::vector<OutputPath>& outputs, const std::vector<std::string>& inputs)
{
    std::error_code error;
    for (const OutputPath& out : outputs)
    {
        if (!fs::exists(out.path, error))
        {
            continue; // a new path: no input is there
        }
        for (const std::string& input : inputs)
        {
            if (!out.folder && io::replacedInput(out.path, {input}) == input)
            {
                throw io::InputError(out.path, 0, 0,
                                     out.flag +
                                         (out.role.empty()
                                              ? " names the input "
                                              : " keeps " + out.role + " in " + out.path + ", the input ") +
                                         input + ": the run would replace the file it reads");
            }
            const fs::path file(input);
            if (out.folder && isFramesFolderFile(file.filename().string()) &&
                fs::equivalent(file.parent_path().empty() ? fs::path(".") : file.parent_path(), out.path,
                               error))
            {
                throw io::InputError(out.path, 0, 0,
                                     out.flag + " names the folder of the input " + input +
                                         ": the run would replace or remove that file (frames and " +
                                         cIncompleteMarker + " are its own)");
            }
        }
    }
}

void removeStaleOutputTemporaries(const JobOutputs& out)
{
    for (const OutputPath& path : outputPathsOf(out))
    {
        if (!path.folder && path.role.empty())
        {
            io::removeStaleTemporariesOf(path.path);
        }
    }
}

namespace
{
// Outputs are checked before the run starts (README "Exit codes"): each must be a regular file or
// a new path (io::outputPathProblem), none may be one of the inputs (the run would replace the
// file it reads), and no two may be one file (the last renamed into place would win). `written`:
// the files of the jobs planned so far, with the flag that names each.
void checkOutputs(const JobOutputs& job, const std::vector<std::string>& inputs,
                  std::map<fs::path, std::string>& written)
{
    for (const OutputPath& out : outputPathsOf(job))
    {
        if (!out.role.empty())
        {
            continue;
        }
        checkOutputPath(out.flag, out.path, inputs, out.folder);
        const auto [at, added] = written.emplace(canonicalOutput(out.path), out.flag);
        if (!added)
        {
            throw io::InputError(out.path, 0, 0,
                                 at->second + " and " + out.flag + " would write the same file");
        }
    }
}
} // namespace

std::string jobName(const std::string& inputPath)
{
    return std::filesystem::path(inputPath).stem().string();
}

std::vector<JobOutputs> planOutputs(const std::vector<std::string>& inputs, const JobOutputs& given)
{
    std::map<std::filesystem::path, std::string> written;
    if (inputs.size() == 1)
    {
        checkOutputs(given, inputs, written);
        return {given};
    }
    std::vector<JobOutputs> out;
    std::set<std::string> seen;
    auto inFolder = [](const std::string& folder, const std::string& name)
    { return folder.empty() ? std::string() : (std::filesystem::path(folder) / name).string(); };
    for (const std::string& input : inputs)
    {
        const std::string name = jobName(input);
        if (!seen.insert(name).second)
        {
            throw io::InputError(input, 0, 0,
                                 "two inputs of the batch are named '" + name +
                                     "': their output files would collide");
        }
        JobOutputs job;
        job.trajectory = inFolder(given.trajectory, name + ".csv");
        job.stats = inFolder(given.stats, name + ".json");
        job.frames = inFolder(given.frames, name);
        job.video = inFolder(given.video, name + ".mp4");
        job.joints = inFolder(given.joints, name + ".joints.csv");
        job.contacts = inFolder(given.contacts, name + ".contacts.csv");
        checkOutputs(job, inputs, written);
        out.push_back(job);
    }
    return out;
}

} // namespace frontier::app
