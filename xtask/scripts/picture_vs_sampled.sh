#!/bin/bash
# Alternating runs of the picture bake and the 720-sample baseline; prints each pair and the medians.
cd "$(dirname "$0")/../.."
XTASK=target/release/xtask
cargo build --release -q -p xtask
for spec in "spot|keenan-crane/spot/spot_quadrangulated.obj" "blub|keenan-crane/blub/blub_quadrangulated.obj"; do
  name=${spec%%|*}; path=assets/models/${spec#*|}
  for p in ortho persp; do
    flag=""; [ $p = persp ] && flag="--persp 1024"
    a=(); b=()
    for i in 1 2 3 4 5; do
      a+=($("$XTASK" bake $path --axis yaw --pitch 20 $flag 2>&1 | grep -o "picture: [0-9.]*" | cut -d' ' -f2))
      b+=($("$XTASK" bake $path --axis yaw --pitch 20 $flag --sorter bsp --method sampled --budget-mib 4000 2>&1 | grep -o "sampled: [0-9.]*" | cut -d' ' -f2))
    done
    ma=$(printf '%s\n' "${a[@]}" | sort -n | sed -n 3p); mb=$(printf '%s\n' "${b[@]}" | sort -n | sed -n 3p)
    echo "$name $p picture ${a[*]} | baseline ${b[*]} | medians $ma / $mb = $(python3 -c "print(round($ma/$mb,2))")"
  done
done
