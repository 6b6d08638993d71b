// Progress lines on stderr (cli/ProgressLines.h): which reports become lines
// and how they read, and radiosity-cli solve printing them for a long solve
// and not for a quick one.

#include <gtest/gtest.h>

#include <cctype>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/ProgressLines.h"
#include "support/Cli.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using cli::ProgressLines;
using cli::progressLine;

SolveProgress report(double fraction, std::optional<double> left = std::nullopt,
                     std::string line = "round 2: sweep 6, change 0.013") {
    return SolveProgress{std::move(line), fraction, left};
}

TEST(ProgressLines, Wording) {
    EXPECT_EQ(progressLine("solve", report(0.42, 3.2), 2.0),
              "solve: 42%, about 3 s left (round 2: sweep 6, change 0.013)");
    EXPECT_EQ(progressLine("solve", report(0.42), 2.0), "solve: 42% (round 2: sweep 6, change 0.013)");
    // Under a second left still reads as one; 100% is for the end only.
    EXPECT_EQ(progressLine("solve", report(0.999, 0.2, ""), 2.0), "solve: 99%, about 1 s left");
    EXPECT_EQ(progressLine("frame 3 full solve", report(1.0, 0.0, "done: 4 rounds, 19 sweeps"), 4.31),
              "frame 3 full solve: 100% in 4.3 s (done: 4 rounds, 19 sweeps)");
}

TEST(ProgressLines, NoneInTheFirstSecondThenAtMostOneASecond) {
    ProgressLines lines("solve");
    EXPECT_FALSE(lines.line(report(0.1), 0.2));
    EXPECT_FALSE(lines.line(report(0.3, 2.0), 0.9));
    EXPECT_TRUE(lines.line(report(0.4, 1.5), 1.1));
    EXPECT_FALSE(lines.line(report(0.5, 1.2), 1.6));
    EXPECT_FALSE(lines.line(report(0.6, 1.0), 2.05));
    EXPECT_TRUE(lines.line(report(0.7, 0.8), 2.15));
    // The end is always said, even right after another line.
    const auto last = lines.line(report(1.0, 0.0, "done: 4 rounds, 19 sweeps"), 2.3);
    ASSERT_TRUE(last);
    EXPECT_EQ(*last, "solve: 100% in 2.3 s (done: 4 rounds, 19 sweeps)");
}

TEST(ProgressLines, NoneForASolveUnderASecond) {
    ProgressLines lines("solve");
    for (double t = 0.0; t < 0.95; t += 0.1) EXPECT_FALSE(lines.line(report(t), t));
    EXPECT_FALSE(lines.line(report(1.0, 0.0), 0.95));
}

// A progress line: "solve: N%..." (parsed by hand: <regex> trips GCC 12's
// maybe-uninitialized warning under the sanitizers' -Werror build).
bool isProgress(const std::string& l) {
    const std::string head = "solve: ";
    if (l.rfind(head, 0) != 0) return false;
    std::size_t i = head.size();
    while (i < l.size() && std::isdigit(static_cast<unsigned char>(l[i]))) ++i;
    return i > head.size() && i < l.size() && l[i] == '%';
}
bool contains(const std::string& l, const std::string& part) { return l.find(part) != std::string::npos; }

// The progress lines of radiosity-cli's output, in order.
std::vector<std::string> progressLines(const std::string& output) {
    std::vector<std::string> lines;
    std::istringstream in(output);
    for (std::string l; std::getline(in, l);)
        if (isProgress(l)) lines.push_back(l);
    return lines;
}

TEST(ProgressLines, CliPrintsPercentAndTimeLeftForALongSolve) {
    // The office at a fine epsilon takes 2 to 4 s (Release, two cores).
    const auto r = test::runCli("solve " + test::shellQuote(test::sourcePath("scenes/office.gltf")) +
                                " --epsilon 3e-5");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::vector<std::string> lines = progressLines(r.output);
    ASSERT_GE(lines.size(), 2u) << r.output;
    bool withEstimate = false;
    int previous = -1;
    for (const std::string& l : lines) {
        withEstimate = withEstimate || (contains(l, "%, about ") && contains(l, " s left (") && l.back() == ')');
        const int percent = std::stoi(l.substr(l.find(' ') + 1));
        EXPECT_GE(percent, previous) << l;
        previous = percent;
    }
    EXPECT_TRUE(withEstimate) << r.output;
    const std::string& end = lines.back();
    EXPECT_TRUE(end.rfind("solve: 100% in ", 0) == 0 && contains(end, " s (done: ") && end.back() == ')') << end;
}

TEST(ProgressLines, CliPrintsNoneForAQuickSolve) {
    const auto r = test::runCli("solve " + test::shellQuote(test::kCornell) + " --epsilon 1e-2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(progressLines(r.output).empty()) << r.output;
}

}  // namespace
}  // namespace rad
