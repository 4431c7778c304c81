#!/usr/bin/env bash
# RMSE against time of each integrator on the caustic, mirror-lit and door-gap scenes (docs/integrators.md): a long
# reference per scene (`bdpt`, unbiased; `vcm` for the caustic scene, whose light seen through the glass only
# merging renders without fireflies, and which converges as its radius shrinks), then every integrator under
# several time budgets (`time_limit`, which stops at a pass boundary; the EXR's torte:render_seconds is the time
# used). Pixels of the reference brighter than 100x its mean (the lamps' own reflections in mirrors and glass, whose
# antialiasing noise no integrator changes) are left out. Prints RMSE and RMSE at equal time (RMSE * sqrt(seconds), as Monte Carlo error falls as 1/sqrt(time)),
# writes out/integrator-rmse/results.csv and plots docs/integrator-rmse.png.
# Usage: scripts/integrator-rmse.sh [build dir]; W, H (160x120), BUDGETS ("2 4 8 16" seconds), REF_SECONDS (300),
# SCENES ("caustic mirror-lit door-gap") and INTEGRATORS ("path bdpt vcm mlt") override the defaults; renders that
# exist are reused unless FORCE=1. Run it on an idle machine:
# equal-time comparisons are only as good as the clock. Needs scripts/install-deps.sh --plots.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
W=${W:-160}
H=${H:-120}
BUDGETS=(${BUDGETS:-2 4 8 16})
REF_SECONDS=${REF_SECONDS:-300}
SCENES=(${SCENES:-caustic mirror-lit door-gap})
INTEGRATORS=(${INTEGRATORS:-path bdpt vcm mlt})
OUT=out/integrator-rmse
mkdir -p "$OUT"
bash scripts/install-deps.sh --plots
run() {  # scene integrator seconds seed output
  "$BUILD/torte" --quiet "scenes/$1.lua" width="$W" height="$H" spp=16000000 integrator="$2" time_limit="$3" \
    seed="$4" output="$5"
}
for s in "${SCENES[@]}"; do
  ref_integrator=bdpt
  [[ $s == caustic ]] && ref_integrator=vcm
  ref="$OUT/$s-ref-${REF_SECONDS}s-${W}x$H.exr"
  if [[ ! -f $ref ]]; then
    echo "integrator-rmse: $s: reference, $ref_integrator for $REF_SECONDS s" >&2
    run "$s" "$ref_integrator" "$REF_SECONDS" 7 "$ref"
  fi
  for i in "${INTEGRATORS[@]}"; do
    for b in "${BUDGETS[@]}"; do
      f="$OUT/$s-$i-${b}s-${W}x$H.exr"
      [[ -f $f && -z ${FORCE:-} ]] && continue  # FORCE=1 renders again
      echo "integrator-rmse: $s: $i for $b s" >&2
      run "$s" "$i" "$b" 1 "$f"
    done
  done
done
/usr/bin/python3 - "$OUT" "$REF_SECONDS" "$W" "$H" "${#SCENES[@]}" "${SCENES[@]}" "${INTEGRATORS[@]}" -- \
  "${BUDGETS[@]}" <<'PY'
import sys, numpy as np, OpenImageIO as oiio
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
args = sys.argv[1:]
out, ref_seconds, w, h, n = args[0], args[1], args[2], args[3], int(args[4])
scenes = args[5:5 + n]
rest = args[5 + n:]
integrators, budgets = rest[:rest.index("--")], rest[rest.index("--") + 1:]
def load(path):
    b = oiio.ImageBuf(path)
    if b.has_error:
        sys.exit(f"integrator-rmse: cannot read {path}: {b.geterror()}")
    spec = b.spec()
    return (b.get_pixels(oiio.FLOAT)[:, :, :3], float(spec.get_float_attribute("torte:render_seconds")),
            spec.get_string_attribute("torte:integrator"))
rows = []
fig, axes = plt.subplots(1, len(scenes), figsize=(5.5 * len(scenes), 4.2), squeeze=False)
for ax, s in zip(axes[0], scenes):
    ref, ref_t, ref_i = load(f"{out}/{s}-ref-{ref_seconds}s-{w}x{h}.exr")
    # The lamps seen in mirrors and glass: a few pixels hundreds of times the mean, whose antialiasing noise (how
    # much of the pixel the tiny reflection covers) no integrator reduces and which would swamp the RMSE.
    level = ref.mean(axis=2)
    keep = level <= 100 * level.mean()
    print(f"{s}: reference {ref_i} {ref_t:.0f} s, mean {ref.mean():.5f}; {int((~keep).sum())} pixels above 100x the "
          f"mean left out")
    equal = {}
    for i in integrators:
        ts, es = [], []
        for b in budgets:
            img, t, _ = load(f"{out}/{s}-{i}-{b}s-{w}x{h}.exr")
            e = float(np.sqrt(((img - ref) ** 2)[keep].mean()))
            ts.append(t)
            es.append(e)
            rows.append((s, i, b, t, e, e * np.sqrt(t)))
            print(f"{s} {i:5s} budget {b:>3s} s: {t:6.2f} s, RMSE {e:.5f}, RMSE*sqrt(s) {e * np.sqrt(t):.5f}, "
                  f"mean {img.mean():.5f}")
        equal[i] = float(np.median([e * np.sqrt(t) for e, t in zip(es, ts)]))
        ax.loglog(ts, es, "o-", label=i)
    best = min((x for x in integrators if x != "path"), key=lambda x: equal[x])
    if "path" in equal:
        print(f"{s}: at equal time (median over budgets) {best} has {equal['path'] / equal[best]:.2f}x lower RMSE "
              f"than path")
    ax.set_title(f"{s}.lua ({w}x{h}; reference: {ref_i}, {ref_t:.0f} s)")
    ax.set_xlabel("render time (s, 2 threads)")
    ax.set_ylabel("RMSE against the reference")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
fig.tight_layout()
fig.savefig("docs/integrator-rmse.png", dpi=100)
with open(f"{out}/results.csv", "w") as f:
    f.write("scene,integrator,budget_s,seconds,rmse,rmse_sqrt_s\n")
    for r in rows:
        f.write(",".join(str(x) for x in r) + "\n")
print("integrator-rmse: wrote docs/integrator-rmse.png and", f"{out}/results.csv")
PY
