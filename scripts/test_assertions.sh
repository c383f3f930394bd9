#!/usr/bin/env bash
# The test suites once more with every assertion on (assert, Boost, Eigen, CGAL): a
# consumer's default build has them, and they catch what a Release build hides (Boost's
# push-relabel checks its flow with exact equalities, for one). Run by .ci/run.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
cmake -S . -B build-assertions -DCMAKE_BUILD_TYPE=Release -DICM_ASSERTIONS=ON -DICM_BUILD_BENCHMARKS=OFF
cmake --build build-assertions -j"$(nproc)"
ctest --test-dir build-assertions --output-on-failure -j"$(nproc)"
