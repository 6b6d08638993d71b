#include "support/TempDir.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cctype>

namespace rad::test {

namespace {

// The running test as "Suite.Name", with anything but letters and digits
// (parameterised tests contain '/') turned into '_'.
std::string currentTestName() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "no-test";
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-') c = '_';
    return name;
}

}  // namespace

TempDir::TempDir() {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("radiosity-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) +
             "-" + currentTestName());
    std::filesystem::remove_all(path_);  // left over from an earlier process with the same id
    std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
}

}  // namespace rad::test
