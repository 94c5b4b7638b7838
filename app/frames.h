// app/frames.h: frames sampled from simulated time and rendered to PNG, in parallel.
//
// Frame k shows the first state whose time is at or after k / fps (s), for every k with
// k / fps within the run. `frontier run --frames` and `frontier render` use the same rule, so a
// trajectory recorded at every step renders to the same images as the run did, pixel for pixel.
#pragma once

#include "app/job_result.h"
#include "core/model.h"
#include "core/state.h"

#include <functional>
#include <string>
#include <vector>

namespace frontier::app
{

class FrameSampler
{
  public:
    explicit FrameSampler(double fps) : mFps(fps) {}
    // True when `time` (s) reaches the next frame's time; advances past every frame it covers.
    bool due(double time);

  private:
    double mFps;
    long mNext = 0;
};

// The most frames a run or a render may write (a million PNGs at 640 x 480 take hours and hundreds
// of gigabytes; more is a typo in --fps or --duration).
inline constexpr double cMaxFrames = 1e6;

// The frames of `duration` (s) sampled at `fps` from `states` states: min(states, duration fps + 1).
// Throws io::InputError naming `source` when above cMaxFrames.
void checkFrameCount(double duration, double fps, double states, const std::string& source);

struct FrameSettings
{
    std::string folder;
    int width = 640;
    int height = 480;
    int threads = 1;
};

// The file that marks a frames folder as incomplete: written when the folder is prepared, before
// the simulation, removed after the last frame, so a folder that holds it (a run that failed, or
// was interrupted or killed before its last frame) does not look complete.
inline constexpr const char* cIncompleteMarker = "INCOMPLETE";

// Whether `name` (no folder) is a file a run writes or removes in its frames folder: a frame
// (frame_00000.png), a frame's temporary (frame_00000.png.tmp-XXXXXX), cIncompleteMarker.
bool isFramesFolderFile(const std::string& name);

// Before a run or a render: creates the folder, checks it can be written, writes cIncompleteMarker
// (as a new file: a link of that name is replaced, not written through), and removes the
// frame_*.png an earlier run left there (so it never mixes two runs' frames) and the temporaries
// of frames a killed run left.
// With a `video` to make, first checks that ffmpeg is installed. Throws io::OutputError naming
// the folder or the video.
void prepareFrameFolder(const std::string& folder, const std::string& video);

// Renders frames[k] to folder/frame_%05d.png, k = 0.., with `threads` renderers whose camera is
// framed once over all the frames (Renderer::frameRun): the bodies stay in view for the whole run,
// and the camera does not move. progress(done) is called from the calling thread. Stops early when
// a signal arrives (interruptSignal, run/run_loop.h), leaving cIncompleteMarker; removes the marker
// after the last frame. Returns the frames written. Throws io::OutputError.
std::size_t renderFrames(const core::Model& model, const std::vector<core::State>& frames,
                         const FrameSettings& settings, const std::function<void(std::size_t)>& progress);

// The message of frames stopped by `signal` after `rendered` of `total`: the folder keeps its
// cIncompleteMarker.
std::string interruptedFramesMessage(int signal, std::size_t rendered, std::size_t total,
                                     const std::string& folder);

// Assembles folder/frame_%05d.png into an MP4 (H.264, whatever the name's extension) with ffmpeg,
// which writes a temporary file (io/atomic_file.h) renamed onto `video` when it succeeded. Returns
// false when a signal arrived meanwhile (interruptSignal, passed on to ffmpeg): no file is left
// under either name. Throws io::OutputError when ffmpeg is not installed or fails.
bool assembleVideo(const std::string& folder, double fps, const std::string& video);

// What `run --frames` and `render` do with their frames: renderFrames, with "rendering D / N
// frames" to `status` as they go, then the video at `fps` when `video` is not empty
// (assembleVideo). Returns cExitOk (app/commands.h) and no error; when a signal stopped the
// rendering or the video, its interruptedExitCode (run/run_loop.h) and the error saying so. Throws
// io::OutputError.
JobResult writeFrames(const core::Model& model, const std::vector<core::State>& frames,
                      const FrameSettings& settings, double fps, const std::string& video,
                      const JobStatus& status);

} // namespace frontier::app
