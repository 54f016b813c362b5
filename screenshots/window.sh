#!/usr/bin/env bash
# Screenshots of the previewer window: runs it under Xvfb (a virtual display), drives it
# with xdotool as a person would, and saves what the screen shows into screenshots/.
# Needs: apt-get install xvfb xdotool imagemagick
# The coordinates are those of the window's layout at its first size, 1280x720 (a fresh
# XDG_DATA_HOME: no remembered size), with no window manager placing it.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
export DISPLAY=":${RAYLAB_DISPLAY:-97}"
# 48 pixels more than the window: room for a taskbar, so the window keeps its first size
# (a window that does not fit its screen is made to fit).
Xvfb "$DISPLAY" -screen 0 1280x768x24 >/dev/null 2>&1 &
xvfb=$!
# Start from each scene's defaults, not from what an earlier run remembered.
XDG_DATA_HOME=$(mktemp -d)
export XDG_DATA_HOME
trap 'kill $xvfb 2>/dev/null; rm -rf "$XDG_DATA_HOME"' EXIT
# Wait until the display answers.
for _ in $(seq 50); do xdotool getmouselocation >/dev/null 2>&1 && break; sleep 0.2; done

app=
launch() {
  RAYLAB_CLOSE_AFTER=90 ./target/release/raylab "$@" --threads 2 >/dev/null 2>&1 &
  app=$!
  win=$(xdotool search --sync --name '^raylab' | head -1)
  xdotool windowfocus --sync "$win"
}
quit() { kill "$app" 2>/dev/null || true; wait "$app" 2>/dev/null || true; }
shot() { import -window root -crop 1280x720+0+0 +repage "screenshots/$1.png"; echo "screenshots/$1.png"; }
click() { xdotool mousemove "$1" "$2"; sleep 0.2; xdotool click 1; sleep 0.3; }
# Press at (x1, y1), move to (x2, y2) in steps; the button stays down.
press_and_move() {
  xdotool mousemove "$1" "$2"; sleep 0.2; xdotool mousedown 1; sleep 0.2
  xdotool mousemove $(( ($1 + $3) / 2 )) "$4"; sleep 0.2
  xdotool mousemove "$3" "$4"; sleep 0.15
}

# The default scene, refined.
launch default
sleep 5
shot window-default

# Dragging the IOR slider: the coarse previews follow the hand.
press_and_move 61 60 110 60
shot window-ior-drag
xdotool mouseup 1
sleep 5
shot window-ior-2.3

# Pixel-peeping: zoom into the glass sphere's rim with the wheel.
xdotool mousemove 1130 330
for _ in $(seq 12); do xdotool click 4; sleep 0.05; done
sleep 1
shot window-zoom
quit

# Total internal reflection, with water's IOR: the prism opens onto the red wall.
launch tir
sleep 1
click 51 83
sleep 7
shot window-tir-water
quit

# Depth of field: "Click to focus", then the far red sphere.
launch depth-of-field
sleep 2
click 72 620
click 905 330
sleep 6
shot window-focus
quit

# The instruments. Menu entries, 23 pixels apart below "Instruments" at (934, 12):
# Fresnel plot, Ray-tree inspector, Cost heat map, the heat map's range, A/B compare (its
# presets open to the left), Contact sheet, Sample patterns.
menu() { click 934 12; click "$1" "$2"; }
launch glass
sleep 3
menu 960 39
menu 960 62
# Inspect a pixel of the glass sphere (the image sits left of the two docks now).
click 500 310
sleep 2
shot window-fresnel-inspector
quit

# A/B compare, third preset: constant | Fresnel reflectance.
launch glazed
sleep 1
click 934 12
click 940 131
click 760 177
sleep 7
shot window-ab-compare
quit

launch ray-tree
sleep 4
menu 960 85
sleep 1
shot window-cost-heat-map
quit

launch soft-shadows
sleep 1
menu 960 177
sleep 1
shot window-sample-patterns
quit

# A lecture slide: the Lecture menu at (1014, 12), fourth entry (total internal reflection).
launch default
sleep 1
click 1014 12
click 850 108
sleep 6
shot window-lecture-tir
quit

# A scene file with an error: the window shows where, and keeps the previous scene.
bad=$(mktemp --suffix=.toml)
printf '[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\n[[sphere]]\ncenter = [0, 1, 0]\nradius = -2\n' > "$bad"
launch "$bad"
sleep 4
shot window-error
# Ctrl+O: the file dialog.
xdotool key ctrl+o
sleep 1
shot window-open
quit
rm -f "$bad"

# Contact sheets, from the command line.
./target/release/raylab sweep antialiasing --param spp=1,4,16,64 --set pattern=jittered -o screenshots/sheet-antialiasing-spp.png
./target/release/raylab sweep glazed --param fresnel=constant,schlick_naive,schlick,exact -o screenshots/sheet-glazed-fresnel.png
