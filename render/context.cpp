// render/context.cpp: OSMesa context creation (core profile 3.3).
#define GL_GLEXT_PROTOTYPES 1
#include "render/context.h"

#include <GL/osmesa.h>
#include <mutex>
#include <stdexcept>
#include <string>

namespace frontier::render
{
namespace
{
// Context creation and destruction touch Mesa's process-wide state; serialise them.
std::mutex& lifetimeMutex()
{
    static std::mutex m;
    return m;
}
} // namespace

Context::Context(int width, int height) : width_(width), height_(height)
{
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    {
        throw std::runtime_error("render: image size " + std::to_string(width) + "x" +
                                 std::to_string(height) + " is out of range (1..16384)");
    }
    buffer_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4, 0);
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_STENCIL_BITS,
                              8,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              3,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              3,
                              0};
    {
        const std::lock_guard<std::mutex> lock(lifetimeMutex());
        context_ = OSMesaCreateContextAttribs(attributes, nullptr);
    }
    if (context_ == nullptr)
    {
        throw std::runtime_error("render: cannot create an OSMesa OpenGL 3.3 core-profile context");
    }
    makeCurrent();
}

Context::~Context()
{
    const std::lock_guard<std::mutex> lock(lifetimeMutex());
    if (OSMesaGetCurrentContext() == context_)
    {
        OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    }
    OSMesaDestroyContext(context_);
}

void Context::makeCurrent()
{
    if (OSMesaGetCurrentContext() == context_)
    {
        return;
    }
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_))
    {
        throw std::runtime_error("render: OSMesaMakeCurrent failed");
    }
    OSMesaPixelStore(OSMESA_Y_UP, 0); // row 0 of buffer_ is the top of the image
}

} // namespace frontier::render
