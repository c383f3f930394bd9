#!/usr/bin/env bash
# ICM as a package, the two ways a user takes it (run by .ci/run after the tests; expects
# build/ configured and built by scripts/build.sh):
# 1. `cmake --install` into a temporary prefix; test/consumer (find_package(ICM CONFIG
#    REQUIRED) + target_link_libraries(... ICM::ICM), nothing else) configured against it,
#    built, and run on a bundled mesh; with CHOLMOD in the package the consumer must get it,
#    can opt out of it, and is told what is missing when it is not there.
# 2. test/subproject: a parent that add_subdirectory()s ICM keeps its build type (Debug, and
#    none) and gets no ICM test, benchmark or tool; it is built and run too.
# 3. When build/ has the Python module: the installed package icm, imported by Debian's
#    /usr/bin/python3 from the prefix (PYTHONPATH=PREFIX/lib/python3.X/dist-packages, not
#    build/python), parameterizes a bundled mesh.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
mesh=$root/examples/data/nefertiti.off
work=$(mktemp -d "${TMPDIR:-/tmp}/icm_package.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "check_package: $*" >&2; exit 1; }
# configure LOG ARGS...: cmake ARGS with its output in LOG, shown when it fails.
configure() {
  local log=$1
  shift
  cmake "$@" >"$log" 2>&1 || { cat "$log"; fail "cmake $* failed"; }
}

echo "== install into $work/prefix"
cmake --install build --prefix "$work/prefix" >"$work/install.log"
config_dir=$work/prefix/share/cmake/ICM
for f in ICMConfig.cmake ICMConfigVersion.cmake ICMTargets.cmake ICMFindCHOLMOD.cmake ICMFindStbRectPack.cmake ICMFindStbImageWrite.cmake \
         ICMFindTinyGLTF.cmake; do
  [ -f "$config_dir/$f" ] || fail "$f not installed"
done
[ -f "$work/prefix/include/ICM/Inverse_curvature_map_parameterizer_3.h" ] || fail "headers not installed"

if grep -q '^ICM_BUILD_PYTHON:BOOL=ON' build/CMakeCache.txt; then
  echo "== the Python package icm from the installed package"
  python_dir=$work/prefix/$(sed -n 's/^ICM_PYTHON_INSTALL_DIR:STRING=//p' build/CMakeCache.txt)
  for f in __init__.py __init__.pyi py.typed batch.py _batch_child.py _batch_command_line.py _batch_jobs.py \
           _batch_summary.py; do
    [ -f "$python_dir/icm/$f" ] || fail "icm/$f not installed in $python_dir"
  done
  compgen -G "$python_dir/icm/_icm.cpython-*.so" >/dev/null || fail "icm/_icm not installed in $python_dir"
  # From $work, so that no icm of the source tree or of build/ can be the one imported.
  (cd "$work" && PYTHONPATH=$python_dir /usr/bin/python3 - "$mesh" "$python_dir") <<'PYTHON' || fail "the installed icm does not run"
import sys
import icm
mesh, python_dir = sys.argv[1], sys.argv[2]
assert icm.__file__.startswith(python_dir), "imported " + icm.__file__ + ", not the installed package"
V, F, repairs = icm.read_mesh(mesh)
for boundary in ("free", "circle"):  # ICM::parameterize, and the disk parameterizer
    result = icm.parameterize(V, F, boundary=boundary)
    assert result.fuv.shape == F.shape and result.report["flipped_faces"] == 0, result.report
    print(f"{icm.__file__}: {result.report['faces']} faces, {result.charts} chart, {boundary} border")
PYTHON
  # icm.batch and its parts import from the installed package (--help needs no Dask).
  (cd "$work" && PYTHONPATH=$python_dir /usr/bin/python3 -m icm.batch --help >/dev/null) ||
    fail "the installed icm.batch does not import"
fi

echo "== test/consumer: find_package(ICM) from the installed package"
configure "$work/consumer.log" -S test/consumer -B "$work/consumer" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix"
grep 'ICM ' "$work/consumer.log"
grep -q "from $config_dir" "$work/consumer.log" || fail "the consumer did not find the installed package"
cmake --build "$work/consumer" -j"$(nproc)"
"$work/consumer/icm_consumer" "$mesh" | tee "$work/consumer.out"
if grep -q '^set(ICM_HAS_CHOLMOD ON)' "$config_dir/ICMConfig.cmake"; then
  grep -q 'CHOLMOD: yes' "$work/consumer.out" || fail "ICM was installed with CHOLMOD, the consumer has none"
  # Opting out (ICM_WITH_CHOLMOD=OFF) gives ICM::ICM without CHOLMOD (configured only).
  configure "$work/no-cholmod.log" -S test/consumer -B "$work/consumer-no-cholmod" \
    -DCMAKE_PREFIX_PATH="$work/prefix" -DICM_WITH_CHOLMOD=OFF
  grep -q 'CHOLMOD: OFF' "$work/no-cholmod.log" || fail "ICM_WITH_CHOLMOD=OFF is not honoured"
  # CHOLMOD missing on the user's machine (its headers hidden from the search): find_package
  # fails and says why (configured only).
  cholmod_include=$(sed -n 's/^ICM_CHOLMOD_INCLUDE_DIR:PATH=//p' build/CMakeCache.txt)
  if cmake -S test/consumer -B "$work/consumer-missing" -DCMAKE_PREFIX_PATH="$work/prefix" \
       -DCMAKE_IGNORE_PATH="$cholmod_include" >"$work/missing.log" 2>&1; then
    fail "find_package(ICM) succeeded without the CHOLMOD it was installed with"
  fi
  grep -q 'installed with SuiteSparse CHOLMOD, which is not found' "$work/missing.log" \
    || { cat "$work/missing.log"; fail "find_package(ICM) without CHOLMOD does not say why"; }
fi

echo "== test/subproject: add_subdirectory(ICM) in a Debug parent"
configure "$work/subproject.log" -S test/subproject -B "$work/subproject" -DICM_SOURCE_DIR="$root" \
  -DCMAKE_BUILD_TYPE=Debug
grep 'ICM as a subdirectory' "$work/subproject.log"
cmake --build "$work/subproject" -j"$(nproc)"
"$work/subproject/icm_consumer" "$mesh"
echo "== test/subproject: add_subdirectory(ICM) in a parent without a build type (configured only)"
configure "$work/no-type.log" -S test/subproject -B "$work/subproject-no-type" -DICM_SOURCE_DIR="$root"
grep "build type '' kept" "$work/no-type.log" || fail "add_subdirectory(ICM) set a build type on a parent without one"
echo "check_package: all passed"
