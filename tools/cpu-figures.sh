#!/bin/sh
# The CPU figures of docs/benchmarks.md: meshing time (fresh cache) and step time per
# mesh level on the first second of the paper sweep, and the full paper sweep with and
# without the tumour on the coarse mesh. Usage: tools/cpu-figures.sh OUTDIR [LEVELS]
set -eu
out=${1:?usage: tools/cpu-figures.sh OUTDIR [LEVELS]}
levels=${2:-"coarse paper fine"}
bin=$(dirname "$0")/../build/app/palpation
mkdir -p "$out"
export PALPATION_CACHE_DIR="$out/cache"
rm -rf "$PALPATION_CACHE_DIR"
"$bin" scenario paper-sweep > "$out/paper-sweep.json"
for level in $levels; do
  python3 - "$out" "$level" <<'PY'
import json, sys
out, level = sys.argv[1], sys.argv[2]
s = json.load(open(f"{out}/paper-sweep.json"))
s["patient"]["resolution"] = level
s["duration"] = 1.0
json.dump(s, open(f"{out}/step-{level}.json", "w"))
PY
  "$bin" run "$out/step-$level.json" --out "$out/step-$level" 2> "$out/step-$level.log"
  grep -h "meshing:" "$out/step-$level.log" || true
  python3 -c "import json;s=json.load(open('$out/step-$level/summary.json'));print('$level', s['nodes'], s['tetrahedra'], 'step_ms_median', round(s['step_ms_median'],3), 'p99', round(s['step_ms_p99'],3), 'cg mean', round(s['cg_iterations_mean'],1), 'max', s['cg_iterations_max'])"
done
