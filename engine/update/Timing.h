#pragma once
// Wall-clock seconds for the frame figures (FrameStats).

#include <chrono>

namespace rad {

inline double secondsSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace rad
