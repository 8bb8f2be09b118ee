#!/usr/bin/env bash
# Installs every build, test and plotting dependency of markerbench from Debian 12's archive.
# Idempotent and non-interactive; runs apt-get as root, or through sudo otherwise.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git clang-format
  clang libclang-rt-14-dev
  libeigen3-dev
  libopencv-dev libopencv-contrib-dev
  libapriltag-dev
  libceres-dev libgoogle-glog-dev libgflags-dev
  libopenimageio-dev openimageio-tools
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libzstd-dev zstd libssl-dev
  libcmark-gfm-dev libcmark-gfm-extensions-dev libcairo2-dev fonts-dejavu-core
  libgtest-dev libgmock-dev libbenchmark-dev valgrind
  python3 python3-matplotlib python3-opencv python3-yaml
  libxml2-utils
  slurm-wlm munge
)

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  sudo_cmd=(sudo)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
