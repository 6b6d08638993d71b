#include "update/BudgetControl.h"

#include <algorithm>
#include <cmath>

namespace rad {

void BudgetControl::record(std::size_t linkUpdates, double seconds) {
    if (!std::isfinite(seconds) || seconds < 0.0) return;
    frames_.emplace_back(double(linkUpdates), seconds);
    if (frames_.size() > kWindow) frames_.pop_front();
}

std::pair<double, double> BudgetControl::fit() const {
    double n = 0.0, sx = 0.0, sy = 0.0;
    for (const auto& [x, y] : frames_) {
        n += 1.0;
        sx += x;
        sy += y;
    }
    if (n == 0.0) return {0.0, initialCost_};
    const double mx = sx / n, my = sy / n;
    double sxx = 0.0, sxy = 0.0;
    for (const auto& [x, y] : frames_) {
        sxx += (x - mx) * (x - mx);
        sxy += (x - mx) * (y - my);
    }
    // Too little spread in the update counts to separate the two terms: all
    // of the time is charged to the updates.
    if (sxx > 0.0 && sxy > 0.0 && frames_.size() >= 4) {
        const double cost = sxy / sxx;
        const double overhead = my - cost * mx;
        if (overhead >= 0.0) return {overhead, cost};
    }
    return {0.0, sx > 0.0 ? sy / sx : initialCost_};
}

std::size_t BudgetControl::budgetFor(double targetSeconds) const {
    const auto [overhead, cost] = fit();
    if (!(cost > 0.0) || !(targetSeconds > overhead)) return 0;
    const double budget = (targetSeconds - overhead) / cost;
    return budget >= 1e15 ? std::size_t(1e15) : static_cast<std::size_t>(budget);
}

}  // namespace rad
