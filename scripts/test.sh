#!/usr/bin/env bash
# The project's test command (the README's, and what CI runs).
# On Debian/Ubuntu without any Vulkan driver it first installs Mesa's software one (lavapipe,
# package mesa-vulkan-drivers), so the rendering tests run on a machine with no GPU.
set -euo pipefail
cd "$(dirname "$0")/.."

have_vulkan_driver() {
    ls /usr/share/vulkan/icd.d/*.json /etc/vulkan/icd.d/*.json /usr/local/share/vulkan/icd.d/*.json >/dev/null 2>&1
}

if ! have_vulkan_driver; then
    if command -v apt-get >/dev/null 2>&1; then
        sudo=""
        [ "$(id -u)" -eq 0 ] || sudo="sudo"
        echo "scripts/test.sh: no Vulkan driver found; installing mesa-vulkan-drivers (lavapipe)"
        $sudo apt-get update -qq
        DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq mesa-vulkan-drivers >/dev/null
    else
        echo "scripts/test.sh: no Vulkan driver found and no apt-get; install Mesa's lavapipe or a GPU driver" >&2
        exit 1
    fi
fi

if ! command -v cargo >/dev/null 2>&1; then
    echo "scripts/test.sh: cargo not found; install Rust 1.85 or newer from https://rustup.rs" >&2
    exit 1
fi

# wgpu would also probe GL/EGL and log a harmless DRI2 error; Vulkan is what we test on.
export WGPU_BACKEND="${WGPU_BACKEND:-vulkan}"
# Mesa's WSI complains without it; harmless, but noisy.
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
cargo test --locked "$@"
