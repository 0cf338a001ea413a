#!/usr/bin/env bash
# Counted, not timed (docs/onboard.md, "Counted"): the exported θ–D (N = 3, N = 1), hover LQR and
# capped SDRE (K = 2 Newton–Kleinman steps per pass) steps in float and double, built for a
# Cortex-M7 (arm-none-eabi-g++, -mcpu=cortex-m7 -mfpu=fpv5-d16 -mfloat-abi=hard), aarch64 Linux
# and x86-64, all at -O2 -fno-exceptions -fno-rtti with the compilers' default contraction (FMA
# where the target has it), as a flight build would be.
# Instructions per step: the Cortex-M7 build under qemu-system-arm (mps2-an500) and the aarch64
# build under qemu-aarch64, one instruction per translation block (-singlestep) with every block
# logged (-d exec,nochain), counted between the driver's two marks; the x86-64 build under
# callgrind (instructions in run_steps()). Each counts every sample of the check data (5 runs of 4
# consecutive samples over 20 s of scenario I) and divides by the samples. Code, constant data and
# state from the Cortex-M7 link (arm-none-eabi-nm symbol sizes), worst stack from its call graph
# (-fcallgraph-info=su). Prints one markdown table; took 24 minutes on a 2-vCPU host under a load
# average of 6 (the SDRE's 4 million instructions a step are each logged under qemu).
#   scripts/onboard_counts.sh [THETAD (default build/apps/thetad)] [OUT (default out/onboard_counts)]
# Needs scripts/install-deps.sh's gcc-arm-none-eabi, libnewlib-arm-none-eabi, qemu-system-arm,
# g++-aarch64-linux-gnu, qemu-user and valgrind.
set -euo pipefail
source_dir=$(cd "$(dirname "$0")/.." && pwd)
thetad=$(realpath "${1:-$source_dir/build/apps/thetad}")
out=${2:-out/onboard_counts}
mkdir -p "$out"
out=$(cd "$out" && pwd)
driver=$source_dir/bench/onboard/count_step.cpp
common=(-std=c++20 -O2 -fno-exceptions -fno-rtti -Wall -Wextra -Wpedantic)
m7=(-mcpu=cortex-m7 -mfpu=fpv5-d16 -mfloat-abi=hard -mthumb)

printf 'theta-d:\n  terms: 1\n' >"$out/one-term.settings.yaml"
specs=(theta-d "n1=theta-d:$out/one-term.settings.yaml" lqr "sdre-capped=sdre:$source_dir/scenarios/sdre-capped.settings.yaml")

# Instructions executed between the first and the second entry into count_mark in a qemu
# -d exec log on stdin (one "Trace" line per instruction with -singlestep; the symbol last).
count_between_marks() {
  awk '/^Trace/ { mark = ($NF ~ /count_mark/); if (mark && !was) entries++; was = mark; if (entries == 1) n++ }
       END { print n }'
}

