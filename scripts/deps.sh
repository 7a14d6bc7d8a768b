#!/usr/bin/env bash
# Installs the Debian 12 packages that libicshadow's build, tests, benchmarks and figures need.
# Checks with dpkg first, so a second run costs nothing. As root it runs apt-get; otherwise it
# prints the exact apt-get line and exits non-zero.
set -euo pipefail

packages=(
  # build
  build-essential cmake pkg-config
  # tests: MPFR references, GLSL and OpenCL compile checks of the generated LUT headers
  libmpfr-dev libgmp-dev glslang-tools pocl-opencl-icd ocl-icd-opencl-dev opencl-headers
  # tests: locale sources, so cli_locale_numbers can compile a decimal-comma locale (localedef)
  locales
  # tests: the libFuzzer harnesses (fuzz/; clang 14 with its runtime libraries)
  clang libclang-rt-14-dev
  # benchmarks: Boost.Math as a peer for the elliptic integrals
  libboost-dev
  # optional components: OpenEXR environment maps, jansson for lights/scene JSON (the renderer),
  # libpng for render previews, Assimp for mesh files in scenes, Embree 3 for the Monte-Carlo
  # reference's mesh crossings
  libopenexr-dev libjansson-dev libpng-dev libassimp-dev libembree-dev
  # figures, notebooks and table generators (Debian's python3, not a runtime dependency)
  python3 python3-numpy python3-matplotlib python3-mpmath python3-scipy
  jupyter-nbconvert python3-ipykernel python3-nbformat
  # the Mitsuba 3 outside check: a virtual environment for the PyPI wheel (make mitsuba)
  python3-venv
  # the sweep as a real Slurm job array on a single-node cluster on localhost
  # (tests/cli/evt_slurm.sh through scripts/slurm_local.sh, which starts private daemons under a
  # scratch directory; munge's own install script may start the system's munge service, which
  # the test does not use)
  slurm-wlm munge
)

# Installed means dpkg's package state "installed", whatever the selection: a package on hold
# ("hold ok installed") is installed too (it was reported missing, and deps.sh failed as
# non-root). One line per installed architecture of a Multi-Arch: same package.
missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}\n' "$p" 2>/dev/null || true)
  printf '%s\n' "$status" | grep -qx installed || missing+=("$p")
done

[ ${#missing[@]} -eq 0 ] && exit 0

cmd="apt-get install -y --no-install-recommends ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then
  echo "deps.sh: missing Debian packages: ${missing[*]}" >&2
  echo "deps.sh: run as root:  apt-get update && $cmd" >&2
  exit 1
fi
echo "deps.sh: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
$cmd
