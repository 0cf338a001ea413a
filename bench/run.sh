#!/usr/bin/env bash
# Runs every benchmark program of a build, then bench/report.py:
#   bash bench/run.sh BUILD_DIR OUT_DIR [benchmark flags]
# Each program writes OUT_DIR/NAME.json (Google Benchmark JSON) and prints its console table;
# report.py turns controllers_bench.json and scaling_bench.json into the generated tables of
# docs/performance.md and the PNGs in docs/figures/.
# Without flags every program runs 20 repetitions of at least 0.1 s each and shows only their
# aggregates (the JSON keeps every repetition: report.py takes percentiles over them). Extra
# arguments replace those defaults and go to every program. The runs are pinned to CPU 1 with
# taskset when it exists (BENCH_CPU=N picks another CPU, BENCH_CPU= turns pinning off).
set -euo pipefail

build_dir=${1:?usage: bash bench/run.sh BUILD_DIR OUT_DIR [benchmark flags]}
out_dir=${2:?usage: bash bench/run.sh BUILD_DIR OUT_DIR [benchmark flags]}
shift 2
flags=("$@")
if (( ${#flags[@]} == 0 )); then
  flags=(--benchmark_repetitions=20 --benchmark_min_time=0.1 --benchmark_display_aggregates_only=true)
fi

cpu=${BENCH_CPU-1}
pin=()
if [[ -n $cpu ]] && command -v taskset >/dev/null && taskset -c "$cpu" true 2>/dev/null; then
  pin=(taskset -c "$cpu")
fi

mkdir -p "$out_dir"
shopt -s nullglob
programs=("$build_dir"/bench/*_bench)
if (( ${#programs[@]} == 0 )); then
  echo "bench/run.sh: no *_bench programs in $build_dir/bench (build them first)" >&2
  exit 1
fi
echo "bench/run.sh: $(uptime)"
for program in "${programs[@]}"; do
  name=$(basename "$program")
  echo "== $name ${pin[*]}"
  "${pin[@]}" "$program" --benchmark_out="$out_dir/$name.json" --benchmark_out_format=json "${flags[@]}"
done
if [[ -f $out_dir/controllers_bench.json ]]; then
  MPLBACKEND=Agg /usr/bin/python3 "$(dirname "$0")/report.py" "$out_dir" "$build_dir"
fi
