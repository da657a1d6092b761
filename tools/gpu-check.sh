#!/usr/bin/env bash
# GPU check: build the Qt-free configuration with CUDA, check GPU against CPU,
# benchmark. Meant for the lent GPU machine (no Qt, Eigen, Gmsh, JSON or CLI11 packages
# there): run from the repository root through the device tool with .gpu-carry carried,
#   run(command="bash tools/gpu-check.sh", carry=[".gpu-carry"])
# .gpu-carry/include holds eigen3/, nlohmann/, CLI/; .gpu-carry/models the model cache
# (breast meshes coarse/paper/xfine, generated on a machine with Gmsh, and the cached CPU
# reference traces of check-backends). See docs/gpu-notes.md.
#
# Stages (arguments; default: build check hertz micro bench idle sweep):
#   build  cmake + ninja (Release, -DCMAKE_CUDA_ARCHITECTURES=90)
#   check  palpation check-backends (paper-sweep + hertz, linear and nodal-pressure element,
#          1,000 steps; then paper-sweep-layered, nodal-pressure): exit 1 on disagreement
#   levels check-backends on the other mesh levels (LEVELS, default coarse:1000 fine:300
#          xfine:300, level:steps), nodal-pressure element: check-coarse.json, ... Not a
#          default stage (xfine's CPU reference takes minutes); exit 1 on disagreement
#   hertz  palpation hertz on CUDA (hertz.txt): the nodal-pressure element at Poisson's ratio
#          0.40-0.499, two radii and moduli, 28 cells across, with each preconditioner of
#          HERTZ_PRECONDITIONERS (default block-jacobi multigrid multigrid-chebyshev), exit 1 beyond 5 % of
#          Hertz; the linear element beside it on the same mesh (its locking, no limit;
#          HERTZ_LINEAR= leaves it out)
#   micro  design alternatives on the paper and xfine meshes (palpation run + env switches)
#   ncu    Nsight Compute on one step's kernels (paper mesh, in contact)
#   bench  palpation bench: cuda on coarse, paper, xfine in double and float; the library
#          baselines cuda-bsr (the good first port) and cuda-csr (the textbook one) on paper
#          and xfine in double at CG 1e-3 and 1e-6 (the equal-error comparison)
#   baselines that comparison alone, one bench run per mesh of BASELINE_MESHES, then the fast
#          backend with the multigrid on the same element and tolerances; the speed-ups
#          printed at equal tolerance (block-Jacobi against block-Jacobi) and at equal
#          error (the fast backend's quickest point with no larger force error), every
#          backend in each precision of BASELINE_PRECISIONS (default double,float)
#          (baselines.csv, baselines.txt). Not a default stage
#   multigrid block-Jacobi against the multigrid preconditioners on CUDA, one bench run per
#          preconditioner and mesh of MG_MESHES (default paper,xfine,0.00201: the 800k-tet
#          breast), double, CG 1e-3 and 1e-6 and the force error held at 1 % (multigrid.csv,
#          multigrid.txt); MG_PRECONDITIONERS picks some of the three. Not a default stage
#   smoother the multigrid's finest smoothing against Poisson's ratio on the breast: the paper
#          sweep's first SMOOTHER_SECONDS (default 3) with tissue and tumour at each ratio of
#          SMOOTHER_NUS (default 0.45 0.47 0.48 0.484 0.486 0.488 0.49), on SMOOTHER_MESHES
#          (default paper), CUDA, double, CG 1e-3 fixed, with multigrid-jacobi and
#          multigrid-chebyshev back to back: CG iterations, step time and the nodal-pressure
#          share at the build (smoother.txt), where MultigridKeeper::kChebyshevShare should
#          lie. Not a default stage
#   path   the finger path followed linearly between its keys against the monotone cubic
#          (the paper sweeps' default; `palpation bench --path`): each point of PATH_RUNS
#          (default "paper:6000:double paper:6000:float xfine:1000:float",
#          mesh:steps:precision) PATH_REPEAT times (default 2), the two paths alternated, held
#          at 1 %, on the same keys; then an 8 s session on the paper mesh with each path
#          (path.txt: every run's median / p99 ms and CG iterations from its series, the mean
#          and 99th percentile of the iterations, the force error). Not a default stage
#   warmstart the CG's warm start (`palpation bench --warm-start`): each point of
#          WARMSTART_RUNS (default "paper:1000:double paper:1000:float xfine:1000:float")
#          WARMSTART_REPEAT times (default 2), extrapolated and last alternated, held at 1 %;
#          then an 8 s session on the paper mesh with each, twice (warmstart.txt). Not a
#          default stage
#   idle   palpation bench --scenario idle (no contact, at rest)
#   control the error-controlled tolerance against the fixed ones: bench (all tolerances and
#          fe1%; fe1% with its checks in the step and auto, twice) and palpation session with
#          --force-error 0 and 0.01, on CONTROL_MESHES
#          (default paper xfine): control.txt, control-MESH.csv. Not a default stage
#   sweep  the paper's Fig. 6 sweep on CUDA at SWEEP_MESHES (default paper), with and without
#          the tumour, with each of SWEEP_ELEMENTS (default linear nodal-pressure), on each of
#          SWEEP_SCENARIOS (default paper-sweep, the paper's uniform tissue, and
#          paper-sweep-layered, skin, fat and glandular tissue), with each skin membrane
#          thickness of SWEEP_SKIN (default 0: none; e.g. "0 0.0015"): step time, largest push
#          per pass and the tumour/no-tumour ratio (sweep.txt)
#   tests  the sim/ and device/ QtTest suites, packed here beforehand (below; tests.log,
#          tests-summary.txt). Not a default stage; needs no build stage.
#   ab     this tree against an older one on the same machine: the older tree's files,
#          packed here beforehand by `tools/gpu-check.sh ab-pack REV` (below), are laid
#          over a copy of this one; both are built side by side, then `palpation bench`
#          runs each point of AB_RUNS (default "xfine:1000:float 0.00201:400:float",
#          mesh:steps:precision[:preconditioner]) AB_REPEAT times (default 2), new and old
#          alternated, held at 1 % (AB_BENCH_ARGS, default "--force-error 0.01"), with
#          AB_ENV (e.g. PALPATION_CUDA_PHASES=1) in the environment: ab.txt (every run's
#          median / p99 / iterations / force error, and per point the median of each
#          side's medians and their ratio), ab-runs.tar (each run's output). Not a default
#          stage; it builds both trees itself.
# Results go to $OUT (at most 8 files come back from the device tool): run.log, check.json,
# micro.txt, ncu.txt, bench.csv, bench.png (matplotlib where present), idle.csv.
#
# The QtTest suites of sim/ and device/ (tests/sim, tests/device) on the GPU: two steps,
# neither a default stage. The GPU machine has no Qt and no Gmsh, so the suites are built
# HERE and carried as one archive, .gpu-tests/gpu-tests.tar.xz (ignored):
#   tools/gpu-check.sh tests-pack   here, on a machine with Qt 6, CUDA 13 (nvcc) and Ninja:
#       configures TESTS_BUILD (default build-gpu-tests) with CUDA on (sm_90) and Gmsh off,
#       builds the suites CTest lists under tests/sim and tests/device but TESTS_EXCLUDE
#       (default tst_phantom: it meshes with Gmsh), and packs them with the shared
#       libraries that the GPU machine lacks (by ldd: Qt6Test, Qt6Core and theirs; not
#       libc/libm/libstdc++/libgcc_s, nor CUDA's, which are in /usr/local/cuda/lib64 there)
#       and the *.pmesh of TESTS_MODELS_FROM (default build/model-cache: the breast
#       meshes that a ctest run of a build with Gmsh cached; the suites load them there).
#   run(command="bash tools/gpu-check.sh tests", carry=[".gpu-tests"])   on the GPU machine:
#       unpacks into /tmp, runs each suite with LD_LIBRARY_PATH on the carried libraries,
#       QT_QPA_PLATFORM=offscreen and PALPATION_CACHE_DIR on the carried models; writes
#       $OUT/tests.log (all QtTest output; the CUDA cases of tst_backend_agreement print
#       their force and position errors) and $OUT/tests-summary.txt (per suite: exit code,
#       time, passed/failed/skipped). Exit 1 on a failure or crash, or when a CUDA case of
#       tst_backend_agreement skipped (the GPU was not used). TESTS_ONLY="tst_a tst_b" runs
#       those suites alone.
#
# An A/B of two commits on one GPU machine (machines of one kind differ by several per cent,
# so a before and an after are compared only within one run): two steps, neither a default
# stage.
#   tools/gpu-check.sh ab-pack REV   here: writes the files of the build's trees (CMakeLists.txt,
#       app, device, sim, ui, tests, tools, resources, translations) that differ between REV
#       and this working tree, as REV has them, to .gpu-carry/ab/old/, the paths REV lacks to
#       .gpu-carry/ab/removed.txt and REV's short hash to .gpu-carry/ab/rev.txt.
#   run(command="bash tools/gpu-check.sh ab", carry=[".gpu-carry"])   on the GPU machine (the
#       stage above).
set -uo pipefail
ROOT=$(pwd)
# The trees a build reads (ab-pack and ab, below).
AB_TREES="CMakeLists.txt app device sim ui tests tools resources translations"
if [[ ${1:-} == ab-pack ]]; then
  # The older tree of an A/B, as the files that differ from this working tree (above).
  set -e
  REV=${2:?usage: tools/gpu-check.sh ab-pack REV}
  AB=$ROOT/.gpu-carry/ab
  rm -rf "$AB" && mkdir -p "$AB/old"
  git -C "$ROOT" rev-parse --short "$REV" >"$AB/rev.txt"
  : >"$AB/removed.txt"
  # shellcheck disable=SC2086  # the trees are words
  git -C "$ROOT" diff --name-only "$REV" -- $AB_TREES | while read -r f; do
    if git -C "$ROOT" cat-file -e "$REV:$f" 2>/dev/null; then
      mkdir -p "$AB/old/$(dirname "$f")"
      git -C "$ROOT" show "$REV:$f" >"$AB/old/$f"
    else
      echo "$f" >>"$AB/removed.txt"
    fi
  done
  echo "ab-pack: $(find "$AB/old" -type f | wc -l) files as $(cat "$AB/rev.txt") has them, $(wc -l <"$AB/removed.txt") it lacks, in $AB"
  exit 0
