#!/usr/bin/env bash
# Fuzzes the parsers (docs/fuzzing.md): installs Clang if it is missing, builds the libFuzzer
# targets of tests/fuzz/ in build/fuzz (ASan/UBSan, coverage), runs each for N seconds on a
# working copy of its seed corpus, and prints one line per target. Exit 1 when anything was found.
#
#   tools/fuzz.sh N [TARGET...]   N seconds per target; every target when none is named
#
# Per target, under build/fuzz/: corpus/<name>/ (seeds plus what the fuzzer kept; grows from run
# to run), crashes/<name>/ (crash-*, timeout-*, oom-*: replay one with
# build/fuzz/tests/fuzz/<name>_fuzz FILE), logs/<name>.log.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$root/build/fuzz"
jobs=$(nproc 2>/dev/null || echo 2)

if [[ $# -lt 1 || ! $1 =~ ^[0-9]+$ ]]; then
    echo "usage: tools/fuzz.sh SECONDS [TARGET...]" >&2
    exit 2
fi
seconds=$1
shift
if [ $# -gt 0 ]; then
    targets=("$@")
else
    targets=()
    for f in "$root"/tests/fuzz/*_fuzz.cpp; do
        name=$(basename "$f" _fuzz.cpp)
        targets+=("$name")
    done
fi

# Debian 12: clang 14; libFuzzer's runtime is in libclang-rt-dev (only recommended by clang).
# shellcheck source=tools/apt-install.sh
source "$root/tools/apt-install.sh"

build_targets() {
    command -v ccache >/dev/null && export CMAKE_CXX_COMPILER_LAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER:-ccache}
    CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DFIBRECELL_FUZZ=ON -DFIBRECELL_TESTS=OFF -DFIBRECELL_BENCH=OFF >/dev/null
    local names=()
    for t in "${targets[@]}"; do names+=("${t}_fuzz"); done
    nice -n 19 cmake --build "$build" --parallel "$jobs" --target "${names[@]}"
}

# fuzz_one NAME: runs the target, prints its line; returns 1 when it found something.
fuzz_one() {
    local name=$1
    local corpus="$build/corpus/$name" crashes="$build/crashes/$name" log="$build/logs/$name.log"
    mkdir -p "$corpus" "$crashes" "$build/logs"
    cp "$root/tests/fuzz/corpus/$name"/* "$corpus"/
    local before
    before=$(ls "$crashes")
    local status=0
    # -timeout: one input running this long is a hang; -rss_limit_mb: an allocation this big
    # from a few KB of input is a finding too.
    nice -n 19 "$build/tests/fuzz/${name}_fuzz" -max_total_time="$seconds" -timeout=10 \
        -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$crashes/" "$corpus" \
        >"$log" 2>&1 || status=$?
    local execs size found
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    size=$(find "$corpus" -type f | wc -l)
    found=$(comm -13 <(echo "$before") <(ls "$crashes") | tr '\n' ' ')
    if [ -n "$found" ] || [ "$status" -ne 0 ]; then
        printf '%-13s executions %10s  corpus %5s  FOUND %s(exit %s, %s)\n' "$name" \
            "${execs:-?}" "$size" "$found" "$status" "${log#"$root"/}"
        return 1
    fi
    printf '%-13s executions %10s  corpus %5s  nothing found\n' "$name" "${execs:-?}" "$size"
}

install_missing fuzz clang libclang-rt-dev
build_targets
echo "fuzz: ${#targets[@]} targets, ${seconds} s each"
failed=0
for t in "${targets[@]}"; do
    fuzz_one "$t" || failed=1
done
exit $failed
