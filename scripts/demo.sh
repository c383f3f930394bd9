#!/usr/bin/env bash
# The main job: parameterize a bundled mesh, write the UV'd OBJ and an SVG of the layout.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
mesh=${1:-examples/data/three_peaks.off}
name=$(basename "${mesh%.*}")
./build/examples/icm_param "$mesh" -o "out/${name}_uv.obj" --svg "out/${name}_uv.svg" --json
echo "wrote out/${name}_uv.obj and out/${name}_uv.svg"
