#!/bin/sh
# bench/load_scaling.sh: how the cost of loading grows with the size of a robot or scene
# (docs/benchmarks.md, "Loading large models"). Writes chains of N links and times
# `frontier info` on each, one process per row:
#
#   urdf-revolute  a URDF chain of N links, each on a revolute joint (N bodies)
#   urdf-fixed     the same chain on fixed joints (all N links welded into one body)
#   yaml-ball      a YAML scene of N boxes on ball joints (scenes/tools/make_chain.py)
#
# Every link has an inertial and a 0.12 x 0.02 x 0.02 m box 0.1 m after the previous one (the
# neighbours overlap: the starting-overlap filter has work to do).
#
# Columns: kind, N, CPU seconds (user + system, which a shared machine's load inflates far less
# than wall time), wall seconds, max RSS MB, and CPU time / (N log2 N) in nanoseconds: roughly
# constant when the growth is no faster than N log N.
#
# Usage: bench/load_scaling.sh [FRONTIER] [N ...]
#   FRONTIER  the program (default build/app/frontier)
#   N         sizes (default 10000 100000 1000000)
# Set KINDS to a subset ("urdf-revolute urdf-fixed yaml-ball") to time fewer kinds.
set -eu

here=$(cd "$(dirname "$0")" && pwd)
frontier=${1:-"$here/../build/app/frontier"}
[ $# -gt 0 ] && shift
sizes=${*:-"10000 100000 1000000"}
kinds=${KINDS:-"urdf-revolute urdf-fixed yaml-ball"}
# A URDF chain of a million links is 350 to 420 MB, above the default input limit of 256 MiB.
export FRONTIER_MAX_INPUT_BYTES="${FRONTIER_MAX_INPUT_BYTES:-1073741824}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT INT TERM

# A URDF chain of $1 links on joints of type $2 (revolute or fixed), to stdout.
urdf_chain() {
    awk -v n="$1" -v type="$2" 'BEGIN {
        print "<?xml version=\"1.0\"?>"
        print "<robot name=\"chain\">"
        for (i = 0; i < n; ++i) {
            printf "<link name=\"l%d\"><inertial><mass value=\"0.1\"/>", i
            printf "<inertia ixx=\"1e-5\" ixy=\"0\" ixz=\"0\" iyy=\"1e-4\" iyz=\"0\" izz=\"1e-4\"/></inertial>"
            printf "<collision><origin xyz=\"0.05 0 0\"/><geometry><box size=\"0.12 0.02 0.02\"/></geometry>"
            print "</collision></link>"
            if (i == 0) continue
            printf "<joint name=\"j%d\" type=\"%s\"><parent link=\"l%d\"/><child link=\"l%d\"/>", i, type, i - 1, i
            printf "<origin xyz=\"0.1 0 0\"/>"
            if (type == "revolute")
                printf "<axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"1\"/>"
            print "</joint>"
        }
        print "</robot>"
    }'
}

printf '%-14s %9s %8s %8s %8s %14s\n' kind N "CPU s" "wall s" "RSS MB" "ns/(N log2 N)"
for kind in $kinds; do
    for n in $sizes; do
        case $kind in
        urdf-revolute) file="$work/chain.urdf"; urdf_chain "$n" revolute >"$file" ;;
        urdf-fixed) file="$work/chain.urdf"; urdf_chain "$n" fixed >"$file" ;;
        yaml-ball) file="$work/chain.yaml"; python3 "$here/../scenes/tools/make_chain.py" "$n" "$file" ;;
        *) echo "unknown kind '$kind'" >&2; exit 2 ;;
        esac
        if /usr/bin/time -f '%e %U %S %M' -o "$work/time" "$frontier" info "$file" >/dev/null 2>"$work/err"; then
            read -r wall user system kb <"$work/time"
            awk -v k="$kind" -v n="$n" -v w="$wall" -v u="$user" -v s="$system" -v kb="$kb" 'BEGIN {
                cpu = u + s
                printf "%-14s %9d %8.2f %8.2f %8.0f %14.1f\n", k, n, cpu, w, kb / 1024, cpu * 1e9 / (n * log(n) / log(2))
            }'
        else
            printf '%-14s %9d  failed: %s\n' "$kind" "$n" "$(tail -n 1 "$work/err")"
        fi
        rm -f "$file"
    done
done
