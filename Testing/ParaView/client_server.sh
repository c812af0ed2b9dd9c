#!/usr/bin/env bash
# A pvpython client connected to a pvserver of 1 and of 3 MPI processes: the
# "Monte Carlo X-Ray" representation's picture must be the same bytes.
#   client_server.sh PLUGIN VOLUME.vti OUTPUT_PREFIX   (PYTHONPATH: ParaView's)
# Needs a display (run under Testing/with-display) and pvserver, pvpython
# and mpiexec (MCXRAY_PVPYTHON and MCXRAY_PVSERVER name them if not on PATH).
set -euo pipefail
plugin="$1" volume="$2" prefix="$3"
here="$(cd "$(dirname "$0")" && pwd)"
pvpython="${MCXRAY_PVPYTHON:-pvpython}"
pvserver="${MCXRAY_PVSERVER:-pvserver}"
export HWLOC_COMPONENTS=-gl # Open MPI's hwloc would probe the X displays
free_port() {
  python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}
# One session: the server, then the client; the server exits when the client
# disconnects. False if either fails or takes over 120 s.
session() {
  local processes="$1" port log server
  port="$(free_port)"
  log="$prefix-server-$processes.log"
  timeout 120 mpiexec --allow-run-as-root --oversubscribe -np "$processes" \
    "$pvserver" --server-port="$port" >"$log" 2>&1 &
  server=$!
  for _ in $(seq 1 100); do
    grep -q "Accepting connection" "$log" && break
    sleep 0.2
  done
  local status=0
  timeout 120 "$pvpython" "$here/pvpython_client_server.py" "$plugin" "$volume" "$port" \
    "$prefix-$processes.npy" || status=$?
  wait "$server" || status=$?
  return "$status"
}
for processes in 1 3; do
  rm -f "$prefix-$processes.npy"
  # A second try: ParaView's first parallel render deadlocks now and then on
  # this machine (see Testing/same_output_for_any_process_count.cmake).
  session "$processes" || session "$processes"
done
cmp "$prefix-1.npy" "$prefix-3.npy"
echo "the pictures of 1 and 3 server processes are identical"
