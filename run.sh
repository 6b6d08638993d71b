#!/usr/bin/env bash
# Installs what is missing, builds in Release and runs the main job: the viewer
# when a display exists, otherwise a headless demo that writes into out/.
set -euo pipefail
cd "$(dirname "$0")"
source .ci/deps.sh
install_missing_packages

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"

if [ -n "${DISPLAY:-}" ] && [ -x build/app/radiosity-viewer ]; then
  exec build/app/radiosity-viewer "$@"
fi

echo "No display (or no viewer yet): running the headless demo." >&2
mkdir -p out
cli=build/app/radiosity-cli
scene=scenes/cornell-box.gltf
# out/ belongs to this demo: its files are replaced on every run.
$cli render "$scene" --image out/cornell-box-preview.png --size 512x512 --force
$cli solve "$scene" --image out/cornell-box.png --size 512x512 --report out/cornell-box-report.json --force
echo "Wrote:"
ls -1 out/* | sed 's/^/  /'
