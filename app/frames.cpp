// app/frames.cpp: frame sampling, parallel rendering, video assembly.
#include "app/frames.h"

#include "app/commands.h"
#include "io/atomic_file.h"
#include "io/scene.h"
#include "render/renderer.h"
#include "run/run_loop.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <mutex>
#include <spawn.h>
#include <string_view>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

extern char** environ;

namespace frontier::app
{

bool FrameSampler::due(double time)
{
    constexpr double cTimeTolerance = 1e-9; // s: round-off of accumulated step times
    const double reach = time + cTimeTolerance;
    if (reach < static_cast<double>(mNext) / mFps)
    {
        return false;
    }
    // Past every frame time k / fps <= reach in one jump (a long gap between states, or a high
    // fps, must not count frame by frame), then to the first frame after it: the division decides,
    // as it did when counting, so the frames picked do not depend on the jump.
    const double ticks = std::min(std::floor(reach * mFps), 1e18); // within a long
    mNext = std::max(mNext, static_cast<long>(ticks) - 1);
    while (static_cast<double>(mNext) <= ticks + 1.0 && static_cast<double>(mNext) / mFps <= reach)
    {
        ++mNext;
    }
    return true;
}

void checkFrameCount(double duration, double fps, double states, const std::string& source)
{
    const double frames = std::min(states, std::floor(duration * fps) + 1.0);
    if (frames > cMaxFrames)
    {
        char text[200];
        std::snprintf(text, sizeof text, "%.6g s at --fps %.6g makes %.6g frames; at most %.0e (lower --fps)",
                      duration, fps, frames, cMaxFrames);
        throw io::InputError(source, 0, 0, text);
    }
}

namespace
{
std::string framePath(const std::string& folder, std::size_t index)
{
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%05zu.png", index);
    return folder + name;
}

// frame_ followed by digits and .png: the names framePath writes.
bool isFrameName(std::string_view name)
{
    constexpr std::string_view cPrefix = "frame_";
    constexpr std::string_view cSuffix = ".png";
    if (name.size() <= cPrefix.size() + cSuffix.size() || !name.starts_with(cPrefix) ||
        !name.ends_with(cSuffix))
    {
        return false;
    }
    const std::string_view digits =
        name.substr(cPrefix.size(), name.size() - cPrefix.size() - cSuffix.size());
    return std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
}

bool onPath(const std::string& program);
} // namespace

bool isFramesFolderFile(const std::string& name)
{
    const std::string base = io::temporaryBase(name);
    return isFrameName(base.empty() ? name : base) || name == cIncompleteMarker;
}

void prepareFrameFolder(const std::string& folder, const std::string& video)
{
    if (!video.empty() && !onPath("ffmpeg"))
    {
        throw io::OutputError(video + ": ffmpeg is not installed, so no video can be made; install it "
                                      "(`apt-get install ffmpeg`, or scripts/install-deps.sh --with-extras) "
                                      "or leave out --video");
    }
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (error || !std::filesystem::is_directory(folder))
    {
        throw io::OutputError(folder + ": cannot create the frames folder" +
                              (error ? " (" + error.message() + ")" : std::string(" (not a folder)")));
    }
    // Written as a new file: a link named like the marker is replaced, never written through.
    io::writeNewFile(folder + "/" + cIncompleteMarker,
                     "frontier was writing the frames of this folder and stopped before the last one "
                     "(failed, interrupted or killed): they are incomplete\n");
    io::removeStaleTemporaries(folder, [](const std::string& base) { return isFrameName(base); });
    std::vector<std::filesystem::path> stale;
    for (const std::filesystem::directory_entry& entry : std::filesystem::directory_iterator(folder, error))
    {
        if (isFrameName(entry.path().filename().string()))
        {
            stale.push_back(entry.path());
        }
    }
    for (const std::filesystem::path& path : stale)
    {
        if (!std::filesystem::remove(path, error) || error)
        {
            throw io::OutputError(path.string() + ": cannot remove an earlier run's frame" +
                                  (error ? " (" + error.message() + ")" : std::string()));
        }
    }
}

namespace
{
// The frames shared out among render threads: each thread takes the next frame not taken, until
// none is left, a signal arrives, or a thread fails (the others stop then).
class FrameQueue
{
  public:
    FrameQueue(const core::Model& model, const std::vector<core::State>& frames,
               const FrameSettings& settings)
        : mModel(model), mFrames(frames), mSettings(settings)
    {
    }

