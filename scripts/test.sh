#!/usr/bin/env bash
# The project's test command (the README's, and what CI runs).
# On Debian/Ubuntu without any Vulkan driver it first installs Mesa's software one (lavapipe,
# package mesa-vulkan-drivers), so the rendering tests run on a machine with no GPU.
set -euo pipefail
cd "$(dirname "$0")/.."

have_vulkan_driver() {
    local icd
    for icd in /usr/share/vulkan/icd.d/*.json /etc/vulkan/icd.d/*.json /usr/local/share/vulkan/icd.d/*.json; do
        [ -e "$icd" ] && return 0
    done
    return 1
}

# What the tests need that a fresh Debian/Ubuntu machine lacks: a Vulkan driver (Mesa's lavapipe
# when there is no GPU), Xvfb + xdotool for the viewer test, assimp's test models.
missing=()
have_vulkan_driver || missing+=(mesa-vulkan-drivers)
command -v Xvfb >/dev/null 2>&1 || missing+=(xvfb)
command -v xdotool >/dev/null 2>&1 || missing+=(xdotool)
# wgpu's GL backend (the second pass below, and what a machine without Vulkan gets): EGL and
# Mesa's software GL driver (llvmpipe).
ldconfig -p 2>/dev/null | grep -q "libEGL.so.1" || missing+=(libegl1)
ldconfig -p 2>/dev/null | grep -q "libEGL_mesa.so.0" || missing+=(libegl-mesa0)
ls /usr/lib/*/dri/swrast_dri.so >/dev/null 2>&1 || missing+=(libgl1-mesa-dri)
# Real-world OBJ files, valid and broken, for the bad-input test.
[ -d /usr/share/assimp/models/OBJ ] || missing+=(assimp-testmodels)
# The X11 client libraries winit opens at run time for the viewer's window.
for lib in libX11.so.6:libx11-6 libX11-xcb.so.1:libx11-xcb1 libxkbcommon-x11.so.0:libxkbcommon-x11-0 \
    libXcursor.so.1:libxcursor1 libXrandr.so.2:libxrandr2 libXi.so.6:libxi6; do
    ldconfig -p 2>/dev/null | grep -q "${lib%%:*}" || missing+=("${lib##*:}")
done
if [ ${#missing[@]} -gt 0 ]; then
    if command -v apt-get >/dev/null 2>&1; then
        sudo=""
        [ "$(id -u)" -eq 0 ] || sudo="sudo"
        echo "scripts/test.sh: installing ${missing[*]}"
        $sudo apt-get update -qq
        DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
    else
        echo "scripts/test.sh: missing ${missing[*]} and no apt-get; install them (a Vulkan driver: Mesa's lavapipe or a GPU driver)" >&2
        exit 1
    fi
fi

if ! command -v cargo >/dev/null 2>&1; then
    echo "scripts/test.sh: cargo not found; install Rust 1.95 or newer from https://rustup.rs" >&2
    exit 1
fi

# Mesa's device-select layer prints an XDG_RUNTIME_DIR error without a Wayland session; it only
# reorders adapters, which the renderer ranks itself (the binary sets the same switch).
export NODEVICE_SELECT="${NODEVICE_SELECT:-1}"

# The formatting first: a diff fails here in a second, not after minutes of building.
if cargo fmt --version >/dev/null 2>&1; then
    echo "scripts/test.sh: cargo fmt --check"
    cargo fmt --check
else
    echo "scripts/test.sh: rustfmt is not installed (rustup component add rustfmt); formatting not checked" >&2
fi

# Mesa's CPU rasterisers (lavapipe, llvmpipe) start rasteriser threads of their own, as many as
# there are cores, for every device; the harness already runs a test on each core, so they only
# contend (0: each device rasterises on its own queue thread; the suite 0.85-0.89x on Vulkan,
# docs/testing.md). A GPU's driver does not read it.
export LP_NUM_THREADS="${LP_NUM_THREADS:-0}"

# The test binaries, built once for both backends.
cargo test --locked --no-run "$@"

# Everything on Vulkan (lavapipe without a GPU) and every test that renders once more on GL
# (llvmpipe without a GPU), with the same assertions, so a shader or a binding that breaks one
# backend cannot land. The rendering tests are the `gpu` and `cli` modules of the one test crate,
# and the two tests with a process of their own: a new rendering test runs on both backends by
# where it lives. The two backends run side by side (each waits on its device for part of its
# time; together 0.74x their time one after the other, docs/testing.md), GL's output held until
# Vulkan's is done; the viewer's tests, which wait on a window against a clock, run after, alone.
gl_log="$(mktemp)"
trap 'rm -f "$gl_log"' EXIT
echo "scripts/test.sh: the rendering tests on wgpu's GL backend, beside Vulkan's (their output follows it)"
(
    WGPU_BACKEND=gl cargo test --locked --test it "$@" -- gpu:: cli:: --skip cli::viewer &&
        WGPU_BACKEND=gl cargo test --locked --test memory --test resources "$@"
) >"$gl_log" 2>&1 &
gl_pid=$!
echo "scripts/test.sh: the whole suite on wgpu's Vulkan backend"
vulkan=0
WGPU_BACKEND=vulkan cargo test --locked "$@" -- --skip cli::viewer || vulkan=$?
gl=0
wait "$gl_pid" || gl=$?
echo "scripts/test.sh: the rendering tests on wgpu's GL backend (run beside Vulkan's)"
cat "$gl_log"
[ "$vulkan" -eq 0 ] || echo "scripts/test.sh: the tests on Vulkan failed" >&2
[ "$gl" -eq 0 ] || echo "scripts/test.sh: the tests on GL failed" >&2
[ "$vulkan" -eq 0 ] && [ "$gl" -eq 0 ] || exit 1
echo "scripts/test.sh: the viewer's tests, on Vulkan then on GL"
WGPU_BACKEND=vulkan cargo test --locked --test it "$@" -- cli::viewer
WGPU_BACKEND=gl cargo test --locked --test it "$@" -- cli::viewer