fi
if [[ ${1:-} == tests-pack ]]; then
  # Here, not on the GPU machine (see above).
  set -e
  TB=${TESTS_BUILD:-$ROOT/build-gpu-tests}
  MODELS_FROM=${TESTS_MODELS_FROM:-$ROOT/build/model-cache}
  EXCLUDE=" ${TESTS_EXCLUDE:-tst_phantom} "
  say() { echo "[gpu-check tests-pack $(date +%H:%M:%S)] $*"; }
  say "configure $TB (CUDA sm_90, Gmsh off)"
  cmake -S "$ROOT" -B "$TB" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPALPATION_WITH_CUDA=ON \
    -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_CUDA_COMPILER=/usr/local/cuda/bin/nvcc -DPALPATION_WITH_GMSH=OFF \
    >"/tmp/gpu-tests.cmake.log" 2>&1 || { tail -30 /tmp/gpu-tests.cmake.log; exit 2; }
  grep -E "palpation:" /tmp/gpu-tests.cmake.log
  suites=()
  for d in sim device; do
    for t in $(ctest --test-dir "$TB/tests/$d" -N | sed -n 's/^ *Test *#[0-9]*: *//p'); do
      if [[ $EXCLUDE == *" $t "* ]]; then say "not packed: $t (TESTS_EXCLUDE)"; continue; fi
      suites+=("$d/$t")
    done
  done
  say "build ${#suites[@]} suites: ${suites[*]}"
  ninja -C "$TB" -j"${JOBS:-2}" "${suites[@]##*/}"
  P=$TB/gpu-tests
  rm -rf "$P"
  mkdir -p "$P/bin" "$P/lib" "$P/models"
  for s in "${suites[@]}"; do cp "$TB/tests/$s" "$P/bin/"; done
  strip --strip-debug "$P"/bin/*
  # Shared libraries by ldd, less the system's own and CUDA's (the GPU machine has both).
  ldd "$P"/bin/* | awk '/=> \// {print $1, $3}' | sort -u |
    grep -Ev '^(libc|libm|libstdc\+\+|libgcc_s|ld-linux[^ ]*|libpthread|libdl|librt|libcu[A-Za-z]*|libnv[A-Za-z]*)\.so' |
    while read -r name path; do cp -L "$path" "$P/lib/$name"; done
  cp "$MODELS_FROM"/*.pmesh "$P/models/" 2>/dev/null || say "no *.pmesh in $MODELS_FROM: breast-mesh cases will fail"
  say "libraries: $(ls "$P/lib" | tr '\n' ' ')"
  say "models: $(ls "$P/models" | tr '\n' ' ')"
  mkdir -p "$ROOT/.gpu-tests"
  tar -C "$TB" -cf - gpu-tests | xz -T0 -6 >"$ROOT/.gpu-tests/gpu-tests.tar.xz"
  say "packed $(du -sh "$P" | cut -f1) into .gpu-tests/gpu-tests.tar.xz ($(du -h "$ROOT/.gpu-tests/gpu-tests.tar.xz" | cut -f1))"
  exit 0
fi
OUT=${OUT:-$PWD/gpu-out}
mkdir -p "$OUT"
BUILD=${BUILD:-/tmp/palpation-build-gpu}
export PALPATION_CACHE_DIR=${PALPATION_CACHE_DIR:-$ROOT/.gpu-carry/models}
export PATH=/usr/local/cuda/bin:$PATH
STAGES=${*:-build check hertz micro bench idle sweep}
BENCH_MESHES=${BENCH_MESHES:-coarse,paper,xfine}
BASELINE_MESHES=${BASELINE_MESHES:-paper,xfine}
BASELINE_PRECISIONS=${BASELINE_PRECISIONS:-double,float}
MG_MESHES=${MG_MESHES:-paper,xfine,0.00201}
BENCH_TIMEOUT=${BENCH_TIMEOUT:-330}
LOG=$OUT/run.log
exec > >(tee -a "$LOG") 2>&1
say() { echo "[gpu-check $(date +%H:%M:%S)] $*"; }
has() { [[ " $STAGES " == *" $1 "* ]]; }
status=0

say "stages: $STAGES; commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.max.sm,clocks.mem,temperature.gpu,power.draw \
  --format=csv || true

P=$BUILD/app/palpation
# The Qt-free CUDA configuration of source tree $1 built in $2 (palpation only) on $3 jobs
# (default all cores); logs beside $2. Non-zero, with the errors printed, on a failure.
build_tree() {
  cmake -S "$1" -B "$2" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPALPATION_WITH_QT=OFF -DPALPATION_WITH_GMSH=OFF \
    -DPALPATION_WITH_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_CUDA_COMPILER=/usr/local/cuda/bin/nvcc \
    >"$2.cmake.log" 2>&1 || { tail -40 "$2.cmake.log"; say "configure of $1 FAILED"; return 2; }
  grep -E "palpation:" "$2.cmake.log"
  ninja -C "$2" -j"${3:-$(nproc)}" palpation >"$2.ninja.log" 2>&1 ||
    { grep -E "error|FAILED" -A3 "$2.ninja.log" | head -60; say "build of $1 FAILED"; return 2; }
}
if has build; then
  say "configure + build"
  build_tree "$ROOT" "$BUILD" || exit 2
  say "built $P"
fi
if [[ " $STAGES " != " tests " && " $STAGES " != " ab " ]]; then
  [[ -x $P ]] || { say "no $P"; exit 2; }
fi

if has tests; then
  # The sim/ and device/ QtTest suites packed by `tools/gpu-check.sh tests-pack` (above).
  T=/tmp/palpation-gpu-tests
  rm -rf "$T" && mkdir -p "$T"
  xz -dc "$ROOT/.gpu-tests/gpu-tests.tar.xz" | tar -C "$T" -xf - ||
    { say "no .gpu-tests/gpu-tests.tar.xz: run tools/gpu-check.sh tests-pack here and carry .gpu-tests"; exit 2; }
  T=$T/gpu-tests
  export LD_LIBRARY_PATH=$T/lib:/usr/local/cuda/lib64${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  export QT_QPA_PLATFORM=offscreen OMP_NUM_THREADS=${OMP_NUM_THREADS:-8} QTEST_FUNCTION_TIMEOUT=${QTEST_FUNCTION_TIMEOUT:-300000}
  grep -qw avx2 /proc/cpuinfo || say "no AVX2 here: suites built for x86-64-v3 die of SIGILL"
  say "tests: $(ls "$T/bin" | tr '\n' ' '); models: $(ls "$T/models" | tr '\n' ' ')"
  ldd "$T"/bin/* | grep "not found" | sort -u
  TLOG=$OUT/tests.log
  SUM=$OUT/tests-summary.txt
  : >"$TLOG"
  : >"$SUM"
  for exe in "$T"/bin/*; do
    name=$(basename "$exe")
    if [[ -n ${TESTS_ONLY:-} && " $TESTS_ONLY " != *" $name "* ]]; then continue; fi
    say "suite $name"
    t0=$(date +%s%N)
    PALPATION_CACHE_DIR=$T/models timeout "${TESTS_TIMEOUT:-300}" "$exe" -o -,txt >"$T/$name.txt" 2>&1
    rc=$?
    ms=$(( ($(date +%s%N) - t0) / 1000000 ))
    cat "$T/$name.txt" >>"$TLOG"
    grep -E "^(FAIL!|SKIP|QINFO|QFATAL)|^   Loc:" "$T/$name.txt" | head -40
    tot=$(grep -Eo "Totals: [0-9]+ passed, [0-9]+ failed, [0-9]+ skipped" "$T/$name.txt" | tail -1)
    printf '%-24s exit %3d %8.1f s  %s\n' "$name" "$rc" "$(( ms / 100 ))e-1" "${tot:-no totals (crashed?)}" | tee -a "$SUM"
    [[ $rc -ne 0 ]] && status=1
  done
  python3 - "$SUM" "$T/tst_backend_agreement.txt" <<'EOF' | tee -a "$SUM"
# Sums of the suites' totals; the CUDA cases of tst_backend_agreement must have run.
import re, sys
n = p = f = s = 0
for line in open(sys.argv[1]):
    n += 1
    m = re.search(r"Totals: (\d+) passed, (\d+) failed, (\d+) skipped", line)
    if m:
        p, f, s = p + int(m[1]), f + int(m[2]), s + int(m[3])
print(f"{n} suites: {p} passed, {f} failed, {s} skipped (test functions and data rows, "
      "initTestCase/cleanupTestCase included)")
try:
    lines = open(sys.argv[2]).read().splitlines()
except FileNotFoundError:
    lines = []
cuda = [l for l in lines if re.match(r"(PASS   |FAIL!  |SKIP   ): .*::(autoPicksCudaWithGpu|doubleAgreesWithCpu|cappedAgreesWithCpu|baselinesRefuseNodalPressure|floatAgreesWithinTolerance)", l)]
for l in cuda:
    print("CUDA case:", l)
if len(cuda) < 10 or not all(l.startswith("PASS") for l in cuda):
    print("CUDA cases of tst_backend_agreement: not all ran and passed")
    sys.exit(1)
EOF
  [[ ${PIPESTATUS[0]} -ne 0 ]] && status=1
fi

if has ab; then
  # This tree against the older one that ab-pack laid out in .gpu-carry/ab (above).
  AB=$ROOT/.gpu-carry/ab
  [[ -f $AB/rev.txt ]] || { say "no .gpu-carry/ab/rev.txt: run tools/gpu-check.sh ab-pack REV here, carry .gpu-carry"; exit 2; }
  OLD_SRC=/tmp/palpation-ab-old
  OLD_BUILD=/tmp/palpation-ab-old-build
  rm -rf "$OLD_SRC" && mkdir -p "$OLD_SRC"
  for d in $AB_TREES; do [[ -e $ROOT/$d ]] && cp -r "$ROOT/$d" "$OLD_SRC/"; done
  cp -r "$AB/old/." "$OLD_SRC/"
  while read -r f; do [[ -n $f ]] && rm -f "$OLD_SRC/$f"; done <"$AB/removed.txt"
  find "$OLD_SRC" -type d -empty -delete
  ln -s "$ROOT/.gpu-carry" "$OLD_SRC/.gpu-carry"  # the carried headers and libraries
  say "ab: building this tree and $(cat "$AB/rev.txt")'s side by side"
  half=$(( ($(nproc) + 1) / 2 ))
  build_tree "$ROOT" "$BUILD" "$half" &
  new_pid=$!
  build_tree "$OLD_SRC" "$OLD_BUILD" "$half" || exit 2
  wait "$new_pid" || exit 2
  AB_RUNS=${AB_RUNS:-xfine:1000:float 0.00201:400:float}
  AB_REPEAT=${AB_REPEAT:-2}
  AB_BENCH_ARGS=${AB_BENCH_ARGS:---force-error 0.01}
  AB_ENV=${AB_ENV:-}
  RUNS=/tmp/palpation-ab-runs
  rm -rf "$RUNS" && mkdir -p "$RUNS"
  for point in $AB_RUNS; do
    IFS=: read -r mesh steps prec pc <<<"$point"
    for ((k = 1; k <= AB_REPEAT; ++k)); do
      for side in new old; do
        exe=$P
        [[ $side == old ]] && exe=$OLD_BUILD/app/palpation
        d=$RUNS/$mesh-$prec${pc:+-$pc}-$k-$side
        mkdir -p "$d"
        # shellcheck disable=SC2086  # AB_ENV and AB_BENCH_ARGS are words
        env $AB_ENV timeout "$BENCH_TIMEOUT" "$exe" bench --backends cuda --meshes "$mesh" --precisions "$prec" \
          ${pc:+--preconditioner "$pc"} --steps "$steps" $AB_BENCH_ARGS --out "$d" >"$d/stdout.txt" 2>"$d/stderr.txt"
        say "ab $point run $k $side: exit $?"
      done
    done
  done
  python3 - "$RUNS" "$(cat "$AB/rev.txt")" "$OUT/ab.txt" <<'EOF'
import csv, pathlib, statistics, sys
runs, old_rev, out = pathlib.Path(sys.argv[1]), sys.argv[2], sys.argv[3]
points = {}
lines = [f"A/B: this tree (new) against {old_rev} (old), built side by side, runs in the order taken; "
         "median / p99 ms, CG iterations median / max, force error"]
for d in sorted(runs.iterdir(), key=lambda p: p.stat().st_mtime):
    point, side = d.name.rsplit("-", 2)[0], d.name.rsplit("-", 1)[1]
    f = d / "bench.csv"
    if not f.exists():
        lines.append(f"{d.name:40s} no result (stderr: {(d / 'stderr.txt').read_text()[-200:]!r})")
        continue
    r = next(csv.DictReader(f.open()))
    med = float(r["step_ms_median"])
    points.setdefault(point, {}).setdefault(side, []).append(med)
    lines.append(f"{d.name:40s} {med:8.4f} / {float(r['step_ms_p99']):8.4f}  {float(r['cg_iterations_median']):4.1f} / "
                 f"{r['cg_iterations_max']:>4s}  {float(r['force_error']):.2e}")
lines.append("per point, the median of each side's medians:")
for point, sides in points.items():
    if "new" in sides and "old" in sides:
        n, o = statistics.median(sides["new"]), statistics.median(sides["old"])
        lines.append(f"{point:40s} new {n:8.4f}  old {o:8.4f}  new/old {n / o:.3f}")
pathlib.Path(out).write_text("\n".join(lines) + "\n")
print("\n".join(lines))
EOF
  tar -C "$RUNS" -cf "$OUT/ab-runs.tar" .
fi

if has check; then
  say "check-backends (GPU vs CPU, 1,000 steps, CG 1e-10)"
  timeout 300 "$P" check-backends --out "$OUT/check" ; rc=$?
  [[ -f $OUT/check/check.json ]] && mv "$OUT/check/check.json" "$OUT/check.json" && rmdir "$OUT/check" 2>/dev/null
  say "check-backends exit $rc"
  [[ $rc -ne 0 ]] && status=1
  # The layered breast (fat over glandular tissue: per-element tissue moduli) with the
  # default element, its own file: check-layered.json.
  say "check-backends, layered breast (paper-sweep-layered, nodal-pressure)"
  timeout 240 "$P" check-backends --scenarios paper-sweep-layered --elements nodal-pressure --out "$OUT/check-layered"
  rc=$?
  [[ -f $OUT/check-layered/check.json ]] && mv "$OUT/check-layered/check.json" "$OUT/check-layered.json" &&
    rmdir "$OUT/check-layered" 2>/dev/null
  say "check-backends (layered) exit $rc"
  [[ $rc -ne 0 ]] && status=1
fi

if has levels; then
  # GPU against CPU on every mesh level of the breast, the default (nodal-pressure) element:
  # coarse over 1,000 steps, fine and xfine over 300 (their CPU references take 46 s and
  # 4.6 minutes on the GPU machine's 16 cores); paper is the check stage's. Needs the fine
  # and xfine meshes in the carried model cache (the GPU machine has no Gmsh).
  for rs in ${LEVELS:-coarse:1000 fine:300 xfine:300}; do
    r=${rs%%:*}
    n=${rs##*:}
    say "levels: check-backends on $r, $n steps"
    timeout 560 "$P" check-backends --scenarios paper-sweep --elements nodal-pressure --resolution "$r" --steps "$n" \
      --out "$OUT/check-$r"
    rc=$?
    [[ -f $OUT/check-$r/check.json ]] && mv "$OUT/check-$r/check.json" "$OUT/check-$r.json" && rmdir "$OUT/check-$r" 2>/dev/null
    say "levels: $r exit $rc"
    [[ $rc -ne 0 ]] && status=1
  done
fi

if has hertz; then
  say "hertz: nodal-pressure within 5 % on CUDA, linear beside it (hertz.txt)"
  : >"$OUT/hertz.txt"
  for pc in ${HERTZ_PRECONDITIONERS:-block-jacobi multigrid multigrid-chebyshev}; do
    for args in "--radius 0.01 --young 19000" "--radius 0.015 --young 60000"; do
      # shellcheck disable=SC2086
      timeout 240 "$P" hertz --backend cuda --elements nodal-pressure --nu 0.40,0.45,0.49,0.499 --cells 28 $args \
        --preconditioner "$pc" --limit 0.05 | tee -a "$OUT/hertz.txt"
      rc=${PIPESTATUS[0]}
      say "hertz nodal-pressure, $pc ($args) exit $rc"
      [[ $rc -ne 0 ]] && status=1
    done
  done
  [[ -n ${HERTZ_LINEAR-1} ]] &&
    timeout 240 "$P" hertz --backend cuda --elements linear --nu 0.40,0.45,0.49,0.499 --cells 28 | tee -a "$OUT/hertz.txt"
fi

if has smoother; then
  say "smoother: one Jacobi sweep against Chebyshev of degree 2 by Poisson's ratio (smoother.txt)"
  M=/tmp/palpation-smoother
  mkdir -p $M
  "$P" scenario paper-sweep >$M/sweep.json
  : >"$OUT/smoother.txt"
  for mesh in ${SMOOTHER_MESHES:-paper}; do
    for nu in ${SMOOTHER_NUS:-0.45 0.47 0.48 0.484 0.486 0.488 0.49}; do
      for pc in multigrid-jacobi multigrid-chebyshev; do
        python3 - "$M/sweep.json" "$M/s.json" "$mesh" "$nu" "$pc" "${SMOOTHER_SECONDS:-3}" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
s["duration"] = float(sys.argv[6])
s["patient"]["resolution"] = sys.argv[3]
s["tissue"]["poisson_ratio"] = float(sys.argv[4])
for inc in s.get("inclusions", []):
    inc["poisson_ratio"] = float(sys.argv[4])
s["solver"].update({"backend": "cuda", "precision": "double", "cg_tolerance": 1e-3, "preconditioner": sys.argv[5]})
json.dump(s, open(sys.argv[2], "w"))
EOF
        rm -rf "$M/out"
        timeout 300 "$P" run "$M/s.json" --force-error 0 --out "$M/out" --quiet
        python3 - "$M/out/summary.json" "$mesh" "$nu" "$pc" <<'EOF' | tee -a "$OUT/smoother.txt"
import json, sys
d = json.load(open(sys.argv[1]))
print(f"{sys.argv[2]:<6} nu {float(sys.argv[3]):.3f} {sys.argv[4]:<20} share {d['multigrid_pressure_share']:.3f} "
      f"{d['multigrid_smoother']:<9} builds {d['multigrid_builds']}  CG mean {d['cg_iterations_mean']:.2f} max {d['cg_iterations_max']}"
      f"  step med {d['step_ms_median']:.3f} p99 {d['step_ms_p99']:.3f} ms  solved {d['steps_solved']}")
EOF
      done
    done
  done
fi

if has micro; then
  say "micro: design alternatives (palpation run, paper-sweep 1 s = 1,000 steps)"
  M=/tmp/palpation-micro
  mkdir -p $M
  "$P" scenario paper-sweep >$M/sweep.json
  mk() {  # mk NAME RESOLUTION TOL CAP PRECISION
    python3 - "$M/sweep.json" "$M/$1.json" "$2" "$3" "$4" "$5" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
s["duration"] = 1.0
s["patient"]["resolution"] = sys.argv[3]
s["solver"].update({"backend": "cuda", "cg_tolerance": float(sys.argv[4]), "cg_max_iterations": int(sys.argv[5]),
                    "precision": sys.argv[6]})
json.dump(s, open(sys.argv[2], "w"))
EOF
  }
  one() {  # one LABEL SCENARIO [ENV...]
    local label=$1 sc=$2
    shift 2
    local out
    out=$(env "$@" PALPATION_CUDA_PROFILE=1 timeout 120 "$P" run "$M/$sc.json" --out "$M/out" --quiet 2>&1 | grep "cuda profile")
    python3 - "$M/out/summary.json" "$label" "$out" <<'EOF' | tee -a "$OUT/micro.txt"
import json, sys
d = json.load(open(sys.argv[1]))
print(f"{sys.argv[2]:<34} med {d['step_ms_median']:.4f} ms  p99 {d['step_ms_p99']:.4f}  it_mean {d['cg_iterations_mean']:.1f}  "
      f"solved {d['steps_solved']}  | {sys.argv[3].split(':',1)[-1].strip()}")
EOF
  }
  : >"$OUT/micro.txt"
  mk p6 paper 1e-6 1000 double
  mk p3 paper 1e-3 1000 double
  mk p2 paper 1e-2 1000 double
  mk p3f paper 1e-3 1000 float
  mk p2f paper 1e-2 1000 float
  mk x3 xfine 1e-3 1000 double
  mk x4 xfine 1e-4 1000 double
  mk x4f xfine 1e-4 1000 float
  one "paper d 1e-6 (default)" p6
  one "paper d 1e-6 again" p6
  one "paper d 1e-6 256-thread blocks" p6 PALPATION_CUDA_PCG_BLOCK=256
  one "paper d 1e-6 rows not in registers" p6 PALPATION_CUDA_CACHE=0
  one "paper d 1e-6 3 barriers" p6 PALPATION_CUDA_CG=3sync
  one "paper d 1e-6 one reduction" p6 PALPATION_CUDA_CG=1sync
  mk p6l paper 1e-6 1000 double
  python3 -c "import json,sys; s=json.load(open(sys.argv[1])); s['tissue']['element']='linear'; json.dump(s,open(sys.argv[1],'w'))" "$M/p6l.json"
  one "paper d 1e-6 linear (default)" p6l
  one "paper d 1e-6 linear 2 barriers" p6l PALPATION_CUDA_CG=fused
  one "paper d 1e-3" p3
  one "paper d 1e-2" p2
  one "paper f 1e-3" p3f
  one "paper f 1e-2" p2f
  one "xfine d 1e-3" x3
  one "xfine d 1e-3 256-thread blocks" x3 PALPATION_CUDA_PCG_BLOCK=256
  one "xfine d 1e-4" x4
  one "xfine f 1e-4" x4f
fi

if has ncu; then
  say "ncu: one step's kernels (paper mesh, CG 1e-3, in contact)"
  M=/tmp/palpation-micro
  mkdir -p $M
  "$P" scenario paper-sweep | python3 -c '
import json, sys
s = json.load(sys.stdin)
s["duration"] = 0.1
s["solver"].update({"backend": "cuda", "cg_tolerance": 1e-3, "cg_max_iterations": 1000})
json.dump(s, open("/tmp/palpation-micro/ncu.json", "w"))'
  timeout 150 ncu --clock-control none --kernel-name regex:'k_element|k_assemble|k_pcg' --launch-skip 60 --launch-count 3 \
    --section SpeedOfLight --section Occupancy --section LaunchStats --section WarpStateStats \
    "$P" run $M/ncu.json --out $M/ncu-out --quiet >"$OUT/ncu.txt" 2>&1
  say "ncu exit $?"
  grep -E "k_element|k_assemble|k_pcg|Duration|Memory Throughput|DRAM Throughput|Compute \(SM\)|Achieved Occupancy|Registers Per|Warp Cycles Per Issued|Grid Size" "$OUT/ncu.txt" | head -60
fi

if has bench; then
  say "bench: cuda on $BENCH_MESHES (double, float); cuda-bsr, cuda-csr on $BASELINE_MESHES (double); timeout ${BENCH_TIMEOUT}s each"
  rm -rf /tmp/palpation-bench-a /tmp/palpation-bench-b
  timeout "$BENCH_TIMEOUT" "$P" bench --meshes "$BENCH_MESHES" --backends cuda --precisions double,float \
    --out /tmp/palpation-bench-a
  say "bench (cuda) exit $?"
  # The baselines have the linear element and block-Jacobi only: they are compared with cuda
  # on the same element and preconditioner (auto would take the multigrid on xfine).
  timeout "$BENCH_TIMEOUT" "$P" bench --meshes "$BASELINE_MESHES" --backends cuda,cuda-bsr,cuda-csr --precisions double \
    --element linear --preconditioner block-jacobi --tolerances 1e-3,1e-6 --out /tmp/palpation-bench-b
  say "bench (cuda, cuda-bsr, cuda-csr; linear element) exit $?"
  python3 - /tmp/palpation-bench-a/bench.csv /tmp/palpation-bench-b/bench.csv "$OUT/bench.csv" <<'EOF'
import os, sys
rows, header = [], None
for f in sys.argv[1:-1]:
    if os.path.exists(f):
        lines = open(f).read().splitlines()
        header = header or lines[0]
        rows += lines[1:]
if header:
    open(sys.argv[-1], "w").write("\n".join([header] + rows) + "\n")
EOF
  cp /tmp/palpation-bench-a/bench.json "$OUT/bench.json" 2>/dev/null
  if [[ -f $OUT/bench.csv ]]; then

    python3 - "$OUT/bench.csv" "$OUT/bench.png" <<'EOF' || say "no plot (matplotlib?)"
# Step time against force error, one curve per mesh x backend x precision (the Qt-free
# build cannot draw PNGs itself).
import csv, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
rows = list(csv.DictReader(open(sys.argv[1])))
curves = {}
for r in rows:
    curves.setdefault((r["mesh"], r["backend"] + ("" if r.get("element", "linear") == "linear" else " nodal"), r["precision"]), []).append(
        (max(float(r["force_error"]), 1e-12), float(r["step_ms_median"])))
fig, ax = plt.subplots(figsize=(11, 6.5))
colours = {"coarse": "tab:green", "paper": "tab:blue", "fine": "tab:purple", "xfine": "tab:red"}
for (mesh, backend, prec), pts in sorted(curves.items()):
    pts.sort()
    ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o" if prec == "double" else "s",
            linestyle={"cuda-csr": "--", "cuda-bsr": "-."}.get(backend.split()[0], ":" if backend.startswith("cpu") else "-"),
            color=colours.get(mesh, "black"), label=f"{mesh} {backend} {prec}")
ax.axvline(1e-2, color="grey", lw=0.8)
ax.axhline(0.2, color="tab:blue", lw=0.8, ls="-.")
ax.axhline(1.0, color="tab:red", lw=0.8, ls="-.")
ax.text(1.1e-2, 0.21, "paper target 0.2 ms", color="tab:blue", fontsize=8)
ax.text(1.1e-2, 1.05, "xfine target 1 ms", color="tab:red", fontsize=8)
ax.set_xscale("log"); ax.set_yscale("log")
ax.set_xlabel("force error (relative L2 against the reference: double, CG 1e-10)")
ax.set_ylabel("median step time [ms]")
dev = rows[0]["device"] if rows else ""
ax.set_title(f"paper-sweep, dt = 1 ms: step time against error on {dev} ({rows[0]['date'][:10] if rows else ''})")
ax.grid(True, which="both", lw=0.3)
ax.legend(fontsize=7, ncol=2)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
EOF
  fi
fi

if has baselines; then
  # The fast backend against the good first port (cuda-bsr) and the textbook one (cuda-csr)
  # on the same element and tolerance (the same algorithm: equal iterations, equal error),
  # each mesh its own bench run; the speed-ups from one run's medians.
  rm -f "$OUT/baselines.csv"
  for m in ${BASELINE_MESHES//,/ }; do
    say "baselines: $m, ${BASELINE_PRECISIONS}, linear element, CG 1e-3 and 1e-6"
    rm -rf "/tmp/palpation-baselines-$m"
    timeout "$BENCH_TIMEOUT" "$P" bench --meshes "$m" --backends cuda,cuda-bsr,cuda-csr --precisions "$BASELINE_PRECISIONS" \
      --element linear --preconditioner block-jacobi --tolerances 1e-3,1e-6 --out "/tmp/palpation-baselines-$m" | tee -a "$OUT/baselines.txt"
    say "baselines $m exit ${PIPESTATUS[0]}"
    f=/tmp/palpation-baselines-$m/bench.csv
    [[ -f $f ]] && { [[ -f $OUT/baselines.csv ]] && tail -n +2 "$f" >>"$OUT/baselines.csv" || cp "$f" "$OUT/baselines.csv"; }
    # The fast backend with its other preconditioner on the same element and tolerances
    # (the baselines have block-Jacobi only): the comparison at equal error takes whichever
    # of the fast backend's points is quicker at no larger force error. Nothing looser than
    # 1e-3: a looser fixed tolerance solves on to the rescue tolerance, 1e-3, the same point.
    say "baselines: $m, cuda with the multigrid, the same element and tolerances"
    rm -rf "/tmp/palpation-baselines-mg-$m"
    timeout "$BENCH_TIMEOUT" "$P" bench --meshes "$m" --backends cuda --precisions double --preconditioner multigrid \
      --element linear --tolerances 1e-3,1e-4,1e-6 --out "/tmp/palpation-baselines-mg-$m" | tee -a "$OUT/baselines.txt"
    say "baselines $m multigrid exit ${PIPESTATUS[0]}"
    f=/tmp/palpation-baselines-mg-$m/bench.csv
    [[ -f $f ]] && tail -n +2 "$f" >>"$OUT/baselines.csv"
  done
  [[ -f $OUT/baselines.csv ]] && python3 - "$OUT/baselines.csv" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
pts = {(r["mesh"], r["precision"], r["cg_tolerance"], r["backend"]): r for r in rows if r["preconditioner"] == "block-jacobi"}
print("Same algorithm (block-Jacobi PCG), same precision and tolerance:")
print("mesh    prec.   tol     cuda ms (it)   cuda-bsr ms (it)  cuda-csr ms (it)  bsr/cuda  csr/cuda  force error cuda/bsr/csr")
for (mesh, prec, tol, b), r in sorted(pts.items()):
    if b != "cuda": continue
    o = {k: pts.get((mesh, prec, tol, k)) for k in ("cuda-bsr", "cuda-csr")}
    t = float(r["step_ms_median"])
    def cell(x): return f'{float(x["step_ms_median"]):8.3f} ({float(x["cg_iterations_median"]):4.0f})' if x else "       -       "
    def ratio(x): return f'{float(x["step_ms_median"]) / t:8.2f}' if x else "       -"
    errs = "/".join(f'{float(x["force_error"]):.1e}' if x else "-" for x in (r, o["cuda-bsr"], o["cuda-csr"]))
    print(f"{mesh:7s} {prec:6s}  {float(tol):.0e}  {cell(r)}  {cell(o['cuda-bsr'])}  {cell(o['cuda-csr'])}  {ratio(o['cuda-bsr'])}  {ratio(o['cuda-csr'])}  {errs}")
# At equal error: for each baseline point, the quickest point of the fast backend (either
# preconditioner, either precision, any tolerance) whose force error is no larger, give or
# take 10 % (the same algorithm at the same tolerance lands within a few percent of the
# same error: 1.7e-6 against 1.6e-6 on the paper mesh at CG 1e-3). The errors are all
# against the one converged double reference, so a float point counts only where float
# reaches the baseline's error; the baselines run in float too, and each of their points
# is a row.
fast = [r for r in rows if r["backend"] == "cuda"]
print("At equal error (the fast backend's quickest point with no larger force error, within 10 %):")
print("mesh    baseline  prec.  tol    base ms   error     fast ms  (preconditioner, precision, tol, error)  speed-up")
for r in sorted(rows, key=lambda r: (r["mesh"], r["backend"], r["precision"], float(r["cg_tolerance"]))):
    if r["backend"] == "cuda": continue
    e = float(r["force_error"])
    ok = [f for f in fast if f["mesh"] == r["mesh"] and float(f["force_error"]) <= 1.1 * e]
    if not ok:
        print(f'{r["mesh"]:7s} {r["backend"]:9s} {r["precision"]:6s} {float(r["cg_tolerance"]):.0e} {float(r["step_ms_median"]):8.3f}  {e:.1e}   none at that error')
        continue
    b = min(ok, key=lambda f: float(f["step_ms_median"]))
    print(f'{r["mesh"]:7s} {r["backend"]:9s} {r["precision"]:6s} {float(r["cg_tolerance"]):.0e} {float(r["step_ms_median"]):8.3f}  {e:.1e}  '
          f'{float(b["step_ms_median"]):8.3f}  ({b["preconditioner"]}, {b["precision"]}, {float(b["cg_tolerance"]):.0e}, {float(b["force_error"]):.1e})  '
          f'{float(r["step_ms_median"]) / float(b["step_ms_median"]):6.2f}x')
EOF
fi

if has multigrid; then
  # The same meshes and tolerances under each preconditioner; the reference (block-Jacobi,
  # CG 1e-10) computed by the first run of a mesh and cached for the others.
  rm -f "$OUT/multigrid.csv"
  for m in ${MG_MESHES//,/ }; do
    for pc in ${MG_PRECONDITIONERS:-block-jacobi multigrid multigrid-chebyshev}; do
      say "multigrid: $m, $pc, double, CG 1e-3, 1e-6 and the force error held at 1 %"
      rm -rf "/tmp/palpation-mg-$m-$pc"
      timeout "$BENCH_TIMEOUT" "$P" bench --meshes "$m" --backends cuda --precisions double --preconditioner "$pc" \
        --tolerances 1e-3,1e-6 --force-error 0.01 --out "/tmp/palpation-mg-$m-$pc" | tee -a "$OUT/multigrid.txt"
      say "multigrid $m $pc exit ${PIPESTATUS[0]}"
      f=/tmp/palpation-mg-$m-$pc/bench.csv
      [[ -f $f ]] && { [[ -f $OUT/multigrid.csv ]] && tail -n +2 "$f" >>"$OUT/multigrid.csv" || cp "$f" "$OUT/multigrid.csv"; }
    done
  done
  [[ -f $OUT/multigrid.csv ]] && python3 - "$OUT/multigrid.csv" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print("mesh        setting  preconditioner        median ms  p99 ms   CG it. median/max  force error  vs block-Jacobi")
def setting(r): return f'fe{float(r["force_error_target"]) * 100:g}%' if float(r.get("force_error_target") or 0) > 0 else r["cg_tolerance"]
base = {(r["mesh"], setting(r)): float(r["step_ms_median"]) for r in rows if r["preconditioner"] == "block-jacobi"}
for r in rows:
    t = float(r["step_ms_median"]); b = base.get((r["mesh"], setting(r)))
    print(f'{r["mesh"]:11s} {setting(r):8s} {r["preconditioner"]:20s} {t:9.3f} {float(r["step_ms_p99"]):8.3f}  '
          f'{float(r["cg_iterations_median"]):6.0f} / {float(r["cg_iterations_max"]):5.0f}  {float(r["force_error"]):11.2e}  '
          + (f'{b / t:6.2f}x' if b else "-"))
EOF
fi

if has idle; then
  say "idle: no contact, at rest"
  timeout 120 "$P" bench --scenario idle --meshes paper,xfine --backends cuda,cpu --precisions double,float \
    --steps 1000 --out /tmp/palpation-idle
  [[ -f /tmp/palpation-idle/bench.csv ]] && cp /tmp/palpation-idle/bench.csv "$OUT/idle.csv"
  timeout 120 "$P" bench --scenario idle --meshes paper,xfine --backends cuda-csr --precisions double,float \
    --element linear --steps 1000 --out /tmp/palpation-idle-csr
  [[ -f /tmp/palpation-idle-csr/bench.csv ]] && tail -n +2 /tmp/palpation-idle-csr/bench.csv >>"$OUT/idle.csv"
fi
# bench_ab STAGE OPTION RUNS VALUE...: for each point of RUNS (mesh:steps:precision),
# REPEAT times (default 2), `palpation bench ... --OPTION VALUE` for each VALUE in turn,
# held at 1 %, with its series: every run's line and the step median / p99 and CG
# iterations from its series into STAGE.txt.
bench_ab() {
  local stage=$1 option=$2 runs=$3
  shift 3
  for run in $runs; do
    IFS=: read -r m n prec <<<"$run"
    for round in $(seq "${REPEAT:-2}"); do
      for value in "$@"; do
        d=/tmp/palpation-$stage-$m-$n-$prec-$value-$round
        say "$stage: bench $m, $n steps, $prec, --$option $value, round $round"
        timeout "$BENCH_TIMEOUT" "$P" bench --meshes "$m" --backends cuda --precisions "$prec" --force-error 0.01 \
          --steps "$n" --"$option" "$value" --series --out "$d" | grep -E "^$m |error controller" | tee -a "$OUT/$stage.txt"
        python3 - "$d/series.csv" "$value" <<'EOF2' | tee -a "$OUT/$stage.txt"
import csv, statistics, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["timed"] == "1"]
it = sorted(int(r["cg_iterations"]) for r in rows)
ms = sorted(float(r["step_ms"]) for r in rows)
n = len(rows)
print(f"  {sys.argv[2]}: {n} timed steps, step median {statistics.median(ms):.4f} / p99 {ms[int(0.99 * n)]:.4f} ms, "
      f"CG iterations mean {sum(it) / n:.2f}, median {statistics.median(it):.0f}, p99 {it[int(0.99 * n)]}, max {it[-1]}")
EOF2
      done
    done
  done
}

# session_ab STAGE LABEL...: twice, for each LABEL in turn, an 8 s `palpation session` of
# /tmp/palpation-STAGE-LABEL.json (written by the caller) on the paper mesh, CUDA, held at
# 1 %, the emulated HandHIRO; each run's rate, dt, step median / p99 / max, largest CG
# count and divergence resets from its loop.json into STAGE.txt.
session_ab() {
  local stage=$1
  shift
  for round in 1 2; do
    for label in "$@"; do
      say "$stage: session paper-sweep ($label), paper mesh, held at 1 %, 8 s, round $round"
      timeout 120 "$P" session "/tmp/palpation-$stage-$label.json" --device emulator --backend cuda --resolution paper \
        --force-error 0.01 --duration 8 --quiet --out "/tmp/palpation-$stage-session-$label-$round" >/dev/null 2>&1
      python3 - "/tmp/palpation-$stage-session-$label-$round/loop.json" "$label" <<'EOF2' | tee -a "$OUT/$stage.txt"
import json, sys
j = json.load(open(sys.argv[1]))["simulation"]
print(f"session {sys.argv[2]}: {j['step_rate_hz']:.0f} steps/s, dt median {j['dt_ms_median']:.3f} ms, "
      f"step median {j['step_ms_median']:.3f} / p99 {j['step_ms_p99']:.3f} / max {j['step_ms_max']:.3f} ms, "
      f"CG max {j['cg_iterations_max']}, resets {j['divergence_resets']}")
EOF2
    done
  done
}

if has warmstart; then
  REPEAT=${WARMSTART_REPEAT:-2} bench_ab warmstart warm-start "${WARMSTART_RUNS:-paper:1000:double paper:1000:float xfine:1000:float}" \
    extrapolated last
  for ws in extrapolated last; do
    "$P" scenario paper-sweep | python3 -c "import json,sys; j=json.load(sys.stdin); j['solver']['warm_start']='$ws'; print(json.dumps(j))" \
      >"/tmp/palpation-warmstart-$ws.json"
  done
  session_ab warmstart extrapolated last
fi

if has path; then
  REPEAT=${PATH_REPEAT:-2} bench_ab path path "${PATH_RUNS:-paper:6000:double paper:6000:float xfine:1000:float}" \
    linear monotone-cubic
  "$P" scenario paper-sweep >/tmp/palpation-path-monotone-cubic.json
  sed '/"interpolation"/d' /tmp/palpation-path-monotone-cubic.json >/tmp/palpation-path-linear.json
  session_ab path linear monotone-cubic
fi

if has control; then
  # The error-controlled tolerance (solver.force_error) against the fixed ones, through the
  # bench (Simulation::step, force error against the converged reference) and through the
  # real-time pipeline (palpation session, emulator), on CONTROL_MESHES.
  for m in ${CONTROL_MESHES:-paper xfine}; do
    say "control: bench $m (the fixed tolerances and fe1%), double"
    timeout "$BENCH_TIMEOUT" "$P" bench --meshes "$m" --backends cuda --precisions double --out "/tmp/palpation-control-$m" \
      | tee -a "$OUT/control.txt"
    [[ -f /tmp/palpation-control-$m/bench.csv ]] && cp "/tmp/palpation-control-$m/bench.csv" "$OUT/control-$m.csv"
    # Where the converged checks are solved: in the step against auto (beside the steps
    # where they solve with block-Jacobi), alternated twice (docs/simulation.md).
    for round in 1 2; do
      for c in in-step auto; do
        say "control: bench $m held at 1 %, checks $c, round $round"
        timeout "$BENCH_TIMEOUT" "$P" bench --meshes "$m" --backends cuda --precisions double --force-error 0.01 \
          --check "$c" --out "/tmp/palpation-control-$m-$c" | grep -E "^$m |error controller" | tee -a "$OUT/control.txt"
      done
    done
    for fe in 0 0.01; do
      say "control: session paper-sweep on $m, --force-error $fe, 8 s"
      timeout 120 "$P" session paper-sweep --device emulator --backend cuda --resolution "$m" --force-error "$fe" \
        --duration 8 --quiet --out "/tmp/palpation-control-session-$m-$fe" >/dev/null 2>&1
      python3 - "/tmp/palpation-control-session-$m-$fe/loop.json" "$m" "$fe" <<'EOF2' | tee -a "$OUT/control.txt"
import json, sys
j = json.load(open(sys.argv[1]))["simulation"]
e = j.get("error_control", {})
print(f"session {sys.argv[2]} force_error {sys.argv[3]}: {j['step_rate_hz']:.0f} steps/s, dt median {j['dt_ms_median']:.3f} ms, "
      f"step median {j['step_ms_median']:.3f} / p99 {j['step_ms_p99']:.3f} / max {j['step_ms_max']:.3f} ms, "
      f"CG max {j['cg_iterations_max']}, resets {j['divergence_resets']}; controller {e}")
EOF2
    done
  done
fi
if has sweep; then
  for base in ${SWEEP_SCENARIOS:-paper-sweep paper-sweep-layered}; do
  for el in ${SWEEP_ELEMENTS:-linear nodal-pressure}; do
  for skin in ${SWEEP_SKIN:-0}; do
    tag=$el; [[ $skin != 0 ]] && tag=$el-skin$skin
    for res in ${SWEEP_MESHES:-paper}; do
      for sc in $base $base-no-tumour; do
        say "sweep: $sc on $res, $el element, skin $skin m"
        "$P" scenario $sc | python3 -c '
import json, sys
s = json.load(sys.stdin)
s.setdefault("tissue", {})["element"] = sys.argv[1]
if float(sys.argv[3]) > 0: s["tissue"]["skin"] = {"thickness": float(sys.argv[3])}
json.dump(s, open(sys.argv[2], "w"))' "$el" "/tmp/palpation-sweep-$tag-$sc.json" "$skin"
        timeout 200 "$P" run "/tmp/palpation-sweep-$tag-$sc.json" --backend cuda --resolution "$res" \
          --out "/tmp/palpation-sweep-$tag-$res-$sc" | tail -1
      done
      python3 - "/tmp/palpation-sweep-$tag-$res-$base/summary.json" \
        "/tmp/palpation-sweep-$tag-$res-$base-no-tumour/summary.json" "$res" "$tag" "$base" <<'EOF' | tee -a "$OUT/sweep.txt"
import json, sys
t, n = (json.load(open(f)) for f in sys.argv[1:3])
def near(s, p):
    v = [q["fz"] for q in s["sweep"]["pushes"] if q["pass"] == p and abs(q["x"] - 0.125) < 0.0045 and q["fz"] > 0.2]
    return max(v) if v else float("nan")
passes = t["sweep"]["passes"]
within = sum(abs(p["peak_x"] - 0.125) <= 0.01 for p in passes)
print(f"{sys.argv[5]}, {sys.argv[3]}, {sys.argv[4]}: {t['nodes']} nodes, step {t['step_ms_median']:.3f} ms median, "
      f"{t['step_ms_p99']:.3f} ms p99, CG {t['cg_iterations_mean']:.1f} mean; largest push per pass at",
      ", ".join(f"{p['peak_x']:.4f} m ({p['peak_fz']:.2f} N)" for p in passes),
      f"-> {within} of {len(passes)} within 1 cm; tumour/no-tumour per pass",
      ", ".join(f"{near(t, p) / near(n, p):.3f}" for p in range(len(passes))))
EOF
    done
  done
  done
  done
fi
say "done (status $status)"
exit $status
