#!/usr/bin/env bash
# run.sh BUILD_DIR ICSHADOW — installs the Python package from python/ (pip, as README says, into
# BUILD_DIR/tmp/python-pkg, over BUILD_DIR's libraries) and runs tests/python/test_icshadow.py.
# Exits 77 (skipped, with the reason) when Python lacks cffi, numpy or pip.
set -euo pipefail
build=$(cd "$1" && pwd) cli=$(realpath "$2")
here=$(cd "$(dirname "$0")" && pwd) repo=$(cd "$(dirname "$0")/../.." && pwd)
py=${PYTHON:-/usr/bin/python3}
for m in cffi numpy pip setuptools; do
  "$py" -c "import $m" 2>/dev/null || { echo "skipped: $py has no module $m (scripts/deps.sh installs it)"; exit 77; }
done
pkg=$build/tmp/python-pkg scratch=$build/tmp/python-test
rm -rf "$pkg" "$scratch"
mkdir -p "$scratch"
ICSHADOW_BUILD_DIR=$build "$py" -m pip install --quiet --disable-pip-version-check --no-build-isolation \
  --no-index --no-deps --target "$pkg" "$repo/python" 2>&1 | grep -v "Running pip as the 'root' user" || true
test -f "$pkg/icshadow/__init__.py" || { echo "pip install ./python failed"; exit 1; }
cd "$scratch"
PYTHONPATH=$pkg ICSHADOW_CLI=$cli ICSHADOW_TMP=$scratch "$py" "$here/test_icshadow.py" 2>&1
