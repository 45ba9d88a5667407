#!/usr/bin/env bash
# fuzz/run.sh - what `make fuzz` runs: replay every input in fuzz/crashes/
# (inputs that once broke an invariant: they must pass now), then run the
# libFuzzer harness on a copy of the seed corpus (fuzz/corpus/) for a fixed
# time.
#
#   fuzz/run.sh FUZZER SECONDS WORKDIR
#
# The corpus copy and any new crash land under WORKDIR (corpus/, artifacts/,
# fuzz.log).  Prints a short report and ends with the plain line
# "1 passed, 0 failed" or "0 passed, 1 failed" (tests/run.sh's format);
# exits 1 on failure.  Extra libFuzzer flags: FUZZ_FLAGS="-jobs=2 ...".
set -u
cd "$(dirname "$0")/.." || exit 1

fuzzer=${1:?usage: fuzz/run.sh FUZZER SECONDS WORKDIR}
seconds=${2:?usage: fuzz/run.sh FUZZER SECONDS WORKDIR}
work=${3:?usage: fuzz/run.sh FUZZER SECONDS WORKDIR}
log=$work/fuzz.log

fail() {
    printf '  FAIL  %s\n' "$1"
    echo "0 passed, 1 failed"
    exit 1
}

[ -x "$fuzzer" ] || fail "$fuzzer not built (needs clang with libFuzzer: Debian's libclang-rt-14-dev)"
rm -rf "$work/corpus" "$work/artifacts"
mkdir -p "$work/corpus" "$work/artifacts" || fail "cannot create $work"
cp fuzz/corpus/* "$work/corpus/" || fail "cannot copy fuzz/corpus"
seeds=$(find "$work/corpus" -type f | wc -l)

# Inputs that once broke an invariant replay first, one run each: they
# must pass now.  While any fails, there is no fuzzing run.
replayed=0
broken=0
for input in fuzz/crashes/*; do
    [ -f "$input" ] || continue
    replayed=$((replayed + 1))
    if "$fuzzer" -artifact_prefix="$work/artifacts/" "$input" >"$work/replay.log" 2>&1; then
        printf '  ok    replay %s\n' "$input"
    else
        broken=$((broken + 1))
        printf '  FAIL  replay %s\n' "$input"
        grep -E '^manylods fuzz:|^==[0-9]+==ERROR|^SUMMARY: [A-Za-z]+Sanitizer|^SUMMARY: libFuzzer: timeout' \
            "$work/replay.log" | head -n 3 | cut -c1-400 | sed 's/^/      | /'
    fi
done
if [ "$broken" != 0 ]; then
    echo "      $broken of $replayed inputs in fuzz/crashes/ still fail: no fuzzing run"
    echo "      replay one: MANYLODS_FUZZ_VERBOSE=1 $fuzzer fuzz/crashes/NAME"
    echo "0 passed, 1 failed"
    exit 1
fi

echo "fuzzing $fuzzer for ${seconds}s from $seeds seeds"
# shellcheck disable=SC2086
"$fuzzer" -seed=1 -max_len=4096 -max_total_time="$seconds" -timeout=25 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$work/artifacts/" ${FUZZ_FLAGS:-} "$work/corpus" >"$log" 2>&1
status=$?

runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n 1)
grown=$(find "$work/corpus" -type f | wc -l)
if [ "$status" != 0 ]; then
    artifact=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log" | tail -n 1)
    printf '  FAIL  %s exited with status %s after %s runs\n' "$fuzzer" "$status" "${runs:-?}"
    grep -E '^manylods fuzz:|^==[0-9]+==ERROR|^SUMMARY' "$log" | head -n 5 | sed 's/^/      | /'
    echo "      --- $log (last 30 lines)"
    tail -n 30 "$log" | sed 's/^/      | /'
    if [ -n "$artifact" ]; then
        echo "      the input: $artifact"
        echo "      replay it: MANYLODS_FUZZ_VERBOSE=1 $fuzzer $artifact"
        echo "      keep it as a regression input: cp $artifact fuzz/crashes/"
    fi
    echo "0 passed, 1 failed"
    exit 1
fi
printf '  ok    %s: %s runs in %ss (%s/s), corpus %s -> %s inputs, every invariant held\n' \
    "$fuzzer" "${runs:-?}" "$seconds" "${speed:-?}" "$seeds" "$grown"
echo "1 passed, 0 failed"
