#!/usr/bin/env bash
# Installs the Debian packages Frontier needs, only those that are missing.
# Usage: scripts/install-deps.sh [--with-extras] [--for-tests] [--with-peers]
#   --with-extras also installs ffmpeg (--video). gnuplot-nox (the charts of `frontier sweep`)
#   is in the main list: the sweep test draws one in CI.
#   python3-dev, pybind11-dev and python3-numpy are in the main list: the Python module (python/).
#   --for-tests also installs python3-pytest (the module's tests, tests/python); dart-doc: real
#   robot files (KUKA KR5, Barrett WAM, DRC-Hubo, Atlas) that the robot corpus test
#   (tests/robots) runs; and clang with libclang-rt-14-dev (libFuzzer)
#   for the fuzz targets (fuzz/, scripts/fuzz.sh); and slurm-wlm with munge for the test of
#   `frontier batch --slurm` on a private one-node cluster (tests/slurm).
#   libmujoco-dev is in the main list: MuJoCo's compiler reads MJCF files (io/mjcf_compile.h).
#   --with-peers also installs Bullet and ODE for bench/peers (the comparison harness,
#   cmake -DFRONTIER_PEERS=ON); scripts/test.sh builds and runs it.
# Run as root, or as a user with sudo; otherwise it prints the apt-get line to run.
set -euo pipefail

packages=(
  cmake g++ pkg-config make
  libeigen3-dev libfcl-dev libccd-dev libqhull-dev liburdfdom-dev libyaml-cpp-dev libassimp-dev libsdformat-dev
  libosmesa6-dev libpng-dev
  libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev libssl-dev
  gnuplot-nox
  python3-dev pybind11-dev python3-numpy
  libmujoco-dev
)
for option in "$@"; do
  case "$option" in
    --with-extras) packages+=(ffmpeg) ;;
    --for-tests) packages+=(python3-pytest dart-doc clang libclang-rt-14-dev slurm-wlm munge) ;;
    --with-peers) packages+=(libbullet-dev libode-dev) ;;
    -h|--help) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "install-deps: unknown option '$option' (expected --with-extras, --for-tests, --with-peers or --help)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
if [[ $(id -u) -eq 0 ]]; then
  apt_get=(apt-get)
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  apt_get=(sudo apt-get)
else
  echo "install-deps: not root and no passwordless sudo. Run this as root:" >&2
  echo "  apt-get update && apt-get install -y --no-install-recommends ${missing[*]}" >&2
  exit 2
fi
export DEBIAN_FRONTEND=noninteractive
"${apt_get[@]}" update -qq
"${apt_get[@]}" install -y -qq --no-install-recommends "${missing[@]}"
