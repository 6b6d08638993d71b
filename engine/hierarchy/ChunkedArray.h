#pragma once
// An array addressed by index that lives in fixed-size chunks: it grows
// without ever copying itself, and holds at most one chunk of slack.
//
// Why not a std::vector: its growth copies every item into fresh memory, and
// fresh memory costs a page fault per 4 KiB touched. On this project's
// machines a fault takes about 11 us, so that growing 7,917 H-elements (a
// random room of `bench/untuned/random_room.py`, seed 10) took 15.7 ms in
// the middle of a 16.7 ms frame; `office`'s 23,000 would take about 45 ms.
// Here a new chunk is the only fresh memory, once per 2^Shift items.

#include <algorithm>
#include <array>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace rad {

template <class T, unsigned Shift>
class ChunkedArray {
public:
    using value_type = T;
    static constexpr std::size_t kChunk = std::size_t(1) << Shift;
    static constexpr std::size_t kChunkBytes = kChunk * sizeof(T);

    T& operator[](std::size_t i) { return (*chunks_[i >> Shift])[i & kMask]; }
    const T& operator[](std::size_t i) const { return (*chunks_[i >> Shift])[i & kMask]; }
    std::size_t size() const { return size_; }
    std::size_t capacity() const { return chunks_.size() * kChunk; }

    void push_back(T item) {
        if (size_ == capacity()) chunks_.push_back(std::make_unique<Chunk>());
        (*this)[size_++] = std::move(item);
    }
    // Items past the old size are `value`; those past the new one are dropped.
    void resize(std::size_t n, const T& value = T{}) {
        while (capacity() < n) chunks_.push_back(std::make_unique<Chunk>());
        for (std::size_t i = size_; i < n; ++i) (*this)[i] = value;
        for (std::size_t i = n; i < size_; ++i) (*this)[i] = T{};
        size_ = n;
    }
    // n items, each `value`.
    void assign(std::size_t n, const T& value) {
        const std::size_t kept = std::min(n, size_);
        resize(n, value);
        for (std::size_t i = 0; i < kept; ++i) (*this)[i] = value;
    }
    // Frees the chunks past the last item.
    void shrink_to_fit() {
        chunks_.resize((size_ + kChunk - 1) / kChunk);
        chunks_.shrink_to_fit();
    }
    std::size_t memoryBytes() const {
        return chunks_.size() * sizeof(Chunk) + chunks_.capacity() * sizeof(chunks_[0]);
    }

private:
    static constexpr std::size_t kMask = kChunk - 1;
    using Chunk = std::array<T, kChunk>;
    std::vector<std::unique_ptr<Chunk>> chunks_;
    std::size_t size_ = 0;
};

}  // namespace rad
