#!/bin/sh
# Installs, builds and runs every test (the README's second command calls this).
#
# The database tests run on SQLite and on PostgreSQL: unless PALPATION_TEST_PG already
# names a server (.ci/run starts one for both of its stages), this starts a private
# cluster for the run (tools/pg-cluster.sh: a temporary folder, 127.0.0.1, a free port)
# and stops it at the end, also when a test fails or the run is interrupted.
# PALPATION_TEST_PG=off runs them on SQLite only (the PostgreSQL cases say SKIP).
set -eu
cd "$(dirname "$0")/.."
./tools/install-deps.sh
./tools/build.sh
export QT_QPA_PLATFORM=offscreen
if [ "${PALPATION_TEST_PG:-}" = off ]; then
  unset PALPATION_TEST_PG
elif [ -z "${PALPATION_TEST_PG:-}" ]; then
  pg_dir=$(mktemp -d "${TMPDIR:-/tmp}/palpation-pg.XXXXXX")
  pg_tool=$(pwd)/tools/pg-cluster.sh  # the trap may run from another folder
  trap '"$pg_tool" stop "$pg_dir"' EXIT
  trap 'exit 130' INT TERM
  pg_start=$(date +%s)
  PALPATION_TEST_PG=$("$pg_tool" start "$pg_dir")
  export PALPATION_TEST_PG
  echo "test: PostgreSQL test server on ${PALPATION_TEST_PG##*@} (started in $(( $(date +%s) - pg_start )) s)"
fi
# The "compute" suites (accuracy and stress: headless, not paced by the clock) run two at
# a time, then the rest one at a time: the real-time suites (haptic loop, pacing, session,
# GUI) keep the machine to themselves. Both groups run even when the first fails.
status=0
ctest --test-dir build --output-on-failure -j 2 -L compute || status=1
ctest --test-dir build --output-on-failure -j 1 -LE compute || status=1
exit $status
