#!/bin/sh
# tests/check_twins.sh - every C function of manylods.h with a GLSL twin in
# shaders/common.glsl or shaders/lookup.glsl (GLSL_FILES) names it in a line
# "/* GLSL twin: NAME */" just above its definition, and the twin names it
# back in a line "// C twin: mlod__X" (or a public mlod_X) just above its
# own; each GLSL file's pairs stand in the same order as in manylods.h.
# Fails on a tag whose partner is missing, does not name it back, or stands
# elsewhere in the order.  Prints "N passed, M failed" for tests/run.sh.
cd "$(dirname "$0")/.." || exit 1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

GLSL_FILES="shaders/common.glsl shaders/lookup.glsl"
# C: "c_name glsl_name" per tag, in file order (the definition is the next
# line: the function's name, mlod__X or a public mlod_X, before its
# parenthesis, else the first mlod__X on it, as for an array).
awk '/^\/\* GLSL twin: / { twin = $4; next }
     twin != "" { if (match($0, /mlod_[a-z0-9_]+\(/)) print substr($0, RSTART, RLENGTH - 1), twin
                  else if (match($0, /mlod__[a-z0-9_]+/)) print substr($0, RSTART, RLENGTH), twin
                  else print "?", twin
                  twin = "" }' \
    manylods.h >"$tmp/c"
# GLSL: "c_name glsl_name" per tag, in file order (the definition follows
# the tag's comment lines), a file of them per GLSL file, and all of them.
n=0
for f in $GLSL_FILES; do
    n=$((n + 1))
    awk '/^\/\/ C twin: / { twin = $4; next }
         twin != "" && /^\/\// { next }
         twin != "" { line = $0; sub(/\(.*/, "", line); sub(/\[.*/, "", line); n = split(line, w, " "); print twin, w[n]; twin = "" }' \
        "$f" >"$tmp/glsl.$n"
done
cat "$tmp"/glsl.* >"$tmp/glsl"

passed=0
failed=0
check() { # condition-status, message
    if [ "$1" = 0 ]; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL: $2"; fi
}
n=0
for f in $GLSL_FILES; do
    n=$((n + 1))
    [ -s "$tmp/c" ] && [ -s "$tmp/glsl.$n" ]
    check $? "no twin tags found (manylods.h: $(wc -l <"$tmp/c"), $f: $(wc -l <"$tmp/glsl.$n"))"
done
while read -r c g; do
    grep -qx "$c $g" "$tmp/glsl"
    check $? "manylods.h: $c names the GLSL twin $g, which does not name it back (or does not exist)"
done <"$tmp/c"
n=0
for f in $GLSL_FILES; do
    n=$((n + 1))
    while read -r c g; do
        grep -qx "$c $g" "$tmp/c"
        check $? "$f: $g names the C twin $c, which does not name it back (or does not exist)"
    done <"$tmp/glsl.$n"
    # its pairs in manylods.h's order (its pairs among manylods.h's)
    grep -Fx -f "$tmp/glsl.$n" "$tmp/c" >"$tmp/c.$n"
    cmp -s "$tmp/c.$n" "$tmp/glsl.$n"
    check $? "the pairs of $f stand in another order there than in manylods.h:
$(diff "$tmp/c.$n" "$tmp/glsl.$n" | sed 's/^/    /')"
done
echo "$(wc -l <"$tmp/c") twin pairs ($(for f in $GLSL_FILES; do printf '%s: %s ' "$f" "$(grep -c '^// C twin: ' "$f")"; done | sed 's/ $//')), in manylods.h's order"
echo "$passed passed, $failed failed"
[ "$failed" = 0 ]
