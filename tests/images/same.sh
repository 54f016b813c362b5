#!/usr/bin/env bash
# Renders the images a change must not alter, with two builds, and compares their pixels:
# every scene in scenes/ and benches/ at 160x90, 4 spp, in six light transports and
# sampling variants (EXR, compared pixel by pixel: an EXR's header records when and how
# long it rendered), and every lecture slide at 320x180 with its caption (PNG, compared
# pixel by pixel: its text chunks name the build's version and commit).
#
#     tests/images/same.sh OLD_RAYLAB NEW_RAYLAB
#
# Build the old one in a target dir of its own, e.g.
#     git worktree add /tmp/old HEAD~1 && (cd /tmp/old && cargo build --release)
# Needs Python 3 with `pip install OpenEXR numpy pillow`. Exits 1 if any pair differs.
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 OLD_RAYLAB NEW_RAYLAB" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
render() { # BIN DIR
  mkdir -p "$2"
  for s in "$repo"/scenes/*.toml "$repo"/benches/*.toml; do
    n=$(basename "$s" .toml)
    for v in asis pattern=random transport=path tree=stochastic \
      transport=transmissive_shadows transport=photons; do
      set_arg=()
      [ "$v" != asis ] && set_arg=(--set "$v")
      "$1" render "$s" --size 160x90 --spp 4 --threads 2 -q ${set_arg[@]+"${set_arg[@]}"} \
        -o "$2/$n-${v//=/_}.exr"
    done
  done
  for i in $(seq 1 "$("$1" lecture | wc -l)"); do
    "$1" render --slide "$i" --size 320x180 --threads 2 -q --caption -o "$2/slide-$i.png"
  done
}
render "$1" "$out/old"
render "$2" "$out/new"
python3 "$here/compare.py" "$out/old" "$out/new"
