// app/run_command.cpp: `frontier run`: one scene, or several as a batch (app/run_one.h runs each).
#include "app/commands.h"
#include "app/job_board.h"
#include "app/outputs.h"
#include "app/progress.h"
#include "app/run_one.h"
#include "io/scene.h"
#include "run/run_loop.h"

#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>

namespace frontier::app
{

int runCommand(const RunOptions& options)
{
    std::vector<JobOutputs> outputs;
    try
    {
        outputs = planOutputs(options.scenes, {options.trajectory, options.stats, options.frames,
                                               options.video, options.joints, options.contacts});
        if (!options.video.empty() && options.frames.empty())
        {
            throw io::InputError(options.video, 0, 0, "--video needs --frames (the frames it is made from)");
        }
        if (options.scenes.size() > 1 && !options.video.empty())
        {
            std::filesystem::create_directories(options.video);
        }
    }
    catch (const io::InputError& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitBadInput;
    }
    run::installInterruptHandlers();
    const bool terminal = !options.quiet && stderrIsTerminal();
    if (options.scenes.size() == 1)
    {
        std::string summary, error;
        bool shown = false;
        const int code = runOne(
            options, options.scenes.front(), outputs.front(), options.jobs,
            [&](const std::string& text)
            {
                if (terminal)
                {
                    std::fprintf(stderr, "\r\033[K%s", text.c_str());
                    shown = true;
                }
            },
            summary, error);
        if (shown)
        {
            std::fprintf(stderr, "\r\033[K");
        }
        if (!options.quiet && !summary.empty())
        {
            std::printf("%s\n", summary.c_str());
        }
        if (!error.empty())
        {
            std::cerr << "frontier: " << error << "\n";
        }
        return code;
    }
    // A batch: scenes in parallel, one progress line each; a failing job does not stop the others.
    std::vector<std::string> names;
    for (const std::string& scene : options.scenes)
    {
        names.push_back(jobName(scene));
    }
    return runBatch(names, options.jobs, options.quiet,
                    [&](std::size_t job, const std::function<void(const std::string&)>& status,
                        std::string& summary, std::string& error) {
                        return runOne(options, options.scenes[job], outputs[job], 1, status, summary, error);
                    });
}

} // namespace frontier::app
