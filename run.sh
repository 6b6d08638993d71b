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

echo "No display: running the headless demo (radiosity-viewer needs one)." >&2
mkdir -p out
cli=build/app/radiosity-cli
scene=scenes/cornell-box.gltf
# out/ belongs to this demo: its files are replaced on every run.
$cli render "$scene" --image out/cornell-box-preview.png --size 512x512 --force
$cli solve "$scene" --image out/cornell-box.png --size 512x512 --report out/cornell-box-report.json --force
$cli animate "$scene" --object short-block --frames 8 --translate 0,0,0.2 --rotate 0,1,0,30 --compare-full \
  --images out/frames --size 384x384 --report out/cornell-box-animate.json --force
echo "Wrote:"
find out -type f | sort | sed 's/^/  /'
