#!/usr/bin/env bash
# run.sh --install|--test BUILD_DIR ICSHADOW
#   --install  installs the Python package from python/ with pip, as README says, over BUILD_DIR's
#              libraries, into BUILD_DIR/tmp/python-pkg (the CTest fixture python_install);
#   --test     runs tests/python/test_icshadow.py against the CLI ICSHADOW with that package.
# Exits 77 (skipped, with the reason) when Python lacks cffi, numpy, pip or setuptools.
set -euo pipefail
mode=$1 build=$(cd "$2" && pwd) cli=$(realpath "$3")
here=$(cd "$(dirname "$0")" && pwd) repo=$(cd "$(dirname "$0")/../.." && pwd)
py=${PYTHON:-/usr/bin/python3}
for m in cffi numpy pip setuptools; do
  "$py" -c "import $m" 2>/dev/null || { echo "skipped: $py has no module $m (scripts/deps.sh installs it)"; exit 77; }
done
pkg=$build/tmp/python-pkg
case $mode in
  --install)
    rm -rf "$pkg"
    ICSHADOW_BUILD_DIR=$build "$py" -m pip install --quiet --disable-pip-version-check --root-user-action=ignore \
      --no-build-isolation --no-index --no-deps --target "$pkg" "$repo/python"
    test -f "$pkg/icshadow/__init__.py" || { echo "pip install ./python failed"; exit 1; }
    echo "installed: $pkg" ;;
  --test)
    test -f "$pkg/icshadow/__init__.py" || { echo "no package in $pkg: run the python_install test first"; exit 1; }
    scratch=$build/tmp/python-test
    rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
    PYTHONPATH=$pkg ICSHADOW_CLI=$cli ICSHADOW_TMP=$scratch "$py" "$here/test_icshadow.py" 2>&1 ;;
  *) echo "usage: run.sh --install|--test BUILD_DIR ICSHADOW" >&2; exit 2 ;;
esac
