#!/usr/bin/env bash
# Wall time and peak memory of whole shadowref processes, start to exit, against their targets:
#   --help, check and info of the room       at most 20 ms each
#   render the room (800x640, z-fail) to PNG at most 60 ms, and to EXR at most 60 ms
#   peak memory (max RSS) of those renders    at most 40 MB
# with `oiiotool --version` beside them as a yardstick of what loading OpenImageIO costs.
# hyperfine (Debian package, scripts/setup.sh --role bench) runs each command RUNS times after
# WARMUP runs; the table shows the mean and the fastest run, and the target is judged on the
# median. GNU time gives the peak memory. Exits 1 if a target is missed.
#   scripts/bench-startup.sh [BUILD_DIR] [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
runs=${2:-30}
cli=$build/shadowref
for tool in hyperfine /usr/bin/time; do
  command -v "$tool" > /dev/null || { echo "bench-startup: $tool not found (scripts/setup.sh --role bench)" >&2; exit 2; }
done
[ -x "$cli" ] || { echo "bench-startup: no $cli; build it first (scripts/setup.sh --role render)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

names=(help check info render-png render-exr)
commands=("$cli --help" "$cli check scenes/room.yaml" "$cli info scenes/room.yaml"
          "$cli render scenes/room.yaml -o $out/x.png --quiet" "$cli render scenes/room.yaml -o $out/x.exr --quiet")
targets=(20 20 20 60 60)
if command -v oiiotool > /dev/null; then
  names+=(oiiotool)
  commands+=("oiiotool --version")
  targets+=(-)
fi

printf 'machine: %s CPUs (%s in this process'"'"'s mask), %s; load average %s\n' "$(nproc --all)" "$(nproc)" \
  "$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)" "$(cut -d' ' -f1-3 /proc/loadavg)"
printf 'shadowref: %s\n\n' "$("$cli" --version | head -1)"
printf '%-11s %10s %10s %10s %9s %8s  %s\n' command "mean ms" "min ms" "median ms" "target" "max RSS" verdict
status=0
for i in "${!names[@]}"; do
  hyperfine -N --warmup 3 --runs "$runs" --export-csv "$out/${names[$i]}.csv" "${commands[$i]}" > /dev/null 2>&1
  # CSV: command,mean,stddev,median,user,system,min,max (seconds)
  read -r mean min median < <(awk -F, 'NR == 2 { print $2 * 1000, $7 * 1000, $4 * 1000 }' "$out/${names[$i]}.csv")
  # shellcheck disable=SC2086
  rss=$(/usr/bin/time -f %M ${commands[$i]} 2>&1 > /dev/null | tail -1)
  rss_mb=$(awk -v k="$rss" 'BEGIN { printf "%.1f", k / 1024 }')
  verdict=""
  if [ "${targets[$i]}" != - ]; then
    if awk -v m="$median" -v t="${targets[$i]}" 'BEGIN { exit !(m <= t) }'; then verdict="met"; else verdict="MISSED"; status=1; fi
    if [[ ${names[$i]} == render-* ]]; then
      if awk -v r="$rss_mb" 'BEGIN { exit !(r <= 40) }'; then verdict+=", memory met"; else verdict+=", memory MISSED"; status=1; fi
    fi
  fi
  printf '%-11s %10.1f %10.1f %10.1f %9s %6s MB  %s\n' "${names[$i]}" "$mean" "$min" "$median" \
    "$([ "${targets[$i]}" = - ] && echo "-" || echo "${targets[$i]} ms")" "$rss_mb" "$verdict"
done
exit $status
