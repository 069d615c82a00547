#!/usr/bin/env bash
# Coverage-guided fuzzing of the loaders with cargo-fuzz (libFuzzer), on the nightly toolchain.
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     default: 600 s each, every target:
#   obj (OBJ + MTL), skybox (six faces), gltf (.gltf + a buffer + an image), glb, panorama,
#   preset (a --preset file)
# Installs cargo-fuzz (from crates.io) and the nightly toolchain (through rustup) where missing.
# A crash stops its target and leaves the input in fuzz/artifacts/<target>/; copy it into
# fuzz/regressions/<target>/ before fixing it: the tests run every file there through the same
# body (tests/it/cpu/fuzz_entries.rs, which the targets include). CI runs those and the bounded
# property tests in tests/it/cpu/fuzz_loaders.rs instead of this.
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
seconds="${1:-600}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(obj skybox gltf glb panorama preset)

if ! rustup toolchain list | grep -q '^nightly'; then
    echo "scripts/fuzz.sh: installing the nightly toolchain"
    rustup toolchain install nightly --profile minimal
fi
if ! cargo fuzz --version >/dev/null 2>&1; then
    echo "scripts/fuzz.sh: installing cargo-fuzz"
    cargo install cargo-fuzz --locked
fi

status=0
for target in "${targets[@]}"; do
    mkdir -p "corpus/$target" "artifacts/$target"
    echo "scripts/fuzz.sh: $target for ${seconds} s"
    # -rss_limit_mb: a loader that allocates without bound is a finding too.
    # fuzz/seeds/<target> holds valid inputs to start from (read, never written).
    seeds=()
    [ -d "seeds/$target" ] && seeds=("seeds/$target")
    if ! cargo +nightly fuzz run "$target" "corpus/$target" "${seeds[@]}" -- \
        -max_total_time="$seconds" -rss_limit_mb=4096 -print_final_stats=1 2>&1 | tee "artifacts/$target/last_run.log" \
        | grep -E "^(#[0-9]+.*(DONE|pulse|NEW)|stat::|==.*ERROR|SUMMARY|artifact_prefix|Test unit written)" | tail -n 40; then
        status=1
    fi
    if ls "artifacts/$target"/crash-* "artifacts/$target"/oom-* "artifacts/$target"/timeout-* >/dev/null 2>&1; then
        echo "scripts/fuzz.sh: $target found inputs that fail: $(ls "artifacts/$target" | grep -E '^(crash|oom|timeout)-' | tr '\n' ' ')"
        status=1
    fi
done
exit $status
