#!/bin/sh
# bench/readme_figures.sh - the benchmark figures README.md shows, from the
# files `make bench` writes; never copied by hand.
#
#   bench/readme_figures.sh [FIGURES]                 print the block
#   bench/readme_figures.sh --update README [FIGURES] rewrite README's block
#
# Input: FIGURES (default docs/bench_figures.txt), which bench/report.c
# (write_figures) writes beside docs/BENCHMARKS.md in the same run: lines
# "key=value", each value as BENCHMARKS.md prints it, "#" lines comments.
# The keys read here:
#   run.date run.machine run.compiler run.flags run.threads run.embree
#   object.views object.map_px object.n object.cut_splat_ms object.embree_ms
#   object.wrong object.exact_wrong object.splat_pts object.spheres_pts
#   object.spheres_time object.ism_pts        (largest N, epsilon 1, basic cut)
#   object.same_ms object.full_splat object.part_kept object.part_tiles object.part_patched
#   object.part_pixels object.part_cut        (the Targets' frames that change little)
#   object.budget object.budget_ms object.budget_allowed object.budget_spent
#   object.budget_basic_ms object.budget_updates (the lazy budget's row)
#   object.ir_ms object.ir_basic_ms object.ir_ratio object.ir_redrawn
#                                             (instant radiosity, Metropolis-Hastings VPLs)
#   room.wrong room.exact_wrong room.splat_pts room.spheres_pts room.spheres_time
#   views.map_px views.group_radius views.COUNT.ms views.COUNT.embree_ms
#       (COUNT in VIEW_ROWS below, and views.most)
#   views.most views.most.wrong views.most.exact_wrong views.most.splat_pts
#   views.most.spheres_wrong views.most.spheres_time views.most.memory
#   views.MOST.grouped_ms                     (MOST: the value of views.most)
# A missing key stops it (exit 1, the key named) before anything is written.
#
# Output: the lines from "<!-- bench:begin ..." to "<!-- bench:end -->",
# both included: which run, a table (setting | manylods | Embree) and the
# sentences with the error figures.  --update replaces README's lines
# between those markers, which must stand there once each, in that order.
# `make bench` runs --update at its end, `make readme-figures` without a
# run; tests/check_readme_figures.sh compares README.md with a fresh print.
set -u
LC_ALL=C
export LC_ALL
root=$(dirname "$0")/..
# the view counts with a row of their own; the most views close the table
VIEW_ROWS="1024 65536 262144"

