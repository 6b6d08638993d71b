#include "cli/ProgressLines.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

namespace rad::cli {

std::string progressLine(const std::string& label, const SolveProgress& p, double elapsed) {
    std::ostringstream out;
    out.setf(std::ios::fixed);
    // Whole percent, rounded down: 100% only at the end.
    const int percent = p.fraction >= 1.0 ? 100 : std::clamp(int(std::floor(100.0 * p.fraction)), 0, 99);
    out << label << ": " << percent << '%';
    if (p.fraction >= 1.0) {
        out.precision(1);
        out << " in " << elapsed << " s";
    } else if (p.secondsLeft) {
        out << ", about " << std::max(1L, std::lround(*p.secondsLeft)) << " s left";
    }
    if (!p.line.empty()) out << " (" << p.line << ')';
    return out.str();
}

std::optional<std::string> ProgressLines::line(const SolveProgress& p, double elapsed) {
    if (!(elapsed > 1.0)) return std::nullopt;
    if (p.fraction < 1.0 && printedAt_ && elapsed - *printedAt_ < 1.0) return std::nullopt;
    printedAt_ = elapsed;
    return progressLine(label_, p, elapsed);
}

Engine::Progress progressOnStderr(const std::string& label) {
    auto lines = std::make_shared<ProgressLines>(label);
    const auto start = std::chrono::steady_clock::now();
    return [lines, start](const SolveProgress& p) {
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (const std::optional<std::string> line = lines->line(p, elapsed)) std::fprintf(stderr, "%s\n", line->c_str());
    };
}

}  // namespace rad::cli
