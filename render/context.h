// render/context.h: one OSMesa OpenGL core-profile context with its colour buffer.
#pragma once

#include <cstdint>
#include <vector>

struct osmesa_context;

namespace frontier::render
{

// Owns an OSMesa context (GL 3.3 core or later; llvmpipe gives 4.5 core) bound to a
// width x height RGBA buffer whose row 0 is the top of the image. A context belongs to one
// thread at a time; makeCurrent() binds it to the calling thread.
class Context
{
  public:
    // Throws std::runtime_error when the context cannot be created.
    Context(int width, int height);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    // Throws std::runtime_error on failure.
    void makeCurrent();
    // The default framebuffer's pixels (valid after glFinish), top row first.
    const std::vector<std::uint8_t>& pixels() const { return buffer_; }
    int width() const { return width_; }
    int height() const { return height_; }

  private:
    osmesa_context* context_ = nullptr;
    int width_;
    int height_;
    std::vector<std::uint8_t> buffer_;
};

} // namespace frontier::render
