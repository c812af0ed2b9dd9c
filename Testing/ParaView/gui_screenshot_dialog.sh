#!/usr/bin/env bash
# The real ParaView GUI under Xvfb, driven by xdotool as a user: File > Save
# Screenshot, a file name, then the options dialog stays open for 4 s (its
# preview mode lays the view out anew) and is cancelled. Every frame drawn at
# the view's own size must be the refined X-ray (every point), not a noisy
# prefix; at least one frame at another size shows the preview happened.
# Exits 77 (skipped) without xdotool.
#   gui_screenshot_dialog.sh PLUGIN_DIRECTORY RECORD_FILE   (from the repository root)
set -u
command -v xdotool > /dev/null || { echo "MCXRAY_SKIPPED: no xdotool to drive the GUI"; exit 77; }
plugins="$1"
record="$2"
rm -f "$record"
# One script under one display: the GUI, then the keys typed into it.
PV_PLUGIN_PATH="$plugins" MCX_DIALOG_OUT="$record" setsid Testing/with-display bash -c '
  paraview --dr --script=Testing/ParaView/gui_screenshot_dialog.py &
  gui=$!
  for _ in $(seq 1 480); do grep -q "^ready" "$MCX_DIALOG_OUT" 2> /dev/null && break; sleep 0.25; done
  sleep 2
  window=$(xdotool search --name "^ParaView" | head -n 1)
  xdotool windowfocus --sync "$window"; sleep 0.5
  # File menu: Open is active; Save Screenshot is the eighth entry.
  xdotool key alt+f; sleep 1
  xdotool key Down Down Down Down Down Down Down Return; sleep 2
  xdotool type "$(dirname "$MCX_DIALOG_OUT")/gui-screenshot-dialog.png"; xdotool key Return
  sleep 4
  xdotool key Escape; sleep 2
  kill "$gui"; wait "$gui"' > "$record.log" 2>&1
cat "$record" 2> /dev/null || { echo "no record; the GUI said:"; cat "$record.log"; exit 1; }
awk 'BEGIN { ready = 0; full = 4194303 }
  /^ready/ { ready = 1; next }
  / points / {
    if (!ready) { w = $4; h = $5; next }
    if ($4 == w && $5 == h) { same++; if ($7 != full) bad++ } else { other++ }
  }
  END {
    if (other < 1) { print "FAILED: no frame at another size than " w " x " h " (did the dialog open?)"; exit 1 }
    if (same < 1) { print "FAILED: no frame at the view size " w " x " h " after the preview"; exit 1 }
    if (bad > 0) { print "FAILED: " bad " of " same " frames at the view size " w " x " h " drew a prefix, not every point"; exit 1 }
    print other " frames at the preview sizes, " same " at the view size, every one refined"
  }' "$record"
