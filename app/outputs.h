// app/outputs.h: where a job's files go. One scene writes exactly the paths given; several scenes
// (a batch) treat --trajectory, --stats, --joints, --contacts and --frames as folders:
// DIR/<scene>.csv, DIR/<scene>.json, DIR/<scene>.joints.csv, DIR/<scene>.contacts.csv,
// DIR/<scene>/frame_00000.png, and --video as a folder of DIR/<scene>.mp4.
#pragma once

#include "io/atomic_file.h"

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

using io::failedPath; // io/atomic_file.h

// Throws io::InputError when two inputs of a batch share a name, when two outputs are the same
// file (their files would collide), when an output is one of the inputs, or when an output path is
// not a regular file or a new path (a symbolic link, a device, a fifo; a folder for a file, a file
// for --frames).
// One output path checked as planOutputs does (`folder`: --frames, a folder or a new path); throws
// io::InputError naming `flag`.
void checkOutputPath(const std::string& flag, const std::string& path, const std::vector<std::string>& inputs,
                     bool folder = false);

std::vector<JobOutputs> planOutputs(const std::vector<std::string>& inputs, const JobOutputs& given);

// A path a command writes, with the flag that names it: a file, or a folder it writes files into
// (--frames: frames and the INCOMPLETE marker, app/frames.h). `role` says what the flag keeps
// there when it is not the output itself ("a failed run's rows"), "" for the output.
struct OutputPath
{
    std::string flag;
    std::string path;
    bool folder = false;
    std::string role;
};

// The paths `out` writes: each output given, and the failedPath names of the row files.
std::vector<OutputPath> outputPathsOf(const JobOutputs& out);

// Throws io::InputError (exit 2) naming the flag, the output and the input when an output would
// replace a file the command read: a file output that is one of `inputs` (compared as files, so a
// symbolic link, a hard link or another spelling of the path counts), or a folder that holds one
// of them under a name the command writes or removes there (isFramesFolderFile). Called after the
// load (io::LoadReport::inputFiles lists every file it read: scene, URDFs, meshes and the files
// they name, CSV tables) and before anything is written.
void checkInputsKept(const std::vector<OutputPath>& outputs, const std::vector<std::string>& inputs);

// Removes the temporaries (io::removeStaleTemporariesOf) of the file outputs of `out` that a run
// killed outright (SIGKILL) left; the frames folder's are prepareFrameFolder's.
void removeStaleOutputTemporaries(const JobOutputs& out);

} // namespace frontier::app
