// io/input_digest.cpp: SHA-256 with OpenSSL's EVP interface, the program's identity, a run's digest.
#include "io/input_digest.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <link.h>
#include <memory>
#include <openssl/evp.h>
#include <stdexcept>

namespace frontier::io
{

namespace
{

// Incremental SHA-256.
class Sha256
{
  public:
    Sha256() : mContext(EVP_MD_CTX_new(), &EVP_MD_CTX_free)
    {
        if (!mContext || EVP_DigestInit_ex(mContext.get(), EVP_sha256(), nullptr) != 1)
        {
            throw std::runtime_error("SHA-256 is not available from OpenSSL");
        }
    }
    void add(std::string_view bytes) { EVP_DigestUpdate(mContext.get(), bytes.data(), bytes.size()); }
    // A part of a message made of several: its length (decimal) and a newline, then its bytes.
    void addPart(std::string_view bytes)
    {
        add(std::to_string(bytes.size()) + "\n");
        add(bytes);
    }
    std::string hex()
    {
        unsigned char digest[EVP_MAX_MD_SIZE];
        unsigned int size = 0;
        EVP_DigestFinal_ex(mContext.get(), digest, &size);
        std::string out;
        char pair[3];
        for (unsigned int k = 0; k < size; ++k)
        {
            std::snprintf(pair, sizeof pair, "%02x", digest[k]);
            out += pair;
        }
        return out;
    }

  private:
    std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> mContext;
};

// The SHA-256 of a file's bytes, read in blocks (an executable can be larger than the input limit
// of io/file_util.h, and is no input of a scene); "unreadable" when it cannot be read.
std::string fileDigest(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
        return "unreadable";
    }
    Sha256 hash;
    char buffer[1 << 16];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0)
    {
        hash.add(std::string_view(buffer, static_cast<std::size_t>(in.gcount())));
    }
    return in.bad() ? "unreadable" : hash.hex();
}

// Frontier's shared libraries loaded by this process (none when they are linked in statically).
std::vector<std::string> frontierSharedLibraries()
{
    std::vector<std::string> paths;
    dl_iterate_phdr(
        [](dl_phdr_info* info, std::size_t, void* data)
        {
            const std::string name = info->dlpi_name == nullptr ? "" : info->dlpi_name;
            if (name.find("/libfrontier_") != std::string::npos)
            {
                static_cast<std::vector<std::string>*>(data)->push_back(name);
            }
            return 0;
        },
        &paths);
    return paths;
}

std::string computeProgramIdentity()
{
    // File names, not paths: the same build installed elsewhere (another node) is the same program.
    std::string text = frontierVersion() + "\nexecutable " + fileDigest("/proc/self/exe") + "\n";
    for (const std::string& library : frontierSharedLibraries())
    {
        text += "library " + std::filesystem::path(library).filename().string() + " " + fileDigest(library) +
                "\n";
    }
    return text;
}

} // namespace

std::vector<std::string> inputPaths(const std::vector<InputFile>& files)
{
    std::vector<std::string> paths;
    paths.reserve(files.size());
    for (const InputFile& file : files)
    {
        paths.push_back(file.path);
    }
    return paths;
}

std::string sha256Hex(std::string_view bytes)
{
    Sha256 hash;
    hash.add(bytes);
    return hash.hex();
}

const std::string& frontierVersion()
{
    static const std::string version = std::string("frontier ") + FRONTIER_VERSION;
    return version;
}

const std::string& programIdentity()
{
    static const std::string identity = computeProgramIdentity(); // thread-safe, once per process
    return identity;
}

std::string inputsDigest(const std::string& program, const std::string& runText,
                         const std::vector<InputFile>& files)
{
    Sha256 hash;
    hash.addPart("frontier inputs digest 1"); // the layout of what follows
    hash.addPart(program);
    hash.addPart(runText);
    hash.addPart(std::to_string(files.size()));
    for (const InputFile& file : files)
    {
        hash.addPart(file.sha256);
    }
    return hash.hex();
}

} // namespace frontier::io
