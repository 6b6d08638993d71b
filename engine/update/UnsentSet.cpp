#include "update/UnsentSet.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace rad {

bool UnsentSet::join(ElementId e) {
    if (contains(e)) return false;
    cover(std::size_t(e) + 1);
    term_[e] = 0.0;  // in the sum once made
    members_.push_back(e);
    if (known_) recount_.push_back(e);
    return true;
}

void UnsentSet::clear() {
    for (ElementId e : members_) term_[e] = kNotMember;
    members_.clear();
    recount_.clear();
    sum_ = 0.0;
    known_ = true;  // of nothing
}

void UnsentSet::mayHaveChanged(std::span<const ElementId> elements) {
    if (known_ && !members_.empty())
        recount_.insert(recount_.end(), elements.begin(), elements.end());
}

double UnsentSet::sum(const Term& term) {
    if (!known_) {
        tbb::parallel_for(std::size_t(0), members_.size(), [&](std::size_t i) {
            term_[members_[i]] = term(members_[i]);  // each member once
        });
        sum_ = 0.0;
        for (ElementId e : members_) sum_ += term_[e];
        recount_.clear();
        known_ = true;
        return sum_;
    }
    std::erase_if(recount_, [&](ElementId e) { return !contains(e); });
    // An element listed twice gets the same term twice: the second replaces
    // the first by itself, and adds nothing.
    std::vector<double> terms(recount_.size());
    tbb::parallel_for(std::size_t(0), recount_.size(),
                      [&](std::size_t i) { terms[i] = term(recount_[i]); });
    for (std::size_t i = 0; i < recount_.size(); ++i) {
        double& kept = term_[recount_[i]];
        sum_ += terms[i] - kept;
        kept = terms[i];
    }
    recount_.clear();
    return sum_;
}

}  // namespace rad
