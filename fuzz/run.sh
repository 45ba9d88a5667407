#!/usr/bin/env bash
# fuzz/run.sh - one libFuzzer harness: replay every input in its
# fuzz/crashes/NAME/ (inputs that once broke an invariant: they must pass
# now), then fuzz it on a copy of its seeds, fuzz/corpus/NAME/, for a fixed
# time.  NAME comes from the program's name, build/fuzz/fuzz_NAME.
# fuzz/run_all.sh (what `make fuzz` runs) calls it once per harness.
#
#   fuzz/run.sh FUZZER SECONDS WORKDIR
#
# The corpus copy, any new crash and the logs land under WORKDIR (corpus/,
# artifacts/, fuzz.log, replay.log).  A harness without a corpus directory
# starts from an empty corpus.  FUZZ_PHASE=replay only replays,
# FUZZ_PHASE=fuzz only fuzzes (both by default).  libFuzzer flags: the
# defaults below, then those of a line "FUZZ_FLAGS: ..." in the harness's
# source (e.g. a larger -max_len), then the environment's FUZZ_FLAGS.
# Prints a short report and ends with the plain line "1 passed, 0 failed"
# or "0 passed, 1 failed" (tests/run.sh's format); exits 1 on failure.
set -u
cd "$(dirname "$0")/.." || exit 1

usage="usage: fuzz/run.sh FUZZER SECONDS WORKDIR"
fuzzer=${1:?$usage}
seconds=${2:?$usage}
work=${3:?$usage}
phase=${FUZZ_PHASE:-both}
name=$(basename "$fuzzer")
name=${name#fuzz_}
corpus=fuzz/corpus/$name
crashes=fuzz/crashes/$name
log=$work/fuzz.log

fail() {
    printf '  FAIL  %s\n' "$1"
    echo "0 passed, 1 failed"
    exit 1
}

[ -x "$fuzzer" ] || fail "$fuzzer not built (needs clang with libFuzzer: Debian's libclang-rt-14-dev)"
mkdir -p "$work/artifacts" || fail "cannot create $work"

# Inputs that once broke an invariant replay first, one run each: they
# must pass now.  While any fails, there is no fuzzing run.
if [ "$phase" != fuzz ]; then
    replayed=0
    broken=0
    for input in "$crashes"/*; do
        [ -f "$input" ] || continue
        replayed=$((replayed + 1))
        if "$fuzzer" -timeout=25 -rss_limit_mb=2048 -artifact_prefix="$work/artifacts/" "$input" >"$work/replay.log" 2>&1; then
            printf '  ok    replay %s\n' "$input"
        else
            broken=$((broken + 1))
            printf '  FAIL  replay %s\n' "$input"
            grep -E '^manylods fuzz:|^==[0-9]+==ERROR|^SUMMARY: [A-Za-z]+Sanitizer|^SUMMARY: libFuzzer: timeout' \
                "$work/replay.log" | head -n 3 | cut -c1-400 | sed 's/^/      | /'
        fi
    done
    if [ "$broken" != 0 ]; then
        echo "      $broken of $replayed inputs in $crashes/ still fail: no fuzzing run"
        echo "      replay one: MANYLODS_FUZZ_VERBOSE=1 $fuzzer $crashes/FILE"
        echo "0 passed, 1 failed"
        exit 1
    fi
    if [ "$phase" = replay ]; then
        printf '  ok    %s: %s inputs of %s/ replayed\n' "$name" "$replayed" "$crashes"
        echo "1 passed, 0 failed"
        exit 0
    fi
fi

rm -rf "$work/corpus"
mkdir -p "$work/corpus" || fail "cannot create $work/corpus"
if [ -d "$corpus" ]; then
    find "$corpus" -maxdepth 1 -type f -exec cp {} "$work/corpus/" \; || fail "cannot copy $corpus"
fi
seeds=$(find "$work/corpus" -type f | wc -l)
# the harness's own flags: the words of its "FUZZ_FLAGS:" line that look
# like -name=value (so a comment's closing */ is not taken for a path)
source_flags=""
for word in $(sed -n 's/.*FUZZ_FLAGS://p' "fuzz/fuzz_$name.c" 2>/dev/null | head -n 1 | tr -c 'A-Za-z0-9_=.:/-' ' '); do
    case $word in
    -[a-z]*=*) source_flags="$source_flags $word" ;;
    esac
done

echo "fuzzing $fuzzer for ${seconds}s from $seeds seeds"
# shellcheck disable=SC2086
"$fuzzer" -seed=1 -max_len=4096 -timeout=25 -rss_limit_mb=2048 $source_flags ${FUZZ_FLAGS:-} \
    -max_total_time="$seconds" -print_final_stats=1 -artifact_prefix="$work/artifacts/" "$work/corpus" >"$log" 2>&1
status=$?

runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n 1)
cov=$(grep -o 'cov: [0-9]*' "$log" | tail -n 1)
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
        echo "      keep it as a regression input: mkdir -p $crashes && cp $artifact $crashes/"
    fi
    echo "0 passed, 1 failed"
    exit 1
fi
printf '  ok    %s: %s runs in %ss (%s/s, %s), corpus %s -> %s inputs, every invariant held\n' \
    "$fuzzer" "${runs:-?}" "$seconds" "${speed:-?}" "${cov:-cov: ?}" "$seeds" "$grown"
echo "1 passed, 0 failed"
