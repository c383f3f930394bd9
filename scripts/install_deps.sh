#!/usr/bin/env bash
# Installs the Debian 12 packages ICM needs, only those missing. Needs root (or sudo).
# libopenblas0-pthread takes over the system BLAS, on which CHOLMOD's supernodal factorization
# (the default solver from 25k vertices) runs: 0.9 s against 2.5 s for the reference BLAS on
# 533k unknowns (doc/solvers.md). libtinygltf-dev writes the glTF output: Debian builds its
# implementation (with nlohmann-json and stb) into a shared library, found by CMake. pybind11,
# numpy and pytest build and test the Python module (doc/python.md) for Debian's /usr/bin/python3;
# python3-distributed (Dask) runs its batches on a cluster (doc/batch.md, python/tests/test_batch.py);
# blender (3.4, on the same Python 3.11) runs the headless tests of the add-on ICM Unwrap (doc/blender.md).
# libopenmesh-dev gives the tests OpenMesh's meshes, FaceGraph models through CGAL's graph traits
# (test/test_facegraph_models.cpp); the library itself does not need it.
set -euo pipefail
packages=(build-essential cmake libcgal-dev libeigen3-dev libboost-dev libsuitesparse-dev
          libgtest-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev libtinygltf-dev libopenmesh-dev doxygen python3
          clang-format libopenblas0-pthread libstb-dev
          pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-distributed blender)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -q
  $sudo_cmd apt-get install -y -q "${missing[@]}"
fi
