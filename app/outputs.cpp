// app/outputs.cpp: output paths of single and batch jobs.
#include "app/outputs.h"

#include "io/scene.h"

#include <filesystem>
#include <map>
#include <set>
#include <utility>

namespace frontier::app
{

namespace
{
// Two files at one path would overwrite each other (the last one renamed into place wins), so
// the run is refused before it starts. `written`: the files of the jobs planned so far, with the
// flag that names each.
void checkDistinctFiles(const JobOutputs& job, std::map<std::filesystem::path, std::string>& written)
{
    const std::pair<const char*, const std::string*> files[] = {{"--trajectory", &job.trajectory},
                                                                {"--stats", &job.stats},
                                                                {"--joints", &job.joints},
                                                                {"--contacts", &job.contacts},
                                                                {"--video", &job.video}};
    for (const auto& [flag, path] : files)
    {
        if (path->empty())
        {
            continue;
        }
        const auto [at, added] = written.emplace(std::filesystem::path(*path).lexically_normal(), flag);
        if (!added)
        {
            throw io::InputError(*path, 0, 0, at->second + " and " + flag + " would write the same file");
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
        checkDistinctFiles(given, written);
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
        checkDistinctFiles(job, written);
        out.push_back(job);
    }
    return out;
}

} // namespace frontier::app
