#!/usr/bin/env bash
# Fuzzes scene loading with libFuzzer (clang, with ASan and UBSan), seeded with Debian's assimp-testmodels glTF files,
# tests/fuzz/seeds (every input form the loader reads: tests/fuzz/seeds/README.md) and tests/fuzz/regressions.
#   tools/fuzz-gltf.sh [SECONDS] [WORKERS]   default 60 seconds, one worker per core; prints the workers' summed stats
#   tools/fuzz-gltf.sh --runs N [WORKERS]    N executions in all (N / WORKERS each), however long that takes
#   tools/fuzz-gltf.sh build                 only builds the target
# The target is built in build-asan, the sanitized tree tools/test-sanitizers.sh tests (tools/lib/sanitized-tree.sh).
# The test suite runs the default; docs/robustness.md records a run of a million executions. The corpus grows in
# build-asan/fuzz/corpus (kept between runs); crashes land in build-asan/fuzz/ as crash-* files; each worker's log is
# build-asan/fuzz/fuzz-N.log.
set -euo pipefail
cd "$(dirname "$0")/.."
source tools/lib/ccache.sh
source tools/lib/sanitized-tree.sh
jobs=$(nproc 2>/dev/null || echo 2)
configure_sanitized_tree
cmake --build build-asan --target obscura-gltf-fuzzer -j"$jobs"
[ "${1:-}" = build ] && exit 0
if [ "${1:-}" = --runs ]; then
  runs="$2"
  workers="${3:-$jobs}"
  limits=(-runs=$((runs / workers)))
else
  seconds="${1:-60}"
  workers="${2:-$jobs}"
  limits=(-max_total_time="$seconds")
fi

work=build-asan/fuzz
corpus=$work/corpus
mkdir -p "$corpus"
# Seeds named after their path under glTF2/ (several folders hold a BoxTextured.gltf), so every file seeds.
models=/usr/share/assimp/models/glTF2
find "$models" -type f \( -name '*.gltf' -o -name '*.glb' \) -printf '%P\n' | while IFS= read -r relative; do
  cp -n "$models/$relative" "$corpus/seed-${relative//\//_}"
done
cp -n tests/fuzz/regressions/* "$corpus/"
for seed in tests/fuzz/seeds/*.gltf tests/fuzz/seeds/*.glb; do cp -n "$seed" "$corpus/seed-$(basename "$seed")"; done

# One libFuzzer process per worker on the shared corpus (each reloads what the others add), each for the whole time:
# the stage gets every core. -max_len stays libFuzzer's default (1 MiB, set from the corpus): the largest seed, the
# 1.8 MB uncompressed 2CylinderEngine, is fuzzed in its first MiB (its Draco twin and the .gltf whole).
fuzzer=$PWD/build-asan/tests/fuzz/obscura-gltf-fuzzer
cd "$work"
rm -f fuzz-*.log repro-*.log
status=0
start=$(date +%s)
# While fuzzing, ASan keeps no stack for each allocation and free (malloc_context_size=0): the unwinding and the stack
# depot cost 5 to 12 % of a run (CPU seconds per execution, alternating runs from the seeds; docs/robustness.md) and
# serve only the reports. Every finding is replayed below with the full stacks. The user's ASAN_OPTIONS come after.
user_asan_options="${ASAN_OPTIONS:-}"
# Two schedules. A run takes 0.1 to 0.3 ms for most inputs (sanitized and instrumented), but about 130 ms for a mutant
# of the Draco engine seed, 30 ms with a 512x512 PNG and 21 ms for the pretty-printed 90 KB Draco .gltf: under
# libFuzzer's entropic schedule alone those few take most of the time. Worker 0 (and every even one) scales each
# input's energy by its execution time (-entropic_scale_per_exec_time, up to 30x for the fastest), which reaches more
# of the loader in the same minute; the odd ones keep the plain entropic schedule, so the heavy inputs (the
# Draco engine, large images) keep their share and the edges only they reach. docs/robustness.md has the measures.
worker_pids=()
for ((worker = 0; worker < workers; worker++)); do
  ASAN_OPTIONS="malloc_context_size=0${user_asan_options:+:$user_asan_options}" "$fuzzer" "${limits[@]}" -timeout=10 \
    -rss_limit_mb=4096 -entropic_scale_per_exec_time=$(( worker % 2 == 0 )) -print_final_stats=1 corpus \
    >"fuzz-$worker.log" 2>&1 &
  worker_pids+=($!)
done
for pid in "${worker_pids[@]}"; do wait "$pid" || status=$?; done
seconds=$(( $(date +%s) - start ))
for log in fuzz-*.log; do
  echo "$log: $(grep -E '^#[0-9]+[[:space:]]+(DONE|pulse|NEW|REDUCE)' "$log" | tail -n 1)"
done
awk -F: -v workers="$workers" -v seconds="$seconds" '
  /^stat::number_of_executed_units/ { runs += $NF } /^stat::peak_rss_mb/ { if ($NF > rss) rss = $NF }
  END { printf "fuzz-gltf: %d workers, %d executions in %d s (%d per minute), peak RSS %d MB\n",
        workers, runs, seconds, runs * 60 / (seconds > 0 ? seconds : 1), rss }' fuzz-*.log
if grep -l -E 'ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)|runtime error:|SUMMARY: ' fuzz-*.log; then
  # Replay each saved input with ASan's full allocation and free stacks (the user's ASAN_OPTIONS, else the defaults).
  for finding in crash-* leak-* timeout-* oom-*; do
    [ -e "$finding" ] || continue
    ASAN_OPTIONS="$user_asan_options" "$fuzzer" -timeout=10 -rss_limit_mb=4096 "$finding" >"repro-$finding.log" 2>&1 ||
      true
    echo "fuzz-gltf: $finding replayed with full stacks:"
    grep -A 40 -m 1 -E 'ERROR: |runtime error:' "repro-$finding.log" || tail -n 40 "repro-$finding.log"
  done
  echo "fuzz-gltf: a worker found a bug (its log above, the input in $work/crash-*, the replays in $work/repro-*.log)"
  exit 1
fi
exit "$status"
