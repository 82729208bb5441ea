#!/usr/bin/env bash
# Installs the Debian packages the project needs; does nothing when all are present.
# Python libraries come from Debian too and are used through /usr/bin/python3.
set -euo pipefail
PACKAGES=(
  build-essential cmake git
  libeigen3-dev nlohmann-json3-dev libceres-dev libgsl-dev
  libgtest-dev libbenchmark-dev libsuitesparse-dev
  gmsh libgmsh-dev calculix-ccx
  python3 python3-matplotlib python3-numpy python3-scipy python3-pytest python3-tqdm python3-meshio
  python3-distributed
  python3-dev pybind11-dev python3-pybind11
  libboost-dev chromium python3-websocket
)
# haptic_sim view's page: three.js and its browser test's puppeteer-core come from npm at build
# time (Debian's nodejs and npm, unless a Node.js with npm is already there).
if ! command -v npm > /dev/null 2>&1; then PACKAGES+=(nodejs npm); fi
missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} Debian packages present"
  exit 0
fi
echo "setup: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
