#!/usr/bin/env bash
# fibrecell developer entry point: installs missing Debian packages, configures, builds, and
# runs one of the two jobs a new user needs.
#
#   tools/setup.sh demo   build (Release), start the simulated cell's service, print the bundled example
#   tools/setup.sh test   build (sanitizers on) and run the whole test suite
#   tools/setup.sh build  only install and build (Release)
#   tools/setup.sh install  only install what any of them needs (.ci/run, before its two builds)
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
jobs=$(nproc 2>/dev/null || echo 2)

# Everything the project builds against, by Debian package name.
packages=(
    g++ cmake ninja-build pkg-config
    libeigen3-dev libboost-dev libboost-graph-dev libsuitesparse-dev
    libopenblas0-pthread  # CHOLMOD factorises ~4x faster than with the reference BLAS
    libspdlog-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libpolyclipping-dev
    libmodbus-dev libsystemd-dev
    libssl-dev  # libcrypto MD5 for RWS digest authentication
    libgtest-dev libgmock-dev
    libsimavr-dev libelf-dev  # gt2560-avr: the GT2560 running real AVR firmware (simavr)
    gcc-avr avr-libc          # the GT2560 test firmware (tests/firmware)
    nodejs                    # the dashboard's npm packages (web/package.json)
)
# What makes builds fast (docs/building.md): a compiler cache and a faster linker; the build uses
# them when they are installed, and works without them.
build_packages=(ccache mold)
# The dashboard's browser tests (tests/web): Debian's Chromium, driven by puppeteer-core.
test_packages=(chromium fonts-dejavu-core)

# shellcheck source=tools/apt-install.sh
source "$root/tools/apt-install.sh"

# phase NAME COMMAND...: runs COMMAND, then says how long it took (a slow phase is found at a
# glance; docs/building.md says what each should take).
phase() {
    local name=$1 start=$SECONDS
    shift
    "$@"
    echo "setup: $name took $((SECONDS - start)) s"
}

# The dashboard's packages from the npm registry, exactly as web/package-lock.json pins them;
# again only when the lockfile changed. The pages use them as they are: no bundler, no build step.
install_web_packages() {
    command -v npm >/dev/null || install_missing setup npm
    local stamp="$root/web/node_modules/.package-lock.json"
    if [ ! -f "$stamp" ] || [ "$root/web/package-lock.json" -nt "$stamp" ]; then
        echo "setup: installing the dashboard's npm packages (web/package-lock.json)"
        (cd "$root/web" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
    fi
}

# configure_and_build DIR [cmake args...]
configure_and_build() {
    local dir=$1
    shift
    cmake -S "$root" -B "$dir" -G Ninja "$@" >/dev/null
    cmake --build "$dir" --parallel "$jobs"
}

# The service in simulation mode on a private socket and state directory, the bundled Loop
# example submitted, printed with live progress, and a summary at the end (docs/demo.md).
run_demo() {
    local demo="$root/out/demo"
    local sock="$demo/api.sock" log="$demo/fibrecelld.log"
    rm -rf "$demo"
    mkdir -p "$demo"
    # The dashboard too (docs/dashboard.md), with a token of this demo's own.
    (umask 077 && od -An -tx1 -N16 /dev/urandom | tr -d ' \n' >"$demo/dashboard.token")
    "$release_dir/daemon/fibrecelld" --config "$root/config/cell-demo.yaml" \
        --state-dir "$demo/state" --socket "$sock" \
        --dashboard-token-file "$demo/dashboard.token" >"$log" 2>&1 &
    local pid=$!
    # shellcheck disable=SC2064  # the pid is fixed now; the trap runs after this function
    trap "kill $pid 2>/dev/null; wait $pid 2>/dev/null" EXIT
    for _ in $(seq 100); do
        grep -q '^fibrecelld: dashboard on' "$log" 2>/dev/null && break  # after the socket
        kill -0 "$pid" 2>/dev/null || { cat "$log" >&2; echo "demo: fibrecelld did not start" >&2; exit 1; }
        sleep 0.1
    done
    echo "demo: fibrecelld (simulated cell) is up on $sock; log: $log"
    local url
    url=$(sed -n 's/^fibrecelld: dashboard on //p' "$log" | head -1)
    echo "demo: watch it in a browser: $url (token: $(cat "$demo/dashboard.token"))"
    export FIBRECELL_SOCKET="$sock"
    # The cell's state is shown whatever the outcome; the exit status is the print's (0 only
    # for completed).
    local outcome=0
    "$release_dir/tools/fibrecell" submit "$root/examples/loop/loop.job.yaml" --start --watch ||
        outcome=$?
    "$release_dir/tools/fibrecell" status
    # What the print used, by the board's count, beside the plan (docs/history.md).
    "$release_dir/tools/fibrecell" history
    return "$outcome"
}

# The whole suite but the soak test (label soak, tests/print/print_soak_test.cpp, run by hand:
# ctest -L soak). One slot more than cores: the print through the board simulator (real time,
# mostly waiting) runs beside the rest instead of taking a core's place (docs/building.md). When a
# test fails, why it failed comes last, where the tail of a CI log shows it.
run_suite() {
    local status=0
    (cd "$test_dir" && ctest --output-on-failure --parallel "$((jobs + 1))" --timeout 300 -LE soak) ||
        status=$?
    if [ "$status" -ne 0 ]; then "$root/tools/why-tests-failed.sh" "$test_dir" || true; fi
    return "$status"
}

release_dir="$root/build/release"
test_dir="$root/build/test"

case "${1:-demo}" in
    build)
        phase "installing packages" install_missing setup "${packages[@]}" "${build_packages[@]}"
        phase "the dashboard's packages" install_web_packages
        phase "the Release build" configure_and_build "$release_dir" -DCMAKE_BUILD_TYPE=Release \
            -DFIBRECELL_TESTS=OFF
        ;;
    demo)
        phase "installing packages" install_missing setup "${packages[@]}" "${build_packages[@]}"
        phase "the dashboard's packages" install_web_packages
        phase "the Release build" configure_and_build "$release_dir" -DCMAKE_BUILD_TYPE=Release \
            -DFIBRECELL_TESTS=OFF
        run_demo
        ;;
    test)
        phase "installing packages" install_missing setup "${packages[@]}" "${build_packages[@]}" \
            "${test_packages[@]}"
        phase "the dashboard's packages" install_web_packages
        phase "the sanitizer build" configure_and_build "$test_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
            -DFIBRECELL_SANITIZE=ON -DFIBRECELL_BENCH=OFF -DFIBRECELL_SOAK=OFF
        phase "the test suite" run_suite
        ;;
    install)
        phase "installing packages" install_missing setup "${packages[@]}" "${build_packages[@]}" \
            "${test_packages[@]}"
        phase "the dashboard's packages" install_web_packages
        ;;
    *)
        echo "usage: tools/setup.sh [demo|test|build|install]" >&2
        exit 2
        ;;
esac
