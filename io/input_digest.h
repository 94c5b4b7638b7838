// io/input_digest.h: what a run's results depend on, as one SHA-256 digest: the scene as it is run,
// the bytes of every file its load read, and the program that runs it. `frontier batch` keeps a
// job's results only while this digest is the one its stats recorded (docs/batch.md).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace frontier::io
{

// A file a load read (recorded by io::detail::InputFileLog, io/file_util.h): its path as opened and
// the SHA-256 of its bytes (64 lower-case hex digits).
struct InputFile
{
    std::string path;
    std::string sha256;
};

// The paths of `files`, in order.
std::vector<std::string> inputPaths(const std::vector<InputFile>& files);

// SHA-256 (FIPS 180-4, computed by OpenSSL's libcrypto) of `bytes`: 64 lower-case hex digits.
std::string sha256Hex(std::string_view bytes);

// "frontier 0.1.0": the name and version `frontier --version` prints.
const std::string& frontierVersion();

// The running program: frontierVersion(), then the SHA-256 of the executable's bytes
// (/proc/self/exe) and of each of Frontier's own shared libraries it loaded (libfrontier_*, in a
// -DBUILD_SHARED_LIBS build). Computed once per process (the first call reads the files); a file
// that cannot be read counts as "unreadable". Any rebuild with other code changes it.
const std::string& programIdentity();

// The digest of a run's inputs (64 hex digits): SHA-256 over `program` (programIdentity()),
// `runText` (what is run besides files: the scene text as run, the loader's options) and the
// SHA-256 of each file in the order read. Each part is preceded by its length, so different parts
// never give the same bytes. Paths are left out: the same files reached from another folder give
// the same digest, and a file found elsewhere with other bytes changes it.
std::string inputsDigest(const std::string& program, const std::string& runText,
                         const std::vector<InputFile>& files);

} // namespace frontier::io
