#!/usr/bin/env bash
# tests/run.sh - run test programs and add up what they report.
#
#   tests/run.sh [--section TITLE] PROGRAM... [--check PROGRAM]...
#
# Every PROGRAM ends its output with the plain line "N passed, M failed"
# (tests/harness.h prints it).  A program counts as one extra failure, named
# below, when it is missing (did not build), crashes, times out, prints no
# such line, or exits non-zero while reporting no failure (a sanitizer's
# report at exit, for instance).  "--check PROGRAM" runs a program that
# prints no counts: exit status 0 is one pass, anything else one failure.
# "--section TITLE" prints a heading before the programs that follow it.
# A program that prints a line "SKIPPED: reason" (and counts nothing) is
# shown as SKIP with its reason.
#
# Prints one line per program, with the seconds it took, and ends with the
# summed plain line "N passed, M failed"; exits 1 when anything failed, 0 otherwise.
#
# Environment: TEST_TIMEOUT  seconds allowed per program (default 600)
#              VERBOSE=1     show every program's output, not only a failing one's
set -u

timeout_s=${TEST_TIMEOUT:-600}
verbose=${VERBOSE:-0}
total_passed=0
total_failed=0
log_dir=$(mktemp -d "${TMPDIR:-/tmp}/manylods-run.XXXXXX")
trap 'rm -rf "$log_dir"' EXIT

# Line-buffered stdout (stdbuf), so that the result line survives a
# sanitizer that ends the process at exit without flushing stdio; a time
# limit (timeout).  Both are coreutils; without them programs run plainly.
wrap=()
command -v timeout >/dev/null 2>&1 && wrap+=(timeout -k 10 "$timeout_s")
command -v stdbuf >/dev/null 2>&1 && wrap+=(stdbuf -oL)

# Print the last lines of a captured stream, indented, under a label.
show_tail() { # label file lines
    [ -s "$2" ] || return 0
    printf '      --- %s (last %s lines)\n' "$1" "$3"
    tail -n "$3" "$2" | sed 's/^/      | /'
}

# Describe a non-zero exit status in words.
describe_status() { # status
    case $1 in
        124) printf 'timed out after %ss' "$timeout_s" ;;
        126) printf 'could not be executed' ;;
        127) printf 'not found' ;;
        *)
            if [ "$1" -gt 128 ]; then
                printf 'killed by signal %s (SIG%s)' "$(($1 - 128))" "$(kill -l "$(($1 - 128))" 2>/dev/null || echo '?')"
            else
                printf 'exit status %s' "$1"
            fi ;;
    esac
}

# run_one MODE PROGRAM: MODE is "counts" or "check".
run_one() {
    local mode=$1 program=$2 out="$log_dir/out" err="$log_dir/err" status line passed failed note="" took
    if [ ! -x "$program" ]; then
        total_failed=$((total_failed + 1))
        printf '  FAIL  %-40s not built (missing or not executable)\n' "$program"
        return
    fi
    # The braces' 2>/dev/null silences the shell's own "Segmentation fault"
    # notice; the program's stderr still goes to $err.
    local start=$SECONDS
    { ${wrap[@]+"${wrap[@]}"} "$program" </dev/null >"$out" 2>"$err"; } 2>/dev/null
    status=$?
    took="$((SECONDS - start)) s"

    if [ "$mode" = check ]; then
        if [ "$status" = 0 ]; then
            total_passed=$((total_passed + 1))
            printf '  ok    %-40s %5s  ran, exit status 0 (1 check)\n' "$program" "$took"
            [ "$verbose" = 1 ] && { show_tail stdout "$out" 1000; show_tail stderr "$err" 1000; }
        else
            total_failed=$((total_failed + 1))
            printf '  FAIL  %-40s %5s  %s\n' "$program" "$took" "$(describe_status "$status")"
            show_tail stdout "$out" 60
            show_tail stderr "$err" 40
        fi
        return
    fi

    line=$(grep -E '^[0-9]+ passed, [0-9]+ failed$' "$out" | tail -n 1)
    if [ -z "$line" ]; then
        total_failed=$((total_failed + 1))
        if [ "$status" = 0 ]; then note="printed no 'N passed, M failed' line"; else note="$(describe_status "$status") before printing its result line"; fi
        printf '  FAIL  %-40s %5s  %s (counted as 1 failure)\n' "$program" "$took" "$note"
        show_tail stdout "$out" 60
        show_tail stderr "$err" 40
        return
    fi
    passed=${line%% passed*}
    failed=${line#*, }
    failed=${failed%% failed}
    total_passed=$((total_passed + passed))
    total_failed=$((total_failed + failed))
    if [ "$status" != 0 ] && { [ "$failed" = 0 ] || [ "$status" -gt 1 ]; }; then
        total_failed=$((total_failed + 1))
        printf '  FAIL  %-40s %5s  %s, then %s (counted as 1 more failure)\n' "$program" "$took" "$line" "$(describe_status "$status")"
        show_tail stdout "$out" 60
        show_tail stderr "$err" 40
    elif [ "$failed" != 0 ]; then
        printf '  FAIL  %-40s %5s  %s\n' "$program" "$took" "$line"
        show_tail stdout "$out" 60
        show_tail stderr "$err" 40
    elif grep -q '^SKIPPED: ' "$out"; then
        # a skip counts nothing, and says why
        printf '  SKIP  %-40s %5s  %s\n' "$program" "$took" "$(grep '^SKIPPED: ' "$out" | head -n 1 | cut -c10-)"
    else
        printf '  ok    %-40s %5s  %s\n' "$program" "$took" "$line"
        [ "$verbose" = 1 ] && { show_tail stdout "$out" 1000; show_tail stderr "$err" 1000; }
    fi
}

while [ $# -gt 0 ]; do
    case $1 in
        --section) shift; printf '%s\n' "${1:-}"; shift ;;
        --check) shift; [ $# -gt 0 ] && { run_one check "$1"; shift; } ;;
        -h|--help) sed -n '2,/^set -u/p' "$0" | sed '$d'; exit 0 ;;
        *) run_one counts "$1"; shift ;;
    esac
done

echo "$total_passed passed, $total_failed failed"
[ "$total_failed" = 0 ]
