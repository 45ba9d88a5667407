#!/bin/sh
# fuzz/make_megaviews_corpus.sh - write the seeds of fuzz/fuzz_megaviews.c
# into fuzz/corpus/megaviews/ (run from anywhere; rewrites the seed-* files).
# Each seed is the harness's header (its flags byte, then the failing
# allocation when bit 4 asks for one, the chance of hostile fields when
# bit 7 does) and 1200 bytes of a Park-Miller generator from a fixed start:
# the harness reads every field from them.  The starts were picked so that
# each seed without hostile fields renders, and the delta = 0 ones compare
# with the per-view path (MANYLODS_FUZZ_VERBOSE=1 shows how far each got).
set -eu
export LC_ALL=C
cd "$(dirname "$0")/corpus" && mkdir -p megaviews && cd megaviews
rm -f seed-*
seed() { # NAME HEADER START
    {
        printf "$2"
        awk -v x="$3" 'BEGIN { for (i = 0; i < 1200; i++) { x = (x * 16807) % 2147483647; printf "%c", int(x / 8388608) } }'
    } >"seed-$1"
}
# flags: 1 mesh, 2 normals, 4 colours, 8 hook, 16 a failing allocation,
# 32 directions, 64 per-view half fields of view, 128 hostile
seed points-omni '\000' 8919
seed points-cones-colours '\006' 8919
seed mesh-cones-colours '\007' 8919
seed points-directions '\040' 32676
seed points-directions-fovs-cones-colours '\146' 40595
seed mesh-directions-fovs-hook '\157' 16838
seed points-colours-hook '\016' 1000
seed points-failing-allocation '\026\050' 1000
seed points-directions-failing-allocation '\066\132' 8919
seed points-hostile-low '\206\010' 48514
seed points-hostile-high '\246\100' 8919
seed mesh-directions-fovs-hostile '\347\030' 230651
seed points-hostile-failing-allocation '\366\036\040' 569253
