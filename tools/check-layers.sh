#!/usr/bin/env bash
# The layering, checked from the sources (docs/layout.md): every #include "a/b/..." of a folder
# (or of a file named in the table) must name the folder itself or a folder below it in this
# table; every C++ file of the product and its programs belongs to an entry, so a new folder is
# placed in the layering before it lands. The build enforces the same through each library's
# include root; this check also covers headers nothing compiles yet and says which rule broke.
# Exit 1 with one line per offending include or file.
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
    [drivers/abb]="config"
    [drivers/sim]="config drivers/marlin drivers/extruder drivers/device_state.hpp drivers/abb"
    [daemon/cell]="config drivers/marlin drivers/extruder drivers/device_state.hpp drivers/abb"
    [daemon/sync]="config drivers/marlin drivers/extruder drivers/device_state.hpp drivers/abb"
    [daemon/api]="config"
    [daemon/http]="config daemon/api"
    [daemon/print]="config planner drivers/marlin drivers/extruder drivers/device_state.hpp drivers/abb daemon/cell daemon/sync"
    [daemon/component]="config daemon/api daemon/http"
    [daemon/devices]="config drivers daemon/cell daemon/sync daemon/print daemon/api daemon/http daemon/component"
    [daemon/jobs]="config planner drivers/marlin drivers/extruder drivers/device_state.hpp drivers/abb daemon/cell daemon/sync daemon/print daemon/api daemon/http daemon/component"
    [daemon/printer]="config planner drivers daemon/cell daemon/sync daemon/print daemon/api daemon/http daemon/component daemon/devices daemon/jobs"
    [daemon/queue]="config daemon/cell daemon/api daemon/http daemon/component daemon/devices daemon/jobs daemon/printer"
    [daemon/history]="config daemon/cell daemon/api daemon/http daemon/component daemon/devices daemon/jobs daemon/printer"
    [daemon/spools]="config daemon/cell daemon/api daemon/http daemon/component daemon/devices daemon/jobs daemon/printer daemon/queue"
    [daemon/log]="config daemon/api daemon/http daemon/component"
    [daemon/service]="config planner drivers daemon/cell daemon/sync daemon/api daemon/http daemon/print daemon/component daemon/devices daemon/jobs daemon/printer daemon/queue daemon/history daemon/spools daemon/log"
    [daemon/main.cpp]="config planner drivers daemon"
    [drivers/device_state.hpp]=""
    [drivers/device_state.cpp]="drivers/device_state.hpp"
    # The programs: the CLI is the service's client and plans offline, never the service itself;
    # the simulators' programs know the simulated devices (and the cell YAML), nothing of jobs.
    [tools/fibrecell]="config planner daemon/api daemon/cell daemon/jobs"
    [tools/fibrecell-simcell]="config drivers/abb drivers/sim"
    [tools/gt2560-avr]="config daemon/cell drivers/sim/avr"
    [tools/mock-gt2560]="config drivers/sim"
    [tools/board-check]=""
)

bad=0
for folder in "${!may[@]}"; do
    [ -e "$root/$folder" ] || continue
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
# Every C++ file under an entry of the table.
while IFS= read -r file; do
    rel=${file#"$root"/}
    placed=0
    for folder in "${!may[@]}"; do
        if [[ $rel == "$folder" || $rel == "$folder"/* ]]; then placed=1; break; fi
    done
    if [ $placed -eq 0 ]; then
        echo "$rel: in no folder of the layering table (tools/check-layers.sh, docs/layout.md)"
        bad=1
    fi
done < <(find "$root/config" "$root/planner" "$root/drivers" "$root/daemon" "$root/tools" \
         \( -name node_modules -prune \) -o \( -name '*.cpp' -o -name '*.hpp' \) -print 2>/dev/null)
exit $bad
