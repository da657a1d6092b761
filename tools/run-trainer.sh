#!/bin/sh
# Starts the workstation GUI (build/ui/palpation-trainer). With a display ($DISPLAY or
# $WAYLAND_DISPLAY) it opens the window; without one it runs under a virtual X server
# (xvfb-run) and says so: the session keeps running with the simulated HandHIRO, and
# --screenshot FILE.png still works. Arguments go to palpation-trainer.
set -eu
cd "$(dirname "$0")/.."
exe="${PALPATION_TRAINER:-./build/ui/palpation-trainer}"  # another build: PALPATION_TRAINER=path
if [ ! -x "$exe" ]; then
  echo "run-trainer: $exe not found: run ./tools/build.sh first" >&2
  exit 2
fi
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}"
if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
  exec "$exe" "$@"
fi
if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "run-trainer: no display and no xvfb-run (apt-get install xvfb xauth): cannot start the GUI" >&2
  exit 2
fi
echo "run-trainer: no display (\$DISPLAY unset): running the workstation under Xvfb (xvfb-run -a);" \
     "the window is invisible, the simulated HandHIRO session keeps running until you press Ctrl+C." \
     "Use --screenshot FILE.png to see it." >&2
export QT_QPA_PLATFORM=xcb
exec xvfb-run -a -s "-screen 0 1600x1000x24" "$exe" "$@"
