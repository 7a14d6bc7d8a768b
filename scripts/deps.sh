#!/usr/bin/env bash
# Installs the Debian 12 packages that libicshadow's build, tests, benchmarks and figures need:
# `scripts/deps.sh` (or `deps.sh test`) everything, `deps.sh JOB...` what those jobs need (core,
# demo, figs, notebooks, bench, analysis, fuzz, python); `deps.sh --list [JOB...]` prints them instead.
# Checks with dpkg first, so a second run costs nothing. As root it runs apt-get; otherwise it prints the exact apt-get line and exits non-zero.
set -euo pipefail

# The packages of each job (scripts/deps.sh JOB...; no JOB: everything, which `make test` needs).
# A job lists only what it uses, so a user without root who lacks, say, Boost can still run the
# demo.
core=(build-essential cmake pkg-config)
# the renderer (jansson: scenes and lights files; libpng: previews) and OpenEXR (maps, renders)
render=(libjansson-dev libpng-dev libopenexr-dev)
# Python: figures, notebooks and the icshadow package (python/: cffi compiles its binding against
# Python.h; pip and venv install it)
python=(python3 python3-numpy python3-matplotlib python3-mpmath python3-scipy python3-cffi python3-dev
        python3-pip python3-venv python3-setuptools)
opencl=(pocl-opencl-icd ocl-icd-opencl-dev opencl-headers)
# the gl backend's contexts: EGL (Mesa's surfaceless platform, llvmpipe, without a GPU) and OSMesa;
# the GL headers (GL/glcorearb.h); glslangValidator for its shader checks
gl=(libegl-dev libgl-dev libosmesa6-dev libegl-mesa0 glslang-tools)
declare -A jobs=(
  [core]="${core[*]}"
  [demo]="${core[*]} ${render[*]}"
  # figures and table generators (Debian's python3, not a runtime dependency)
  [figs]="${core[*]} ${render[*]} ${python[*]}"
  # the Python package (python/, docs/python.md)
  [python]="${core[*]} ${render[*]} ${python[*]}"
  [notebooks]="${core[*]} ${render[*]} ${python[*]} jupyter-nbconvert python3-ipykernel python3-nbformat"
  # benchmarks: Boost.Math as a peer for the elliptic integrals, OpenCL and OpenGL for
  # --backend cl and gl
  [bench]="${core[*]} ${render[*]} libboost-dev ${opencl[*]} ${gl[*]}"
  # the stability sweep against MPFR and the scipy comparison
  [analysis]="${core[*]} ${render[*]} libmpfr-dev libgmp-dev ${python[*]}"
  # the libFuzzer harnesses (fuzz/; clang 14 with its runtime libraries)
  [fuzz]="${core[*]} ${render[*]} clang libclang-rt-14-dev"
)
packages=(
  "${core[@]}" "${render[@]}" "${python[@]}" "${opencl[@]}" "${gl[@]}"
  # tests: MPFR references, GLSL compile checks of the generated LUT headers (OpenCL: above)
  libmpfr-dev libgmp-dev glslang-tools
  # tests: locale sources, so cli_locale_numbers can compile a decimal-comma locale (localedef)
  locales
  # tests: the libFuzzer harnesses
  clang libclang-rt-14-dev
  # tests: the NEON loops built for AArch64 and run under qemu-user (tests/cross/neon.sh)
  gcc-aarch64-linux-gnu libc6-dev-arm64-cross qemu-user
  # benchmarks: Boost.Math
  libboost-dev
  # optional components of the renderer: Assimp for mesh files in scenes, Embree 3 for the
  # Monte-Carlo reference's mesh crossings
  libassimp-dev libembree-dev
  # notebooks
  jupyter-nbconvert python3-ipykernel python3-nbformat
  # the Mitsuba 3 outside check: a virtual environment for the PyPI wheel (make mitsuba)
  python3-venv
  # the sweep as a real Slurm job array on a single-node cluster on localhost
  # (tests/cli/evt_slurm.sh through scripts/slurm_local.sh, which starts private daemons under a
  # scratch directory; munge's own install script may start the system's munge service, which
  # the test does not use)
  slurm-wlm munge
)
list=0
if [ "${1:-}" = "--list" ]; then # print the packages (one per line) instead of checking them
  list=1
  shift
fi
if [ $# -gt 0 ]; then
  wanted=()
  for j in "$@"; do
    case "$j" in
      all | test) wanted+=("${packages[@]}") ;;
      *)
        if [ -z "${jobs[$j]+x}" ]; then
          echo "deps.sh: unknown job '$j' (jobs: core demo figs notebooks bench analysis fuzz test all)" >&2
          exit 2
        fi
        read -r -a more <<< "${jobs[$j]}"
        wanted+=("${more[@]}")
        ;;
    esac
  done
  packages=("${wanted[@]}")
fi

# Installed means dpkg's package state "installed", whatever the selection: a package on hold
# ("hold ok installed") is installed too (it was reported missing, and deps.sh failed as
# non-root). One line per installed architecture of a Multi-Arch: same package.
if [ $list -eq 1 ]; then
  printf '%s\n' "${packages[@]}" | sort -u
  exit 0
fi

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
