#!/usr/bin/env bash
# The error-against-time sweep (analysis/error_vs_time.py) as a real Slurm job array, on a
# private single-node cluster this test starts on localhost (scripts/slurm_local.sh: munged,
# slurmctld and slurmd with every file in the scratch directory, ports 16817+) and stops: the
# references as one job, shards 0/3, 1/3, 2/3 as an array depending on it, the merge as a job
# depending on the array — docs/results.md's lines. Every job must end COMPLETED, and the merged
# CSV must equal the whole sweep run here against the same references, byte for byte
# (--no-times). Skipped with the reason when not root (the daemons run as SlurmUser=root) or when
# slurm-wlm / munge are not installed (scripts/deps.sh installs them).
set -u
py=$1 evt=$2 slurm=$3  # the icshadow package on PYTHONPATH (tests/python.cmake)
"$py" -c "import icshadow" 2>/dev/null || {
  echo "SKIPPED: the icshadow Python package is not importable (the CTest fixture python_install builds it; it needs cffi)"
  exit 77; }
if [ "$(id -u)" -ne 0 ]; then
  echo "SKIPPED: cli_error_vs_time_slurm needs root (a private slurmctld and slurmd as SlurmUser=root)"
  exit 77
fi
for p in sbatch squeue scontrol slurmctld slurmd munged mungekey; do
  command -v "$p" > /dev/null || {
    echo "SKIPPED: cli_error_vs_time_slurm: $p not found (scripts/deps.sh installs slurm-wlm and munge)"
    exit 77
  }
done
. "$(dirname "$0")/checks.sh"
chmod 0755 "$dir"  # munged: every folder above its socket searchable by all
trap '"$slurm" stop "$dir/cluster" > /dev/null 2>&1; rm -rf "$dir"' EXIT
if ! "$slurm" start "$dir/cluster" 2> "$dir/start.log"; then
  cat "$dir/start.log"
  echo "FAILED: the single-node Slurm cluster did not start"
  exit 1
fi
export SLURM_CONF=$dir/cluster/slurm.conf
E="$py $evt --quick --resolution 64x48 --resolutions 32x24 --ref-spp 16 --reps 1 --no-times --ref $dir/ref.exr"
ref=$(sbatch --parsable -D "$dir" -o "$dir/refs.out" --wrap "$E --refs-only")
arr=$(sbatch --parsable -D "$dir" --kill-on-invalid-dep=yes --dependency=afterok:$ref --array=0-2 -o "$dir/shard_%a.out" \
      --wrap "$E --shard \$SLURM_ARRAY_TASK_ID/3 --csv $dir/shard_\$SLURM_ARRAY_TASK_ID.csv")
mrg=$(sbatch --parsable -D "$dir" --kill-on-invalid-dep=yes --dependency=afterok:$arr -o "$dir/merge.out" \
      --wrap "$py $evt --merge $dir/shard_0.csv $dir/shard_1.csv $dir/shard_2.csv --csv $dir/merged.csv")
expect '[ -n "$ref" ] && [ -n "$arr" ] && [ -n "$mrg" ]'
for _ in $(seq 1 480); do  # at most 120 s
  [ -z "$(squeue -h -j "$ref,$arr,$mrg" 2> /dev/null)" ] && break
  sleep 0.25
done
states=$(for j in "$ref" "$arr" "$mrg"; do scontrol -o show job "$j"; done 2> /dev/null | sed -n 's/.* JobState=\([A-Z_]*\) .*/\1/p' | sort | uniq -c | tr -s ' ')
echo "job states: $states (references, 3 array tasks, merge)"
expect '[ "$states" = " 5 COMPLETED" ]'
[ "$states" = " 5 COMPLETED" ] || cat "$dir"/*.out
$E --csv "$dir/all.csv" 2>> "$dir/log"; expect '[ $? -eq 0 ]'
expect '[ "$(wc -l < "$dir/all.csv")" -eq 6 ] && cmp "$dir/all.csv" "$dir/merged.csv"'
finish cli_error_vs_time_slurm
