#!/usr/bin/env bash
# The campaign targets of issue 20, timed back to back on one θ–D campaign (scenario I):
#   bash bench/campaign_scaling.sh BUILD_DIR OUT_DIR [DRAWS] [REPEATS]
# - parallel efficiency of 2 worker threads and of 2 MPI ranks against 1 worker:
#   T(1 worker) / (2 T(2 workers)), the variants interleaved REPEATS times (default 3), medians;
# - campaign overhead per run: (campaign wall time - sum of the flights' wall times) / runs, with 1
#   worker, against the mean flight (process start, the controllers' set-up, scheduling, SQLite and
#   the summary all count as overhead);
# - summary-only against CSV: `thetad run` of one θ–D scenario-I flight with --summary-only and
#   with its CSV log (thetad run's default: every controller sample), interleaved.
# DRAWS (default 8) θ–D flights of scenario I per campaign. Results: OUT_DIR/campaign_scaling.txt.
set -euo pipefail

build_dir=${1:?usage: bash bench/campaign_scaling.sh BUILD_DIR OUT_DIR [DRAWS] [REPEATS]}
out_dir=${2:?usage: bash bench/campaign_scaling.sh BUILD_DIR OUT_DIR [DRAWS] [REPEATS]}
draws=${3:-8}
repeats=${4:-3}
thetad=$(realpath "$build_dir/apps/thetad")
[[ -x $thetad ]] || { echo "campaign_scaling.sh: no $thetad (build the thetad target)" >&2; exit 1; }
mkdir -p "$out_dir"
out_dir=$(realpath "$out_dir")
rm -rf "${out_dir:?}"/runs
mkdir -p "$out_dir/runs"
campaign=$out_dir/scaling.yaml
cat >"$campaign" <<YAML
campaign: scaling
scenarios: [scenario-1]
controllers: [{controller: theta-d}]
draws: {count: $draws, base_seed: 1}
YAML
# Loopback Open MPI, allowed as root (containers).
export OMPI_MCA_btl=self,vader OMPI_MCA_pml=ob1 OMPI_MCA_oob_tcp_if_include=lo
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
times=$out_dir/times.txt
: >"$times"

timed() {  # timed NAME COMMAND...: appends "NAME seconds" to $times
  local name=$1
  shift
  local start end
  start=$(date +%s.%N)
  "$@" >/dev/null 2>&1
  end=$(date +%s.%N)
  echo "$name $(echo "$end - $start" | bc -l)" >>"$times"
}

echo "campaign_scaling.sh: $(nproc) cores, $(uptime)"
for rep in $(seq 1 "$repeats"); do
  timed jobs1 "$thetad" campaign run "$campaign" --out "$out_dir/runs/jobs1-$rep" --jobs 1 --quiet
  timed jobs2 "$thetad" campaign run "$campaign" --out "$out_dir/runs/jobs2-$rep" --jobs 2 --quiet
  timed mpi2 mpirun -np 2 "$thetad" campaign run "$campaign" --out "$out_dir/runs/mpi2-$rep" --quiet
  timed summary_only "$thetad" run --scenario scenario-1 --controller theta-d --summary-only --quiet \
    --out "$out_dir/runs/summary-$rep"
  timed csv "$thetad" run --scenario scenario-1 --controller theta-d --quiet \
    --out "$out_dir/runs/csv-$rep"
done

/usr/bin/python3 - "$times" "$out_dir" "$draws" <<'PY' | tee "$out_dir/campaign_scaling.txt"
import collections, glob, sqlite3, statistics, sys
times_file, out, draws = sys.argv[1], sys.argv[2], int(sys.argv[3])
times = collections.defaultdict(list)
for line in open(times_file):
    name, seconds = line.split()
    times[name].append(float(seconds))
median = {name: statistics.median(values) for name, values in times.items()}
flight_sums = []
for database in sorted(glob.glob(f"{out}/runs/jobs1-*/campaign.sqlite")):
    with sqlite3.connect(database) as connection:
        flight_sums.append(connection.execute("SELECT SUM(wall_time_s) FROM runs").fetchone()[0])
flights = statistics.median(flight_sums)
overhead_per_run = (median["jobs1"] - flights) / draws
print(f"theta-d campaign of scenario I, {draws} draws; medians of {len(times['jobs1'])} interleaved repeats")
for name in ("jobs1", "jobs2", "mpi2", "summary_only", "csv"):
    print(f"  {name:13s} {median[name]:8.2f} s   ({', '.join(f'{v:.2f}' for v in times[name])})")
print(f"parallel efficiency, 2 threads:   {median['jobs1'] / (2 * median['jobs2']) * 100:5.1f} %  (target >= 90 %)")
print(f"parallel efficiency, 2 MPI ranks: {median['jobs1'] / (2 * median['mpi2']) * 100:5.1f} %  (target >= 85 %)")
print(f"campaign overhead per run: {overhead_per_run:.3f} s = {overhead_per_run / (flights / draws) * 100:.2f} % "
      f"of a {flights / draws:.2f} s flight  (target <= 2 %)")
print(f"summary-only speed-up over the CSV flight: {median['csv'] / median['summary_only']:.2f}x  (target >= 1.5x)")
PY
