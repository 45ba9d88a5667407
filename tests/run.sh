#!/usr/bin/env bash
# tests/run.sh - run test programs and add up what they report.
#
#   tests/run.sh [--section TITLE] [--args "A B"] PROGRAM... [--check PROGRAM]...
#
# Every PROGRAM ends its output with the plain line "N passed, M failed"
# (tests/harness.h prints it).  A program counts as one extra failure, named
# below, when it is missing (did not build), crashes, times out, prints no
# such line, or exits non-zero while reporting no failure (a sanitizer's
# report at exit, for instance).  "--check PROGRAM" runs a program that
# prints no counts: exit status 0 is one pass, anything else one failure.
# "--section TITLE" prints a heading before the programs that follow it;
# "--args 'A B'" gives the next program those arguments (split at spaces).
# A program that prints a line "SKIPPED: reason" (and counts nothing) is
# shown as SKIP with its reason.
#
# Prints one line per program, with the seconds it took, and ends with the
# summed plain line "N passed, M failed"; exits 1 when anything failed, 0 otherwise.
#
# Programs run TEST_JOBS at a time (default: the number of processors),
# each reported in the order given, when it and those before it are done.
#
# Each program may use TEST_TIMEOUT seconds (600) of processor time times a
# factor: the TEST_TIMEOUT_FACTOR given, or else one measured at the start
# against the machine the limits were set on (2 processors, idle): the
# processor time a fixed loop of this shell takes over the reference's (a
# slower processor); never below 1.  Processor time does not grow when
# other work shares the machine (a busy laptop, a CI runner, taskset -c 0),
# so the limit catches a program that loops without failing one that
# waits its turn.  A program that hangs without using the processor is
# stopped by a wall-time limit 4 times that, times the loop's wall time
# over its processor time (a shared processor) and 2 over the processors
# there are (fewer than 2).  A program past a limit is stopped with its
# whole process group; so are the running ones when this script is
# interrupted or ends: no test outlives `make test`.
#
# Environment: TEST_TIMEOUT         seconds per program before the factor (default 600)
#              TEST_TIMEOUT_FACTOR  the factor of both limits (default: measured)
#              TEST_JOBS            programs run at once (default nproc)
#              VERBOSE=1            show every program's output, not only a failing one's
set -u

verbose=${VERBOSE:-0}
jobs_max=${TEST_JOBS:-$(nproc 2>/dev/null || echo 1)}
[ "$jobs_max" -ge 1 ] 2>/dev/null || jobs_max=1
total_passed=0
total_failed=0
log_dir=$(mktemp -d "${TMPDIR:-/tmp}/manylods-run.XXXXXX")
watcher=

