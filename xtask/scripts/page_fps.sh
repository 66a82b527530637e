#!/usr/bin/env bash
# Frames per second of the pages of spot, suzanne, blub and fandisk in headless Chromium with
# software compositing, in one run: the spinning CSS page (`bake --html`) and canvas player
# (`bake --canvas`) of each model's yaw picture bake at pitch 20, then the pages that turn
# with the pointer (`turn --html`, `turn --canvas`: a Presorted certificate) while a pointer
# sweeps across them.
#   bash xtask/scripts/page_fps.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds="${1:-6}"
work="$(mktemp -d)"
cargo build --quiet --release -p xtask
pages=()
for pair in "spot keenan-crane/spot/spot_quadrangulated.obj" "suzanne suzanne/suzanne.obj" \
  "blub keenan-crane/blub/blub_quadrangulated.obj" "fandisk fandisk-quads/fandisk_quads.converted.obj"; do
  set -- $pair
  target/release/xtask bake "assets/models/$2" --axis yaw --pitch 20 \
    --html "$work/$1-css.html" --canvas "$work/$1-canvas.html" | grep -o "[0-9]* cells\|page [0-9]* B\|canvas page [0-9]* B" | tr '\n' ' '
  echo "($1)"
  pages+=("$work/$1-css.html" "$work/$1-canvas.html")
done
turns=()
for pair in "spot keenan-crane/spot/spot_quadrangulated.obj" "suzanne suzanne/suzanne.obj" \
  "blub keenan-crane/blub/blub_quadrangulated.obj" "fandisk fandisk-quads/fandisk_quads.converted.obj"; do
  set -- $pair
  target/release/xtask turn "assets/models/$2" --html "$work/$1-turn-css.html" --canvas "$work/$1-turn-canvas.html" \
    | grep -o "presorted in [0-9]* ms\|page [0-9]* B" | tr '\n' ' '
  echo "($1 turn)"
  turns+=("$work/$1-turn-css.html" "$work/$1-turn-canvas.html")
done
python3 xtask/scripts/live_fps.py "${pages[@]}" --no-still --seconds "$seconds"
python3 xtask/scripts/live_fps.py "${turns[@]}" --sweep --seconds "$seconds"
rm -rf "$work"
