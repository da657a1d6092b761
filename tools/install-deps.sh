#!/bin/sh
# Installs every Debian 12 package the build, the tests and the GUI need.
# Idempotent and non-interactive; run as root (or through sudo). postgresql: the test
# runs start a private server of their own (tools/pg-cluster.sh).
set -eu
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
PACKAGES="build-essential cmake ninja-build git pkg-config \
  qt6-base-dev libqt6opengl6-dev qt6-charts-dev libqt6sql6-sqlite libqt6sql6-psql qt6-tools-dev qt6-tools-dev-tools \
  qt6-l10n-tools libvtk9-dev libassimp-dev libeigen3-dev libgmsh-dev gmsh nlohmann-json3-dev \
  libcli11-dev libzstd-dev xvfb xauth libgl1-mesa-dri fonts-ipafont-gothic postgresql"
missing=""
for p in $PACKAGES; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "install-deps: installing:$missing"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
else
  echo "install-deps: all packages present"
fi
