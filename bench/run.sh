#!/usr/bin/env bash
# Runs every benchmark program of a build: bash bench/run.sh BUILD_DIR OUT_DIR [benchmark flags]
# Each program writes OUT_DIR/NAME.json (Google Benchmark JSON) and prints its console table.
# Extra arguments go to every program (e.g. --benchmark_repetitions=10
# --benchmark_report_aggregates_only=true). Set BENCH_CPU=1 to pin the runs to that CPU.
set -euo pipefail

build_dir=${1:?usage: bash bench/run.sh BUILD_DIR OUT_DIR [benchmark flags]}
out_dir=${2:?usage: bash bench/run.sh BUILD_DIR OUT_DIR [benchmark flags]}
shift 2

pin=()
if [[ -n ${BENCH_CPU:-} ]]; then
  pin=(taskset -c "$BENCH_CPU")
fi

mkdir -p "$out_dir"
shopt -s nullglob
programs=("$build_dir"/bench/*_bench)
if (( ${#programs[@]} == 0 )); then
  echo "bench/run.sh: no *_bench programs in $build_dir/bench (build them first)" >&2
  exit 1
fi
for program in "${programs[@]}"; do
  name=$(basename "$program")
  echo "== $name"
  "${pin[@]}" "$program" --benchmark_out="$out_dir/$name.json" --benchmark_out_format=json "$@"
done
