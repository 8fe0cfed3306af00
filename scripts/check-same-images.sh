#!/usr/bin/env bash
# Renders every scene of scenes/, ../shared/models and the textured test assets with two gpurt
# binaries, on both backends, Whitted and path, at 1 and 4 samples a pixel (with every AOV at 1)
# and as a tile (--tile 1/3, 2 samples; its PNG and sidecar), and path traced with each accelerator
# by name (--accel grid, --accel bvh: the PNG, its prim and steps AOVs),
# and compares the files byte for byte: a refactoring must leave every picture as it was.
#   scripts/check-same-images.sh OLD_GPURT NEW_GPURT [WORKDIR]
# Prints one line per differing file and exits 1 if any differ.
set -euo pipefail
old=$1 new=$2
work=${3:-$(mktemp -d)}
cd "$(dirname "$0")/.."
scenes=(scenes/*.json scenes/*.obj ../shared/models/*.obj tests/assets/textures/globe.glb
        tests/assets/textures/quad_separate.gltf)
render() {  # BIN DIR
    local bin=$1 dir=$2
    mkdir -p "$dir"
    for s in "${scenes[@]}"; do
        local name
        name=$(echo "$s" | tr '/.' '__')
        for backend in gl cpu; do
            for integrator in whitted path; do
                for spp in 1 4; do
                    local out="$dir/$name-$backend-$integrator-$spp"
                    local aovs=()
                    [ "$spp" = 1 ] && aovs=(--aov "depth=$out.depth.pfm" --aov "prim=$out.prim.pfm"
                                          --aov "normal=$out.normal.pfm" --aov "steps=$out.steps.pfm")
                    "$bin" render "$s" -o "$out.png" --size 96x72 --backend "$backend" \
                        --integrator "$integrator" --spp "$spp" "${aovs[@]}" 2>/dev/null ||
                        echo "render failed: $bin $s $backend $integrator $spp" >"$out.failed"
                done
                # A tile of the image (the streams' rows start below the image's top).
                "$bin" render "$s" -o "$dir/$name-$backend-$integrator-tile.png" --size 96x72 --backend "$backend" \
                    --integrator "$integrator" --spp 2 --tile 1/3 2>/dev/null ||
                    echo "render failed: $bin $s $backend $integrator tile" >"$dir/$name-$backend-$integrator-tile.failed"
            done
            # Each accelerator by name (the renders above take --accel auto's choice).
            for accel in grid bvh; do
                local out="$dir/$name-$backend-$accel"
                "$bin" render "$s" -o "$out.png" --size 96x72 --backend "$backend" --accel "$accel" \
                    --integrator path --spp 2 --aov "prim=$out.prim.pfm" --aov "steps=$out.steps.pfm" 2>/dev/null ||
                    echo "render failed: $bin $s $backend $accel" >"$out.failed"
            done
        done
    done
}
render "$old" "$work/old" &
render "$new" "$work/new"
wait
status=0
for f in "$work"/old/*; do
    g="$work/new/$(basename "$f")"
    if ! cmp -s "$f" "$g"; then echo "differs: $(basename "$f")"; status=1; fi
done
[ "$(ls "$work/old" | wc -l)" = "$(ls "$work/new" | wc -l)" ] || { echo "file counts differ"; status=1; }
echo "compared $(ls "$work/old" | wc -l) files in $work"
exit $status