    // One render thread's work, with its own renderer.
    void work()
    {
        try
        {
            render::RenderOptions options;
            options.width = mSettings.width;
            options.height = mSettings.height;
            render::Renderer renderer(mModel, options);
            renderer.frameRun(mFrames); // every frame's bodies in view
            for (std::size_t k = mNext++; k < mFrames.size() && run::interruptSignal() == 0; k = mNext++)
            {
                render::writePng(framePath(mSettings.folder, k), renderer.render(mFrames[k]));
                ++mDone;
            }
        }
        catch (const std::exception& e)
        {
            std::lock_guard<std::mutex> lock(mFailureMutex);
            if (mFailure.empty())
            {
                mFailure = e.what();
            }
            mNext = mFrames.size(); // stop the others
        }
    }

    std::size_t done() const { return mDone; }
    // The first thread's failure ("": none); read after the threads ended.
    const std::string& failure() const { return mFailure; }

  private:
    const core::Model& mModel;
    const std::vector<core::State>& mFrames;
    const FrameSettings& mSettings;
    std::atomic<std::size_t> mNext{0};
    std::atomic<std::size_t> mDone{0};
    std::mutex mFailureMutex;
    std::string mFailure;
};

// Runs queue.work() on `threads` threads, progress(done) from this one every 50 ms until they end.
void renderOnThreads(FrameQueue& queue, int threads, const std::function<void(std::size_t)>& progress)
{
    std::atomic<int> running{threads};
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
    {
        pool.emplace_back(
            [&]()
            {
                queue.work();
                --running;
            });
    }
    while (running > 0)
    {
        if (progress)
        {
            progress(queue.done());
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    for (std::thread& t : pool)
    {
        t.join();
    }
}
} // namespace

std::size_t renderFrames(const core::Model& model, const std::vector<core::State>& frames,
                         const FrameSettings& settings, const std::function<void(std::size_t)>& progress)
{
    const std::string marker = settings.folder + "/" + cIncompleteMarker; // prepareFrameFolder's
    if (frames.empty())
    {
        std::filesystem::remove(marker);
        return 0;
    }
    FrameQueue queue(model, frames, settings);
    renderOnThreads(queue, std::max(1, std::min<int>(settings.threads, static_cast<int>(frames.size()))),
                    progress);
    if (!queue.failure().empty())
    {
        throw io::OutputError(queue.failure());
    }
    const std::size_t done = queue.done();
    if (progress)
    {
        progress(done);
    }
    if (done == frames.size())
    {
        std::filesystem::remove(marker);
    }
    return done;
}

namespace
{
bool onPath(const std::string& program)
{
    const char* path = std::getenv("PATH");
    if (path == nullptr)
    {
        return false;
    }
    std::string paths = path;
    std::size_t start = 0;
    while (start <= paths.size())
    {
        const std::size_t end = std::min(paths.find(':', start), paths.size());
        const std::filesystem::path candidate =
            std::filesystem::path(paths.substr(start, end - start)) / program;
        std::error_code error;
        if (std::filesystem::is_regular_file(candidate, error))
        {
            return true;
        }
        start = end + 1;
    }
    return false;
}

// Runs `argv` (argv[0] found on the PATH, stdin from /dev/null) and returns its wait status. A
// signal that arrives meanwhile (interruptSignal) is passed on to it, and it is waited for (killed
// when it has not ended cKillAfterPolls polls later).
int runChild(std::vector<std::string> argv, const std::string& what)
{
    std::vector<char*> pointers;
    for (std::string& arg : argv)
    {
        pointers.push_back(arg.data());
    }
    pointers.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    pid_t pid = 0;
    const int spawned = ::posix_spawnp(&pid, pointers[0], &actions, nullptr, pointers.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0)
    {
        throw io::OutputError(what + ": cannot start " + argv[0] + ": " + std::strerror(spawned));
    }
    constexpr int cKillAfterPolls = 500; // 5 s at a poll every 10 ms
    int status = 0;
    int pollsSinceSignal = -1; // -1: no signal passed on yet
    while (true)
    {
        const pid_t ended = ::waitpid(pid, &status, WNOHANG);
        if (ended == pid || (ended < 0 && errno != EINTR))
        {
            return ended == pid ? status : -1;
        }
        if (const int signal = run::interruptSignal(); signal != 0 && pollsSinceSignal < 0)
        {
            ::kill(pid, signal);
            pollsSinceSignal = 0;
        }
        else if (pollsSinceSignal >= 0 && ++pollsSinceSignal == cKillAfterPolls)
        {
            ::kill(pid, SIGKILL);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
}
} // namespace

bool assembleVideo(const std::string& folder, double fps, const std::string& video)
{
    if (!onPath("ffmpeg")) // prepareFrameFolder checked before the run; this catches a removal since
    {
        throw io::OutputError(video +
                              ": ffmpeg is not installed, so no video was made (the PNG frames are in " +
                              folder + "); install it with `apt-get install ffmpeg`");
    }
    char rate[32];
    std::snprintf(rate, sizeof rate, "%.9g", fps);
    // ffmpeg writes the temporary file (named as AtomicFile names them, so a rerun finds it after
    // a kill), told the container with -f (the temporary's name has no .mp4 at its end); renamed
    // onto `video` when it succeeded, removed otherwise.
    io::AtomicFile file(video);
    const std::vector<std::string> argv = {"ffmpeg",
                                           "-nostdin",
                                           "-y",
                                           "-loglevel",
                                           "error",
                                           "-framerate",
                                           rate,
                                           "-i",
                                           folder + "/frame_%05d.png",
                                           "-vf",
                                           "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                           "-pix_fmt",
                                           "yuv420p",
                                           "-f",
                                           "mp4",
                                           "file:" + file.tempPath()};
    const int status = runChild(argv, video);
    if (run::interruptSignal() != 0)
    {
        return false; // the temporary goes with `file`
    }
    if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    {
        std::string command;
        for (const std::string& arg : argv)
        {
            command += (command.empty() ? "" : " ") + arg;
        }
        throw io::OutputError(video + ": ffmpeg failed (" + command + ")");
    }
    file.commit();
    return true;
}

std::string interruptedFramesMessage(int signal, std::size_t rendered, std::size_t total,
                                     const std::string& folder)
{
    return "interrupted by " + run::signalName(signal) + " after " + std::to_string(rendered) + " of " +
           std::to_string(total) + " frames; " + folder + "/" + cIncompleteMarker +
           " marks the folder as incomplete";
}

JobResult writeFrames(const core::Model& model, const std::vector<core::State>& frames,
                      const FrameSettings& settings, double fps, const std::string& video,
                      const JobStatus& status)
{
    const std::size_t rendered = renderFrames(
        model, frames, settings,
        [&](std::size_t done)
        { status("rendering " + std::to_string(done) + " / " + std::to_string(frames.size()) + " frames"); });
    if (const int signal = run::interruptSignal(); signal != 0)
    {
        return failedJob(run::interruptedExitCode(signal),
                         interruptedFramesMessage(signal, rendered, frames.size(), settings.folder));
    }
    if (!video.empty() && !assembleVideo(settings.folder, fps, video))
    {
        const int signal = run::interruptSignal();
        return failedJob(run::interruptedExitCode(signal),
                         "interrupted by " + run::signalName(signal) + " while ffmpeg made " + video +
                             ": no video written (the frames in " + settings.folder + " are complete)");
    }
    return {};
}

} // namespace frontier::app
