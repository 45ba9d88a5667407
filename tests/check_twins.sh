#!/bin/sh
# tests/check_twins.sh - every C function of manylods.h with a GLSL twin in
# shaders/common.glsl names it in a line "/* GLSL twin: NAME */" just above
# its definition, and the twin names it back in a line "// C twin: mlod__X"
# just above its own; the pairs stand in the same order in both files.
# Fails on a tag whose partner is missing, does not name it back, or stands
# elsewhere in the order.  Prints "N passed, M failed" for tests/run.sh.
cd "$(dirname "$0")/.." || exit 1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# C: "c_name glsl_name" per tag, in file order (the definition is the next line).
awk '/^\/\* GLSL twin: / { twin = $4; next }
     twin != "" { if (match($0, /mlod__[a-z0-9_]+/)) print substr($0, RSTART, RLENGTH), twin; else print "?", twin; twin = "" }' \
    manylods.h >"$tmp/c"
# GLSL: "c_name glsl_name" per tag, in file order (the definition follows the tag's comment lines).
awk '/^\/\/ C twin: / { twin = $4; next }
     twin != "" && /^\/\// { next }
     twin != "" { line = $0; sub(/\(.*/, "", line); sub(/\[.*/, "", line); n = split(line, w, " "); print twin, w[n]; twin = "" }' \
    shaders/common.glsl >"$tmp/glsl"

passed=0
failed=0
check() { # condition-status, message
    if [ "$1" = 0 ]; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL: $2"; fi
}
[ -s "$tmp/c" ] && [ -s "$tmp/glsl" ]
check $? "no twin tags found (manylods.h: $(wc -l <"$tmp/c"), shaders/common.glsl: $(wc -l <"$tmp/glsl"))"
while read -r c g; do
    grep -qx "$c $g" "$tmp/glsl"
    check $? "manylods.h: $c names the GLSL twin $g, which does not name it back (or does not exist)"
done <"$tmp/c"
while read -r c g; do
    grep -qx "$c $g" "$tmp/c"
    check $? "shaders/common.glsl: $g names the C twin $c, which does not name it back (or does not exist)"
done <"$tmp/glsl"
cmp -s "$tmp/c" "$tmp/glsl"
check $? "the pairs stand in another order in the two files:
$(diff "$tmp/c" "$tmp/glsl" | sed 's/^/    /')"
echo "$(wc -l <"$tmp/c") twin pairs, in the same order in manylods.h and shaders/common.glsl"
echo "$passed passed, $failed failed"
[ "$failed" = 0 ]
