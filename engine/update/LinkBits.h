#pragma once
// One bit per link slot: the update's marks on links (found in this frame's
// traversal; in the stale list). A link is 32 bytes; a byte of marks beside
// it was 3% more (`office` 65.79 bytes a link, everything counted).

#include <atomic>
#include <cstdint>

#include "hierarchy/ChunkedArray.h"
#include "hierarchy/HElement.h"

namespace rad {

class LinkBits {
    using Words = ChunkedArray<std::uint64_t, 13>;  // 8,192 words: 524,288 links a chunk

public:
    // Room for `slots` link slots; those added are clear.
    void cover(std::size_t slots) { words_.resize((slots + 63) / 64, 0); }
    void clearAll() { words_.assign(words_.size(), 0); }
    bool test(LinkId id) const { return id / 64 < words_.size() && (words_[id / 64] & bit(id)); }
    // Serial writers; `id` covered.
    void set(LinkId id, bool on) { words_[id / 64] = on ? words_[id / 64] | bit(id) : words_[id / 64] & ~bit(id); }
    // Concurrent writers (the traversal's visits, each of its own links:
    // neighbouring links share a word); `id` covered. setConcurrently is
    // false if the bit was set already.
    bool testConcurrently(LinkId id) { return word(id).load(std::memory_order_relaxed) & bit(id); }
    bool setConcurrently(LinkId id) { return !(word(id).fetch_or(bit(id), std::memory_order_relaxed) & bit(id)); }
    std::size_t memoryBytes() const { return words_.memoryBytes(); }
    static constexpr std::size_t kChunkBytes = Words::kChunkBytes;

private:
    static std::uint64_t bit(LinkId id) { return std::uint64_t(1) << (id % 64); }
    std::atomic_ref<std::uint64_t> word(LinkId id) { return std::atomic_ref<std::uint64_t>(words_[id / 64]); }
    Words words_;
};

}  // namespace rad
