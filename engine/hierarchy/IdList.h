#pragma once
// A list of 32-bit ids (an H-element's children and link lists) in 16
// bytes: a pointer, a 32-bit size and a 32-bit capacity. A std::vector
// takes 24; an H-element holds five such lists, and a small room keeps
// about 25 links per element, so the 40 bytes are 1.6 bytes a link.
// It grows as a vector does (doubling), and is copied by value.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <memory>
#include <span>
#include <stdexcept>
#include <utility>

namespace rad {

class IdList {
  public:
    using value_type = std::uint32_t;
    using iterator = value_type*;
    using const_iterator = const value_type*;

    IdList() = default;
    IdList(std::span<const value_type> ids) { assign(ids.begin(), ids.end()); }
    IdList(std::initializer_list<value_type> ids) { assign(ids.begin(), ids.end()); }
    IdList(const IdList& other) { assign(other.begin(), other.end()); }
    IdList(IdList&& other) noexcept
        : data_(std::move(other.data_)),
          size_(std::exchange(other.size_, 0)),
          capacity_(std::exchange(other.capacity_, 0)) {}
    IdList& operator=(const IdList& other) {
        if (this != &other) assign(other.begin(), other.end());
        return *this;
    }
    IdList& operator=(IdList&& other) noexcept {
        data_ = std::move(other.data_);
        size_ = std::exchange(other.size_, 0);
        capacity_ = std::exchange(other.capacity_, 0);
        return *this;
    }

    std::size_t size() const { return size_; }
    std::size_t capacity() const { return capacity_; }
    bool empty() const { return size_ == 0; }
    value_type* data() { return data_.get(); }
    const value_type* data() const { return data_.get(); }
    iterator begin() { return data_.get(); }
    iterator end() { return data_.get() + size_; }
    const_iterator begin() const { return data_.get(); }
    const_iterator end() const { return data_.get() + size_; }
    value_type& operator[](std::size_t i) { return data_[i]; }
    value_type operator[](std::size_t i) const { return data_[i]; }
    value_type back() const { return data_[size_ - 1]; }
    operator std::span<const value_type>() const { return {begin(), end()}; }

    void push_back(value_type id) {
        if (size_ == capacity_) grow(std::size_t(size_) + 1);
        data_[size_++] = id;
    }
    void pop_back() { --size_; }
    void clear() { size_ = 0; }
    void resize(std::size_t n) {
        if (n > capacity_) grow(n);
        if (n > size_) std::fill(end(), begin() + n, value_type(0));
        size_ = static_cast<std::uint32_t>(n);
    }
    void reserve(std::size_t n) {
        if (n > capacity_) reallocate(n);
    }
    void shrink_to_fit() {
        if (capacity_ > size_) reallocate(size_);
    }
    template <class It>
    void assign(It first, It last) {
        const auto n = static_cast<std::size_t>(std::distance(first, last));
        if (n > capacity_) reallocate(n, false);
        std::copy(first, last, begin());
        size_ = static_cast<std::uint32_t>(n);
    }
    // Appends [first, last), which must not lie in this list.
    template <class It>
    void append(It first, It last) {
        const auto n = static_cast<std::size_t>(std::distance(first, last));
        if (size_ + n > capacity_) grow(size_ + n);
        std::copy(first, last, end());
        size_ += static_cast<std::uint32_t>(n);
    }
    iterator erase(const_iterator at) { return erase(at, at + 1); }
    iterator erase(const_iterator first, const_iterator last) {
        const auto i = first - begin(), n = last - first;
        std::copy(begin() + i + n, end(), begin() + i);
        size_ -= static_cast<std::uint32_t>(n);
        return begin() + i;
    }
    // Removes every entry equal to id (std::erase on a vector).
    std::size_t eraseValue(value_type id) {
        const auto kept = std::remove(begin(), end(), id);
        const auto n = static_cast<std::size_t>(end() - kept);
        size_ -= static_cast<std::uint32_t>(n);
        return n;
    }

  private:
    void grow(std::size_t atLeast) {
        reallocate(std::max<std::size_t>({atLeast, 2 * std::size_t(capacity_), 4}));
    }
    void reallocate(std::size_t capacity, bool keep = true) {
        if (capacity > std::numeric_limits<std::uint32_t>::max())
            throw std::length_error("IdList: more than 2^32 ids");
        std::unique_ptr<value_type[]> fresh =
            capacity > 0 ? std::make_unique_for_overwrite<value_type[]>(capacity) : nullptr;
        if (keep) std::copy(begin(), end(), fresh.get());
        data_ = std::move(fresh);
        capacity_ = static_cast<std::uint32_t>(capacity);
        if (!keep) size_ = 0;
    }

    std::unique_ptr<value_type[]> data_;
    std::uint32_t size_ = 0;
    std::uint32_t capacity_ = 0;
};

}  // namespace rad
