// render/png_io.cpp: RGBA PNG writing (atomic: temporary file, then rename) and reading, with libpng.
#include "render/renderer.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <png.h>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

namespace frontier::render
{
namespace
{

std::string errnoText(int error)
{
    return std::strerror(error);
}

} // namespace

void writePng(const std::string& path, const Image& image)
{
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() !=
            static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4)
    {
        throw std::runtime_error("writePng: " + path +
                                 ": image is empty or its pixel buffer has the wrong size");
    }
    // The temporary file lives next to the target so that rename() is atomic.
    std::string temp = path + ".tmp-XXXXXX";
    const int fd = mkstemp(temp.data());
    if (fd < 0)
    {
        throw std::runtime_error("writePng: cannot create " + path + ": " + errnoText(errno));
    }
    (void)fchmod(fd, 0644); // mkstemp makes 0600; a rendered frame is not a secret
    FILE* file = fdopen(fd, "wb");
    if (file == nullptr)
    {
        const int error = errno;
        close(fd);
        unlink(temp.c_str());
        throw std::runtime_error("writePng: cannot write " + path + ": " + errnoText(error));
    }

    png_image png;
    std::memset(&png, 0, sizeof(png));
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(image.width);
    png.height = static_cast<png_uint_32>(image.height);
    png.format = PNG_FORMAT_RGBA;
    png.flags = PNG_IMAGE_FLAG_FAST; // no filter search, zlib level 3
    const int ok = png_image_write_to_stdio(&png, file, 0, image.rgba.data(), 0, nullptr);
    std::string reason = ok ? std::string() : std::string(png.message);
    png_image_free(&png);

    int error = 0;
    if (ok && std::fflush(file) != 0)
    {
        error = errno;
    }
    if (std::fclose(file) != 0 && ok && error == 0)
    {
        error = errno;
    }
    if (ok && error == 0 && std::rename(temp.c_str(), path.c_str()) != 0)
    {
        error = errno;
    }
    if (!ok || error != 0)
    {
        unlink(temp.c_str());
        throw std::runtime_error("writePng: cannot write " + path + ": " + (ok ? errnoText(error) : reason));
    }
}

Image readPng(const std::string& path)
{
    png_image png;
    std::memset(&png, 0, sizeof(png));
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&png, path.c_str()))
    {
        const std::string reason = png.message;
        png_image_free(&png);
        throw std::runtime_error("readPng: cannot read " + path + ": " + reason);
    }
    png.format = PNG_FORMAT_RGBA;
    Image image;
    image.width = static_cast<int>(png.width);
    image.height = static_cast<int>(png.height);
    image.rgba.resize(PNG_IMAGE_SIZE(png));
    if (!png_image_finish_read(&png, nullptr, image.rgba.data(), 0, nullptr))
    {
        const std::string reason = png.message;
        png_image_free(&png);
        throw std::runtime_error("readPng: cannot decode " + path + ": " + reason);
    }
    png_image_free(&png);
    return image;
}

} // namespace frontier::render
