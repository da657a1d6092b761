#!/bin/sh
# Configures and builds into ./build (Release). CUDA is used when nvcc is found.
set -eu
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build build -j "$(nproc)"
