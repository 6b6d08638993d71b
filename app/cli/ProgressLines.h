#pragma once
// Progress of long solves on stderr: every command that solves (solve,
// animate, sweep) prints these, one line each, and only for a solve that
// has run for more than a second:
//
//   solve: 42%, about 3 s left (round 2: sweep 6, change 0.013)
//   solve: 100% in 4.2 s (done: 3 rounds, 87 sweeps)

#include <optional>
#include <string>
#include <utility>

#include "radiosity/Engine.h"

namespace rad::cli {

// Which of a solve's progress reports become lines: none in its first
// second, then at most one a second, and the last (fraction 1) when the
// solve took more than a second.
class ProgressLines {
  public:
    explicit ProgressLines(std::string label) : label_(std::move(label)) {}
    // The line to print for a report `elapsed` seconds into the solve, if any.
    std::optional<std::string> line(const SolveProgress& progress, double elapsed);

  private:
    std::string label_;
    std::optional<double> printedAt_;
};

// "LABEL: 42%, about 3 s left (LINE)"; "LABEL: 42% (LINE)" without an
// estimate; "LABEL: 100% in 4.2 s (LINE)" at the end.
std::string progressLine(const std::string& label, const SolveProgress& progress, double elapsed);

// Engine::solve's callback printing a ProgressLines' lines on stderr, timed
// from its creation.
Engine::Progress progressOnStderr(const std::string& label);

}  // namespace rad::cli