# Stop every program still running (each runs under timeout, in a process
# group of its own that a terminal's ^C or make's signals do not reach):
# timeout passes the signal on to its group, and kills it 10 s later if it
# is still there.  Then the logs go.
stop_all() {
    local f pid
    for f in "$log_dir"/*.pid; do
        [ -e "$f" ] || continue
        read -r pid <"$f" 2>/dev/null && [ -n "$pid" ] && kill -TERM "$pid" 2>/dev/null
    done
}
cleanup() {
    local tries=0
    trap - EXIT INT TERM HUP
    [ -n "$watcher" ] && kill "$watcher" 2>/dev/null
    # again while any is left: one may have been starting the first time
    while stop_all; [ -n "$(jobs -rp)" ] && [ "$tries" -lt 150 ]; do
        sleep 0.1
        tries=$((tries + 1))
    done
    rm -rf "$log_dir"
}
trap cleanup EXIT
trap 'echo "tests/run.sh: interrupted, stopping the programs still running" >&2; cleanup; exit 130' INT
trap 'cleanup; exit 143' TERM
trap 'cleanup; exit 129' HUP

# The make that runs this script (the nearest ancestor named make; else the
# parent): when it is gone, so are we.  A make stopped by SIGKILL, or by its
# own "wait: No child processes" (GNU make 4.3, when a SIGTERM or SIGINT
# reaches it while it reaps a child: reproduced here 1 time in 80 under
# load), leaves no signal for this script; a watcher sends it SIGTERM.
find_make() {
    local ancestor=$PPID stat name level
    watch_pid=$PPID
    for level in 1 2 3 4; do
        [ -r "/proc/$ancestor/stat" ] && read -r stat <"/proc/$ancestor/stat" || return
        name=${stat#*(}
        case ${name%%)*} in make | gmake) watch_pid=$ancestor; return ;; esac
        stat=${stat##*) }
        set -- $stat
        ancestor=$2
        [ "$ancestor" -gt 1 ] 2>/dev/null || return
    done
}
find_make
( while kill -0 "$watch_pid" 2>/dev/null; do sleep 2; done
  echo "tests/run.sh: its make (process $watch_pid) is gone: stopping the programs still running" >&2
  kill -TERM $$ 2>/dev/null ) </dev/null >/dev/null &
watcher=$!
disown "$watcher" 2>/dev/null

# The factor of the limits, measured (see above).  Processor time from
# /proc (Linux), in clock ticks; without it, not measured.  The reference:
# the loop's fastest runs on the 2-processor machine the limits were set on
# (30 ticks of 10 ms; 30 to 50 there, idle).
reference_ticks=30
calibrate() {
    local stat start_ticks end_ticks start end i hz
    hz=$(getconf CLK_TCK 2>/dev/null || echo 100)
    if [ ! -r /proc/$$/stat ] || [ -z "${EPOCHREALTIME:-}" ]; then
        factor=1
        factor_how="not measured here"
        return
    fi
    read -r stat </proc/$$/stat; stat=${stat##*) }; set -- $stat; start_ticks=$((${12} + ${13}))
    start=$EPOCHREALTIME
    for ((i = 0; i < 200000; i++)); do :; done
    end=$EPOCHREALTIME
    read -r stat </proc/$$/stat; stat=${stat##*) }; set -- $stat; end_ticks=$((${12} + ${13}))
    read -r factor speed share cores < <(awk -v ticks=$((end_ticks - start_ticks)) -v hz="$hz" -v ref="$reference_ticks" \
        -v start="${start/,/.}" -v end="${end/,/.}" -v n="$(nproc 2>/dev/null || echo 1)" 'BEGIN {
        cpu = ticks / hz; if (cpu < 0.01) cpu = 0.01
        speed = ticks / (ref * hz / 100); if (speed < 1) speed = 1
        share = (end - start) / cpu; if (share < 1) share = 1
        cores = n < 2 ? 2 / n : 1
        f = int(speed * 10 + 0.999) / 10
        printf "%.1f %.1f %.1f %.1f\n", f, speed, share, cores }')
    factor_how="measured: processor ${speed}x slower"
}
share=1
cores=1
if [ -n "${TEST_TIMEOUT_FACTOR:-}" ]; then
    factor=$TEST_TIMEOUT_FACTOR
    factor_how="TEST_TIMEOUT_FACTOR"
else
    calibrate
fi
cpu_s=$(awk -v t="${TEST_TIMEOUT:-600}" -v f="$factor" 'BEGIN { s = int(t * f + 0.5); print s < 1 ? 1 : s }')
timeout_s=$(awk -v c="$cpu_s" -v s="$share" -v n="$cores" 'BEGIN { print int(4 * c * s * n + 0.5) }')
echo "limits per program: ${TEST_TIMEOUT:-600} s x $factor = $cpu_s s of processor time ($factor_how)," \
     "$timeout_s s of wall time (4x, ${share}x shared, ${cores}x for fewer processors); $jobs_max at once"

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
        124) printf 'timed out after %s s of wall time (a hang? on a very busy machine raise it: make test TEST_TIMEOUT_FACTOR=%s)' \
                "$timeout_s" "$(awk -v f="$factor" 'BEGIN { print int(f * 2 + 0.999) }')" ;;
        152) printf 'used its %s s of processor time (TEST_TIMEOUT %s s x %s; on a slow processor raise it: make test TEST_TIMEOUT_FACTOR=%s)' \
                "$cpu_s" "${TEST_TIMEOUT:-600}" "$factor" "$(awk -v f="$factor" 'BEGIN { print int(f * 2 + 0.999) }')" ;;
        137) printf 'killed by signal 9 (SIGKILL: out of memory, or 10 s after a time limit when it ignored SIGTERM or SIGXCPU)' ;;
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

# start_one INDEX PROGRAM: run it in the background, its output, exit
# status and seconds into $log_dir/INDEX.{out,err,status,time} (status last,
# so that its presence says the program is done).
start_one() {
    local i=$1 program=$2
    local -a args
    read -r -a args <<<"${arguments[i]}"
    (
        start=$SECONDS
        # the program's processor time: SIGXCPU past it (status 152), SIGKILL 10 s later
        ulimit -S -t "$cpu_s" 2>/dev/null && ulimit -H -t $((cpu_s + 10)) 2>/dev/null
        # In the background, its process id in INDEX.pid for stop_all while
        # it runs.  The braces' 2>/dev/null silences the shell's own
        # "Segmentation fault" notice; the program's stderr still goes to
        # INDEX.err.
        { ${wrap[@]+"${wrap[@]}"} "$program" ${args[@]+"${args[@]}"} </dev/null >"$log_dir/$i.out" 2>"$log_dir/$i.err" & } 2>/dev/null
        echo "$!" >"$log_dir/$i.pid"
        { wait "$!"; } 2>/dev/null
        code=$?
        rm -f "$log_dir/$i.pid"
        echo "$((SECONDS - start))" >"$log_dir/$i.time"
        echo "$code" >"$log_dir/$i.status.tmp" && mv "$log_dir/$i.status.tmp" "$log_dir/$i.status"
    ) &
}

# report_one INDEX MODE PROGRAM: MODE is "counts" or "check"; the program
# is done (or was not built).  It is named with its arguments.
report_one() {
    local i=$1 mode=$2 program=$3 out="$log_dir/$1.out" err="$log_dir/$1.err" status line passed failed note="" took
    if [ ! -x "$program" ]; then
        program="$program${arguments[i]:+ ${arguments[i]}}"
        total_failed=$((total_failed + 1))
        printf '  FAIL  %-40s not built (missing or not executable)\n' "$program"
        return
    fi
    status=$(cat "$log_dir/$i.status")
    took="$(cat "$log_dir/$i.time") s"
    program="$program${arguments[i]:+ ${arguments[i]}}"

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

# The command line as lists: each program's mode and the section printed
# before it (sections after the last program are printed at the end).
modes=()
programs=()
arguments=()
sections=()
pending=""
next_args=""
while [ $# -gt 0 ]; do
    case $1 in
        --section) shift; pending+="${1:-}"$'\n'; shift ;;
        --args) shift; next_args=${1:-}; shift ;;
        --check) shift; [ $# -gt 0 ] && { modes+=(check); programs+=("$1"); arguments+=("$next_args"); sections+=("$pending"); pending=""; next_args=""; shift; } ;;
        -h|--help) sed -n '2,/^set -u/p' "$0" | sed '$d'; exit 0 ;;
        *) modes+=(counts); programs+=("$1"); arguments+=("$next_args"); sections+=("$pending"); pending=""; next_args=""; shift ;;
    esac
done

count=${#programs[@]}
next=0    # the next program to start
running=0 # started and not yet seen done
for ((i = 0; i < count; i++)); do
    # Start programs while there is room, then wait for this one.
    while [ ! -e "$log_dir/$i.status" ] && [ -x "${programs[i]}" ]; do
        if [ "$next" -lt "$count" ] && [ "$(jobs -rp | wc -l)" -lt "$jobs_max" ]; then
            [ -x "${programs[next]}" ] && start_one "$next" "${programs[next]}"
            next=$((next + 1))
        else
            wait -n 2>/dev/null || sleep 0.2
        fi
    done
    printf '%s' "${sections[i]}"
    report_one "$i" "${modes[i]}" "${programs[i]}"
done
printf '%s' "$pending"
wait

echo "$total_passed passed, $total_failed failed"
[ "$total_failed" = 0 ]
