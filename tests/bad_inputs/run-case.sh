#!/usr/bin/env bash
# Runs one case of the bad-input catalogue: torte on tests/bad_inputs/<group>/<case>.lua, in a fresh temporary
# working directory, and checks what a user would see. Usage: run-case.sh TORTE CASE.lua SHARED_DATA
#
# A case is a Lua script whose first comment lines say what must happen:
#   -- expect: TEXT       required: the one stderr line contains TEXT (plain text, not a pattern)
#   -- where: REGEX       the line also matches REGEX (extended regex); default: '<case>.lua:[0-9]+:'
#   -- flags: ...         torte options before the script (--quiet is always given)
#   -- args: k=v ...      key=value arguments after the script
#   -- exit: N            expected exit code (default 1)
#   -- warning            the run succeeds (exit 0 unless `exit:` says otherwise) and stderr is exactly one line
#                         starting with "torte: warning: "
#   -- sigint: SECONDS    send SIGINT (Ctrl-C) that long after the start (default exit then 130)
#   -- needs-data: PATH   skip (exit 77) unless SHARED_DATA/PATH exists
#   -- timeout: SECONDS   a run longer than this is a hang (default 60)
# In flags and args, $DATA is SHARED_DATA, $CASE the case's directory and $TMP the working directory.
# Checked: the exit code; stderr is exactly one line, "torte: error: " (or "torte: warning: ") followed by the
# location and TEXT; no control bytes other than the line end; no crash or hang.
set -uo pipefail
torte=$1 case_file=$2 data=$3
case_file=$(readlink -f "$case_file")
case_dir=$(dirname "$case_file")
name=$(basename "$case_file")

directive() { sed -n "s/^-- $1: *//p" "$case_file" | head -1; }
expect=$(directive expect)
where=$(directive where)
flags=$(directive flags)
args=$(directive args)
exit_want=$(directive exit)
sigint=$(directive sigint)
needs=$(directive needs-data)
limit=$(directive timeout)
warning=0
grep -q '^-- warning *$' "$case_file" && warning=1
[[ -n $expect ]] || { echo "case $name has no '-- expect:' line"; exit 2; }
[[ -n $where ]] || where="${name//./\\.}:[0-9]+:"
[[ -n $limit ]] || limit=60
if [[ -z $exit_want ]]; then
  if ((warning)); then exit_want=0; elif [[ -n $sigint ]]; then exit_want=130; else exit_want=1; fi
fi
if [[ -n $needs && ! -e $data/$needs ]]; then
  echo "skipped: $data/$needs is absent (../shared/data is needed for this case)"
  exit 77
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
subst() { local s=${1//\$DATA/$data}; s=${s//\$CASE/$case_dir}; echo "${s//\$TMP/$tmp}"; }
read -r -a flag_words <<<"$(subst "$flags")"
read -r -a arg_words <<<"$(subst "$args")"

cd "$tmp" || exit 2
# Helpers shared by cases (lib/case.lua, lib/mc_region.lua): `require "case"`.
export LUA_PATH_5_4="$(dirname "$(readlink -f "$0")")/lib/?.lua;;"
if [[ -n $sigint ]]; then
  "$torte" --quiet "${flag_words[@]}" "$case_file" "${arg_words[@]}" >stdout.txt 2>stderr.txt &
  pid=$!
  sleep "$sigint"
  kill -INT "$pid" 2>/dev/null
  for ((i = 0; i < limit * 10; ++i)); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  if kill -0 "$pid" 2>/dev/null; then kill -KILL "$pid"; echo "FAIL: still running ${limit} s after SIGINT"; exit 1; fi
  wait "$pid"
  code=$?
else
  timeout -s KILL "$limit" "$torte" --quiet "${flag_words[@]}" "$case_file" "${arg_words[@]}" >stdout.txt 2>stderr.txt
  code=$?
fi

fail() {
  echo "FAIL: $1"
  echo "--- command: torte --quiet ${flag_words[*]} $case_file ${arg_words[*]}"
  echo "--- exit code: $code (expected $exit_want)"
  echo "--- stderr:"
  cat -v stderr.txt | head -20
  exit 1
}
((code == 137)) && fail "killed after ${limit} s (a hang) or by the OOM killer"
((code >= 128 && code != exit_want)) && fail "died from signal $((code - 128))"
((code == exit_want)) || fail "wrong exit code"
if ((exit_want == 130)) && [[ -n $sigint ]] && ! grep -q "torte: error:" stderr.txt && ((warning == 0)) &&
   [[ $expect == "-" ]]; then
  exit 0  # an interrupt with nothing to report
fi
lines=$(grep -c '' stderr.txt)
((lines == 1)) || fail "stderr has $lines lines, expected exactly one"
line=$(cat stderr.txt)
if LC_ALL=C grep -q '[[:cntrl:]]' <<<"$line"; then fail "the message holds control bytes"; fi
if ((warning)); then prefix="torte: warning: "; else prefix="torte: error: "; fi
[[ $line == "$prefix"* ]] || fail "the line does not start with '$prefix'"
grep -qE -- "$where" <<<"$line" || fail "the line does not name the location (/$where/)"
grep -qF -- "$expect" <<<"$line" || fail "the line does not say '$expect'"
echo "ok: $line"
