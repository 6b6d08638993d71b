#!/usr/bin/env bash
# Installs what is missing, builds with warnings as errors, runs every test:
# once normally and once under AddressSanitizer + UBSan.
set -euo pipefail
cd "$(dirname "$0")"
source .ci/deps.sh
install_missing_packages

jobs=$(nproc)
run_suite() {
  local dir=$1; shift
  echo "== configure and build $dir ($*)"
  cmake -S . -B "$dir" -DRADIOSITY_WERROR=ON "$@" >/dev/null
  cmake --build "$dir" -j"$jobs"
  echo "== test $dir"
  ctest --test-dir "$dir" --output-on-failure -j"$jobs"
}

run_suite build -DCMAKE_BUILD_TYPE=Release
# Leak checking is off: the Vulkan driver keeps process-lifetime allocations.
ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  run_suite build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRADIOSITY_SANITIZE=ON
# The engine thread under ThreadSanitizer: the viewer's headless stress mode
# sends transforms from another thread while snapshots are read.
echo "== ThreadSanitizer: engine thread"
cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRADIOSITY_TSAN=ON -DRADIOSITY_WERROR=ON >/dev/null
cmake --build build-tsan -j"$jobs" --target radiosity-viewer
TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 build-tsan/app/radiosity-viewer --headless-stress 300
# and an object not marked dynamic, attached to the root on that thread.
TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 build-tsan/app/radiosity-viewer --select tall-block --headless-stress 100
echo "All test suites passed."
