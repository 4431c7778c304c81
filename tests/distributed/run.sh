#!/usr/bin/env bash
# Distributed rendering and checkpoint tests (docs/distributed.md), run by ctest on the real binary:
#   run.sh TORTE SOURCE_DIR MPI_FOUND MODE [args]
# Images are compared pixel for pixel with idiff -fail 0 (EXR metadata such as the render time differs).
# Exit 77 (ctest: skipped) for the MPI modes when torte was built without MPI.
set -uo pipefail
torte=$1 src=$2 mpi=$3 mode=$4
shift 4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
scene="$src/scenes/cornell-box.lua"
fail() { echo "FAIL: $*" >&2; exit 1; }
same() {  # same pixels, bit for bit
  idiff -q -fail 0 -warn 0 "$1" "$2" >/dev/null 2>&1 || { idiff -fail 0 -warn 0 "$1" "$2" >&2; fail "$1 and $2 differ"; }
}
need_mpi() {
  if [[ "$mpi" != 1 && "$mpi" != TRUE && "$mpi" != ON ]]; then
    echo "skipped: torte was built without MPI (install libopenmpi-dev: scripts/install-deps.sh)"
    exit 77
  fi
  # Open MPI 4.1 leaves allocations of its components at exit, and unloads them first, so a sanitizer build's
  # leak reports cannot be told from torte's by a suppression (unnamed frames): leak checks are off under mpirun
  # (every other check stays on; torte's leaks are checked by the one-process tests).
  export ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0"
}

