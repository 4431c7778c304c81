#!/usr/bin/env bash
# Runs each libFuzzer harness for SECONDS on its corpus, one after another, then prints per harness the
# executions, coverage (libFuzzer's cov: and ft:), corpus size and crashes. Used by `make fuzz`.
#   fuzz/run.sh BUILD_DIR SECONDS HARNESS...        extra libFuzzer flags: FUZZ_ARGS='-max_len=8192 ...'
# The working corpus grows in BUILD_DIR/fuzz-corpus/<harness> (seeded from fuzz/corpus/<harness> and
# fuzz/regressions/<harness>, which are only read); crash, timeout and out-of-memory inputs land in
# BUILD_DIR/fuzz-artifacts/<harness>/, libFuzzer's output in BUILD_DIR/fuzz-logs/<harness>.log. Exit status 1
# when any harness found a crash.
set -uo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "$1" && pwd)
seconds=$2
shift 2
declare -A dict=([ply]=ply [obj]=obj [nbt]=nbt [region]=nbt)
# Harnesses whose caches (OpenImageIO's, a reused Lua state's garbage) unbalance malloc and free in most inputs:
# libFuzzer would run a leak check after each of those; leaks are still checked when the process exits.
declare -A no_leak_check=([image]=1 [kwargs]=1 [region]=1)
# Byte programs: full-length inputs from the start (libFuzzer's growing length limit would keep them a few
# operations long for minutes).
declare -A max_len=([kwargs]=256 [lua_api]=768)
summary=()
failed=0
for h in "$@"; do
  bin=$build/fuzz/fuzz_$h
  work=$build/fuzz-corpus/$h
  artifacts=$build/fuzz-artifacts/$h
  log=$build/fuzz-logs/$h.log
  mkdir -p "$work" "$artifacts" "$build/fuzz-logs"
  inputs=("$work")
  for dir in "$repo/fuzz/corpus/$h" "$repo/fuzz/regressions/$h"; do [[ -d $dir ]] && inputs+=("$dir"); done
  flags=(-max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1
         -artifact_prefix="$artifacts/")
  [[ -n ${dict[$h]:-} ]] && flags+=(-dict="$repo/fuzz/dict/${dict[$h]}.dict")
  [[ -n ${no_leak_check[$h]:-} ]] && flags+=(-detect_leaks=0)
  [[ -n ${max_len[$h]:-} ]] && flags+=(-max_len="${max_len[$h]}" -len_control=0)
  marker=$build/fuzz-logs/.$h.start
  touch "$marker"
  echo "fuzz: $h for ${seconds}s (log: $log)" >&2
  start=$(date +%s)
  # shellcheck disable=SC2086
  UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1} nice -n "${FUZZ_NICE:-5}" "$bin" "${flags[@]}" ${FUZZ_ARGS:-} "${inputs[@]}" > "$log" 2>&1
  rc=$?
  elapsed=$(( $(date +%s) - start ))
  # slow-unit-* files (inputs past -report_slow_units, 10 s by default, yet within the timeout) are no failure.
  new=$(find "$artifacts" -type f -newer "$marker" ! -name 'slow-unit-*' | sort)
  execs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$')
  last=$(grep -E '^#[0-9]+' "$log" | tail -1)
  cov=$(grep -oE 'cov: [0-9]+' <<< "$last" | grep -o '[0-9]*')
  ft=$(grep -oE 'ft: [0-9]+' <<< "$last" | grep -o '[0-9]*')
  corp=$(grep -oE 'corp: [0-9]+/[0-9]+[a-zA-Z]*' <<< "$last" | cut -d' ' -f2)
  crashes=$(grep -c . <<< "$new")
  if ((rc != 0 || crashes > 0)); then
    failed=1
    echo "fuzz: $h stopped with status $rc; new artifacts:" >&2
    echo "$new" >&2
    grep -m3 -E 'ERROR|SUMMARY|broken promise|Timeout|out-of-memory' "$log" >&2
  fi
  summary+=("$(printf '%-10s %6ss %12s execs %8s exec/s  cov %6s  ft %7s  corpus %-12s crashes %s' "$h" "$elapsed" \
    "${execs:-?}" "$(( ${execs:-0} / (elapsed > 0 ? elapsed : 1) ))" "${cov:-?}" "${ft:-?}" "${corp:-?}" "$crashes")")
done
echo
echo "fuzz summary (${seconds}s per harness):"
printf '%s\n' "${summary[@]}"
exit $failed
