#!/usr/bin/env bash
# pvbatch on 3 MPI processes whose last one cannot read the volume (its
# "volume.vti" is missing, then truncated; its legacy "volume.vtk" is
# missing): every process must report that process's failure from the X-Ray
# Density Index and, with the XML file, from the "Monte Carlo X-Ray"
# representation, and the run must end (no process waits for another).
#   reader_fails_on_one_process.sh PLUGIN VOLUME.vti WORK_DIRECTORY
# Needs a display (run under Testing/with-display) and ParaView's PYTHONPATH;
# MCXRAY_PVBATCH and MCXRAY_MPIEXEC name the programs if not on PATH, and
# MCXRAY_VTK_PYTHON a Python with Debian's VTK (default /usr/bin/python3).
set -euo pipefail
plugin="$(realpath "$1")" volume="$2" work="$3" # each process runs in a folder of its own
here="$(cd "$(dirname "$0")" && pwd)"
pvbatch="${MCXRAY_PVBATCH:-pvbatch}"
mpiexec="${MCXRAY_MPIEXEC:-mpiexec}"
export HWLOC_COMPONENTS=-gl # Open MPI's hwloc would probe the X displays

rm -rf "$work"
mkdir -p "$work/readable" "$work/missing" "$work/truncated"
cp "$volume" "$work/readable/volume.vti"
head -c 3000 "$volume" >"$work/truncated/volume.vti" # the header and a little data
# The same volume as a legacy VTK file, written with Debian's Python and VTK
# (python3-vtk9; ParaView's modules on PYTHONPATH are not for it).
env -u PYTHONPATH "${MCXRAY_VTK_PYTHON:-/usr/bin/python3}" -c '
import sys, vtk
reader = vtk.vtkXMLImageDataReader(); reader.SetFileName(sys.argv[1]); reader.Update()
writer = vtk.vtkStructuredPointsWriter(); writer.SetInputData(reader.GetOutput())
writer.SetFileName(sys.argv[2]); writer.SetFileTypeToBinary()
sys.exit(0 if writer.Write() else 1)' "$volume" "$work/readable/volume.vtk"

expect() { # LOG PATTERN: every process's log line matches PATTERN
  local log="$1" pattern="$2" rank
  for rank in 0 1 2; do
    if ! grep -E "\[pvbatch\.$rank +\].*$pattern" "$log" >/dev/null; then
      echo "FAILED: process $rank did not report: $pattern" >&2
      failed=1
    fi
  done
}

first_error() { # LOG PATTERN: every process's first error of the plugin matches PATTERN
  local log="$1" pattern="$2" rank
  for rank in 0 1 2; do
    if ! grep -E "\[pvbatch\.$rank +\].*ERR\| vtkMCX" "$log" | head -n 1 | grep -E "$pattern" >/dev/null; then
      echo "FAILED: process $rank's first error is not: $pattern" >&2
      failed=1
    fi
  done
}

# A case is the failing process's folder and the file's name there: the XML
# reader fails in its information (missing) or delivers nothing (truncated),
# the legacy reader fails in its data object (missing; the filters only: with
# a display, ParaView's own grid axes representation would wait for ever, see
# pvbatch_reader_fails.py).
for case in missing:volume.vti:all truncated:volume.vti:all missing:volume.vtk:filters; do
  IFS=: read -r folder file parts <<<"$case"
  case="$folder $file"
  log="$work/$folder-$file.log"
  # One more try after a timeout (see
  # Testing/same_output_for_any_process_count.cmake); nothing else is retried.
  for attempt in 1 2; do
    status=0
    timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe \
      -np 2 --wdir "$work/readable" "$pvbatch" --dr "$here/pvbatch_reader_fails.py" "$plugin" "$file" "$parts" : \
      -np 1 --wdir "$work/$folder" "$pvbatch" --dr "$here/pvbatch_reader_fails.py" "$plugin" "$file" "$parts" \
      >"$log" 2>&1 || status=$?
    if [ "$status" -ne 124 ]; then
      break
    fi
    cp "$log" "${log%.log}-try$attempt.log"
    echo "WARNING: the run with a $case timed out (log: ${log%.log}-try$attempt.log); trying again" >&2
  done
  if [ "$status" -ne 0 ]; then
    echo "FAILED: the run with a $case ended with status $status:" >&2
    tail -n 20 "$log" >&2
    exit 1
  fi
  failed=0
  grep -q "the filters returned" "$log" || { echo "FAILED: the filters did not return ($case)" >&2; failed=1; }
  first_error "$log" "vtkMCXDensityIndex.*process 2 of 3: The volume's piece could not be read"
  expect "$log" "vtkMCXDensityIndex.*process 2 of 3: The volume's piece could not be read \(see the reader's error in that process's output\)\."
  if [ "$parts" = all ]; then
    grep -q "the representation rendered" "$log" || { echo "FAILED: no render ($case)" >&2; failed=1; }
    expect "$log" "Monte Carlo X-Ray: process 2 of 3: the volume's piece could not be read \(see the reader's error in that process's output\)\."
  fi
  [ "$failed" -eq 0 ] || exit 1
  echo "a $case on process 2 of 3: every process reported it and the run ended"
done
