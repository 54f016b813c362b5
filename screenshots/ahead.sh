#!/usr/bin/env bash
# Slides rendered ahead, as a lecturer meets them: the window under Xvfb at 1920x1080 in
# presentation mode, each of soft shadows, glossy and depth of field shown by Page Down
# after the slide before it was shown for 30 s. Writes screenshots/ahead-{soft-shadows,
# glossy,depth-of-field}.png, each taken 1 s after the key, and prints the log's lines
# that say when each image was taken from those rendered ahead (RUST_LOG=raylab=debug).
# Under Xvfb the window paints with llvmpipe, about 0.2 s a frame at 1920x1080, so a new
# slide shows 3 frames (0.5-0.7 s) after the key; on a GPU, within 50 ms.
# Needs: apt-get install xvfb xdotool imagemagick
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --locked --quiet
export DISPLAY=":${RAYLAB_DISPLAY:-96}"
Xvfb "$DISPLAY" -screen 0 1920x1128x24 >/dev/null 2>&1 &
xvfb=$!
XDG_DATA_HOME=$(mktemp -d)
export XDG_DATA_HOME
log=$(mktemp)
for _ in $(seq 50); do xdotool getmouselocation >/dev/null 2>&1 && break; sleep 0.2; done
RUST_LOG=raylab=debug RAYLAB_CLOSE_AFTER=300 ./target/release/raylab default 2>"$log" &
app=$!
win=$(xdotool search --sync --onlyvisible --name '^raylab' | head -1)
xdotool windowsize "$win" 1920 1080
xdotool windowfocus --sync "$win"
sleep 2
xdotool key F5
sleep 1
# To slide 12 (blurring), then 13, 14 and 15, each after 30 s on the one before.
for _ in $(seq 12); do xdotool key Next; sleep 0.3; done
for name in soft-shadows glossy depth-of-field; do
  sleep 30
  xdotool key Next
  sleep 1
  import -window root -crop 1920x1080+0+0 +repage "screenshots/ahead-$name.png"
  echo "screenshots/ahead-$name.png"
done
kill "$app" 2>/dev/null || true
wait "$app" 2>/dev/null || true
kill "$xvfb" 2>/dev/null || true
wait "$xvfb" 2>/dev/null || true
grep -E "slide 1[3-5]:|rendered ahead" "$log" || true
rm -rf "$XDG_DATA_HOME" "$log"
