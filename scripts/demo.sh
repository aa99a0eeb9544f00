#!/usr/bin/env bash
# Sets up every dependency, builds the samples and renders them headlessly (EGL) to PNG in out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build --target fresnel_curves tonemap_gallery city svo_demo deferred_city effects -j"$(nproc)"
mkdir -p out
./build/samples/fresnel_curves out/fresnel_curves.png
./build/samples/tonemap_gallery out/tonemap_gallery.png
# The city demo: five named views at 1280x720 (out/city_<view>.png); ./build/samples/city --window
# flies through it when a display is available.
./build/samples/city out
# The voxel demo: voxelised meshes ray cast among rasterised cubes (out/svo_hybrid.png), its
# level-of-detail view (out/svo_lod.png) and secondary rays (out/svo_glass.png); --window animates it.
./build/samples/svo_demo out
# The deferred city: day (cascaded shadows), cascades, night (street lamps as light volumes) and the
# forward-against-deferred comparison (out/deferred_*.png).
./build/samples/deferred_city out
# The effects: smoke as billboards, slices and raytraced volumes; SSAO; relief mapping; light shafts
# (out/effects_*.png).
./build/samples/effects out
echo "demo: wrote $(ls out/*.png | tr '\n' ' ')"
