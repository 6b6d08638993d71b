#pragma once
// The consistency check of the paper's sec. 6.1: the active links cover line
// space completely, one link for every pair of points that face each other.

#include <cstdint>
#include <optional>
#include <string>

#include "radiosity/Engine.h"

namespace rad::test {

struct CoverageResult {
    int pairs = 0;
    int missing = 0;  // no link carries the pair
    int doubled = 0;  // more than one link
    std::string firstBad;
};

// `wanted` random pairs of points on two different polygons that face each
// other (one of them on `object` if given); each must be carried by exactly
// one active link.
CoverageResult checkCoverage(const Engine& engine, unsigned seed, int wanted,
                             std::optional<std::uint32_t> object = std::nullopt);

}  // namespace rad::test
