#!/usr/bin/env bash
# Screenshots of presentation mode, as a hall sees it: the window under Xvfb at 1920x1080
# (a projector) and at 1280x720 (a laptop), F5, then Page Down to eleven slides, each shot
# 12 s after it opens (on 2 cores most reach their target by then; soft shadows' 256 spp
# at the display's size do not, and look clean at about 60 to 70). Writes
# screenshots/present-{1080,720}-{snell,ray-tree,tir,pruning,reflectance,schlick,sampling,
# soft-shadows,depth-of-field,real-lens,polarization}.png; and for the slides a lecturer drags on
# (Snell, reflectance, Schlick, soft shadows, depth of field, polarisation) the frame in
# the middle of a drag, -drag.png: ] held down (the slide's first control stepped at the
# keyboard's repeat rate), or the workbench's drawing dragged with the mouse; the shot
# after it is the image settled.
# Needs: apt-get install xvfb xdotool imagemagick
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
# Slide numbers and names, in the lecture's order (raylab lecture lists them).
slides=(2:snell 3:ray-tree 4:tir 5:pruning 6:reflectance 8:schlick 11:sampling 13:soft-shadows 16:depth-of-field 17:real-lens 19:polarization)
# Slides shot mid-drag, and how: `key` holds ], `bench` drags the workbench's drawing.
declare -A drags=([snell]=key [reflectance]=bench [schlick]=bench [soft-shadows]=key [depth-of-field]=key [polarization]=key)
display=${RAYLAB_DISPLAY:-96}
for size in 1920x1080 1280x720; do
  w=${size%x*}; h=${size#*x}
  # A display of its own for each size: the last one may still be shutting down.
  export DISPLAY=":$display"
  display=$((display + 1))
  # Room for a taskbar under the window, which keeps its size; the shots are the window.
  Xvfb "$DISPLAY" -screen 0 "${w}x$((h + 48))x24" >/dev/null 2>&1 &
  xvfb=$!
  XDG_DATA_HOME=$(mktemp -d)
  export XDG_DATA_HOME
  for _ in $(seq 50); do xdotool getmouselocation >/dev/null 2>&1 && break; sleep 0.2; done
  RAYLAB_CLOSE_AFTER=400 ./target/release/raylab default --threads 2 >/dev/null 2>&1 &
  app=$!
  # --onlyvisible: a window found before it is mapped cannot take the focus.
  win=$(xdotool search --sync --onlyvisible --name '^raylab' | head -1)
  xdotool windowsize "$win" "$w" "$h"
  xdotool windowfocus --sync "$win"
  sleep 2
  xdotool key F5
  sleep 1
  at=0
  for entry in "${slides[@]}"; do
    n=${entry%%:*}; name=${entry#*:}
    while [ "$at" -lt "$n" ]; do xdotool key Next; sleep 0.3; at=$((at + 1)); done
    case "${drags[$name]:-}" in
      key)
        sleep 6
        xdotool keydown bracketright; sleep 1.2
        import -window root -crop "${w}x$h+0+0" +repage "screenshots/present-$h-$name-drag.png"
        xdotool keyup bracketright
        echo "screenshots/present-$h-$name-drag.png" ;;
      bench)
        # The workbench's drawing: the dock's right third, below its middle.
        sleep 6
        x=$((w * 5 / 6)); y=$((h * 55 / 100))
        xdotool mousemove "$x" "$y"; sleep 0.2; xdotool mousedown 1; sleep 0.2
        for dx in 20 40 60 80; do xdotool mousemove "$((x + dx))" "$((y - dx / 2))"; sleep 0.2; done
        import -window root -crop "${w}x$h+0+0" +repage "screenshots/present-$h-$name-drag.png"
        xdotool mouseup 1
        echo "screenshots/present-$h-$name-drag.png" ;;
    esac
    sleep 12
    out="screenshots/present-$h-$name.png"
    import -window root -crop "${w}x$h+0+0" +repage "$out"
    echo "$out"
  done
  kill "$app" 2>/dev/null || true
  wait "$app" 2>/dev/null || true
  kill "$xvfb" 2>/dev/null || true
  wait "$xvfb" 2>/dev/null || true
  rm -rf "$XDG_DATA_HOME"
done
