# checks.sh — sourced by the CLI test scripts that run many checks in one scratch directory:
# makes $dir (removed on exit; the test fails at once if mktemp does), counts checks with
# `expect 'SHELL TEST'` (prints the failing test), and `finish NAME` prints the summary and
# exits non-zero when a check failed.
dir=$(mktemp -d) && [ -d "$dir" ] || { echo "FAILED: mktemp -d"; exit 1; }
trap 'rm -rf "$dir"' EXIT
fail=0 pass=0
expect() { if eval "$1"; then pass=$((pass + 1)); else echo "FAILED: $1"; fail=$((fail + 1)); fi; }
finish() {
  echo "$1: $pass passed, $fail failed"
  exit $((fail > 0))
}
