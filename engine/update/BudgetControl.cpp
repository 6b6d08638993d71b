#include "update/BudgetControl.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rad {

void BudgetControl::record(std::size_t linkUpdates, double seconds) {
    if (!std::isfinite(seconds) || seconds < 0.0) return;
    frames_.emplace_back(double(linkUpdates), seconds);
    if (frames_.size() > kWindow) frames_.pop_front();
}

std::optional<std::pair<double, double>> BudgetControl::fit() const {
    // No frame yet: the fixed part of a frame (traversal, snapshot) is
    // unknown, and it is most of a small budget's frame.
    if (frames_.empty()) return std::nullopt;
    double n = 0.0, sx = 0.0, sy = 0.0;
    for (const auto& [x, y] : frames_) {
        n += 1.0;
        sx += x;
        sy += y;
    }
    const double mx = sx / n, my = sy / n;
    double sxx = 0.0, sxy = 0.0;
    for (const auto& [x, y] : frames_) {
        sxx += (x - mx) * (x - mx);
        sxy += (x - mx) * (y - my);
    }
    if (sxx > 0.0 && sxy > 0.0 && frames_.size() >= 4) {
        const double cost = sxy / sxx;
        const double overhead = my - cost * mx;
        if (overhead >= 0.0) return std::pair{overhead, cost};
    }
    // Too little spread in the update counts to separate the two terms: the
    // first guess of the cost, and the median of what it leaves of the
    // frames as overhead (a median: the first frame of a drag, slower than
    // the rest, must not hold the budget at 0 for a window of frames; the
    // lower one, so that it does not from the second frame either).
    std::vector<double> rest;
    for (const auto& [x, y] : frames_) rest.push_back(y - initialCost_ * x);
    const auto median = rest.begin() + std::ptrdiff_t((rest.size() - 1) / 2);
    std::nth_element(rest.begin(), median, rest.end());
    return std::pair{std::max(0.0, *median), initialCost_};
}

std::pair<double, double> BudgetControl::model() const { return fit().value_or(std::pair{0.0, initialCost_}); }

double BudgetControl::spread() const {
    // Over fewer than six frames the 80th percentile is the slowest: the
    // first frame of a drag (its traversal twice the later ones' in
    // `office`) held the budget at 0 for five frames of a 30 fps target
    // that took 20 ms each.
    if (frames_.size() < kSpreadFrames) return 0.0;
    const auto [overhead, cost] = model();
    std::vector<double> above;
    for (const auto& [x, y] : frames_) above.push_back(y - overhead - cost * x);
    const auto at = above.begin() + std::ptrdiff_t(above.size() * 4 / 5);
    std::nth_element(above.begin(), at, above.end());
    return std::max(0.0, *at);
}

std::size_t BudgetControl::budgetFor(double targetSeconds) const {
    const auto model = fit();
    if (!model) return 0;  // the first frame measures the fixed part
    // Frames of one budget vary (what a link update changes, and the
    // meshing of it): the budget is the one whose frames come within the
    // target four times in five, not on average.
    const auto [fitted, cost] = *model;
    const double overhead = fitted + spread();
    if (!(cost > 0.0) || !(targetSeconds > overhead)) return 0;
    const double budget = (targetSeconds - overhead) / cost;
    return budget >= 1e15 ? std::size_t(1e15) : static_cast<std::size_t>(budget);
}

}  // namespace rad
