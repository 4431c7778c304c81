#!/usr/bin/env bash
# Process start-up of torte: wall time of `torte <empty script>`, median of N runs (issue 23: <= 0.1 s), with the
# number of shared libraries loaded and the dynamic loader's own statistics (LD_DEBUG=statistics).
# Usage: bench/startup.sh <torte binary> [N=5]
set -euo pipefail
torte=${1:?usage: startup.sh <torte binary> [N]}
n=${2:-5}
script=$(mktemp --suffix=.lua)
trap 'rm -f "$script"' EXIT
: >"$script"
"$torte" "$script" >/dev/null  # warm the page cache
times=()
for ((i = 0; i < n; ++i)); do
  t0=$(date +%s%N)
  "$torte" "$script" >/dev/null
  t1=$(date +%s%N)
  times+=("$(((t1 - t0) / 1000))")
done
median_us=$(printf '%s\n' "${times[@]}" | sort -n | sed -n "$(((n + 1) / 2))p")
echo "runs_us=${times[*]}"
echo "libraries=$(ldd "$torte" | wc -l)"
LD_DEBUG=statistics "$torte" "$script" 2>&1 >/dev/null |
  sed -n 's/^ *[0-9]*:[[:space:]]*\(total startup time in dynamic loader\|number of relocations\|time needed for relocation\): */\1: /p'
printf 'startup_median_s=%.3f (limit 0.100; load average %s)\n' "$(echo "$median_us / 1000000" | bc -l)" \
  "$(cut -d' ' -f1 /proc/loadavg)"
