#!/usr/bin/env bash
# fuzz/run_all.sh - what `make fuzz` runs: every harness named (fuzz/fuzz_NAME.c,
# built as BUILD/fuzz_NAME) replays its fuzz/crashes/NAME/ first, all of
# them before any fuzzing; then each harness whose replays passed is fuzzed
# (fuzz/run.sh) for an even share of SECONDS, the total.
#
#   fuzz/run_all.sh BUILD SECONDS NAME...
#
# Work directories: BUILD/work/NAME/.  Ends with the plain line
# "N passed, M failed" counting harnesses (tests/run.sh's format); exits 1
# when any failed: not built, a replay failed, or fuzzing broke an invariant.
set -u
cd "$(dirname "$0")/.." || exit 1

usage="usage: fuzz/run_all.sh BUILD SECONDS NAME..."
build=${1:?$usage}
total=${2:?$usage}
shift 2
[ $# -gt 0 ] || { echo "$usage" >&2; exit 2; }
names=("$@")
count=${#names[@]}
share=$((total / count))
[ "$share" -ge 1 ] || share=1

# run.sh's report without its own total line; its status says the rest.
harness() {
    local phase=$1 name=$2 seconds=$3 out status
    out=$(FUZZ_PHASE=$phase fuzz/run.sh "$build/fuzz_$name" "$seconds" "$build/work/$name" 2>&1)
    status=$?
    printf '%s\n' "$out" | grep -v -E '^[0-9]+ passed, [0-9]+ failed$'
    return $status
}

echo "fuzz: ${count} harnesses (${names[*]}), ${share}s each of ${total}s"
declare -A failed=()
for name in "${names[@]}"; do
    harness replay "$name" 0 || failed[$name]=1
done
for name in "${names[@]}"; do
    [ -z "${failed[$name]:-}" ] || continue
    harness fuzz "$name" "$share" || failed[$name]=1
done
bad=${#failed[@]}
[ "$bad" = 0 ] || echo "failed: ${!failed[*]}"
echo "$((count - bad)) passed, $bad failed"
[ "$bad" = 0 ]
