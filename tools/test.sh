#!/bin/sh
# Installs, builds and runs every test (the README's second command calls this).
set -eu
cd "$(dirname "$0")/.."
./tools/install-deps.sh
./tools/build.sh
export QT_QPA_PLATFORM=offscreen
ctest --test-dir build --output-on-failure -j 1