results=$out/results.txt
: >"$results"
for spec in "${specs[@]}"; do
  label=${spec%%=*}
  name_space=$(printf '%s' "$label" | sed 's/[^A-Za-z0-9_]/_/g')
  dir=$out/$label
  "$thetad" export --controller "$spec" --duration 20 --check-segments 5 --check-samples 4 --quiet --out "$dir" >/dev/null
  defines=(-I"$dir" -DTHETAD_EXPORTED_HEADER="\"$label.hpp\"" -DTHETAD_CHECK_DATA="\"${label}_check_data.hpp\""
           -DTHETAD_EXPORTED_NAMESPACE="$name_space")
  for scalar in float double; do
    base=$dir/$scalar
    flags=("${common[@]}" "${defines[@]}" -DTHETAD_COUNT_SCALAR="$scalar")
    # Cortex-M7: counted under qemu-system-arm; sizes and stack from the same build.
    arm-none-eabi-g++ "${flags[@]}" "${m7[@]}" -fcallgraph-info=su -c "$driver" -o "$base-m7.o"
    arm-none-eabi-g++ "${m7[@]}" -O2 -c "$source_dir/bench/onboard/cortex_m7_start.cpp" -o "$dir/start-m7.o"
    arm-none-eabi-g++ "${m7[@]}" --specs=rdimon.specs -Wl,--section-start=.vectors=0 "$base-m7.o" "$dir/start-m7.o" \
      -o "$base-m7.elf"
    m7_run=$(qemu-system-arm -M mps2-an500 -nographic -monitor none -semihosting -kernel "$base-m7.elf")
    m7_count=$(qemu-system-arm -M mps2-an500 -nographic -monitor none -semihosting -kernel "$base-m7.elf" -singlestep \
      -d exec,nochain -D /dev/stderr 2>&1 >/dev/null | count_between_marks)
    arm-none-eabi-nm -C -S --size-sort "$base-m7.elf" >"$base-m7.symbols"
    # aarch64 Linux under qemu-user.
    aarch64-linux-gnu-g++ "${flags[@]}" "$driver" -o "$base-aarch64"
    aarch64_count=$(qemu-aarch64 -L /usr/aarch64-linux-gnu -singlestep -d exec,nochain -D /dev/stderr "$base-aarch64" \
      2>&1 >/dev/null | count_between_marks)
    # x86-64 under callgrind.
    g++ "${flags[@]}" "$driver" -o "$base-x86"
    valgrind --tool=callgrind --toggle-collect='*run_steps*' --callgrind-out-file="$base-x86.callgrind" "$base-x86" \
      >/dev/null 2>&1
    x86_count=$(awk '/^totals:/ { print $2 }' "$base-x86.callgrind")
    echo "$label $scalar $m7_count $aarch64_count $x86_count $base-m7.symbols $base-m7.ci $name_space $m7_run" >>"$results"
  done
done

/usr/bin/python3 - "$results" <<'EOF'
import re, sys

def worst_stack(ci_file):
    """The deepest stack (bytes) of a call path from run_steps() in GCC's -fcallgraph-info=su graph."""
    text = open(ci_file).read()
    frame, calls = {}, {}
    for title, label in re.findall(r'node: \{ title: "([^"]+)" label: "([^"]*)"', text):
        match = re.search(r"(\d+) bytes \((static|dynamic[^)]*)\)", label)
        frame[title] = int(match.group(1)) if match else 0  # library functions (libm): not known
    for source, target in re.findall(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"', text):
        calls.setdefault(source, set()).add(target)
    def deepest(node, seen=()):
        return frame.get(node, 0) + max((deepest(t, seen + (node,)) for t in calls.get(node, ()) if t not in seen), default=0)
    return deepest(next(t for t in frame if "run_steps" in t))

def sizes(symbol_file, name_space):
    code = data = state = 0
    for line in open(symbol_file):
        parts = line.split(None, 3)
        if len(parts) < 4:
            continue
        size, kind, name = int(parts[1], 16), parts[2].lower(), parts[3].strip()
        ours = "thetad_onboard::" in name or name.startswith(name_space + "::") and "_check::" not in name
        if kind in "tw" and (ours or "run_steps" in name):
            code += size
        elif kind in "rv" and ours:  # the Design arrays are weak objects (V): inline members of a template
            data += size
        elif kind in "bd" and name.endswith("::state"):
            state = size
    return code, data, state

ipc, clock = 1.0, 400e6
print("| step | scalar | Cortex-M7 instructions | aarch64 | x86-64 | passes | code (B) | constant data (B) | state (B) | stack (B) | M7 estimate at IPC 1, 400 MHz |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for line in open(sys.argv[1]):
    label, scalar, m7, aarch64, x86, symbols, ci, name_space, _, steps, _, passes, _, failures = line.split()
    if failures != "0":
        sys.exit(f"{label} {scalar}: {failures} steps failed on the Cortex-M7")
    steps = int(steps)
    code, data, state = sizes(symbols, name_space)
    per_step = int(m7) / steps
    print(f"| {label} | {scalar} | {per_step:,.0f} | {int(aarch64) / steps:,.0f} | {int(x86) / steps:,.0f} | "
          f"{int(passes) / steps:.1f} | {code:,} | {data:,} | {state:,} | {worst_stack(ci):,} | "
          f"~{per_step / ipc / clock * 1e6:,.0f} µs |")
EOF
