#!/usr/bin/env bash
# The layering, checked from the sources (docs/layout.md): every #include "a/b/..." of a folder
# must name the folder itself or a folder below it in this table. The build enforces the same
# through each library's include root; this check also covers headers nothing compiles yet and
# says which rule broke. Exit 1 with one line per offending include.
#
#   tools/check-layers.sh [ROOT]
set -euo pipefail
root=${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}

# folder: the folders its files may include (besides their own). Lower layers first.
declare -A may=(
    [config]=""
    [planner]="config"
    [drivers/marlin]="config drivers/device_state.hpp drivers/extruder"
    [drivers/extruder]="config drivers/marlin drivers/device_state.hpp"
    [drivers/abb]="config planner"
    [drivers/sim]="config planner drivers/marlin drivers/extruder drivers/device_state.hpp drivers/abb"
    [daemon/cell]="config planner drivers/marlin drivers/extruder drivers/device_state.hpp drivers/abb"
    [daemon/sync]="config planner drivers/marlin drivers/extruder drivers/device_state.hpp drivers/abb"
    [daemon/api]="config"
    [daemon/http]="config daemon/api"
    [daemon/print]="config planner drivers/marlin drivers/extruder drivers/device_state.hpp drivers/abb daemon/cell daemon/sync"
    [daemon/jobs]="config planner drivers/marlin drivers/extruder drivers/device_state.hpp drivers/abb daemon/cell daemon/sync daemon/print"
    [daemon/service]="config planner drivers daemon/cell daemon/sync daemon/api daemon/http daemon/print daemon/jobs"
)

bad=0
for folder in "${!may[@]}"; do
    [ -d "$root/$folder" ] || continue
    allowed="$folder ${may[$folder]}"
    while IFS= read -r hit; do
        file=${hit%%:*}
        inc=$(sed -E 's/.*#include "([^"]+)".*/\1/' <<<"${hit#*:*:}")
        [[ $inc == */* ]] || continue  # a header beside the file
        ok=0
        for a in $allowed; do
            if [[ $inc == "$a" || $inc == "$a"/* ]]; then ok=1; break; fi
        done
        if [ $ok -eq 0 ]; then
            echo "${file#"$root"/}: includes $inc, which $folder may not use (tools/check-layers.sh)"
            bad=1
        fi
    done < <(grep -rn --include='*.hpp' --include='*.cpp' '^#include "' "$root/$folder" || true)
done
exit $bad
