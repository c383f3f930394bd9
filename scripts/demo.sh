#!/usr/bin/env bash
# The main job: parameterize a bundled mesh, write the UV'd OBJ, pictures of its layout (SVG
# and PNG, faces coloured by log area ratio) and of the surface with a checkerboard through
# its UVs. Builds only the command-line tool (the tests are scripts/test.sh), so the first
# picture comes after one target's build, not the whole project's.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target icm_param
mkdir -p out
mesh=${1:-examples/data/three_peaks.off}
name=$(basename "${mesh%.*}")
./build/examples/icm_param "$mesh" -o "out/${name}_uv.obj" --svg "out/${name}_uv.svg" --png "out/${name}_uv.png" \
  --preview "out/${name}_preview.png" --json
echo "wrote out/${name}_uv.obj, out/${name}_uv.svg, out/${name}_uv.png and out/${name}_preview.png"
