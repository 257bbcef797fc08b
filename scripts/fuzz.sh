#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz with clang (-fsanitize=fuzzer,address) in their own build folder and runs
# each reader for FUZZ_SECONDS, one after the other, niced. Each run's log and findings go to BUILD/fuzz/READER/;
# the figures (executions, time, peak RSS of the fuzzer and of the reading child processes, findings) are printed and
# appended to BUILD/fuzz/summary.tsv (docs/robustness.md).
#
# usage: scripts/fuzz.sh [READER...]    (default: every reader of tests/fuzz/CMakeLists.txt)
# env:   FUZZ_SECONDS (600 per reader), FUZZ_BUILD_DIR (build-fuzz), FUZZ_JOBS (2)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-600}
build=${FUZZ_BUILD_DIR:-build-fuzz}
jobs=${FUZZ_JOBS:-2}
# The criteria of a clean run: no crash, no input taking over 10 s, no more than 2 GB resident.
timeout_s=10
rss_mb=2048

sanitize="-fsanitize=fuzzer-no-link,address -fno-omit-frame-pointer"
mkdir -p "$build"
# -O1 with line tables: a quick build and readable stacks; assertions (Eigen's index checks) stay on.
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Fuzz -DCMAKE_C_FLAGS_FUZZ="-O1 -gline-tables-only" \
  -DCMAKE_CXX_FLAGS_FUZZ="-O1 -gline-tables-only" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_C_FLAGS="$sanitize" -DCMAKE_CXX_FLAGS="$sanitize" -DFACEHEX_BUILD_GUI=OFF -DFACEHEX_BUILD_TESTS=OFF \
  -DFACEHEX_BUILD_FUZZERS=ON > "$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
cmake --build "$build" -j "$jobs" --target fuzzers

if [ $# -gt 0 ]; then
  readers=("$@")
else
  mapfile -t readers < <(sed -n 's/^set(FACEHEX_FUZZ_READERS \(.*\))$/\1/p' tests/fuzz/CMakeLists.txt | tr ' ' '\n')
fi
summary=$build/fuzz/summary.tsv
mkdir -p "$build/fuzz"
[ -f "$summary" ] || printf 'reader\tseconds\texecutions\tpeak_rss_mb\tchildren_peak_rss_mb\tfindings\tcommit\n' > "$summary"
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
status=0
for reader in "${readers[@]}"; do
  out=$build/fuzz/$reader
  mkdir -p "$out/corpus" "$out/findings"
  dict=()
  [ -f "tests/fuzz/dict/$reader.dict" ] && dict=(-dict="tests/fuzz/dict/$reader.dict")
  start=$(date +%s)
  # The first folder receives the new inputs; the committed seeds stay as they are.
  nice -n 10 "$build/bin/fuzz_$reader" -max_total_time="$seconds" -timeout="$timeout_s" -rss_limit_mb="$rss_mb" \
    -max_len=65536 -print_final_stats=1 -artifact_prefix="$out/findings/" "${dict[@]}" "$out/corpus" \
    "tests/fuzz/corpus/$reader" \
    > "$out/log.txt" 2>&1 || true
  elapsed=$(($(date +%s) - start))
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$out/log.txt" | tail -1)
  rss=$(sed -n 's/^stat::peak_rss_mb: *//p' "$out/log.txt" | tail -1)
  children=$(sed -n 's/^facehex_fuzz: children peak RSS \([0-9]*\) MB$/\1/p' "$out/log.txt" | tail -1)
  findings=$(find "$out/findings" -type f | wc -l)
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$reader" "$elapsed" "${execs:-?}" "${rss:-?}" "${children:-?}" "$findings" \
    "$commit" | tee -a "$summary"
  if [ "$findings" -gt 0 ]; then
    echo "fuzz: $reader found $findings input(s) in $out/findings (reproduce: $build/bin/fuzz_$reader FILE)" >&2
    status=1
  fi
done
exit $status
