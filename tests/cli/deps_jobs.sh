#!/usr/bin/env bash
# deps_jobs.sh DEPS — scripts/deps.sh per job: every job's packages are among the full list
# (`make test` installs the full list, so a job never needs a package it would not get) and
# include the build's core; an unknown job is refused with exit 2 and the list of jobs.
set -u
deps=$1
fail=0
full=$("$deps" --list) || { echo "deps.sh --list failed"; exit 1; }
core=$("$deps" --list core)
for j in core demo figs notebooks bench analysis fuzz test; do
  pk=$("$deps" --list "$j") || { echo "deps.sh --list $j failed"; fail=1; continue; }
  extra=$(comm -23 <(printf '%s\n' "$pk") <(printf '%s\n' "$full"))
  [ -z "$extra" ] || { echo "job $j needs packages outside the full list: $extra"; fail=1; }
  nocore=$(comm -23 <(printf '%s\n' "$core") <(printf '%s\n' "$pk"))
  [ -z "$nocore" ] || { echo "job $j lacks the core packages: $nocore"; fail=1; }
  echo "$j: $(printf '%s\n' "$pk" | wc -l) packages"
done
[ "$("$deps" --list test)" = "$full" ] || { echo "job test is not the full list"; fail=1; }
err=$("$deps" bogus 2>&1); rc=$?
[ $rc -eq 2 ] && printf '%s' "$err" | grep -q "unknown job 'bogus' (jobs: core demo" ||
  { echo "unknown job: exit $rc, '$err'"; fail=1; }
exit $fail
