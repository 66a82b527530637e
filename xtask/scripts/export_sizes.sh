#!/usr/bin/env bash
# File sizes of SVG, HTML and PDF per exact sorter (Newell, merged BSP, BSP) for the
# repository's models at yaw 145, pitch -25, 512 x 512, with each sorter's fragment and SVG
# shape counts: the evidence for Export's choice (the sorter that draws the fewest sprites).
# Usage: bash xtask/scripts/export_sizes.sh   (builds the release xtask first)
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release -q -p xtask
x=target/release/xtask
a=assets/models
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '| model | sorter | fragments | SVG shapes | SVG bytes | HTML bytes | PDF bytes |\n'
printf '|---|---|---:|---:|---:|---:|---:|\n'
while IFS='|' read -r name args; do
    for sorter in newell bsp-merged bsp; do
        # shellcheck disable=SC2086
        line=$($x render $args --yaw 145 --pitch -25 --size 512x512 --sorter "$sorter" \
            --svg "$out/f.svg" --html "$out/f.html" --pdf "$out/f.pdf" -o "$out/f.png" 2>&1 | tail -1)
        fragments=$(grep -o '[0-9]* fragments' <<<"$line" | cut -d' ' -f1)
        shapes=$(grep -o 'svg [0-9]* shapes' <<<"$line" | cut -d' ' -f2)
        printf '| %s | %s | %s | %s | %s | %s | %s |\n' "$name" "$sorter" "$fragments" "$shapes" \
            "$(stat -c %s "$out/f.svg")" "$(stat -c %s "$out/f.html")" "$(stat -c %s "$out/f.pdf")"
    done
done <<EOF
spot|$a/keenan-crane/spot/spot_quadrangulated.obj
spot textured|$a/keenan-crane/spot/spot_quadrangulated.obj --texture $a/keenan-crane/spot/spot_texture.png
suzanne|$a/suzanne/suzanne.obj
blub|$a/keenan-crane/blub/blub_quadrangulated.obj
fandisk|$a/fandisk-quads/fandisk_quads.converted.obj
BoxTextured|$a/gltf/BoxTextured/BoxTextured.gltf
EOF
