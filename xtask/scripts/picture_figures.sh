#!/bin/bash
# The README's picture-bake table: per model and view, the picture bake (verified, with its JSON, binary and page sizes), then the 720-sample baseline.
cd "$(dirname "$0")/../.."
X=target/release/xtask
cargo build --release -q -p xtask
mkdir -p /tmp/fig
for spec in "spot|keenan-crane/spot/spot_quadrangulated.obj" "blub|keenan-crane/blub/blub_quadrangulated.obj" "fandisk|fandisk-quads/fandisk_quads.converted.obj" "suzanne|suzanne/suzanne.obj" "control|keenan-crane/blub/blub_control_mesh.obj" "book|combobulate-samples/book.obj"; do
  name=${spec%%|*}; path=assets/models/${spec#*|}
  for p in ortho persp; do
    flag=""; [ $p = persp ] && flag="--persp 1024"
    out=$($X bake $path --axis yaw --pitch 20 $flag --verify --json /tmp/fig/b.json --bin /tmp/fig/b.bin --html /tmp/fig/spin.html 2>&1 | grep -v "warning" | tr '\n' ' ')
    base=$($X bake $path --axis yaw --pitch 20 $flag --sorter bsp --method sampled --budget-mib 4000 2>&1 | grep -o "sampled: [0-9.]* ms")
    echo "$name $p | $out | $base"
  done
done
