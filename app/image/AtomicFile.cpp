#include "image/AtomicFile.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <system_error>

namespace rad {
namespace {

struct CloseFile {
    void operator()(std::FILE* f) const { std::fclose(f); }
};

[[noreturn]] void fail(const std::string& path, const std::string& what, int error) {
    std::string message = path + ": " + what;
    if (error != 0) message += std::string(" (") + std::strerror(error) + ")";
    throw std::runtime_error(message);
}

}  // namespace

void writeFileAtomically(const std::string& path, std::string_view bytes) {
    // Beside the target, so that the rename stays on one file system.
    const std::string tmp = path + ".tmp";
    std::unique_ptr<std::FILE, CloseFile> file(std::fopen(tmp.c_str(), "wb"));
    if (!file) fail(path, "cannot write", errno);
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file.get()) == bytes.size();
    const int writeError = errno;
    // fclose flushes: its failure is a failed write too.
    const bool closed = std::fclose(file.release()) == 0;
    const int closeError = errno;
    std::error_code ignored;
    if (!written || !closed) {
        std::filesystem::remove(tmp, ignored);
        fail(path, "cannot write", written ? closeError : writeError);
    }
    std::error_code renamed;
    std::filesystem::rename(tmp, path, renamed);
    if (renamed) {
        std::filesystem::remove(tmp, ignored);
        throw std::runtime_error(path + ": cannot replace (" + renamed.message() + ")");
    }
}

}  // namespace rad
