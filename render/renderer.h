// render/renderer.h: public API of the offscreen OSMesa renderer.
#pragma once

#include "core/model.h"
#include "core/state.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace frontier::render
{

struct RenderOptions
{
    int width = 640;     // pixels
    int height = 480;    // pixels
    bool caption = true; // scene name and simulated time in a corner
    // Direction the sunlight travels, world frame (need not be unit). Unset: from high above
    // (55 deg elevation), slightly to the side of the default camera.
    std::optional<core::Vec3> lightDirection;
    int msaaSamples = 4;      // anti-aliasing samples per pixel (<= 1: none); clamped to GL_MAX_SAMPLES
    int shadowMapSize = 1024; // texels per side of the light's shadow map (fitted to the bodies)
};

struct Image
{
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba; // width*height*4, row 0 at the top
};

// Draws a model's bodies with lighting, shadows and a checker floor into an RGBA image, using
// its own OSMesa (software OpenGL 3.3 core) context. A Renderer must be used by one thread at a
// time; several Renderers may render concurrently on different threads.
//
// Camera: Model::camera when camera.automatic is false; otherwise framed once, then kept fixed so
// that an animation does not jitter: around every pose of the moving bodies over a whole run
// (frameRun), or else around the moving bodies (and their drop onto the floor) in the state passed
// to frameFrom or to the FIRST render() call.
class Renderer
{
  public:
    // Throws std::runtime_error when no OSMesa context can be made.
    Renderer(const core::Model& model, const RenderOptions& options);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Throws std::invalid_argument when the state does not match the model.
    Image render(const core::State& state);

    // Fixes the camera framing (and floor placement) from this state, as the first render() would.
    // Several renderers framed from the same state draw any frame identically, so the frames of
    // one run can be rendered in parallel. No effect once framed.
    void frameFrom(const core::State& state);

    // Fixes the camera framing (and floor placement) so that the bodies stay inside the image in
    // every one of `states` (the frames of a whole run): the tightest view of every pose the moving
    // bodies take. Throws std::invalid_argument when a state does not match the model. No effect
    // once framed or when `states` is empty.
    void frameRun(const std::vector<core::State>& states);

    // The unit direction the light travels, world frame.
    core::Vec3 lightDirection() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Writes an RGBA PNG atomically (temporary file, then rename). Throws std::runtime_error.
void writePng(const std::string& path, const Image& image);
Image readPng(const std::string& path);

} // namespace frontier::render
