#!/usr/bin/env bash
# Frame time against pixel count and against triangle count, per mode: the scaling
# tables of docs/performance.md. Runs `ssdo bench --json` on the benchmark room (every pixel is geometry) and prints
# Markdown. Figures are medians of FRAMES frames (default 5) per mode, one run each.
#   scripts/scaling.sh [VARIANT]     (default: the default variant, march)
set -euo pipefail
cd "$(dirname "$0")/.."
export NODEVICE_SELECT=1
variant=${1:-default}
frames=${FRAMES:-5}
cargo build --release --quiet
bin=target/release/ssdo
frame_ms() { # args... -> "off ssao ssdo both" frame times in ms
    "$bin" bench --json --frames "$frames" --variant "$variant" "$@" 2>/dev/null |
        python3 -c 'import json,sys; d=json.load(sys.stdin); print(" | ".join("%.1f" % d["modes"][m]["frame_ms"] for m in ("off","ssao","ssdo","both")))'
}
echo "device: $("$bin" bench --json --frames 1 --size 8x8 2>/dev/null | python3 -c 'import json,sys; print(json.load(sys.stdin)["device"])')"
echo "variant: $variant, 1 light, radius 0.5, median of $frames frames"
echo
echo "| size | pixels | Off | SSAO | SSDO | SSAO+SSDO |"
echo "|---|--:|--:|--:|--:|--:|"
for size in 320x240 640x480 1280x720 1920x1080; do
    w=${size%x*}; h=${size#*x}
    echo "| $size | $((w * h)) | $(frame_ms --scene room --lights 1 --radius 0.5 --size "$size") |"
done
echo
echo "| triangles | Off | SSAO | SSDO | SSAO+SSDO |"
echo "|--:|--:|--:|--:|--:|"
for n in 1000 50000 500000 2000000; do
    echo "| $n | $(frame_ms --scene room --triangles "$n" --lights 1 --radius 0.5 --size 800x600) |"
done
