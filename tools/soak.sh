#!/bin/sh
# Soak test of the workstation (docs/stability.md, "Soak"): runs build/ui/palpation-trainer
# with the default patient and the simulated HandHIRO (scripted hand) under Xvfb for
# DURATION seconds (default 3600), recording into a temp folder, and samples every 10 s:
# elapsed s, VmRSS and VmHWM (kB, /proc/PID/status), recording size (bytes).
#   tools/soak.sh [DURATION]        CSV and log kept in $SOAK_DIR (default: a mktemp -d)
# The program has no "quit after N s" option of its own except --screenshot FILE --seconds S
# (palpate S seconds after the patient is ready, save the window, exit cleanly: the
# recorder closes the recording with its end chunk), so that is what ends the run; SIGTERM
# (the program has no handler: it just dies, the recording stays recoverable) only if it
# has not exited 120 s after DURATION. Exit 1 if the program died early or failed, or if
# the recording does not read back.
set -eu
cd "$(dirname "$0")/.."
dur="${1:-3600}"
exe="${PALPATION_TRAINER:-./build/ui/palpation-trainer}"
cli="${PALPATION_CLI:-./build/app/palpation}"
[ -x "$exe" ] && [ -x "$cli" ] || { echo "soak: $exe or $cli missing: build first" >&2; exit 2; }
dir="${SOAK_DIR:-$(mktemp -d /tmp/palpation-soak.XXXXXX)}"
mkdir -p "$dir/config" "$dir/data"
rec="$dir/soak.palrec" csv="$dir/soak.csv" log="$dir/trainer.log"
# Own settings and data folders: no stored patient/layout, and other people's recordings
# folder is not touched (the workstation recovers interrupted recordings it finds there).
export XDG_CONFIG_HOME="$dir/config" XDG_DATA_HOME="$dir/data" QT_QPA_PLATFORM=xcb
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}"

# The shell inside xvfb-run writes its pid, then execs the trainer: that pid is the trainer's.
xvfb-run -a -s "-screen 0 1600x1000x24" sh -c 'echo $$ >"$0/pid"; exec "$@"' "$dir" \
  "$exe" --device simulated --record "$rec" --screenshot "$dir/end.png" --seconds "$dur" >"$log" 2>&1 &
xpid=$!
while [ ! -s "$dir/pid" ]; do sleep 0.2; done
pid=$(cat "$dir/pid")
t0=$(date +%s)
echo "soak: pid $pid, $dur s, files in $dir (commit $(git rev-parse --short HEAD 2>/dev/null || echo ?))" >&2

echo "t_s,vmrss_kb,vmhwm_kb,recording_bytes" >"$csv"
killed=0
while kill -0 "$pid" 2>/dev/null; do
  now=$(($(date +%s) - t0))
  st=$(cat "/proc/$pid/status" 2>/dev/null) || break
  rss=$(echo "$st" | awk '/^VmRSS:/ {print $2}')
  hwm=$(echo "$st" | awk '/^VmHWM:/ {print $2}')
  [ -n "$rss" ] || break  # a zombie: gone
  size=$(stat -c %s "$rec" 2>/dev/null || echo 0)
  echo "$now,$rss,$hwm,$size" >>"$csv"
  if [ "$now" -ge $((dur + 120)) ] && [ "$killed" = 0 ]; then
    echo "soak: still running at $now s: SIGTERM" >&2
    kill -TERM "$pid"; killed=1
  fi
  sleep 10
done
set +e
wait "$xpid"; rc=$?
set -e
end=$(($(date +%s) - t0))
final=$(stat -c %s "$rec" 2>/dev/null || echo 0)

# Summary: RSS at about 1 min, at the end, max; least-squares growth of RSS per 10 min over
# the samples after 5 min; recording MB/min over the whole run.
awk -F, -v end="$end" -v final="$final" 'NR > 1 {
    n++; t[n] = $1; r[n] = $2; if ($2 > mx) mx = $2; hwm = $3
    if (d1 == "" || ($1 - 60) ^ 2 < d1) { d1 = ($1 - 60) ^ 2; r1 = $2; t1 = $1 }
    if ($1 >= 300) { m++; sx += $1; sy += $2; sxx += $1 * $1; sxy += $1 * $2 } }
  END {
    printf "soak: %d samples, ran %d s; RSS at start (%d s) %.1f MiB, at %d s %.1f MiB, at the end (%d s) %.1f MiB, max %.1f MiB (VmHWM %.1f MiB)\n",
      n, end, t[1], r[1] / 1024, t1, r1 / 1024, t[n], r[n] / 1024, mx / 1024, hwm / 1024
    if (m >= 3) printf "soak: RSS growth after 5 min: %+.2f MiB per 10 min (least squares, %d samples)\n",
      (m * sxy - sx * sy) / (m * sxx - sx * sx) * 600 / 1024, m
    else print "soak: RSS growth after 5 min: n/a (run shorter than 5.5 min)"
    printf "soak: recording %.2f MiB, %.2f MiB/min\n", final / 1048576, final / 1048576 / (end / 60) }' "$csv"

# Does the recording read back? --check prints what it holds (ticks, steps, footer).
ok=0
"$cli" replay "$rec" --check >"$dir/check.txt" 2>&1 || ok=1
sed 's/^/soak: check: /' "$dir/check.txt" | head -20
tail -n 3 "$log" | sed 's/^/soak: trainer: /'
if [ "$killed" = 0 ] && [ "$rc" = 0 ] && [ "$end" -ge "$dur" ] && [ "$ok" = 0 ]; then
  echo "soak: OK (exit 0, clean end after $end s)"
  exit 0
fi
echo "soak: FAILED: exit status $rc, ran $end of $dur s, SIGTERM sent: $killed, recording check failed: $ok" >&2
exit 1
