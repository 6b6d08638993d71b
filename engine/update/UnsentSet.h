#pragma once
// The elements whose change of radiosity a deadline kept from being sent
// (bounced), and the sum over them of what each has yet to send, which the
// live error estimate reads every frame.
//
// The sum is kept term by term: a deadline can leave hundreds of thousands
// unsent frame after frame while a push changes a few of them, and summing
// 239,000 again took 10 ms of each 25 fps frame on the building floor.
// Whoever changes what an unsent element holds says so (mayHaveChanged);
// its term is made again at the next sum(), and only then, once however
// often it was named (a frame's pushes name some elements twice).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "hierarchy/ChunkedArray.h"
#include "hierarchy/HElement.h"

namespace rad {

class UnsentSet {
    using Terms = ChunkedArray<double, 12>;
    using States = ChunkedArray<std::uint8_t, 14>;

  public:
    bool contains(ElementId e) const { return e < state_.size() && (state_[e] & kMember); }
    // Room for the elements with ids under n, made now rather than by the
    // first joins (on the building floor, 38 ms of a frame). It grows
    // without copying.
    void cover(std::size_t n) {
        if (term_.size() < n) term_.resize(n, 0.0);
        if (state_.size() < n) state_.resize(n, 0);
    }
    bool empty() const { return members_.empty(); }
    std::size_t size() const { return members_.size(); }
    const std::vector<ElementId>& members() const { return members_; }

    // Joins e (once: false if it is a member already). Its term is made at
    // the next sum.
    bool join(ElementId e);
    // All leave (a bounce sends them).
    void clear();
    // What these hold may have changed (their B, their facets' powers, the
    // links leaving them): the terms of those that are members are made
    // again at the next sum. Others are passed over.
    void mayHaveChanged(std::span<const ElementId> elements);
    // Every term is made again at the next sum (an edit changed what every
    // element holds; elements were freed, and an id may now be another's).
    void forget() { known_ = false; }

    // The sum over the members of term(e), made only for the terms that may
    // have changed since the last call (every term after forget()), on all
    // cores and added in order, so that a run gives the same sums each time.
    using Term = std::function<double(ElementId)>;
    double sum(const Term& term);

    // What it keeps whatever its size (a chunk of each array), and per element.
    static constexpr std::size_t kFixedBytes = Terms::kChunkBytes + States::kChunkBytes;
    static constexpr std::size_t kBytesPerElement = sizeof(double) + sizeof(std::uint8_t);

    std::size_t memoryBytes() const {
        return term_.memoryBytes() + state_.memoryBytes() +
               (members_.capacity() + recount_.capacity()) * sizeof(ElementId);
    }

  private:
    // Per element, one byte: read for every element a push visits, it stays
    // in cache where the terms (eight bytes) would not.
    static constexpr std::uint8_t kMember = 1, kQueued = 2;  // kQueued: on recount_
    std::vector<ElementId> members_;
    Terms term_;    // per member: its term in sum_
    States state_;  // per element: kMember | kQueued
    std::vector<ElementId> recount_;        // members whose terms are made again at the next sum
    double sum_ = 0.0;
    bool known_ = false;
};

}  // namespace rad
