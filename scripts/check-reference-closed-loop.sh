#!/usr/bin/env bash
# Flies θ–D (k = l = 1, 3 terms, 1 kHz) through both paper scenarios in the ideal setting and
# checks the max position errors against the independent reference of docs/model.md §13 (5 % or 1 mm,
# whichever is larger). A long study (about 15 s of wall time), not part of `make test`.
#
#   scripts/check-reference-closed-loop.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
out=${2:-out/reference-check}
thetad="$build/apps/thetad"
[ -x "$thetad" ] || { echo "check-reference-closed-loop: $thetad not built (run make build)" >&2; exit 2; }

# scenario, then §10.5's max |x - x_c|, |y - y_c|, |z - z_c| (m)
references=(
  "scenario-1 0.54 0.52 0.037"
  "scenario-2 0.88 0.29 0.037"
)
status=0
for row in "${references[@]}"; do
  read -r scenario rx ry rz <<<"$row"
  "$thetad" run --scenario "scenarios/$scenario.yaml" --controller theta-d --ideal --summary-only --quiet --out "$out/$scenario" >/dev/null
  python3 - "$out/$scenario/theta-d.json" "$scenario" "$rx" "$ry" "$rz" <<'PY' || status=1
import json, sys
path, scenario, *reference = sys.argv[1:]
summary = json.load(open(path))
got = [summary[f"max_error_{axis}_m"] for axis in "xyz"]
ok = summary["status"] == "completed"
line = []
for axis, g, r in zip("xyz", got, map(float, reference)):
    bound = max(0.05 * r, 0.001)
    good = abs(g - r) <= bound
    ok &= good
    line.append(f"{axis} {g:.4f} (reference {r}, {'ok' if good else 'OFF'})")
print(f"{scenario}: {summary['status']}; max error " + ", ".join(line))
sys.exit(0 if ok else 1)
PY
done
exit $status
