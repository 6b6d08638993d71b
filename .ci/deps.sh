#!/usr/bin/env bash
# Installs the Debian 12 packages the project needs, only those missing.
# Sourced by run.sh and test.sh.
RADIOSITY_PACKAGES=(cmake g++ pkg-config libvulkan-dev mesa-vulkan-drivers vulkan-tools
  vulkan-validationlayers glslang-tools glslang-dev spirv-tools libglfw3-dev libglm-dev
  libtinygltf-dev libimgui-dev libstb-dev libembree-dev libtbb-dev libgtest-dev
  libbenchmark-dev nlohmann-json3-dev libcli11-dev libcairo2-dev fonts-dejavu-core libexpat1-dev
  xvfb xauth imagemagick x11-apps xdotool python3)

install_missing_packages() {
  local missing=()
  for p in "${RADIOSITY_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "Installing missing packages: ${missing[*]}" >&2
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq || { echo "error: apt-get update failed" >&2; return 1; }
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null ||
    { echo "error: apt-get install failed for: ${missing[*]}" >&2; return 1; }
}
