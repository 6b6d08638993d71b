#pragma once
// Target frame time to link-update budget (paper sec. 6.1). The cost unit is
// one link update; frames are modelled as t = overhead + cost * updates, fitted
// by least squares over the last frames, so the budget follows the machine.

#include <cstddef>
#include <deque>
#include <utility>

namespace rad {

class BudgetControl {
public:
    // A first guess of the cost of one link update (from the initial solve).
    explicit BudgetControl(double secondsPerLink) : initialCost_(secondsPerLink) {}

    void record(std::size_t linkUpdates, double seconds);
    // Link updates that fit in the target frame time (0 when even the fixed
    // overhead does not).
    std::size_t budgetFor(double targetSeconds) const;

private:
    std::pair<double, double> fit() const;  // (overhead, cost)
    static constexpr std::size_t kWindow = 32;
    double initialCost_;
    std::deque<std::pair<double, double>> frames_;  // (updates, seconds)
};

}  // namespace rad
