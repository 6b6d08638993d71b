// How the CLI prints warnings (app/cli/Warnings.h): one line each, and a kind
// that fires at many objects as its largest case and a count.

#include <gtest/gtest.h>

#include <string>

#include "cli/Warnings.h"

namespace rad::cli {
namespace {

int lines(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

TEST(Warnings, FewArePrintedOneLineEach) {
    testing::internal::CaptureStderr();
    printWarnings({{"energy_guard", "at 'a'", {"a"}, 1.2}, {"memory_limit", "stopped", {}, 0.3}});
    const std::string out = testing::internal::GetCapturedStderr();
    EXPECT_EQ(out, "warning: at 'a'\nwarning: stopped\n");
}

TEST(Warnings, ManyOfOneKindPrintTheLargestAndACount) {
    std::vector<Warning> w;
    for (int i = 0; i < 10; ++i) w.push_back({"energy_guard", "at '" + std::to_string(i) + "'", {}, i == 6 ? 2.5 : 1.1});
    w.push_back({"memory_limit", "stopped", {}, 0.3});
    testing::internal::CaptureStderr();
    printWarnings(w);
    const std::string out = testing::internal::GetCapturedStderr();
    EXPECT_EQ(lines(out), 2) << out;
    EXPECT_NE(out.find("warning: at '6' (and 9 more 'energy_guard' warnings"), std::string::npos) << out;
    EXPECT_NE(out.find("warning: stopped\n"), std::string::npos) << out;
}

}  // namespace
}  // namespace rad::cli
