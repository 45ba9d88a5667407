#!/bin/sh
# tests/check_readme_figures.sh - README.md's benchmark figures are the
# files' of the last `make bench`, never copied by hand:
#   1. the block between "<!-- bench:begin ..." and "<!-- bench:end -->"
#      equals what bench/readme_figures.sh prints from docs/bench_figures.txt
#      now (else: make readme-figures);
#   2. outside that block, fenced and indented code and `code spans`, no
#      line holds a figure that looks measured: a number followed by ms, ns,
#      us, s, %, GiB, MiB, KiB, GB, MB or KB, or a decimal number followed
#      by x or "points" (1.61x, 0.15 points);
#   3. every value of docs/bench_figures.txt appears in docs/BENCHMARKS.md,
#      where the same run printed it the same way;
#   4. README.md's first C block is examples/minimal.c, which make test
#      builds and runs.
# Prints "N passed, M failed" for tests/run.sh.
cd "$(dirname "$0")/.." || exit 1
LC_ALL=C
export LC_ALL
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0
check() { # status, message
    if [ "$1" = 0 ]; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL: $2"; fi
}

# 1. the block, fresh against README's
if bench/readme_figures.sh docs/bench_figures.txt >"$tmp/fresh" 2>"$tmp/err"; then
    awk '/^<!-- bench:begin/ { inside = 1 } inside { print } /^<!-- bench:end -->$/ { inside = 0 }' README.md >"$tmp/readme"
    cmp -s "$tmp/fresh" "$tmp/readme"
    check $? "README.md's benchmark block differs from docs/bench_figures.txt's figures (run make readme-figures;
   a figure is never edited by hand): diff README.md fresh
$(diff "$tmp/readme" "$tmp/fresh" | sed 's/^/    /')"
else
    check 1 "bench/readme_figures.sh could not print the block: $(cat "$tmp/err")"
fi

# 2. no measured figure outside the block
awk '
    /^<!-- bench:begin/ { block = 1; next }
    block { if ($0 ~ /^<!-- bench:end -->$/) block = 0; next }
    /^[ \t]*(```|~~~)/ { fence = !fence; next }
    fence || /^(    |\t)/ { next }
    {
        line = $0
        gsub(/`[^`]*`/, "", line)
        if (match(line, /(^|[^A-Za-z0-9_.])[0-9][0-9.,]* ?(ms|ns|us|s|%|GiB|MiB|KiB|GB|MB|KB)([^A-Za-z0-9_]|$)/) ||
            match(line, /(^|[^A-Za-z0-9_.])[0-9]+\.[0-9]+( ?x| points?)([^A-Za-z0-9_]|$)/))
        {
            figure = substr(line, RSTART, RLENGTH)
            sub(/^[^0-9]/, "", figure)
            sub(/[^A-Za-z0-9_%]$/, "", figure)
            printf "    README.md:%d: %s\n", NR, figure
        }
    }' README.md >"$tmp/stray"
[ ! -s "$tmp/stray" ]
check $? "README.md has figures outside the block make bench writes (move them into bench/readme_figures.sh):
$(cat "$tmp/stray")"

# 3. the figures file against the report of the same run
: >"$tmp/absent"
while IFS= read -r line; do
    case $line in "#"* | "") continue ;; esac
    value=${line#*=}
    grep -qF -- "$value" docs/BENCHMARKS.md || echo "    $line" >>"$tmp/absent"
done <docs/bench_figures.txt
[ ! -s "$tmp/absent" ]
check $? "docs/bench_figures.txt has values docs/BENCHMARKS.md does not show (not the same run?):
$(cat "$tmp/absent")"

# 4. the README's program (its first ```c block) is examples/minimal.c, which make test builds and runs
awk '/^```c$/ && !done { inside = 1; next } inside && /^```$/ { inside = 0; done = 1 } inside { print }' README.md >"$tmp/program"
cmp -s "$tmp/program" examples/minimal.c
check $? "README.md's first C block is not examples/minimal.c (the program make test builds and runs)"

echo "README.md's benchmark figures checked against docs/bench_figures.txt and docs/BENCHMARKS.md; its program is examples/minimal.c"
echo "$passed passed, $failed failed"
[ "$failed" = 0 ]
