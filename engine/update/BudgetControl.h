#pragma once
// Target frame time to link-update budget (paper sec. 6.1). The cost unit is
// one link update; frames are modelled as t = overhead + cost * updates, fitted
// by least squares over the last frames, so the budget follows the machine.

#include <cstddef>
#include <deque>
#include <optional>
#include <utility>

namespace rad {

class BudgetControl {
public:
    // A first guess of the cost of one link update (from the initial solve).
    explicit BudgetControl(double secondsPerLink) : initialCost_(secondsPerLink) {}

    void record(std::size_t linkUpdates, double seconds);
    // Link updates that fit in the target frame time (0 when even the fixed
    // overhead does not, and before the first frame: it measures the
    // overhead, which the first guess of the cost says nothing about).
    std::size_t budgetFor(double targetSeconds) const;
    // The fitted (overhead, cost): what `updates` more would take is
    // overhead + cost * updates. Before any frame: (0, the first guess).
    std::pair<double, double> model() const;
    // How far above the model frames come: the 80th percentile of the
    // frames' time less the model's (0 before six frames).
    double spread() const;

private:
    std::optional<std::pair<double, double>> fit() const;  // (overhead, cost), none before a frame
    static constexpr std::size_t kWindow = 32;
    static constexpr std::size_t kSpreadFrames = 6;
    double initialCost_;
    std::deque<std::pair<double, double>> frames_;  // (updates, seconds)
};

}  // namespace rad
