#pragma once
// A fresh empty directory under the system temporary directory, removed with
// everything in it when the object goes out of scope.

#include <filesystem>
#include <string>

namespace rad::test {

class TempDir {
  public:
    // Named after the process, a per-process counter and the running gtest
    // test, so parallel and repeated tests never share a directory.
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

  private:
    std::filesystem::path path_;
};

}  // namespace rad::test
