#!/usr/bin/env bash
# Regenerates the images of docs/gallery.md. Needs a GPU adapter; without one, Mesa's
# software Vulkan driver works: apt-get install mesa-vulkan-drivers; WGPU_BACKEND=vulkan.
set -euo pipefail
cd "$(dirname "$0")/.."
export WGPU_BACKEND="${WGPU_BACKEND:-vulkan}"
cargo build -q -p subsurf-cli
subsurf=target/debug/subsurf
img=docs/img
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The car with every crease tag set to sharpness 1, 3 and 10 (infinitely sharp). Level 5:
# a crease of sharpness s is refined with the sharp rules for s levels, so sharpness 3 and
# 10 differ only from level 4 on.
for s in 1 3 10; do
  sed -E "s/^t crease 2\/1\/0 ([0-9]+) ([0-9]+) .*/t crease 2\/1\/0 \1 \2 $s/" \
    examples/car.obj > "$tmp/car_s$s.obj"
  $subsurf render "$tmp/car_s$s.obj" -o "$img/car_sharpness_$s.png" \
    --level 5 --up z --view iso --size 640x360
done
$subsurf render examples/car.obj -o "$img/car_creases.png" \
  --level 3 --up z --view iso --size 640x360 --color-by sharpness

# Refinement levels 0-3 of the pawn with its control cage.
for l in 0 1 2 3; do
  $subsurf render examples/pawn.obj -o "$img/pawn_level_$l.png" \
    --level $l --cage --up z --view front --size 360x400
done

# Side by side: level 0 against level 3.
$subsurf compare examples/pawn.obj@refine:0 examples/pawn.obj@refine:3 \
  -o "$img/pawn_compare.png" --cage --up z --view iso --size 360x400

# The p-rep (Myles, Yeo and Peters 2008) of a closed quad mesh whose vertices are all
# extraordinary: without (left) and with (right) the bi-5 perturbation, as in the paper's
# Figure 7.
$subsurf compare testdata/shapes/catmark_toroidal_tet.obj@prep-bicubic:12 \
  testdata/shapes/catmark_toroidal_tet.obj@prep:12 \
  -o "$img/prep_perturbation.png" --view iso --size 400x360

# Patch kinds of a p-rep: B-quads (blue, bicubic only) and perturbed patches (orange).
$subsurf render testdata/shapes/catmark_lefthanded.obj -o "$img/prep_patch_kinds.png" \
  --method prep --tess 8 --color-by patch-kind --cage --view iso --size 640x400

# Limit surface patches of the car (feature-adaptive, isolation level 4): regular patches of
# base faces (blue), regular patches at adaptive levels (green), single-crease patches
# (orange) and Gregory end caps (red).
$subsurf render examples/car.obj -o "$img/limit_patch_kinds.png" \
  --method limit --tess 5 --color-by patch-kind --up z --view iso --size 640x360

# The pawn's limit patches coloured by adaptive level (grey 0, orange 1, blue 2, green 3,
# red 4).
$subsurf render examples/pawn.obj -o "$img/limit_levels.png" \
  --method limit --tess 9 --color-by level --up z --view iso --size 400x440
