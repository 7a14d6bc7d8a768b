#!/usr/bin/env bash
# Where `-o` may point (cli_output in cli/cliutil.c): a symbolic link is written through (the
# link stays, its target gets the file), a dangling link creates its target, a FIFO is written
# in place (not replaced by a regular file), a directory is refused (exit 1), and a failed run
# leaves an existing file exactly as it was.
set -u
cli=$1
. "$(dirname "$0")/checks.sh"

echo old > "$dir/real.h"
ln -s "$dir/real.h" "$dir/link.h"
"$cli" lut --size 8 --lang c -o "$dir/link.h"; rc=$?
expect '[ $rc -eq 0 ]'
expect '[ -L "$dir/link.h" ]'
expect 'grep -q "generated" "$dir/real.h"'

ln -s "$dir/new.h" "$dir/dangling.h"
"$cli" lut --size 8 --lang c -o "$dir/dangling.h"; rc=$?
expect '[ $rc -eq 0 ] && [ -L "$dir/dangling.h" ] && grep -q "generated" "$dir/new.h"'

mkfifo "$dir/fifo"
cat "$dir/fifo" > "$dir/from_fifo" &
reader=$!
"$cli" lut --size 8 --lang c -o "$dir/fifo"; rc=$?
wait $reader
expect '[ $rc -eq 0 ] && [ -p "$dir/fifo" ] && grep -q "generated" "$dir/from_fifo"'

mkdir "$dir/adir"
"$cli" lut --size 8 --lang c -o "$dir/adir" 2> "$dir/err"; rc=$?
expect '[ $rc -eq 1 ] && grep -q "is a directory" "$dir/err" && [ -d "$dir/adir" ]'

echo keep > "$dir/keep.h"
"$cli" lut --size 3 --lang c -o "$dir/keep.h" 2> /dev/null; rc=$?
expect '[ $rc -eq 2 ] && [ "$(cat "$dir/keep.h")" = keep ]'
expect '[ -z "$(ls "$dir" | grep tmp)" ]'

finish cli_output_targets
