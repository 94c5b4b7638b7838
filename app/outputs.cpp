// app/outputs.cpp: output paths of single and batch jobs.
#include "app/outputs.h"

#include "io/scene.h"

#include <filesystem>
#include <set>

namespace frontier::app
{

std::string jobName(const std::string& inputPath)
{
    return std::filesystem::path(inputPath).stem().string();
}

std::vector<JobOutputs> planOutputs(const std::vector<std::string>& inputs, const JobOutputs& given)
{
    if (inputs.size() == 1)
    {
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
        out.push_back({inFolder(given.trajectory, name + ".csv"), inFolder(given.stats, name + ".json"),
                       inFolder(given.frames, name), inFolder(given.video, name + ".mp4")});
    }
    return out;
}

} // namespace frontier::app
