#!/usr/bin/env bash
# Installs, with apt-get, only the Debian 12 packages thetad needs that are missing.
# Idempotent: when everything is present it touches nothing and needs no network.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev
  coinor-libipopt-dev
  libnlopt-cxx-dev
  libgtest-dev libgmock-dev
  libbenchmark-dev
  liblapack-dev liblapacke-dev libslicot-dev
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libssl-dev
  python3-matplotlib python3-scipy python3-mpmath
  python3-dev pybind11-dev python3-numpy python3-pandas python3-pytest python3-statsmodels
  jupyter-nbconvert python3-nbformat python3-ipykernel python3-tqdm
  libsqlite3-dev libopenmpi-dev openmpi-bin
  strace
  # The exported controllers' cross builds (docs/onboard.md): aarch64 Linux run under qemu-user (a
  # test), Cortex-M7 counted under qemu-system-arm, and callgrind's counts (scripts/onboard_counts.sh).
  g++-aarch64-linux-gnu qemu-user
  gcc-arm-none-eabi libnewlib-arm-none-eabi libstdc++-arm-none-eabi-newlib qemu-system-arm valgrind
)

# Extra packages for one target only (make fuzz: Clang and its libFuzzer runtime).
packages+=("$@")

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

if [ "$(id -u)" -ne 0 ]; then
  sudo=sudo
else
  sudo=
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
