#!/usr/bin/env bash
# Cost of null-collision tracking (issue 27): smoke-plume (a grid plume filling 5 % of its box)
# rendered with the exact optical depth, delta tracking against the majorant block grid, and
# delta tracking against the global maximum, at several density multipliers; RUNS runs each,
# median wall and CPU seconds of the whole process, and the camera and light passes' seconds
# (--verbose). Usage: tools/bench_tracking.sh [RUNS] [PASSES] (defaults 5 and 2).
# Another scene: SCENE=tools/bench/ground-fog.toml MEDIUM=fog MULTS=1 tools/bench_tracking.sh 5 4
# (the thin layer; MULTS=1 leaves the density as the scene has it). A density without a
# `multiplier` key (noise) is scaled through the medium's coefficients: SIGMA="6 0.05" gives the
# scene's sigma_s and sigma_a, which are multiplied, e.g.
# SCENE=tools/bench/ground-fog.toml MEDIUM=fog SIGMA="6 0.05" MULTS="1 3 10" tools/bench_tracking.sh 5 4
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
passes=${2:-2}
bin=target/release/brume
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf "%-5s %-13s %9s %9s %9s %9s\n" mult tracking wall_s cpu_s camera_s light_s
scene=${SCENE:-scenes/smoke-plume.toml}
medium=${MEDIUM:-smoke}
for mult in ${MULTS:-1 10 30 100}; do
  scale=()
  if [ "$mult" != 1 ] && [ -n "${SIGMA:-}" ]; then
    read -r ss sa <<<"$SIGMA"
    scale=(--set "media.$medium.sigma_s=$(awk -v a="$ss" -v m="$mult" 'BEGIN{print a*m}')"
      --set "media.$medium.sigma_a=$(awk -v a="$sa" -v m="$mult" 'BEGIN{print a*m}')")
  elif [ "$mult" != 1 ]; then scale=(--set "media.$medium.density.multiplier=$mult"); fi
  for t in exact delta delta-global; do
    rows=()
    for r in $(seq "$runs"); do
      log="$out/log"
      /usr/bin/time -f "TIME %e %U %S" "$bin" render "$scene" --passes "$passes" \
        --seed "$r" --set "media.$medium.tracking=\"$t\"" "${scale[@]}" \
        -o "$out/x.exr" --verbose >"$log" 2>&1
      w=$(awk '/^TIME/{print $2}' "$log"); c=$(awk '/^TIME/{print $3+$4}' "$log")
      cam=$(sed -n 's/.*seconds: camera \([0-9.]*\),.*/\1/p' "$log" | tail -1)
      lp=$(sed -n 's/.*seconds: camera .*, light \([0-9.]*\).*/\1/p' "$log" | tail -1)
      rows+=("$w $c $cam $lp")
    done
    printf "%s\n" "${rows[@]}" | sort -n | awk -v m="$mult" -v t="$t" -v n="$runs" \
      '{w[NR]=$1; c[NR]=$2; a[NR]=$3; l[NR]=$4} END {k=int((n+1)/2); printf "%-5s %-13s %9.2f %9.2f %9.3f %9.3f  (wall %.2f-%.2f)\n", m, t, w[k], c[k], a[k], l[k], w[1], w[n]}'
  done
done
