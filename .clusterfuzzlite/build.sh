#!/bin/bash -eu
# Builds every cargo-fuzz target of fuzz/ into $OUT, with a seed corpus per target
# (fuzz/corpus/TARGET and fuzz/regressions/TARGET, as $OUT/TARGET_seed_corpus.zip).
#
# ClusterFuzzLite runs this inside .clusterfuzzlite/Dockerfile's image ($SRC, $OUT set by
# the image; the nightly toolchain is its default). .ci/run runs it on the host with SRC
# and OUT set to temporary folders, $SRC/zipmesh a link to the checkout and
# RUSTUP_TOOLCHAIN=nightly: the build is the one of `cargo +nightly fuzz build` (release,
# the host target, RUSTFLAGS as given), so that run reuses the fuzz stage's build.

cd "$SRC/zipmesh"

# Release with debug assertions and overflow checks: what plain `cargo fuzz build` (the
# fuzz stage of .ci/run) builds, spelled as the Rust integration guide suggests. `-O` alone
# would drop the assertions and, its flags differing, rebuild everything (4 minutes here).
# No RUSTFLAGS here either, for the same reason. ZIPMESH_FUZZ_FLAGS (unset in the image, so
# ASan and compare tracing as ClusterFuzzLite expects) lets .ci/run reuse its faster build.
# shellcheck disable=SC2086 # the flags are words
cargo fuzz build -O --debug-assertions ${ZIPMESH_FUZZ_FLAGS:-}

# The targets are the [[bin]] names of fuzz/Cargo.toml (what `cargo fuzz list` prints; not
# called here because the image's cargo wrapper turns every `cargo fuzz` call into a build
# in coverage builds).
targets=$(awk '/^\[\[bin\]\]/ { bin = 1; next } /^\[/ { bin = 0 }
    bin && $1 == "name" { gsub(/"/, "", $3); print $3 }' fuzz/Cargo.toml)

# cargo fuzz builds for the host triple (it passes --target itself, so CARGO_BUILD_TARGET
# plays no part) into the fuzz workspace's target directory, which CARGO_TARGET_DIR or a
# cargo config may move: ask cargo.
target_dir=$(cargo metadata --manifest-path fuzz/Cargo.toml --format-version 1 --no-deps |
    sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
bin_dir="$target_dir/x86_64-unknown-linux-gnu/release"

for target in $targets; do
    cp "$bin_dir/$target" "$OUT/"
    seeds=()
    for dir in "fuzz/corpus/$target" "fuzz/regressions/$target"; do
        if [ -d "$dir" ]; then
            seeds+=("$dir")
        fi
    done
    if [ "${#seeds[@]}" -gt 0 ] && command -v zip >/dev/null; then
        rm -f "$OUT/${target}_seed_corpus.zip"
        zip -q -r -j "$OUT/${target}_seed_corpus.zip" "${seeds[@]}"
    fi
done
