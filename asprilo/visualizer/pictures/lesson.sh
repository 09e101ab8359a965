#!/usr/bin/env bash
# The README's pictures of a lesson you can present, taken at 1366x768 on a real X server
# (Xvfb, no window manager) with the keys and clicks a teacher would use (xdotool) and
# ImageMagick's `import -window root`:
#   lesson-presentation.png  the presentation mode (F11) at step 23 of wrong_outcome.txt
#   lesson-rule.png          Esc, then the violation deliver/orderAmount clicked: its checker rules
#   lesson-strip-dialog.png  File > Export strip of states… (the dialog, from the File menu)
#   lesson-strip.png         the strip export itself (viz --export --strip 21-26, 40 px per cell)
#   lesson-mistake.png       a plan file with three mistakes opened: the reader's warnings, with
#                            the file's lines, in the Atoms tab (clicked) and the status bar
# Screenshots are kept small: 256 colours (PNG8).
#
# Usage (needs Xvfb, xdotool and ImageMagick; `viz` on the PATH):
#   asprilo/visualizer/pictures/lesson.sh [OUT-FOLDER]          (default: asprilo/visualizer/pictures)
# Clicks go to places of the first window's layout at 1366x768 (the Violations tab and its
# first row, the Atoms tab); a changed layout needs new coordinates below.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
out="${1:-$here}"
small="$root/examples/asprilo/dom-a/small"
instance="$small/x11_y6_n66_r3_s12_ps2_pr5_u50_o3_N001.lp"
plan="$small/wrong_outcome.txt"
display=":${LESSON_DISPLAY:-8}"
settings="$(mktemp -d)"

Xvfb "$display" -screen 0 1366x768x24 >/dev/null 2>&1 &
xvfb=$!
viz_pid=""
cleanup() {
  [ -n "$viz_pid" ] && kill "$viz_pid" 2>/dev/null || true
  kill "$xvfb" 2>/dev/null || true
  rm -rf "$settings"
}
trap cleanup EXIT
export DISPLAY="$display"
for _ in $(seq 50); do xdpyinfo >/dev/null 2>&1 && break; sleep 0.1; done

# wait for the viewer's window titled "$1 — asprilo viz" and focus it
focus_window() {
  local window=""
  for _ in $(seq 100); do
    window="$(xdotool search --onlyvisible --name "$1 — asprilo viz" 2>/dev/null | head -1 || true)"
    [ -n "$window" ] && break
    sleep 0.2
  done
  [ -n "$window" ] || { echo "lesson.sh: the viewer's window did not appear" >&2; exit 1; }
  sleep 1
  xdotool windowfocus --sync "$window"
}

# a fresh settings folder: the first window's layout, no recent files
XDG_CONFIG_HOME="$settings" viz "$instance" "$plan" --step 23 &
viz_pid=$!
focus_window wrong_outcome.txt
shoot() {
  sleep 1.5
  import -window root "$out/$1"
  convert "$out/$1" -strip -colors 256 "PNG8:$out/$1"
  echo "wrote $out/$1"
}

xdotool key F11                                    # the presentation mode
shoot lesson-presentation.png
xdotool key Escape                                 # back to the window as it was
sleep 1
xdotool mousemove 1075 665 click 1                 # the Violations tab
sleep 0.5
xdotool mousemove 1010 435 click 1                 # its first row: deliver/orderAmount at step 23
xdotool mousemove 1300 30                           # the mouse where no tooltip shows
shoot lesson-rule.png
xdotool key alt+f                                  # File > Export strip of states…
sleep 0.5
xdotool key i
shoot lesson-strip-dialog.png
xdotool key Escape
kill "$viz_pid"
viz_pid=""

# (exit status 1: the plan is invalid, as check says; the picture is written all the same)
viz "$instance" "$plan" --export "$out/lesson-strip.png" --strip 21-26 --cell 40 --columns 3 || [ $? -eq 1 ]

# a student's plan with three mistakes, written next to the settings and opened by its
# relative name (the warnings name the file as it was given, as `check` does)
cat >"$settings/mistakes.lp" <<'PLAN'
% a plan with mistakes
occur(object(robot,1),action(move,(1,0)),2).
occurs(object(robot,1),action(mvoe,(1,0)),3).
occurs(object(robot,2),action(move,(0,1),4)).
PLAN
(cd "$settings" && XDG_CONFIG_HOME="$settings" exec viz "$instance" mistakes.lp 2>/dev/null) &
viz_pid=$!
focus_window mistakes.lp
xdotool mousemove 1171 665 click 1                 # the Atoms tab
xdotool mousemove 1300 30                           # the mouse where no tooltip shows
shoot lesson-mistake.png
kill "$viz_pid"
viz_pid=""
