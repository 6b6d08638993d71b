#include "update/UnsentSet.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace rad {

bool UnsentSet::join(ElementId e) {
    if (contains(e)) return false;
    cover(std::size_t(e) + 1);
    term_[e] = 0.0;  // in the sum once made
    state_[e] = kMember;
    members_.push_back(e);
    if (known_) {
        state_[e] |= kQueued;
        recount_.push_back(e);
    }
    return true;
}

void UnsentSet::clear() {
    for (ElementId e : members_) state_[e] = 0;
    members_.clear();
    recount_.clear();
    sum_ = 0.0;
    known_ = true;  // of nothing
}

void UnsentSet::mayHaveChanged(std::span<const ElementId> elements) {
    if (!known_ || members_.empty()) return;
    for (ElementId e : elements)
        if (e < state_.size() && state_[e] == kMember) {
            state_[e] |= kQueued;
            recount_.push_back(e);
        }
}

double UnsentSet::sum(const Term& term) {
    if (!known_) {
        tbb::parallel_for(std::size_t(0), members_.size(), [&](std::size_t i) {
            term_[members_[i]] = term(members_[i]);  // each member once
        });
        sum_ = 0.0;
        for (ElementId e : members_) sum_ += term_[e];
        for (ElementId e : recount_) state_[e] = kMember;
        recount_.clear();
        known_ = true;
        return sum_;
    }
    std::vector<double> terms(recount_.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, recount_.size(), 1024), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) terms[i] = term(recount_[i]);
    });
    for (std::size_t i = 0; i < recount_.size(); ++i) {
        double& kept = term_[recount_[i]];
        sum_ += terms[i] - kept;
        kept = terms[i];
        state_[recount_[i]] = kMember;
    }
    recount_.clear();
    return sum_;
}

}  // namespace rad
