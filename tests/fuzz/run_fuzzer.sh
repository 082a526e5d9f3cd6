#!/usr/bin/env bash
# Runs one libFuzzer target for a set time and prints one summary line (used by `make fuzz`,
# tests/fuzz/fuzz.mk).
#
#   run_fuzzer.sh NAME BINARY SEED_DIR WORK_DIR SECONDS MAX_LEN [EXTRA_SEED_DIR] [-- FUZZER_ARGS...]
#
# The seeds (SEED_DIR, never written to, and EXTRA_SEED_DIR if given) are copied into
# WORK_DIR/corpus, which is kept between runs so coverage accumulates (FUZZ_FRESH=1 empties it
# first; FUZZ_SKIP_KNOWN=1 leaves the seeds named crash-* out, the saved findings that still fail
# until their bug is fixed). The fuzzer runs with -max_total_time=SECONDS -max_len=MAX_LEN
# -rss_limit_mb=2048 -timeout=10, writes findings (crash-*, leak-*, timeout-*, oom-*) to
# WORK_DIR/artifacts/ and its log to WORK_DIR/fuzz.log. The summary names the time it ran, the
# executions, the coverage (cov/ft of libFuzzer's last status line) and the findings; the exit
# status is 1 when it found something or failed, 0 otherwise.
set -u
name=$1 bin=$2 seeds=$3 work=$4 seconds=$5 max_len=$6
shift 6
extra=""
if [ $# -gt 0 ] && [ "$1" != "--" ]; then extra=$1; shift; fi
[ $# -gt 0 ] && [ "$1" = "--" ] && shift

mkdir -p "$work"
work=$(cd "$work" && pwd)
[ "${FUZZ_FRESH:-0}" = 1 ] && rm -rf "$work/corpus"
rm -rf "$work/artifacts"
mkdir -p "$work/corpus" "$work/artifacts" "$work/tmp"
for dir in "$seeds" $extra; do
  [ -d "$dir" ] || continue
  for f in "$dir"/*; do
    [ -f "$f" ] || continue
    case "$(basename "$f")" in
      crash-*) [ "${FUZZ_SKIP_KNOWN:-0}" = 1 ] && continue ;;
    esac
    cp "$f" "$work/corpus/"
  done
done

start=$(date +%s.%N)
TMPDIR="$work/tmp" "$bin" "$work/corpus" -max_total_time="$seconds" -max_len="$max_len" \
  -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 -artifact_prefix="$work/artifacts/" \
  "$@" > "$work/fuzz.log" 2>&1
rc=$?
end=$(date +%s.%N)

elapsed=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.0f", b - a }')
execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/fuzz.log" | tail -n 1)
if [ -z "$execs" ]; then  # no final stats (the fuzzer died): the last status line's count
  execs=$(grep -oE '^#[0-9]+' "$work/fuzz.log" | tail -n 1 | tr -d '#')
fi
last=$(grep -E '^#[0-9]+.*cov: ' "$work/fuzz.log" | tail -n 1)
cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<< "$last")
ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<< "$last")
corp=$(sed -n 's/.* corp: \([0-9]*\/[0-9A-Za-z]*\).*/\1/p' <<< "$last")
findings=$(cd "$work/artifacts" && ls -1 2>/dev/null | grep -E '^(crash|leak|timeout|oom)-' || true)

if [ -n "$findings" ]; then
  names=$(tr '\n' ' ' <<< "$findings" | sed 's/ $//')
  status="FOUND $(wc -l <<< "$findings" | tr -d ' ') ($names)"
elif [ $rc -ne 0 ]; then
  status="FAILED (exit $rc, no artifact; see $work/fuzz.log)"
else
  status="nothing found"
fi
printf '%-16s %5ss  %10s execs  cov %-6s ft %-7s corpus %-10s %s\n' "$name" "$elapsed" \
  "${execs:-?}" "${cov:-?}" "${ft:-?}" "${corp:-?}" "$status"
if [ -n "$findings" ]; then
  grep -m 1 -E '^==[0-9]+==ERROR|^SUMMARY|==FUZZ FINDING==|runtime error:|ERROR: libFuzzer' \
    "$work/fuzz.log" | sed "s/^/  $name: /"
  for f in $findings; do echo "  $name: input $work/artifacts/$f"; done
  echo "  $name: log $work/fuzz.log"
fi
[ -z "$findings" ] && [ $rc -eq 0 ]
