#!/usr/bin/env bash
# Installs what is missing, builds with warnings as errors and runs every
# test once, under AddressSanitizer + UBSan (a sanitizer run asserts all that a
# plain run does, and catches memory errors and undefined behaviour besides);
# then the engine thread under ThreadSanitizer. ./run.sh builds the Release
# configuration users run.
set -euo pipefail
cd "$(dirname "$0")"
source .ci/deps.sh
install_missing_packages

jobs=$(nproc)
stage() { echo "== $1 (at ${SECONDS} s)"; }
stage "configure and build build-asan (RelWithDebInfo, ASan + UBSan, -Werror)"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRADIOSITY_SANITIZE=ON -DRADIOSITY_WERROR=ON >/dev/null
cmake --build build-asan -j"$jobs"
stage "test build-asan"
# Leak checking is off: the Vulkan driver keeps process-lifetime allocations.
ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan --output-on-failure -j"$jobs"

# The engine thread under ThreadSanitizer: the viewer's headless stress mode
# sends transforms from another thread while snapshots are read.
stage "ThreadSanitizer: engine thread"
cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRADIOSITY_TSAN=ON -DRADIOSITY_WERROR=ON >/dev/null
cmake --build build-tsan -j"$jobs" --target radiosity-viewer
TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 build-tsan/app/radiosity-viewer --headless-stress 300
# and an object not marked dynamic, attached to the root on that thread.
TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 build-tsan/app/radiosity-viewer --select tall-block --headless-stress 100
echo "All test suites passed in ${SECONDS} s."
