// fuzz/fuzz_input.h: what the fuzz targets share: the input written to a file (the loaders read
// files through io/file_util.h, as the commands do), and the one exception that is not a finding.
#pragma once

#include "io/scene.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace frontier::fuzz
{

// A directory of this process (TMPDIR/frontier-fuzz-PID; scripts/fuzz.sh gives each target a
// TMPDIR of its own in the build folder), removed at exit.
inline const std::filesystem::path& scratchDir()
{
    static const std::filesystem::path dir = []
    {
        std::filesystem::path d =
            std::filesystem::temp_directory_path() / ("frontier-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        std::atexit(
            []
            {
                std::error_code ec;
                std::filesystem::remove_all(scratchDir(), ec);
            });
        return d;
    }();
    return dir;
}

// Writes the input to scratchDir()/name (replacing the previous run's) and returns its path.
inline std::string writeInput(const std::uint8_t* data, std::size_t size, const std::string& name)
{
    const std::string path = (scratchDir() / name).string();
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out)
    {
        std::abort(); // the scratch directory is not writable: the harness, not the loader, is broken
    }
    return path;
}

// Runs `load`; an io::InputError is the loaders' documented answer to bad input (README, exit code
// 2) and is not a finding. Anything else escaping (another exception, a crash, a sanitizer report,
// a hang, memory beyond the limit) is.
template <class Load> int expectInputErrorOnly(Load&& load)
{
    try
    {
        load();
    }
    catch (const io::InputError&)
    {
    }
    return 0;
}

} // namespace frontier::fuzz
