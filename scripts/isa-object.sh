#!/bin/bash
# Links the per-ISA copy of the render loop (render/render_isa.h) into one relocatable object whose symbols are
# all local except its entry (torte::render_isa::<isa>), so the final link cannot bind a baseline caller to one
# of its inline functions, templates or vtables (all compiled for an ISA the CPU may lack).
#   isa-object.sh OUT ISA LD NM OBJCOPY OBJECTS...
# COMDAT groups are resolved first (--force-group-allocation): a local symbol must not stay a group's key, or the
# final link could still drop this copy for the baseline one of the same name. Data (function-local statics,
# inline variables, typeinfo) stays global and is shared with the baseline copy, except vtables, which point to
# this copy's functions.
set -euo pipefail
out=$1 isa=$2 ld=$3 nm=$4 objcopy=$5
shift 5
"$ld" -r --force-group-allocation -o "$out.tmp.o" "$@"
entry_mangled="N5torte10render_isa${#isa}${isa}E"
"$nm" --defined-only -g "$out.tmp.o" |
  awk -v keep="$entry_mangled" '($2 ~ /^[TWiV]$/ && index($3, keep) == 0) && ($2 != "V" || $3 ~ /^_ZTV/) {print $3}' \
  >"$out.localize"
"$objcopy" --localize-symbols="$out.localize" "$out.tmp.o" "$out"
# Every defined function but the entry must now be local.
left=$("$nm" --defined-only -g "$out" | awk '$2 ~ /^[TWi]$/' | wc -l)
if [ "$left" != 1 ]; then
  echo "isa-object.sh: $out keeps $left global functions (expected only its entry)" >&2
  exit 1
fi
rm -f "$out.tmp.o"
