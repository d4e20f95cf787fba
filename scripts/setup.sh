#!/usr/bin/env bash
# Installs every Debian 12 package Lantern needs to build, test and run.
# Idempotent: when everything is present it only checks, in well under a second.
set -euo pipefail

PACKAGES=(
    build-essential cmake ninja-build pkg-config git python3
    clang libclang-rt-14-dev
    libgtest-dev libgmock-dev libbenchmark-dev
    libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
    glslang-tools glslang-dev spirv-tools
    libglfw3-dev libglm-dev libimgui-dev libstb-dev nlohmann-json3-dev
    libxrandr-dev libxrender-dev
    libopenal-dev zlib1g-dev
    xvfb xauth
    xdotool x11-apps
    graphviz
)

missing=()
for pkg in "${PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$pkg")
    fi
done

if [ ${#missing[@]} -eq 0 ]; then
    echo "setup: all ${#PACKAGES[@]} packages present"
    exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then
        SUDO="sudo"
    else
        echo "setup: need root (or sudo) to install: ${missing[*]}" >&2
        exit 1
    fi
fi

echo "setup: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "setup: done"
