#!/usr/bin/env bash
# Runs gui_streaming.py in the real ParaView GUI (streaming on, under Xvfb)
# and checks its record: at least three renders after the script's, without
# input, each with more points and a lower estimated error, the last with
# every point. Then ends the GUI (it has no way to quit from a timer).
#   gui_streaming.sh PLUGIN_DIRECTORY RECORD_FILE     (from the repository root)
set -u
plugins="$1"
record="$2"
rm -f "$record"
PV_PLUGIN_PATH="$plugins" MCX_STREAMING_OUT="$record" setsid Testing/with-display \
  paraview --dr --script=Testing/ParaView/gui_streaming.py > "$record.log" 2>&1 &
gui=$!
for _ in $(seq 1 480); do
  grep -q '^done' "$record" 2> /dev/null && break
  sleep 0.25
done
kill -TERM -- "-$gui" 2> /dev/null
wait "$gui" 2> /dev/null
cat "$record" 2> /dev/null || { echo "no record; the GUI said:"; cat "$record.log"; exit 1; }
awk 'BEGIN { n = 0 }
  / points, estimated error / { points[n] = $3; error[n] = $7; n++ }
  END {
    if (n < 4) { print "FAILED: " n - 1 " refinements without input (at least 3 wanted)"; exit 1 }
    for (i = 1; i < n; i++)
      if (!(points[i] > points[i - 1] && error[i] < error[i - 1])) {
        print "FAILED: render " i " did not refine (points " points[i - 1] " -> " points[i] ", error " error[i - 1] " -> " error[i] ")"; exit 1
      }
    if (points[n - 1] != 16777215) { print "FAILED: refinement stopped at " points[n - 1] " points"; exit 1 }
    print "refined " n - 1 " times without input, to every point"
  }' "$record"
