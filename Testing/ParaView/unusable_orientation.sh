#!/usr/bin/env bash
# Runs pvbatch_unusable_orientation.py and checks that each of its seven files
# is exactly one error line, naming the file (the lying headers' with the
# header check's words), and that nothing else is an error.   unusable_orientation.sh PVBATCH PLUGIN
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
log="$(mktemp)"
"$1" --dr "$here/pvbatch_unusable_orientation.py" "$2" > "$log" 2>&1
status=$?
cat "$log"
errors=$(grep -c 'ERR|' "$log")
status_ok=$([ "$status" -eq 0 ] && echo yes || echo no)
fail=0
[ "$status_ok" = yes ] || { echo "FAILED: pvbatch exited with $status"; fail=1; }
[ "$errors" -eq 7 ] || { echo "FAILED: $errors error lines, expected 7 (one per file)"; fail=1; }
for name in nan-direction.nrrd unknown-space.nrrd far-origin.nrrd zero-row.mha far-offset.mha \
  lying-sizes.nrrd lying-sizes.mha; do
  [ "$(grep 'ERR|' "$log" | grep -c "$name")" -eq 1 ] || { echo "FAILED: $name is not one error line"; fail=1; }
done
for name in lying-sizes.nrrd lying-sizes.mha; do
  grep 'ERR|' "$log" | grep "$name" | grep -q "': truncated: the header claims 400x500x600 voxels (229 MiB)" ||
    { echo "FAILED: $name is not the header check's message"; fail=1; }
done
rm -f "$log"
exit $fail
