#!/usr/bin/env bash
# Why the last ctest run's failed tests failed, in a few lines each: the failure lines of each one's
# output (GoogleTest's "Failure" blocks, the browser test's FAIL, a timeout), read back from CTest's
# own log. tools/setup.sh prints it after a failed suite, last, where a CI log's tail shows it.
#
#   tools/why-tests-failed.sh BUILD_DIR [LINES_PER_TEST]
set -euo pipefail
build=${1:?usage: tools/why-tests-failed.sh BUILD_DIR [LINES_PER_TEST]}
per_test=${2:-12}
log="$build/Testing/Temporary/LastTest.log"
failed="$build/Testing/Temporary/LastTestsFailed.log"
[ -s "$failed" ] && [ -f "$log" ] || exit 0

echo "why the failed tests failed (from $log):"
while IFS=: read -r _ name; do
    echo "--- $name"
    # The test's output: after its "Test: NAME" header, from the rule under "Output:" to the next
    # "<end of output>".
    output=$(awk -v name="$name" '
        $0 ~ /^[0-9]+\/[0-9]+ Test: / { sub(/^[0-9]+\/[0-9]+ Test: /, ""); wanted = ($0 == name); next }
        wanted && /^Output:/ { getline; inside = 1; next }
        inside && /^<end of output>/ { inside = wanted = 0 }
        inside' "$log")
    why=$(grep -E -A4 'Failure$|^FAIL|Expected|Which is|timed out|AddressSanitizer|runtime error|terminate called' \
        <<<"$output" | head -n "$per_test" || true)
    # Nothing that reads as a failure (a timeout, a crash): how its output ended.
    if [ -n "$why" ]; then echo "$why"; else tail -n 5 <<<"$output"; fi
done <"$failed"