case "$mode" in
  ranks)  # run.sh ... ranks R integrator [torte flags]: R ranks make the one-process image
    need_mpi
    ranks=$1 integrator=$2
    flags=("${@:3}")
    args=(width=48 height=40 spp=12 integrator="$integrator")
    "$torte" --quiet --threads 2 "${flags[@]}" "$scene" "${args[@]}" output=one.exr || fail "one-process render"
    timeout 120 mpirun --oversubscribe --allow-run-as-root -n "$ranks" "$torte" --threads 1 "${flags[@]}" "$scene" \
      "${args[@]}" output=many.exr 2>err.txt || { cat err.txt >&2; fail "mpirun -n $ranks"; }
    same one.exr many.exr
    # The other ranks really rendered part of it (a rank rendering the whole frame alone would pass the above).
    share=$(sed -n "s/^distributed over $ranks ranks: \([0-9.]*\) %.*/\1/p" err.txt)
    [[ -n $share ]] || { cat err.txt >&2; fail "no distributed summary line"; }
    (( $(echo "$share > 0" | bc) )) || fail "ranks 1-$((ranks - 1)) rendered $share % of the units"
    ;;
  failing-rank)  # a rank's script error ends the job quickly, naming the rank
    need_mpi
    start=$(date +%s.%N)
    timeout 60 mpirun --oversubscribe --allow-run-as-root -n 2 "$torte" --quiet --threads 1 \
      "$src/tests/distributed/fail_on_rank1.lua" >out.txt 2>&1
    code=$?
    seconds=$(echo "$(date +%s.%N) - $start" | bc)
    [[ $code -ne 0 && $code -ne 124 ]] || { cat out.txt >&2; fail "exit code $code (124: timed out)"; }
    grep -q "torte: error: rank 1: .*rank one refuses to render" out.txt || { cat out.txt >&2; fail "no error line naming rank 1"; }
    (( $(echo "$seconds < 10" | bc) )) || fail "took ${seconds} s (limit 10 s)"
    ;;
  resume)  # run.sh ... resume integrator [R [torte flags]]: Ctrl-C leaves a checkpoint; --resume (on R ranks if given) makes
           # the uninterrupted image. The interruption is of a one-process run: mpirun's own signal handling
           # (SIGTERM, then SIGKILL) is not under test here (docs/distributed.md).
    integrator=$1 ranks=${2:-0}
    flags=("${@:3}")
    run=("$torte")
    resume=("$torte")
    if [[ $ranks -gt 0 ]]; then
      need_mpi
      resume=(mpirun --oversubscribe --allow-run-as-root -n "$ranks" "$torte")
    fi
    args=(width=64 height=64 spp=48 integrator="$integrator")
    "$torte" --quiet --threads 2 "${flags[@]}" "$scene" "${args[@]}" output=full.exr || fail "uninterrupted render"
    "${run[@]}" --quiet --threads 1 "${flags[@]}" --checkpoint ck.bin --checkpoint-every 0 "$scene" "${args[@]}" output=cut.exr &
    pid=$!
    for _ in $(seq 1 400); do [[ -f ck.bin ]] && break; sleep 0.05; done
    [[ -f ck.bin ]] || fail "no checkpoint appeared"
    kill -INT $pid
    wait $pid
    code=$?
    [[ $code -eq 130 ]] || fail "interrupted render exited with $code, expected 130 (finished before the interrupt?)"
    [[ -f cut.exr ]] || fail "the interrupted render wrote no partial image"
    [[ ! -f ck.bin.tmp ]] || fail "a temporary checkpoint was left behind"
    "${resume[@]}" --quiet --threads 1 "${flags[@]}" --resume ck.bin "$scene" "${args[@]}" output=resumed.exr || fail "resume"
    same full.exr resumed.exr
    ;;
  refuse)  # a checkpoint of other settings is refused with one line
    "$torte" --quiet --checkpoint ck.bin "$scene" width=32 height=32 spp=4 output=a.exr || fail "render"
    "$torte" --quiet --resume ck.bin "$scene" width=32 height=32 spp=8 output=b.exr 2>err.txt
    code=$?
    [[ $code -eq 1 ]] || fail "resume of another render exited with $code"
    [[ $(wc -l <err.txt) -eq 1 ]] || { cat err.txt >&2; fail "not one line"; }
    grep -q "checkpoint is of another render (checkpoint has spp=4, this render spp=8)" err.txt ||
      { cat err.txt >&2; fail "unclear message"; }
    "$torte" --quiet --resume ck.bin "$src/scenes/shapes.lua" width=32 height=32 spp=4 output=c.exr 2>err.txt
    [[ $? -eq 1 ]] && grep -q "checkpoint is of another render" err.txt || { cat err.txt >&2; fail "other scene accepted"; }
    # A checkpoint of an older format (version byte 1: no luminance moments) is refused by its version.
    printf '1' | dd of=ck.bin bs=1 seek=7 conv=notrunc status=none
    "$torte" --quiet --resume ck.bin "$scene" width=32 height=32 spp=4 output=d.exr 2>err.txt
    [[ $? -eq 1 ]] && grep -q "a checkpoint of another torte version (format 1, this one reads 2)" err.txt ||
      { cat err.txt >&2; fail "old format not refused by its version"; }
    ;;
  interrupt)  # Ctrl-C on mpirun writes the partial image from rank 0 and ends the job non-zero. mpirun answers
              # SIGINT with SIGCONT, then SIGTERM and SIGKILL each odls_base_sigkill_timeout later (1 s by default:
              # too little for rank 0 to write an image on a loaded machine; docs/distributed.md)
    need_mpi
    start=$(date +%s.%N)
    mpirun --mca odls_base_sigkill_timeout 3 --oversubscribe --allow-run-as-root -n 2 "$torte" --threads 1 --checkpoint ck.bin --checkpoint-every 0 \
      "$scene" width=64 height=64 spp=100000 output=cut.exr >out.txt 2>&1 &
    pid=$!
    for _ in $(seq 1 400); do [[ -f ck.bin ]] && break; sleep 0.05; done
    [[ -f ck.bin ]] || { kill -9 $pid; cat out.txt >&2; fail "the render did not start"; }
    sleep 1  # past MPI start-up: an interrupt inside MPI_Init is mpirun's own business
    kill -INT $pid
    wait $pid
    code=$?
    seconds=$(echo "$(date +%s.%N) - $start" | bc)
    [[ $code -ne 0 ]] || { cat out.txt >&2; fail "an interrupted job exited with 0"; }
    [[ -f cut.exr ]] || { cat out.txt >&2; fail "rank 0 wrote no partial image"; }
    grep -q "INTERRUPTED: partial image" out.txt || { cat out.txt >&2; fail "no summary of the stopped render"; }
    [[ $(grep -c "INTERRUPTED" out.txt) -eq 1 ]] || { cat out.txt >&2; fail "more than one rank printed a summary"; }
    (( $(echo "$seconds < 30" | bc) )) || fail "took ${seconds} s"
    ;;
  dying-rank)  # a rank killed outright (SIGKILL: no error of its own) ends the job within 10 s, naming the rank
    need_mpi
    mpirun --oversubscribe --allow-run-as-root -n 2 "$torte" --threads 1 --checkpoint ck.bin --checkpoint-every 0 \
      "$scene" width=64 height=64 spp=100000 output=cut.exr >out.txt 2>&1 &
    pid=$!
    for _ in $(seq 1 400); do [[ -f ck.bin ]] && break; sleep 0.05; done
    [[ -f ck.bin ]] || { kill -9 $pid; cat out.txt >&2; fail "the render did not start"; }
    sleep 1  # past MPI start-up: an interrupt inside MPI_Init is mpirun's own business
    victim=
    for child in $(pgrep -P $pid); do
      tr '\0' '\n' <"/proc/$child/environ" 2>/dev/null | grep -qx OMPI_COMM_WORLD_RANK=1 && victim=$child
    done
    [[ -n $victim ]] || { kill -9 $pid; fail "rank 1's process not found among mpirun's children"; }
    start=$(date +%s.%N)
    kill -9 "$victim"
    timeout 20 tail --pid=$pid -f /dev/null
    seconds=$(echo "$(date +%s.%N) - $start" | bc)
    wait $pid
    code=$?
    [[ $code -ne 0 ]] || { cat out.txt >&2; fail "the job exited with 0"; }
    grep -qi "rank 1" out.txt || { cat out.txt >&2; fail "no line naming rank 1"; }
    (( $(echo "$seconds < 10" | bc) )) || fail "took ${seconds} s after the rank died (limit 10 s)"
    ;;
  *) fail "unknown mode $mode" ;;
esac
echo "ok: $mode $*"
