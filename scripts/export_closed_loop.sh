#!/usr/bin/env bash
# The float exported controllers in closed loop, paired against double (docs/onboard.md, "Fly it"):
# each case is exported, compiled into a plug-in as thetad_add_exported_plugin() compiles it, and
# flown by `thetad compare` beside the library's controller on the same seed; prints one markdown
# table (completion, J, J_dev, 3-D RMS error; the float and exported-double runs relative to the
# library's).
#   scripts/export_closed_loop.sh [BUILD_DIR (default build)] [OUT (default out/export_closed_loop)]
# Took 8 minutes on a 2-vCPU host under a load average of 3 (eight full flights of three controllers each).
set -euo pipefail
source_dir=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$source_dir/build}" && pwd)
out=${2:-out/export_closed_loop}
thetad=$build/apps/thetad
mkdir -p "$out"
out=$(cd "$out" && pwd)
printf 'theta-d:\n  terms: 1\n' >"$out/one-term.settings.yaml"

# case name | export and compare options | controller spec (its label is the exported namespace)
cases=(
  "scenario I, paper's weights|--scenario scenario-1|theta-d"
  "scenario I, paper's weights, N = 1|--scenario scenario-1|n1=theta-d:$out/one-term.settings.yaml"
  "scenario I, paper's weights, limits on|--scenario scenario-1 --actuator-limits on|theta-d"
  "scenario I, hover LQR|--scenario scenario-1|lqr"
  "scenario I, designed weights, limits on|--scenario scenario-1 --actuator-limits on --settings $source_dir/scenarios/designed.settings.yaml|theta-d"
  "scenario II, designed weights, limits on|--scenario scenario-2 --actuator-limits on --settings $source_dir/scenarios/designed.settings.yaml|theta-d"
  "scenario I, velocity feed-forward, designed weights, limits on|--scenario scenario-1 --actuator-limits on|ffv=theta-d:$source_dir/tests/export/velocity_feedforward.settings.yaml"
  "scenario I, paper's weights, capped SDRE (K = 2)|--scenario scenario-1|sdre-capped=sdre:$source_dir/scenarios/sdre-capped.settings.yaml"
)

echo "| case | controller | status | J | J_dev | 3-D RMS (m) | ΔJ/J | ΔRMS/RMS |"
echo "|---|---|---|---|---|---|---|---|"
for index in "${!cases[@]}"; do
  IFS='|' read -r name options spec <<<"${cases[$index]}"
  label=${spec%%=*}
  dir=$out/case-$index
  rm -rf "$dir"
  # shellcheck disable=SC2086  # options are words
  "$thetad" export --controller "$spec" $options --duration 1 --check-segments 1 --check-samples 1 --quiet \
    --out "$dir/exported" >/dev/null
  name_space=$(printf '%s' "$label" | sed 's/[^A-Za-z0-9_]/_/g')
  c++ -std=c++20 -O3 -DNDEBUG -shared -fPIC -fvisibility=hidden -fvisibility-inlines-hidden -I"$source_dir" \
    -isystem /usr/include/eigen3 -DTHETAD_EXPORTED_HEADER="\"$dir/exported/$label.hpp\"" \
    -DTHETAD_EXPORTED_NAMESPACE="$name_space" -o "$dir/exported.so" "$source_dir/export/plugin/exported_controller_plugin.cpp"
  # shellcheck disable=SC2086
  "$thetad" --plugin "$dir/exported.so" compare $options --controllers "$spec,$label-exported,$label-float" \
    --summary-only --no-timing --quiet --out "$dir/flights" >/dev/null || true  # a failed run is a result
  /usr/bin/python3 - "$dir/flights" "$name" "$label" <<'EOF'
import json, sys
folder, name, label = sys.argv[1:]
def figures(run):
    d = json.load(open(f"{folder}/{run}.json"))
    status = d["status"] if d["status"] == "completed" else f"{d['status']} at {d['end_time_s']:.2f} s"
    return status, d["cost"], d["cost_dev"], d["rms_error_m"]
library = figures(label)
for run in (label, f"{label}-exported", f"{label}-float"):
    status, j, j_dev, rms = figures(run)
    paired = "" if run == label else f" {(j - library[1]) / library[1]:.1e} | {(rms - library[3]) / library[3]:.1e} |"
    print(f"| {name if run == label else ''} | {run} | {status} | {j:.7g} | {j_dev:.7g} | {rms:.6f} |" + (paired or " | |"))
EOF
done
