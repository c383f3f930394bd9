#!/usr/bin/env bash
# Builds the libFuzzer harness (test/fuzz/fuzz_read_parameterize.cpp) with clang, ASan and
# UBSan into build-fuzz/ and runs it for MINUTES minutes (default 10) from the seed corpus
# test/fuzz/seeds/. Installs Debian's clang if it is missing (not needed by the regular
# build or CI). Findings are written to build-fuzz/findings/; each one belongs in
# test/bad_input/ as a regression case (see test/bad_input/generate.py).
#
# usage: test/fuzz/run_fuzz.sh [MINUTES] [extra libFuzzer flags...]
set -euo pipefail
cd "$(dirname "$0")/../.."
minutes=${1:-10}
shift || true

if ! command -v clang++ >/dev/null 2>&1; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -q clang
fi

cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
  -DCMAKE_CXX_COMPILER=clang++ -DICM_BUILD_FUZZERS=ON -DICM_BUILD_TESTS=OFF \
  -DICM_BUILD_EXAMPLES=OFF -DICM_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-fuzz --target fuzz_read_parameterize -j"$(nproc)"

mkdir -p build-fuzz/corpus build-fuzz/findings
# One process, one job: the machine is shared. Each input gets at most 10 s and 2 GB.
build-fuzz/test/fuzz/fuzz_read_parameterize build-fuzz/corpus test/fuzz/seeds \
  -max_total_time=$((minutes * 60)) -timeout=10 -rss_limit_mb=2048 -max_len=16384 \
  -artifact_prefix=build-fuzz/findings/ -print_final_stats=1 "$@" 2>&1 | tee build-fuzz/fuzz.log |
  grep -E "^#[0-9]+ +(INITED|DONE|pulse)|stat::|ERROR|SUMMARY|Test unit written" || true
if ls build-fuzz/findings/* >/dev/null 2>&1; then
  echo "findings in build-fuzz/findings/:"
  ls -l build-fuzz/findings/
  exit 1
fi
echo "no finding in $minutes minutes"