readme=
if [ "${1:-}" = --update ]; then
    [ $# -ge 2 ] || { echo "usage: $0 [--update README] [FIGURES]" >&2; exit 2; }
    readme=$2
    shift 2
fi
figures=${1:-$root/docs/bench_figures.txt}
[ -r "$figures" ] || { echo "$0: cannot read $figures (written by make bench)" >&2; exit 1; }

block() {
    awk -v rows="$VIEW_ROWS" -v source="$figures" '
    function fig(key) {
        if (!(key in F)) { missing = missing " " key; return "?" }
        return F[key]
    }
    # 1048576 -> "1 M", 65536 -> "64 k"
    function lights(n) {
        if (n % 1048576 == 0) return (n / 1048576) " M"
        if (n % 1024 == 0) return (n / 1024) " k"
        return n
    }
    function say(line) { out = out line "\n" }
    /^#/ || !/=/ { next }
    { key = $0; sub(/=.*/, "", key); value = $0; sub(/^[^=]*=/, "", value); F[key] = value }
    END {
        most = fig("views.most")
        say("<!-- bench:begin: written by make bench from docs/bench_figures.txt (bench/readme_figures.sh); make readme-figures rewrites it, make test compares -->")
        say("From the run of " fig("run.date") " on " fig("run.machine") ", with " fig("run.threads") ", " \
            fig("run.compiler") " `" fig("run.flags") "` and Embree " fig("run.embree") ":")
        say("")
        say("| setting | manylods | Embree |")
        say("|---|---:|---:|")
        say("| " fig("object.views") " lights, " fig("object.map_px") " x " fig("object.map_px") " maps, " \
            sprintf("%.3g M", fig("object.n") / 1e6) "-sample object, epsilon 1 px: cut + splat | " \
            fig("object.cut_splat_ms") " ms | " fig("object.embree_ms") " ms |")
        n = split(rows, count, " ")
        for (i = 1; i <= n; i++)
            say("| " lights(count[i]) " lights" \
                (i == 1 ? ", MegaViews, 2 x " fig("views.map_px") " x " fig("views.map_px") " maps, room" : "") " | " \
                fig("views." count[i] ".ms") " ms | " fig("views." count[i] ".embree_ms") " ms |")
        say("| " lights(most) " lights (grouped within " fig("views.group_radius") " of the diameter) | " \
            fig("views." most ".ms") " ms (" fig("views." most ".grouped_ms") " ms) | " fig("views." most ".embree_ms") " ms |")
        say("")
        say("Everything " lights(most) " lights need (scene tree, view tree, atlas, the render'"'"'s peak) fits in " \
            fig("views.most.memory") ".")
        say("Against exact visibility (a shadow ray per receiver facing the light), the default splat (tangent discs, " \
            "for a tree with cones) answers " fig("object.wrong") " % of the object'"'"'s shadow tests wrongly where " \
            "exact maps of the same resolution answer " fig("object.exact_wrong") " % (" fig("object.splat_pts") \
            " points), " fig("room.wrong") " % of the room'"'"'s against " fig("room.exact_wrong") " % (" \
            fig("room.splat_pts") "), and with MegaViews'"'"' 2 x " fig("views.map_px") " x " fig("views.map_px") \
            " maps at " lights(most) " lights " fig("views.most.wrong") " % against " fig("views.most.exact_wrong") \
            " % (" fig("views.most.splat_pts") ").")
        say("Sphere discs (`mlod_atlas_desc.splat` `MLOD_SPLAT_SPHERES`, conservative) add " fig("object.spheres_pts") \
            ", " fig("room.spheres_pts") " and " \
            sprintf("%+.2f", fig("views.most.spheres_wrong") - fig("views.most.exact_wrong")) \
            " points there; the default takes " fig("object.spheres_time") "x, " fig("room.spheres_time") \
            "x and " fig("views.most.spheres_time") "x their time (the splat of the same cut on the object and the room; MegaViews'"'"' render).")
        say("ISM given the time of the incremental cut + splat adds " fig("object.ism_pts") " points on the object.")
        say("A frame where nothing changed costs " fig("object.same_ms") " ms for the object'"'"'s cut + splat (a full splat: " \
            fig("object.full_splat") "); with the top eighth of the object moving under still lights the incremental cut takes " \
            fig("object.part_cut") " a basic cut'"'"'s time and the splat draws " \
            fig("object.part_tiles") " tiles whole and patches " fig("object.part_patched") " (" fig("object.part_kept") \
            " the full splat'"'"'s time) where " fig("object.part_pixels") " of the pixels change.")
        say("With the lights turning 10 degrees per frame, a lazy update given a budget of " fig("object.budget") \
            " node-views spends " fig("object.budget_spent") " of them in " fig("object.budget_ms") \
            " (the target, 1.2 times the budget'"'"'s share of a basic cut'"'"'s " fig("object.budget_basic_ms") ": " \
            fig("object.budget_allowed") ") and reaches the basic cuts " fig("object.budget_updates") \
            " updates after the lights stop.")
        say("In the demo'"'"'s room with the torus twisting and the VPLs drawn by Metropolis-Hastings chains " \
            "(examples/instant_radiosity --sampling), a frame'"'"'s incremental cut + kept atlas takes " fig("object.ir_ms") \
            " against " fig("object.ir_basic_ms") " for basic cuts and full splats of the same VPLs (" fig("object.ir_ratio") \
            "; " fig("object.ir_redrawn") " of the tiles drawn again), with the same maps bit for bit.")
        say("<!-- bench:end -->")
        if (missing != "") {
            print "bench/readme_figures.sh: " source " lacks" missing " (make bench writes them)" > "/dev/stderr"
            exit 1
        }
        printf "%s", out
    }' "$figures"
}

if [ -z "$readme" ]; then
    block
    exit
fi

# --update: the block into README in place of the old one
tmp="$readme.tmp.$$"
trap 'rm -f "$tmp" "$tmp.block"' EXIT
block >"$tmp.block" || exit 1
awk -v blockfile="$tmp.block" -v name="$readme" '
    /^<!-- bench:begin/ { begins++; if (begins == 1 && !ends) { while ((getline line < blockfile) > 0) print line; inside = 1 }; next }
    /^<!-- bench:end -->$/ { ends++; if (!inside) bad = 1; inside = 0; next }
    !inside { print }
    END {
        if (begins != 1 || ends != 1 || bad) {
            printf "bench/readme_figures.sh: %s needs one line \"<!-- bench:begin ...\" and then one \"<!-- bench:end -->\" (found %d and %d)\n", name, begins, ends > "/dev/stderr"
            exit 1
        }
    }' "$readme" >"$tmp" || exit 1
cat "$tmp" >"$readme" # keeps README's mode and links
echo "bench/readme_figures.sh: wrote the benchmark figures of $figures into $readme"
