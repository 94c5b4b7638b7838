// app/outputs.h: where a job's files go. One scene writes exactly the paths given; several scenes
// (a batch) treat --trajectory, --stats, --joints, --contacts and --frames as folders:
// DIR/<scene>.csv, DIR/<scene>.json, DIR/<scene>.joints.csv, DIR/<scene>.contacts.csv,
// DIR/<scene>/frame_00000.png, and --video as a folder of DIR/<scene>.mp4.
#pragma once

#include <string>
#include <vector>

namespace frontier::app
{

struct JobOutputs
{
    std::string trajectory;
    std::string stats;
    std::string frames;
    std::string video;
    std::string joints;
    std::string contacts;
};

std::string jobName(const std::string& inputPath); // file name without folder and extension

// Throws io::InputError when two inputs of a batch share a name, or when two outputs of a job are
// the same file (their files would collide).
std::vector<JobOutputs> planOutputs(const std::vector<std::string>& inputs, const JobOutputs& given);

} // namespace frontier::app
