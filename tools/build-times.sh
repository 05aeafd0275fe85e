#!/usr/bin/env bash
# Where a build's and a test run's time went (docs/building.md), read from what ninja and CTest
# already record in the build directory:
#   - the build: every step's time from .ninja_log (the last run of each output), compile and
#     link totals, the time per library or test folder, and the N most expensive translation
#     units, each with the heavy third-party headers it includes (from ninja's deps log);
#   - the tests: the slowest N of the last ctest run (Testing/Temporary/LastTest.log) and the sum
#     of all their times.
#
#   tools/build-times.sh BUILD_DIR [N]      N defaults to 20 translation units and 30 tests
#
# A step's time is wall time: with more jobs than cores the steps are slower than alone. For a
# figure to compare, build from empty with --parallel equal to the cores (tools/setup.sh does).
set -euo pipefail

dir=${1:?usage: tools/build-times.sh BUILD_DIR [N]}
top=${2:-20}
log="$dir/.ninja_log"
[ -f "$log" ] || { echo "build-times: no $log (build first)" >&2; exit 1; }

# The last record of each output: "seconds output".
steps=$(awk -F'\t' 'NR > 1 { t[$4] = ($2 - $1) / 1000 } END { for (o in t) printf "%.1f %s\n", t[o], o }' "$log" |
    sort -rn)

echo "== build: $dir"
awk '{ all += $1; if ($2 ~ /\.o$/) { c += $1; n++ } else if ($2 !~ /\.cmake$|verify_globs/) { l += $1; m++ } }
     END { printf "%.0f s of steps: %.0f s compiling %d translation units, %.0f s linking and other steps (%d)\n", all, c, n, l, m }' <<<"$steps"

echo
echo "-- per target (compile seconds, translation units)"
awk '$2 ~ /\.o$/ { split($2, p, "/"); t = p[length(p) - 1]; for (i = 1; i < length(p); i++) if (p[i] ~ /\.dir$/) t = p[i];
                   sub(/\.dir$/, "", t); s[t] += $1; n[t]++ }
     END { for (t in s) printf "%7.0f %4d  %s\n", s[t], n[t], t }' <<<"$steps" | sort -rn | head -"$top"

echo
echo "-- the $top most expensive translation units, with the heavy headers each includes"
heavy='boost/asio|boost/beast|eigen3|nlohmann|spdlog|fmt|gtest|gmock|CLI|yaml-cpp'
while read -r seconds obj; do
    libs=$(cd "$dir" && ninja -t deps "$obj" 2>/dev/null |
        grep -oE "/usr/include/($heavy)" | sed 's|/usr/include/||' | sort | uniq -c |
        awk '{ printf "%s%s %d", sep, $2, $1; sep = ", " }')
    printf "%7.1f  %s\n          %s\n" "$seconds" "$obj" "${libs:-(no heavy headers)}"
done < <(grep '\.o$' <<<"$steps" | head -"$top")

# LastTest.log has the measured time of each test the last ctest run ran (CTestCostData.txt is a
# running average that the COST properties of tests/slow_tests.cmake seed).
last="$dir/Testing/Temporary/LastTest.log"
echo
if [ -f "$last" ]; then
    n=$((top > 30 ? top : 30))
    echo "== tests: the $n slowest of the last ctest run (seconds each; $last)"
    awk '/^[0-9]+\/[0-9]+ Testing: / { name = $3 } /^Test time = / { print $4, name }' "$last" |
        sort -rn | awk -v n="$n" '
        { sum += $1; if (NR <= n) printf "%7.1f  %s\n", $1, $2; count++ }
        END { printf "%d tests, %.0f s in all (the wall time is less: CTest runs them side by side)\n", count, sum }'
else
    echo "== tests: no $last (run ctest in $dir first)"
fi
