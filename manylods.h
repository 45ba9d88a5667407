/* manylods.h - v0.1.0 - many-view level of detail on the CPU, single header, C99 / C++

   Pick, for hundreds to a million views at once (virtual point lights, light
   probes, reflection maps, micro-views of point-based GI), the right level of
   detail of a scene from a bounding sphere hierarchy.  After

     M. Hollaender, T. Ritschel, E. Eisemann, T. Boubekeur: "ManyLoDs: Parallel
     Many-View Level-of-Detail Selection for Real-Time Global Illumination",
     EGSR 2011;  and  T. Kol et al.: "MegaViews", Computer Graphics Forum 2018.

   This comment is the manual and the one home of the definitions the code
   honours (the tree, the criterion, the cut, the splat); README.md gives an
   overview and the benchmark figures, and points here.

   CONTENTS (search for a title to get there)
     Manual (this comment)
       USAGE                              one file holds the implementation
       QUICK EXAMPLE                      a tree, then a cut for every view
       CONFIGURATION                      allocator, assert, SIMD, linkage
       FLOATING POINT                     compiler flags; bit-exact results
       PIPELINE                           build, refit, cut
       TREE LAYOUT                        the implicit heap, containment
       SAMPLING                           stratified samples on a mesh
       BUILD                              median splits, axis by volume
       VIEWS AND THE CRITERION            sub-projections; c(node, view)
       THE CUT                            basic, incremental, lazy; filters
       SPLATTING                          drawing the cuts into an atlas
       CHOOSING THE VIEWS                 importance sampling (mlod_sample)
       MANY VIEWS AT ONCE                 MegaViews: view tree, pairs, fusion
       THREADS                            the mlod_parallel hook
       ERRORS                             mlod_result, mlod_error
       MEMORY                             bounds before allocating; huge pages
       LICENSE
     Code: the declarations, in header order, each documented where it
     stands (search for "- title *")
       results                            mlod_result, mlod_error
       allocation and threads             mlod_allocator, mlod_parallel
       input                              mlod_mesh, _points, _build_desc
       the tree                           mlod_tree, mlod_build_*, _refit_*
       views                              mlod_view, mlod_criterion, frames
       cut                                mlod_cut_*
       projection                         mlod_view_project, _pixel_ray
       atlas                              mlod_atlas_*, mlod_splat, _splat_ism
       shadow lookups                     mlod_atlas_lookup, mlod_atlas_shadow
       choosing N                         mlod_suggest_sample_count
       choosing the views                 mlod_sample
       many views at once: MegaViews      mlod_view_tree_*, mlod_megaviews_*
       built-in thread pool               mlod_pool_* (MANYLODS_PTHREADS)
     Code: the implementation (search for "- title --")
       errors                             mlod_result_name, the messages
       allocation                         the allocator, huge-page advice
       float helpers                      vectors, sin, cos, atan2
       sphere and cone merge              enclosing spheres and normal cones
       tree shape                         depths, mlod_tree_depth_nodes
       parallel run                       tasks, with or without a hook
       input checks                       meshes, points, build descs
       tree allocation                    the arrays; parents from children
       sampling                           samples on triangles
       the build                          sorts, splits, mlod_build_*
       refit                              mlod_refit_*
       exact plane predicate              exact sides of culling planes
       views                              sub-projections, mlod_criterion
       float filter                       the cut's float filter, one node
       vector float filter                the same in vector lanes
       cut                                the three modes, mlod_cut_*
       projection                         a sphere's image discs
       the splat's float filter           small discs; mlod_view_project
       atlas                              mlod_atlas_create, _bound
       splat                              bands, plotting pixels
       tangent discs                      drawing nodes; mlod_splat, _ism
       pull-push                          mlod_atlas_fill_holes
       shadow lookups                     mlod_atlas_lookup, mlod_atlas_shadow
       choosing N                         mlod_suggest_sample_count
       choosing the views                 mlod_sample's two samplers
       MegaViews                          (its parts below)
       MegaViews: the view tree           mlod_view_tree_*, eyes' floors
       MegaViews: pair bounds             cones, diameters, motion over a ball
       MegaViews: the traversal's state   view nodes, outputs, the job
       MegaViews: classifying node pairs  cull, draw or split, exactly
       MegaViews: the float pair filter   the same in float vector lanes
       MegaViews: a level's units         the pairs a level classifies
       MegaViews: drawing and fusion      maps from the parent's (inherit)
       MegaViews: level by level          the descent, tasks, memory, checks
       MegaViews: the subtree walks       the 64 subtrees, depth first
       MegaViews: the render              mlod_megaviews_render, _bound, _query
       pthreads thread pool               mlod_pool_* (MANYLODS_PTHREADS)

   USAGE
     In exactly one C or C++ file:
         #define MANYLODS_IMPLEMENTATION
         #include "manylods.h"
     Everywhere else just #include "manylods.h".
     Define MANYLODS_STATIC as well to give the implementation internal linkage
     (private copies in several files).  Define MANYLODS_PTHREADS with the
     implementation to get the built-in thread pool (mlod_pool_*), then link
     with -pthread; the default build needs no thread library.

   QUICK EXAMPLE (examples/minimal.c is the same, complete)
     mlod_mesh mesh = {.positions = xyz, .vertex_count = nv,
                       .indices = tris, .index_count = 3 * nt};
     mlod_build_desc desc = {.sample_count = 100000, .seed = 1};
     mlod_cut_params params = {.mode = MLOD_CUT_BASIC, .epsilon = 1.0f};
     mlod_tree *tree; mlod_cut *cut; mlod_error err;
     if (mlod_build_mesh(&mesh, &desc, &tree, &err) == MLOD_OK &&
         mlod_cut_create(view_count, NULL, &cut, &err) == MLOD_OK &&
         mlod_cut_update(cut, tree, views, &params, &err) == MLOD_OK)
         draw(mlod_cut_get(cut, 0));   // .nodes[0 .. .count), .status[]
     else fprintf(stderr, "manylods: %s\n", err.message);

   CONFIGURATION (define before the implementation)
     MANYLODS_MALLOC(size, user) / MANYLODS_FREE(ptr, user)
                     default allocator; define both or neither.  The per-call
                     mlod_allocator struct overrides them.
     MANYLODS_ASSERT(x)   internal consistency checks (default: assert).
                     Never used on user input: bad input returns an error.
     MANYLODS_NO_SIMD     no vector code (the cut's and the splat's float
                     filters run on scalars, MegaViews' pair filter not at
                     all); the same results either way (VECTOR LANES).
     MANYLODS_NO_AVX2     no AVX2 (nor AVX-512) lanes beside an SSE2
                     build, so no processor test at run time (VECTOR LANES).
     MANYLODS_NO_AVX512   no AVX-512 lanes beside the AVX2 ones.
     MANYLODS_SELF   the name under which the implementation includes its
                     own file again, once per vector level (default
                     "manylods.h", found in the file's own directory):
                     define it where the file has another name.
     MANYLODS_NO_HUGE_PAGES  no madvise of large buffers (MEMORY).
     MANYLODS_DEF    what every public declaration and definition starts
                     with (default: extern, extern "C" in C++, or static
                     with MANYLODS_STATIC), e.g. to add a visibility or
                     dllexport attribute; define it the same in every file.

   FLOATING POINT
     The implementation computes IEEE binary32/binary64 arithmetic exactly
     as written, so that every build of it gives the same trees, cuts and
     images bit for bit, and the bits manylods_vk.h's shaders compute.  The
     flags of the translation unit that holds MANYLODS_IMPLEMENTATION:
       -O0 .. -O3, -march=native, -mfma, -std=c99/gnu11/c++NN: any; the
         implementation turns off the fusing of a * b + c into one
         multiply-add for its own code (gcc in its GNU modes and clang
         within an expression fuse by default once the target has FMA).
       -ffp-contract=fast: the same results with gcc, and with clang on
         x86, where the implementation is compiled for its target without
         FMA instructions (and its public functions are never inlined into
         the caller), except the cut's vector filter, whose decisions are
         exact fused or not (THE CUT); clang on other targets (AArch64)
         fuses whatever a pragma says and defines no macro to tell: do not
         use it there.
       -funsafe-math-optimizations, -fassociative-math, -freciprocal-math,
         -fno-signed-zeros: refused with an #error under gcc (which defines
         macros for them); harmless under clang (which does not), where the
         implementation turns them off with float_control(precise).
       -ffast-math, -Ofast, -ffinite-math-only: refused with an #error
         (finite-only math would drop the checks that refuse NaN input).
     Other translation units may use any flags.  Other compilers: build
     the implementation without floating-point contraction or fast math.
     tests/compile/matrix.sh checks every line above (the fp-* entries).

   VECTOR LANES
     The float filters that decide most node-views (the cut's, the
     splat's small discs and plane tests, MegaViews' pair filter) run in
     float vector lanes, at one of the levels of mlod_simd:
       MLOD_SIMD_AVX512 x86-64: the same 8 lanes compiled for AVX-512
                        (F, VL, DQ, BW: 32 registers, mask registers;
                        gcc builds only), where the processor and its OS
                        have them (about 8 % faster cuts than AVX2 on
                        the bench's AMD EPYC)
       MLOD_SIMD_AVX2   x86-64: 8 lanes, where the processor and its OS
                        have AVX2 (cpuid and xgetbv, read once)
       MLOD_SIMD_SSE2   x86: 4 lanes (every x86-64 build)
       MLOD_SIMD_NEON   AArch64: 4 lanes (every AArch64 build)
       MLOD_SIMD_NONE   scalar code (other processors, MANYLODS_NO_SIMD)
     A plain build (-O2, no -m flags) on x86-64 with gcc 5 or later or
     clang 9 or later holds the SSE2 and the AVX2 lanes, and with gcc the
     AVX-512 ones (each compiled for its target with gcc's and clang's
     target pragmas), and runs the best one the processor has, with no
     flag; a build for AVX2 or AVX-512 (-mavx2, -march=native on such a
     processor) has its own lanes only.  (clang holds no AVX-512 pass:
     under -ffp-contract=fast it fuses a * b + c whatever a pragma says,
     and AVX-512 has FMA instructions.)
     Every build also holds the scalar code.  mlod_simd_level says which
     level runs; mlod_simd_limit lowers it at run time (for comparisons:
     tests/test_simd.c runs every level in one process and compares cuts,
     atlases and renders); MANYLODS_NO_AVX2 leaves the AVX2 lanes out,
     MANYLODS_NO_AVX512 the AVX-512 ones,
     MANYLODS_NO_SIMD every vector instruction.  The splat's exact depths
     of tangent discs and sphere distances run in double lanes beside
     them: 4 doubles at the AVX2 and AVX-512 levels, 2 at the others
     (none with MANYLODS_NO_SIMD), each lane the scalar steps in their
     order.  Every level computes the
     same bits: a lane decides only what the exact path would (THE CUT,
     SPLATTING), so the level is a speed, never a result.  (The lanes
     are written for 4 and 8: AVX-512 runs the 8, not 16.  clang building for FMA without
     AVX2 keeps the SSE2 lanes: its code is compiled for a target without
     FMA, see FLOATING POINT.)  MSVC builds the SSE2 lanes (not compiled
     here: the dispatch to AVX2 needs gcc's or clang's target pragmas).

   PIPELINE
     1. Build (once):   mlod_build_mesh() samples N points on a triangle mesh
        (or mlod_build_points() takes a point cloud) and orders them into a
        bounding sphere hierarchy (BSH): mlod_tree.
     2. Refit (per frame, deforming mesh, same topology): mlod_refit_mesh().
     3. Cut (per frame, all views at once): mlod_cut_update() selects for each
        view the nodes that are just small enough on screen.

   TREE LAYOUT
     N >= 1 leaves, 2N-1 nodes, implicit heap order without pointers: the
     children of node i are 2i+1 and 2i+2, its parent is (i-1)/2.  Nodes
     0 .. N-2 are internal (always two children), nodes N-1 .. 2N-2 are leaves.
     Any N works (no padding to a power of two).  Each node stores a bounding
     sphere (centre, radius) and, only when asked for, a normal cone (unit
     axis, half-angle), the surface area below it and the mean colour of the
     leaves below it.  A leaf is one surface sample: its sphere is centred on
     the sample and its radius is the sample's splat radius.

     Containment: every node's sphere contains its children's spheres exactly
     (in real arithmetic on the stored floats), and with slack: with d the
     distance between the centres, r_parent >= (d + r_child) * (1 + 2^-20).
     Normal cones contain their children's cones with 2^-20 rad to spare:
     angle(axis_parent, axis_child) + alpha_child + 2^-20 <= alpha_parent.  A
     half-angle >= pi means the full sphere of directions.  The slack makes
     the criterion below monotone in floating point, not just on paper.

   SAMPLING (meshes)
     N area-uniform samples, stratified: sample i sits at the position
     (i + xi_i) / N, xi_i in [0,1) hashed from (seed, i), of the cumulative
     triangle area, so a triangle whose share is s = N a / A gets between
     floor(s) - 1 and ceil(s) + 1 samples;
     inside a triangle its k samples form a jittered rank-1 lattice (the 1-D
     stratum and the golden-ratio sequence) mapped to the triangle by the
     area-preserving square-to-triangle map.  Zero-area triangles get none.
     Each sample keeps (triangle, s, t): position = V0 + s (V1-V0) + t (V2-V0).
     Splat radius of a leaf, A the total area at build time:
         r = radius_scale * sqrt(A / N)
     i.e. a disc of pi times the sample's share of the surface, enough to
     cover the surface (tests/test_build.c measures it).  Refit scales each
     leaf radius with sqrt(area_now / area_at_build) of its triangle.

   BUILD
     Top-down median splits.  Node i receives the samples of its subtree,
     split so that the left child gets exactly as many samples as it has
     leaves.  The split axis is the one whose two halves have the smaller sum
     of bounding volumes, where the volume of a set is that of the sphere
     around its axis-aligned box (proportional to the cube of the box
     diagonal; robust for flat and degenerate sets); ties go to x, then y.
     The three axis orders are sorted once (radix sort) and kept sorted by
     stable partitions, as Wald and Havran build kd-trees: O(N log N) total.

   VIEWS AND THE CRITERION
     A view is one to six SUB-PROJECTIONS, each a plain projection
     (perspective, paraboloid or orthographic) with its own frame (u, v, w)
     = (right, up, forward), its sub-tile (a rectangle of the view's tile)
     and its culling half-spaces; the view's kind only says how its
     sub-projections are made (mlod_view_frame_of shows them):
       PERSPECTIVE, PARABOLOID, ORTHOGRAPHIC  one sub-projection, the whole
                                   tile, the view's own frame;
       DUAL_PARABOLOID             two paraboloids: the front (+w) in the
                                   left half of the tile, W/2 x H, and the
                                   back (-w, frame (-u, v, -w)) in the right;
       CUBE                        six 90-degree perspective faces of s x s
                                   pixels in a 3s x 2s tile (see CUBE MAPS).
     A sphere REACHES a sub-projection when it lies in all of that
     sub-projection's culling half-spaces (tested exactly).
     c(node, view) = diameter, in pixels of the view's tile, of the image of
     the node's bounding sphere: the largest, over the sub-projections the
     sphere reaches, of the exact diameter of its image there, which bounds
     the node's projected size from above.  Culling is decided first: c = 0
     when the node is culled (it reaches no sub-projection, or it faces
     away, see BACK-FACE CULLING), even when the eye is inside its sphere; a
     sphere of radius 0 (a point) also has c = 0, and the cut's status
     tells the two apart, except at a paraboloid's eye (d = r = 0, the
     rule below: +inf; perspective and cube views cull a point there by
     their near plane).  A sub-projection's diameter is +inf exactly where the image is
     unbounded: perspective when x.w <= r (the sphere reaches the eye's
     plane, the eye inside or on it included); paraboloid when d <= r (the
     eye inside or on the sphere) or x.w + sqrt(d^2 - r^2) <= 0;
     orthographic never.  Notation: e eye, (u, v, w) the sub-projection's
     frame, x = centre - e, d = |x|, r radius, W x H its sub-tile.

     PERSPECTIVE (pinhole, vertical field of view fov_y, square pixels,
       focal length f = (H/2) / tan(fov_y/2) pixels):
         c = f * 2 r sqrt(d^2 - r^2) / ((x.w)^2 - r^2)      if x.w > r
       (the major axis of the image ellipse: f (tan(t+b) - tan(t-b)) with t
       the angle of the centre off the axis and b = asin(r/d)), +inf if
       x.w <= r.  Culling half-spaces: the six frustum planes (near, far,
       and the four sides through the eye).
     PARABOLOID (hemispherical, a virtual point light at e with normal w;
       direction y maps to (y.u, y.v) / (1 + y.w) in [-1,1]^2, which is a
       stereographic projection, so spheres map to circles):
         c = (max(W,H)/2) * 2 r / (x.w + sqrt(d^2 - r^2))    (+inf if <= 0)
       Culling half-space: the front of the plane (x.w + r >= 0).  A dual
       paraboloid's two halves are two of these, so together they cull
       nothing.
     ORTHOGRAPHIC (a directional light: box of half-extents half_width
       x half_height around e, depth range [near_plane, far_plane] along w):
         c = 2 r * max(W / (2 half_width), H / (2 half_height))
       Culling half-spaces: the six faces of the box.
     CUBE MAPS (kind MLOD_VIEW_CUBE, the reflection-probe format): six
       perspective faces with fov 90 degrees (f = s/2), near_plane and
       far_plane, in the order and orientation of Vulkan's and OpenGL's
       cube maps (layer i = face i) over the axes X = u, Y = v, Z = -w (so a
       view with forward (0,0,-1) and up (0,1,0) is the world-axis cube):
         face  0 +X  1 -X  2 +Y  3 -Y  4 +Z  5 -Z
         w     u     -u    v     -v    -w    w      (the face's axis)
         u     w     -w    u     u     u     -u     (its pixel x, rightwards)
         v     v     v     w     -w    v     v      (its pixel y, upwards)
       Face i is the s x s square at (s (i mod 3), s (i div 3)) of the
       3s x 2s tile.  A direction's face is the one whose axis it is
       closest to (on a tie, the lower face).
     BACK-FACE CULLING (view flag MLOD_VIEW_CULL_BACKFACES, trees with cones):
       a node is also culled when every point of its sphere with every normal
       of its cone faces away from the eye: angle(axis, e - centre) >
       pi/2 + alpha + asin(r/d) (for orthographic views the direction to the
       eye is -w and the asin term is 0).
     Monotone: a child inside its parent has c(child) <= c(parent) for every
     view, culling included (it reaches no sub-projection its parent does
     not, and each diameter is monotone).  The plane tests are evaluated exactly (a
     floating-point filter with an exact expansion-arithmetic fallback); the
     diameters are computed in double precision, whose error the tree's
     slack of 2^-20 dominates.

   THE CUT
     valid(n, v) <=> c(n, v) <= epsilon (epsilon in pixels, > 0).  The cut of a
     view is every valid node whose parent is not valid (the root if valid),
     plus every leaf whose parent is not valid although it is not valid
     either (an oversize leaf: drawn and counted).  Culled nodes stay in the
     cut, marked culled.  The subtrees of a view's cut partition the leaves.
     Each view's cut is listed left to right (the order of the leaves), so
     equal cuts are equal lists.
     MLOD_CUT_BASIC        computes the cut from the root.
     MLOD_CUT_INCREMENTAL  starts from the previous call's cut of the same
                           views: invalid nodes split (down to the cut),
                           valid sibling pairs whose parent is valid merge
                           (through the left child), until nothing changes.
                           The result equals the basic cut, node for node.
     MLOD_CUT_LAZY         the same actions, but at most lazy_steps one-edge
                           moves per node and view and call.  Always a
                           partition; may still hold nodes finer than needed
                           (drawn) or coarser (status MLOD_STATUS_COARSE);
                           converges to the basic cut when views stop.
     Unchanged views are not evaluated, in any mode: an update keeps a
     view's list, with evaluated = steps = 0, when the view (every byte of
     its mlod_view), the tree (the same mlod_tree, with the same revision:
     no mlod_refit_* since) and epsilon are those of the cut's previous
     update and that update left the view's cut exact (the basic cut:
     every basic and incremental update does; a lazy one when it made no
     move for the view).  Every mode would compute that same list again
     (a lazy step finds nothing to do on the basic cut), so results do not
     change; one byte of the view, epsilon, a refit, another tree or
     mlod_cut_reset recomputes the view as before.  A skipped view costs a
     comparison of its bytes (about 4 ns), plus two copies of its list
     while other views of its window change (an update goes through the
     views a window of about 2^18 entries at a time; a window of
     unchanged views is not touched).  A tree is known by its address and revision,
     which starts at a number no earlier tree of the process had: a tree
     built where a destroyed one stood is another tree to the cut.
     Unchanged nodes are not evaluated either, in incremental and lazy
     updates: when only refits changed the tree since such a view's exact
     list (the same view bytes, epsilon and tree, its revision moved on by
     mlod_refit_* alone, fewer than 2^32 times), an entry whose node and
     parent no refit changed since (mlod_tree.changes: their sphere and
     cone are the same bits) keeps its status unevaluated, and its parent,
     invalid in that list, is still invalid: no merge is tried.  Only the
     entries in or next to what moved are evaluated, so an animated part
     of a static scene costs in proportion to its share of the cut; the
     others are carried as whole runs (the entries below a subtree no
     refit changed are consecutive in the list): they are copied once, not
     read entry by entry, and neither counted nor compared again (4.1 M
     entries, one vertex moving: 4.7 ms on two threads, where a basic cut
     takes 55).  The result is what the update computes without the
     record (every entry evaluated), entry for entry (tests/test_cut.c,
     groups skip and unchanged runs).  Moving a
     view, another epsilon or a revision counted up by other code
     evaluates every entry of the views concerned, and so does a refit
     that changed more than half the tree (of the internal nodes at depth
     10: mlod_tree.changes_share), where looking at the record would cost
     more than it saves (the object protocol twisting all over: an
     incremental update took 45 ms instead of 40).
     Decisions are exact, and fast: each node-view first goes through a
     float filter (the criterion in float, x = centre - eye subtracted in
     double, or in float where the eye's coordinates are floats, with
     margins proven from its rounding errors: 2^-12 relative on the
     diameter, 2^-20 of the plane's norm times |x| + r plus its offset on
     each plane; the proof is beside mlod__fast_status) that
     decides valid, invalid or culled only where its margin makes the
     exact path's answer certain, and leaves the rest (about 0.2 % of
     node-views of random views in tests/test_cut.c: near epsilon, a
     plane or the eye) to the exact double path.  The splitting search
     splits the run of coarse entries next in line (up to 32) at once and
     classifies their children together, and an update's input entries
     likewise, in vector lanes (VECTOR LANES): 8 lanes with AVX2 (a pair
     of children's rows, adjacent in the tree, in one load), 4 with SSE2
     or NEON; the lanes'
     statuses leave as bytes in one store.  A paraboloid view (the views
     of virtual point lights) or a perspective one, eye in floats, runs a
     copy of the lanes compiled for its shape, its constants in registers
     (a quarter faster than the lanes for any shape).  MANYLODS_NO_SIMD
     turns them off.  Every build gives the same cuts, bit for bit.
     manylods_vk.h's cut shaders run the same filter, from the floats of
     mlod_view_filter_of, before their double path.
     Incremental and lazy rounds classify the parents their merges ask
     for, and the children of a lazy round's splits, in the same lanes
     (a segment's at once), and pass over runs of statuses with nothing
     to split 8 at a time while planning.
     A budget.  A lazy update given mlod_cut_params.budget = B > 0 (node-
     views, the unit of mlod_cut_view.evaluated) evaluates at most B in
     all: for a real-time frame of fixed cost, whatever the views and
     the tree did.  The views it would update (those not skipped as
     unchanged) are taken oldest first, by the update that last evaluated
     them (equal ones in view order), and each is updated while its bound
     still fits in what is left of B; the others are deferred.  What the
     views taken cost below their bounds goes to the deferred ones in
     another pass over the windows, the same way, up to four passes in
     all (each pass about halves what is left).  The bound
     of a view whose list holds n entries is 3 n (2^q - 1) node-views for
     q = lazy_steps: a round evaluates at most 3 per entry of its input
     (the entry itself, then either the two children it splits into or
     its pair's parent) and at most doubles the entries.  A deferred view
     keeps its list entry for entry, unevaluated (mlod_cut_view.deferred
     = 1, evaluated = steps = 0): still a partition of the leaves, drawn
     as it is, but its statuses are those of the view and tree it was
     computed for (a node since culled is drawn, one since turned towards
     the view may stay culled) until an update reaches it.  Its version
     moves when its view's bytes did (mlod_splat then redraws its tile
     with the view it is given).  The oldest-first order visits every view
     in turn, so once the views and the tree stop, the lists converge to
     the basic cuts as without a budget, provided B holds the bound of
     the largest view's list (a view whose bound exceeds B is never
     updated).  The views' actual cost is below their bounds (about 1.4
     node-views per entry rather than 3 on the protocol of bench/, the
     object under the rig turning 10 degrees per frame), so the passes
     spend most of B: 0.99 B there with B = 1 M.  Views
     that a budget leaves out for many updates stay coarse or fine where
     the view has moved since; spend more where that shows.  Updates
     from the roots (a cut's first, after mlod_cut_reset, or with a tree
     of another node count) give every view its list whatever the budget:
     at most 3 (2^q - 1) node-views per view.  The other modes refuse a
     budget (MLOD_ERROR_INVALID_ARGUMENT), and so does manylods_vk.h.

   SPLATTING
     mlod_splat() draws every drawn node of every view's cut into the view's
     tile of one atlas (mlod_atlas: a grid of tiles, depth plus optional
     normal and colour channels), in every sub-projection the node's sphere
     reaches, clipped to that sub-projection's sub-tile; nearest depth wins,
     and of equal depths the lower node index, so that a pixel is the least
     (depth, node) of what covers it and no atlas depends on the order of
     the draws (the cut's order, threads, a device's atomics).
     The node's disc is the disc around the exact image of its bounding
     sphere, centred on the image's centre, of its diameter there
     (paraboloids: at the larger of their two pixel scales), so it covers
     the node's whole image; its radius is times mlod_atlas_desc.disc_scale.
     What the node draws there depends on mlod_atlas_desc.splat:
       MLOD_SPLAT_TANGENT (the default, MLOD_SPLAT_AUTO, for a tree with
         cones): the node's tangent disc, the disc of the sphere's radius
         (times disc_scale) through the sphere's centre c, normal to its
         cone's axis n.  A pixel whose centre lies in the node's disc casts
         its centre's ray, eye + o + t dir (the ray of mlod_view_pixel_ray,
         not normalised; px, py: the centre's offsets in the sub-tile times
         the reciprocal of the scale; perspective dir = w + px u + py v,
         o = 0; orthographic o = px u + py v, dir = w; paraboloids, px and
         py in [-1, 1] across the disc, dir = 2 px u + 2 py v + (1 - q) w,
         q = px^2 + py^2 <= 1, o = 0), meets the plane at t = n.(c - eye -
         o) / n.dir, and is drawn when that point lies within the disc's
         radius of c (and t > 0 but for orthographic views), at depth t
         (perspective, orthographic: z, as dir.w = 1) or t (1 + q)
         (paraboloids: the distance, as |dir| = 1 + q), all in double, in
         that order.  A node whose cone holds every direction (half-angle
         >= pi) draws its disc's pixel centres at its centre's depth.  A disc covering
         no pixel centre draws nothing: a pixel holds what its centre sees,
         as an exact (ray-cast) map's does, and a surface of tangent discs
         leaves no holes where the cut's nodes overlap (their spheres do).
       MLOD_SPLAT_SPHERES (and MLOD_SPLAT_AUTO for a tree without cones):
         the node's disc itself, at its centre's depth: the pixels whose
         centre lies in it; at disc_scale 1 a disc covering no pixel
         centre sets the pixel holding its centre, so a cut leaves no holes
         where its surface is, at the price of a silhouette that grows by
         up to the drawn node's radius, up to epsilon / 2 pixels, and of a
         pixel that takes the nearest of the sub-pixel nodes anywhere in it
         (false shadows: docs/BENCHMARKS.md measures both).
     Depth means, in the sub-projection's frame:
       perspective (cube faces too), orthographic:  z = (p - eye) . w;
       paraboloid (dual paraboloid halves too):     |p - eye|.
     Pixel (i, j) of a tile covers [i, i+1) x [j, j+1), x to the right
     (along u), y downwards; mlod_view_project and mlod_view_pixel_ray are
     the projection and its inverse.
     mlod_atlas_desc.disc_scale draws smaller discs, sampled at pixel
     centres only; the holes left are filled by mlod_atlas_fill_holes
     (docs/GUIDE.md, "Choosing the disc scale").  mlod_splat_ism() is the Imperfect
     Shadow Maps baseline (a fixed random subset of leaves per view) and
     mlod_atlas_fill_holes() the pull-push hole filling for either.
     mlod_suggest_sample_count() gives the smallest N whose leaves are at
     most epsilon pixels in the closest view: sample only what views resolve.
     Drawing is exact and fast like the cut: a node whose disc is smaller
     than a pixel (most of them at epsilon ~1) can only draw the one pixel
     that holds the disc's centre (at a disc scale below 1 and with tangent
     discs, only where that pixel's centre lies in the disc; tangent discs
     then cast that one ray, in double); a float filter finds that pixel from
     the disc's formulas in float, with a bound on each step's rounding
     (the proof is beside mlod__fast_disc), wherever the disc's centre,
     widened by the bound, lies inside one pixel and its radius below the
     small disc's, in vector lanes (64 nodes at a time), the depth still
     computed as the double path does; every other node takes the double
     path.  In a view of several sub-projections (dual paraboloid, cube)
     the sub-projections a node reaches are found by the cut's plane
     tests in float lanes, with their margins; a lane in doubt takes the
     exact test.  The atlas is the same bit for bit (tests/test_splat.c,
     filtered_discs and reached_lanes); the object protocol's splat takes
     0.55x the double path's time (0.75x with half discs, disc_scale 0.5).
     An atlas follows its cut: mlod_splat keeps each tile that shows what
     it would draw, patches those where it can (below), and clears and
     draws the others whole.  A tile is kept
     when this atlas's last mlod_splat drew or kept it from the same cut
     at the same mlod_cut_view.version, no drawn node of it changed since
     by the tree's record of changes, and disc_scale and splat are as
     they were.  An update gives a view a new version when its view bytes
     or its drawn entries (their nodes, order, and which are culled)
     differ from the previous update's; a reset gives every view one; no
     two cuts of the process share one.  Each refit marks in
     mlod_tree.changes the leaves whose sphere, cone, colour or area bits
     it changed and the nodes above them; the nodes of a tree of another
     build, or of one whose revision other code counted up, count as
     changed (a tile that draws nothing stays).  A tile's pixels are a
     function of its view, its drawn nodes in order and their bits, so a
     kept tile is what a full redraw gives, bit for bit
     (tests/test_redraw.c compares every step with one).  A frame where
     nothing changed costs a comparison per tile; a refit costs a pass
     over the drawn entries of the tiles whose version did not move, and
     the tiles that draw what moved.
     A tile that draws what moved is patched rather than drawn whole when
     it showed the basic cut of its view at an earlier revision of the
     tree and the cut holds the basic cut of the same view and epsilon
     now (mlod_splat says when exactly).  Call a node suspect when a
     refit since changed its parent (the root: itself); a refit that
     changes a node changes every node above it, so a node that is not
     suspect kept its bits, and so did its parent: the node has the
     status it had, its parent stays invalid, and it is an entry of the
     basic cut now exactly when it was one then (a basic cut is the
     valid nodes and oversize leaves whose parent is invalid; an
     invalid parent has invalid ancestors, as a parent's sphere and cone
     contain its children's).  So the drawn entries that are not suspect
     were drawn then with the same bits, and the others are suspect.  A
     pixel holds the least (depth, node) of the discs drawn over it; one
     whose node is not suspect holds a disc still drawn, and the least of
     those still drawn that were drawn then.  A patch empties the pixels
     whose node is suspect and marks them, draws the suspect entries over
     the whole tile and the others over the marked pixels only: every
     pixel gets the least of all the drawn entries' discs, as a full
     redraw gives it, bit for bit (tests/test_redraw.c; the bench checks
     every frame).  A band of rows (64) with most of its pixels marked is
     cleared and drawn whole instead.  In a view of one square paraboloid sub-projection
     (virtual point lights) a patch draws the entries that are not
     suspect only where their directions come within reach of a marked
     pixel: each block of a quarter of the tile's width and height
     bounds its marked pixels' directions by a cone, and a sphere wholly
     outside the cones draws none of them (mlod__patch_outside gives the
     bound).  With the top eighth of the object moving under still
     lights (the bench's Targets table) every tile is patched, and the
     entries that moved, a fifth of those drawn, are most of its time.
     Other writers of the pixels (mlod_splat_ism,
     mlod_atlas_fill_holes, mlod_megaviews_render, mlodvk_atlas_download)
     and mlod_atlas_invalidate make the next mlod_splat draw every tile;
     atlas->redrawn counts the tiles drawn whole, atlas->patched the
     tiles patched.

   CHOOSING THE VIEWS (importance sampling, e.g. of virtual point lights)
     mlod_sample() draws N samples from a discrete domain of D candidates
     (potential VPLs: say the surface points a light's rays hit) in
     proportion to an importance f >= 0 the caller computes (the light a
     candidate would bring to the image), with a weight per sample such
     that (1 / N) sum_j weight_j g(sample_j) estimates sum_i g(i): a VPL
     made from candidate i carries weight_j / N times candidate i's flux.
     The random numbers depend only on the seed: keep it from frame to
     frame and the samples move only where the importance does.
       MLOD_SAMPLER_INVERSE_TRANSFORM  sample j is where u_j falls in the
         cumulative importance (u_j: the base-2 radical inverse of j,
         rotated by the seed); weight F / f(i), F = sum f.  Exactly
         proportional, but a change of f anywhere shifts the cumulative
         sum after it, and with it most samples.
       MLOD_SAMPLER_METROPOLIS  independent Metropolis-Hastings, after
         Barak, Bittner, Havran, "Temporally Coherent Adaptive Sampling
         for Imperfect Shadow Maps", EGSR 2013: sample j is the last state
         of a chain over M uniform proposals, each accepted when
         f(proposal) >= xi f(current) (xi uniform in [0, 1)); weight
         D (s / M) / f(i), s the sum of f over the chain's proposals.  A
         local change of f moves only the chains it touches.  Proposal k of
         chain j is proposal n = j + N k of a sequence that runs through
         random permutations of the domain, D proposals each, so no two
         chains share a candidate while N M <= D (the paper's disjoint
         proposals; its Halton points j + N k made the samples fail a
         chi-square test of their distribution by 6 to 25 times the
         threshold, these pass it).  For finite M the samples follow f
         only approximately (M = 1 is uniform sampling); the weights make
         the estimate exact on average where g is proportional to f.
         Elsewhere it is biased low, the more so as g / f varies and f's
         tail is heavy, and the bias falls with M only once M is large
         against f's spread.  Measured (D = 4096, N = 1024, 100 seeds),
         for g = 1 (each candidate counted once) at M = 4, 16, 64, 256:
         f spread over 51 times: -12, -7, -1.2, -0.7 % (tests/test_sample.c
         checks these); f = 1 / u (1000 times): -13, -14, -10, -4 %, -1 %
         at M = 1024; f = 1 / u^2 (10^8 times): -21 to -29 % up to
         M = 256, -10 % at M = 16384.  For g within [0.5, 1.5] f, within
         2 % in all three.

   MANY VIEWS AT ONCE (after MegaViews: T. Kol, P. Bauszat, S. Lee,
   E. Eisemann, Computer Graphics Forum 2018)
     For thousands to millions of views, mlod_megaviews_render shares work
     among views that would draw the same (manylods_vk.h's
     mlodvk_megaviews_render runs the same traversal on a Vulkan device,
     with the same atlas).  A VIEW TREE
     (mlod_view_tree_build) orders the views by median splits in the scene
     tree's layout (the implicit heap): without directions, of their eyes,
     as the scene tree orders samples; with directions, of their eyes and
     unit directions, six coordinates, each node split along the one whose
     halves have the smaller sum of (p + t q)^3, p a half's diagonal of
     eyes, q of directions, t = 0.02 times the diagonal of all the eyes
     (views of one place that look different ways, a room's corner, are
     parted where that culls more than it shares: on the bench's room 6
     to 8 % fewer pairs from 64 k to 1 M lights).  Each node bounds its
     views' eyes by a sphere (centre c, radius rho; containment as for
     scene spheres), their directions by a cone and their half fields of
     view by the smallest and largest.  A view with a direction u and half
     field of view h culls a sphere when angle(x, u) > h + asin(r / |x|)
     (never when h >= pi or the eye is inside), x = centre - eye.  Every
     view renders the same map, a dual paraboloid of one global
     orientation (mlod_megaviews_view: directions towards +z in the left
     half of the tile, -z in the right, R x R pixels each), so that an
     inner view node's map is a partial rendering all views below share.
     params.forward and up choose that orientation
     (mlod_megaviews_view_oriented: the left half looks along forward),
     both 0 keeping the default (forward +z, up +y).  A paraboloid is
     sharpest at its axis and least sharp at its rim, the seam between
     the halves, where a direction lands on the edge of both discs: point
     forward where the views look most, -y for ceiling lights in a y-up
     scene, whose "straight down" then falls in the middle of the front
     half rather than on the seam.  The bounds below read x.w (w =
     forward, unit) and the angle off w in that frame, and the float
     filter takes them from the axes rounded to float (within its proven
     margins); every result below holds for any orientation.
     The traversal starts from (scene root, view root), level by level
     down the view tree's first six levels, then depth first within each of
     the 64 subtrees below (one task each, so no two threads draw into one
     map); a pair (scene node s, view node v) is
       at a view leaf: decided as the cut decides for that view (after its
         field of view): culled, dropped; valid or an oversize leaf, drawn
         into its map; else s splits;
       at an inner view node:
         culled when no view below can see s: s's sphere grown by rho lies
           outside the views' cone widened by the largest half field of
           view, or it lies behind every eye's field of view by the view
           tree's floors (mlod_view_tree.floors: with a the cone's unit
           axis, every eye below is at least `floor` above c along a, so
           a point p of s has (p - eye).n <= x.a + r - floor + (|x| + r +
           rho) spread for each eye's unit direction n, x = s's centre -
           c; below 0, no view below sees p: this culls what lies under
           lights on a wall or floor, where the ball's reach would not),
           or (MLOD_VIEW_CULL_BACKFACES, with scene cones) faces away
           from every eye of the ball;
         drawn into v's map, as seen from c, when c(s, eye) <= epsilon for
           every eye of v's ball, or s is a scene leaf (nothing finer to
           split into: every view below draws it whole, as an oversize
           leaf where it exceeds epsilon; the near geometry of MegaViews
           3.2.4, its disc filling every pixel it covers; counted in
           stats.shared_leaves), and its image moves by at most delta pixels
           between c and any eye of the ball, it faces every eye (with
           MLOD_VIEW_CULL_BACKFACES) and, with delta = 0 only, lies within
           every field of view below.  With delta > 0 a view's direction
           and field of view act only in culling, as in the paper: a node
           shared for its view node may lie outside one view's field of
           view, and lands in that view's tile outside it (up to delta
           pixels and the pixel holding a small disc's centre inside),
           where the view's own cut leaves the tile empty;
         s splits when it has children and c(s, eye) > epsilon for every
           eye of the ball, or (delta > 0) some eyes find c <= epsilon and
           others not while both children of s are at least as large as
           the ball (MegaViews 3.2.3: the larger node splits; views below
           then get finer nodes than their own cut would give them, never
           coarser); otherwise v splits (both children take s).
       The bounds over the ball: d = |x| moves within [d - rho, d + rho]
       and x.w within [x.w - rho, x.w + rho] in the paraboloid's diameter
       S 2 r / (x.w + sqrt(d^2 - r^2)), per half; any point of the image
       moves by at most S tan(asin(rho / (d - r))) / (1 + cos(phi + b)),
       phi the angle of x off the half's axis and b = asin((r + rho) / d):
       the direction turns by at most that angle and the map's rate, 1 /
       (1 + cos), is largest at the widest angle an eye sees the sphere at.
     Draws into a map follow the atlas's splat setting (SPLATTING; the
     maps of mlod_megaviews_render_maps: MLOD_SPLAT_AUTO), from the map's
     eye (the view node's centre).
     Fusion: each inner node's map starts from its parent's, each pixel's
     node measured again from the node's own centre, then takes its own
     drawn nodes by the same rule (the least depth, then the least node
     index, the parent's node among them); a view's tile
     gets its leaf's map so, each pixel at its node's depth from the view's
     own eye (depth as for paraboloids), with the node's normal and
     colour.  Measured again means: sphere discs, the distance to the
     node's centre, d; tangent discs, where the pixel centre's ray from the
     new eye meets the node's tangent disc of the sphere's radius, the
     depth a view's own draw of that pixel gives (SPLATTING), and where it
     misses the disc, that depth on the disc's plane clamped to [d - r, d +
     r] (d + r where the plane lies behind the eye; d for a node whose cone
     holds every direction).  Maps of inner nodes hold node indices and live until their
     children have theirs; the atlas is the result.  Without fusion
     (mlod_megaviews_render_maps) every node keeps its own map, leaves
     included, and mlod_megaviews_query descends from the root to a
     view's pixel by the same rule: the fused atlas's pixel, at the cost
     of the tree's depth in lookups, for programs that read few pixels.
     delta = 0 shares only among eyes at one point (duplicates), and the
     atlas equals, bit for bit, the per-view cut (mlod_cut_update) and
     splat (mlod_splat) of the views' mlod_megaviews_view (in the params'
     orientation: mlod_megaviews_view_oriented); with
     directions, the per-view cut less what each view's field of view
     culls (nodes at equal distances included: the splat and the fusion
     both keep the least (depth, node)).  delta > 0: a shared node's disc lies within delta pixels of
     the disc the view would draw (centre and radius), the node is one the
     view would draw (or, wholly outside its field of view, one it culls),
     at its exact distance, with one exception: a node within rho (the
     sharing ball's radius) of the plane between the map's halves through
     the view's eye may reach, from the ball's centre, a half that it does
     not reach from the eye, and is drawn there too (near that half's rim,
     within delta of where that half's projection, taken past its culling
     plane, puts it from the eye), where the view draws nothing; what
     changes is which nodes a view gets
     (within epsilon for all eyes of a ball, not at its own cut) and, per
     pixel, which of them is nearest.  tests/test_megaviews.c
     checks both; docs/GUIDE.md measures the cost and the error.
     Grouping (params.group_radius g > 0; the paper's equal-depth octrees
     do the like): a view node whose sphere's radius is at most g is a
     group.  Its pairs are culled as an inner node's are, and otherwise
     decided as the cut decides for one view at its centre (without
     back-face culling there): drawn into its map, or the scene node
     splits.  Every view below gets that map, each pixel at its node's
     distance from the view's own eye: the views see the scene from up to
     g away, with the parallax that brings, and no delta bound holds
     within a group.  docs/GUIDE.md measures the error against exact maps.
     Speed: with delta > 0 and without back-face culling, the pairs of
     every view node (inner, group or leaf) are decided several at a time
     in float (4 lanes with SSE2 or NEON, 8 with AVX2), each decision taken only
     where it clears its threshold by a margin proven to exceed the float
     rounding (under 1 % of the pairs in docs/GUIDE.md's benchmark fall within
     one and take the exact double path).  A view node's pairs are
     classified a level of the scene tree at a time (the scene nodes
     handed to it, then the children of those that split, and so on: each
     level's pairs in full batches of lanes that wait on no other pair's
     answer), then listed and drawn in depth-first order, so every build,
     MANYLODS_NO_SIMD included, renders the same atlas bit for bit
     (tests/test_megaviews.c compares renders with and without the filter,
     and the lists with a plain depth-first recursion).
     Memory: the render writes each view's tile once, in the view tree's
     leaf order; an atlas created with desc.order = the tree's leaf order
     (mlod_view_tree.eyes->leaf_sources) holds those tiles side by side,
     so the writes go out in sequence rather than scattered over the
     atlas: the same pixels in each tile, a seventh less time at a million
     views (docs/GUIDE.md).
     When it pays: against the per-view cut and splat of the same maps
     (make bench, docs/BENCHMARKS.md "From how many lights the view tree
     pays": 2 threads, epsilon 1, delta 0.5, maps 2 x 11 x 11, the view
     tree's build counted), lights inside a scene (the bench's room, on
     its walls looking in) take 0.5 to 0.8 times the per-view time from
     16 lights to 1 k and a quarter at 16 k; lights around a compact object
     (the bench's object, on a sphere looking at it) take 1.2 times at 16
     to 64 lights, as much at 256, 0.9 times at 1 k and 0.3 at 16 k.
     Larger maps move the point up (2 x 32 x 32 around the object: the
     per-view path faster up to 1 k lights, the view tree from 4 k): use
     the view tree for lights inside the scene at any count, and for
     lights around it from a thousand or so.

   THREADS
     mlod_cut_update, mlod_refit_*, mlod_splat*, mlod_atlas_fill_holes,
     mlod_sample, mlod_view_tree_* and mlod_megaviews_render take an
     optional mlod_parallel hook (a parallel-for), the builds one in
     mlod_build_desc.parallel; with none they run on the calling thread.
     Work is split into tasks of bounded size within and among views, so one
     view with a cut 100x the others does not serialise the frame, nor does
     one large view alone (its cut in tasks of about 8192 entries).  Results
     are identical for any thread count.  Distinct objects may be used from
     distinct threads; one object must not be used by two calls at once.

   ERRORS
     Functions return mlod_result; the optional mlod_error receives the code
     and a readable message.  On error the caller's objects are unchanged (or,
     for constructors, the output pointer is set to NULL).  The library never
     prints, aborts or exits.

   MEMORY
     Size before you allocate: mlod_build_mesh_bound and
     mlod_build_points_bound give a build's peak bytes (exactly; N = 2^30
     needs 104 GiB: a build allocates its tree first and keeps the scratch
     of its ordering in the tree's arrays until it writes them, so it
     touches little more memory than the tree and its samples),
     mlod_cut_bound a cut's bytes, between and during updates, for a mean
     cut size (5 bytes per entry with at most an eighth to spare, about
     200 per view, and, during an update, 3 to 16 MB of buffers for one
     window of views; mlod_cut_reserve allocates those buffers beforehand
     and keeps them, after which steady frames allocate nothing),
     mlod_atlas_bound an
     atlas's bytes (exactly), mlod_sample_bound what mlod_sample takes for
     the length of the call (exactly).  Every
     object reports its bytes (mlod_tree.bytes, mlod_cut_bytes,
     mlod_atlas.bytes, mlod_view_tree.bytes).  mlod_megaviews_render
     allocates for its call, per level of the view tree's first six, what
     the pairs of that level need (24 bytes of room per pair handed down, 4
     bytes per pair kept) and the maps of the level's inner nodes that hold
     anything (8 bytes per pixel), two levels at a time; below, each of the
     64 subtree walks holds the scene nodes handed down along its path (4
     bytes each, room for four per scene node handed to its root plus 4096
     first, twice as much when short: the walk goes on from where it
     stopped, the path to it classified again) and one map
     per level (8 bytes per pixel).  It reports its peak
     (mlod_megaviews_stats.peak_bytes: 9 to 13 MB for 64 k to 1 M
     lights in docs/GUIDE.md's benchmark, against the atlas's 4 bytes per
     pixel) and the most pairs one view node classified
     (stats.node_pairs), for which mlod_megaviews_bound bounds the peak
     before the call (3.9 to 5.4 times above it in that benchmark; with the
     scene tree's node count, for any scene: far above);
     mlod_megaviews_render_maps, level by level throughout, keeps
     on top 8 bytes per pixel of every view node that drew anything
     (mlod_megaviews_maps_bytes).  mlod_splat allocates nothing, unless
     the atlas fills holes (mlod_atlas_desc.fill_holes): then the
     pull-push scratch of the tiles it draws, as mlod_atlas_fill_holes
     does for every tile.  Attributes a scene does not ask for take
     no memory.
     A failed call gives back what it allocated (a cut keeps its bytes and
     cuts).  All memory comes from the allocator given at creation (or
     MANYLODS_MALLOC/FREE, or malloc/free); the allocator is only called
     from the calling thread.  On Linux, buffers of 8 MiB or more are
     advised (madvise MADV_HUGEPAGE) to take transparent huge pages where
     the system leaves that to programs: a build of 1.3 M leaves then
     takes 4 k page faults instead of 34 k, and its process 2/3 of the
     time on the machine docs/BENCHMARKS.md's figures come from; advice only,
     ignored for memory that cannot have them.  MANYLODS_NO_HUGE_PAGES
     turns it off.

   LICENSE: MIT or public domain, your choice; see the end of this file.
*/
#ifndef MANYLODS_H
#define MANYLODS_H

#include <stddef.h>
#include <stdint.h>

#define MANYLODS_VERSION_MAJOR 0
#define MANYLODS_VERSION_MINOR 1
#define MANYLODS_VERSION_PATCH 0
/* major * 10000 + minor * 100 + patch */
#define MANYLODS_VERSION 100

#ifndef MANYLODS_DEF
#ifdef MANYLODS_STATIC
#if defined(__GNUC__) || defined(__clang__)
#define MANYLODS_DEF static __attribute__((unused))
#else
#define MANYLODS_DEF static
#endif
#else
#ifdef __cplusplus
#define MANYLODS_DEF extern "C"
#else
#define MANYLODS_DEF extern
#endif
#endif
#endif

/* Largest supported N (samples, leaves): the tree then has 2^31 - 1 nodes. */
#define MANYLODS_MAX_LEAVES 0x40000000u

/* ---------------------------------------------------------------- results */

typedef enum mlod_result {
    MLOD_OK = 0,
    MLOD_ERROR_INVALID_ARGUMENT = 1, /* NULL where an object is needed, bad enum, bad size */
    MLOD_ERROR_NON_FINITE = 2,       /* NaN or infinite number in the input */
    MLOD_ERROR_INDEX_OUT_OF_RANGE = 3, /* triangle index >= vertex count */
    MLOD_ERROR_EMPTY = 4,            /* N = 0, no triangle with area, no point */
    MLOD_ERROR_BAD_EPSILON = 5,      /* epsilon <= 0 or NaN */
    MLOD_ERROR_BAD_VIEW = 6,         /* degenerate frame, tile, field of view, planes */
    MLOD_ERROR_OVERFLOW = 7,         /* a size that does not fit (N, nodes, bytes) */
    MLOD_ERROR_OUT_OF_MEMORY = 8,    /* the allocator returned NULL */
    MLOD_ERROR_MISMATCH = 9,         /* objects that do not belong together */
    MLOD_ERROR_RANGE = 10,           /* coordinates too large for float bounds */
    MLOD_ERROR_CANCELLED = 11,       /* the progress callback asked to stop */
    MLOD_ERROR_DEVICE = 12           /* manylods_vk.h: a Vulkan call failed (device lost, ...)
                                        or the device lacks a needed feature */
} mlod_result;

typedef struct mlod_error {
    mlod_result code;
    char message[200]; /* NUL-terminated, English, no trailing newline */
} mlod_error;

/* A short constant name for a result code ("MLOD_ERROR_EMPTY").  Thread-safe. */
MANYLODS_DEF const char *mlod_result_name(mlod_result result);

/* ------------------------------------------------- allocation and threads */

/* Per-object allocator.  alloc returns memory aligned for any type, or NULL;
   free accepts NULL.  Called only from the thread that calls the library. */
typedef struct mlod_allocator {
    void *(*alloc)(void *user, size_t bytes);
    void (*free)(void *user, void *pointer);
    void *user;
} mlod_allocator;

/* The allocator used where none is given: MANYLODS_MALLOC/FREE as defined
   where MANYLODS_IMPLEMENTATION is (else malloc/free), user NULL.  For
   companions (manylods_vk.h) and wrappers.  Pure, thread-safe. */
MANYLODS_DEF mlod_allocator mlod_default_allocator(void);

/* A parallel-for: run(user, count, task, context) must call
   task(context, i) once for every i in [0, count), from any threads in any
   order, and return when all calls have returned.  Tasks never allocate and
   never call back into the hook.  A task takes up to about 80 KiB of stack
   (mlod_megaviews_render's: 60 KiB at a million views, 1 KiB more for
   each doubling of them), which every usual thread has (glibc's default
   is 8 MiB, musl's 128 KiB): only a fiber or a thread created with a
   small stack needs to mind it. */
typedef void mlod_task_fn(void *context, uint32_t index);
typedef struct mlod_parallel {
    void (*run)(void *user, uint32_t count, mlod_task_fn *task, void *context);
    void *user;
} mlod_parallel;

/* Progress: fraction in [0,1], non-decreasing.  Return non-zero to cancel
   (the call then returns MLOD_ERROR_CANCELLED). Called on the calling thread. */
typedef int mlod_progress_fn(void *user, float fraction);

/* ------------------------------------------------------------------ input */

/* A triangle mesh.  Positions: 3 floats per vertex, position_stride bytes
   apart (0 = tightly packed); every stride is 0 or a multiple of
   sizeof(float) of at least 3 floats (else MLOD_ERROR_INVALID_ARGUMENT).
   Normals and colours are optional (NULL), per vertex, 3 floats each
   (colours are linear RGB, any range), strided likewise.
   index_count is a multiple of 3; every index < vertex_count. */
typedef struct mlod_mesh {
    const float *positions;
    size_t position_stride;
    uint32_t vertex_count;
    const uint32_t *indices;
    uint32_t index_count;
    const float *normals;   /* optional; zero-length normals fall back to the face normal */
    size_t normal_stride;
    const float *colors;    /* optional */
    size_t color_stride;
} mlod_mesh;

/* A point cloud: each point becomes one leaf.  Normals, radii and colours
   are optional (NULL); normals only matter for cones (without them a leaf's
   cone is the full sphere); radii are world units >= 0, and without them a
   radius is estimated from the local density (see mlod_build_points).
   Strides as in mlod_mesh; radius_stride: 0 (packed) or a multiple of
   sizeof(float). */
typedef struct mlod_points {
    const float *positions;
    size_t position_stride;
    uint32_t count;
    const float *normals;
    size_t normal_stride;
    const float *radii;
    size_t radius_stride;
    const float *colors;
    size_t color_stride;
} mlod_points;

/* Attributes a tree may carry beyond its spheres. */
enum {
    MLOD_ATTR_CONE = 1u << 0,  /* normal cones: 16 bytes per node */
    MLOD_ATTR_AREA = 1u << 1,  /* surface area below the node: 4 bytes per node */
    MLOD_ATTR_COLOR = 1u << 2, /* mean leaf colour: 12 bytes per node */
    MLOD_ATTR_REFIT = 1u << 3, /* what refit needs: 12 bytes per leaf, 8 per triangle (40 when
                                  the tree has at least as many leaves as triangles), and 4
                                  per node: which refit last changed the node (mlod_tree.changes),
                                  so that cuts re-evaluate only what moved */
    MLOD_ATTR_REFIT_CACHE = 1u << 4 /* with MLOD_ATTR_REFIT, meshes: the corners of every triangle
                                  as the last refit read them (positions; normals with cones;
                                  colours with colours), so that a refit computes again only the
                                  leaves of triangles whose corners changed: 37 bytes per
                                  triangle, 73 with cones, 109 with cones and colours; ignored for
                                  points (mlod_refit_mesh) */
};

typedef struct mlod_build_desc {
    uint32_t sample_count;     /* N for meshes, 1 .. MANYLODS_MAX_LEAVES; ignored for points */
    uint64_t seed;             /* same seed, same input -> same tree */
    float radius_scale;        /* multiplies every leaf radius; 0 means 1 */
    uint32_t attributes;       /* MLOD_ATTR_* bits */
    const mlod_allocator *allocator; /* NULL: MANYLODS_MALLOC/FREE */
    mlod_progress_fn *progress;      /* optional; called from the calling thread */
    void *progress_user;
    const mlod_parallel *parallel;   /* optional parallel-for hook (NULL: the calling thread) */
} mlod_build_desc;

/* --------------------------------------------------------------- the tree */

/* Precision flags of a tree (mlod_tree.precision). */
enum {
    /* Float positions are quantised coarser than a quarter of the typical
       leaf radius: the spacing of floats at the scene's largest coordinate
       (max(|x| * 2^-23, 2^-149), 2^-149 being the spacing of denormals)
       exceeds radius_scale * sqrt(A/N) / 4.  A scene far from
       the origin, or sampled finer than floats can place.  Samples then
       collapse onto each other; bounds, cuts and partitions stay exact for
       the stored (quantised) positions.  Translate the scene towards the
       origin (and the views with it) to clear it. */
    MLOD_PRECISION_COARSE_POSITIONS = 1u << 0
};

/* A bounding sphere hierarchy.  All arrays are owned by the tree and valid
   until mlod_tree_destroy; read them freely, do not write them.  Node i:
   spheres[4i .. 4i+3] = centre x, y, z, radius (world units);
   cones[4i .. 4i+3]   = unit axis x, y, z, half-angle in radians (>= pi: all
                         directions), or cones == NULL;
   areas[i]            = surface area below the node, in units of
                         area_unit (world units^2), or NULL;
   colors[3i .. 3i+2]  = mean colour of the leaves below, or NULL.
   Leaf j (0 <= j < N) is node N-1+j. */
typedef struct mlod_tree {
    uint32_t leaf_count;    /* N */
    uint32_t node_count;    /* 2N - 1 */
    uint32_t attributes;    /* MLOD_ATTR_* present */
    uint32_t precision;     /* MLOD_PRECISION_* flags */
    float *spheres;
    float *cones;
    float *areas;
    float *colors;
    double area_unit;       /* world units^2 per unit of areas[]: the mean
                               sample area at build, A / N (areas[] stay in
                               float range at any scene scale) */
    /* refit data (MLOD_ATTR_REFIT): for meshes, the source triangle and
       barycentrics (s, t) of every leaf and each triangle's area at build
       time; for point clouds, the source point of every leaf. */
    uint32_t *leaf_sources;      /* N */
    float *leaf_barycentrics;    /* 2N, or NULL for point clouds */
    double *triangle_areas;      /* triangle count, world units^2, or NULL for points */
    double smallest_area;        /* private: the smallest triangle_areas[] > 0 (refit's bound on
                                    how far a triangle can grow), 0 without them */
    void *triangle_leaves;       /* private: refit's per-triangle scratch (32 bytes each) when the
                                    tree has at least as many leaves as triangles, else NULL (each
                                    leaf then works out its triangle's share itself) */
    uint32_t triangle_count;     /* of the mesh built from, 0 for points */
    uint32_t vertex_count;       /* of the mesh built from, 0 for points */
    float *corners;              /* private, MLOD_ATTR_REFIT_CACHE: per triangle, its corners as the
                                    last refit read them (mlod__corner_floats), else NULL */
    unsigned char *corners_changed; /* private, MLOD_ATTR_REFIT_CACHE: refit's scratch, per triangle */
    uint32_t corners_state;      /* private: what corners[] holds: 0 nothing (after the build, or a
                                    refit after the arrays were written otherwise), 1 the corners
                                    without normals, 2 with normals */
    float radius_scale;          /* as used at build */
    size_t bytes;                /* everything the tree allocated */
    size_t bytes_per_node;       /* bytes of the per-node arrays, per node */
    mlod_allocator allocator;
    uint64_t revision;           /* at build, a number no other tree of this process started
                                    from (a multiple of 2^32); every mlod_refit_* that succeeds
                                    and mlodvk_tree_download add 1.  A cut knows an unchanged tree
                                    by its address and revision (THE CUT): code that writes the
                                    arrays otherwise adds 1 itself */
    uint32_t *changes;           /* private, trees with MLOD_ATTR_REFIT: per node, the low 32 bits of
                                    the revision whose refit last changed its sphere, cone, area or
                                    colour, or a child's (0: the build), so that a cut re-evaluates
                                    only what moved and a refit merges only above it; NULL without
                                    MLOD_ATTR_REFIT */
    uint64_t changes_revision;   /* private: the revision changes[] describes; another (code that
                                    wrote the arrays and added 1 to revision itself, or
                                    mlodvk_tree_download): changes[] unknown, the next refit marks
                                    every node */
    float changes_share;         /* private: the share of the internal nodes at depth 10 (or the
                                    deepest that has some) the last refit changed, 0 after the
                                    build */
} mlod_tree;

/* Sizing, before a build: the peak bytes mlod_build_mesh takes from its
   allocator (the high-water mark of its live bytes: the samples, the tree,
   whose arrays hold the ordering's scratch until they are written, and
   what of that scratch they cannot hold) for sample_count N, a mesh of
   triangle_count (index_count / 3) triangles and the MLOD_ATTR_*
   attributes.  Exact for a build that succeeds; one that fails takes no
   more.  About 104 bytes per sample (144 with every attribute) and 8 per
   triangle (48 with MLOD_ATTR_REFIT when N >= triangles; 37 to 109 more
   with MLOD_ATTR_REFIT_CACHE); mlod_tree.bytes
   is the part the tree keeps, in two blocks (the struct, and one for all
   its arrays).  0 when the build refuses N (0, above MANYLODS_MAX_LEAVES)
   before allocating, (size_t)-1 beyond size_t.  Pure. */
MANYLODS_DEF size_t mlod_build_mesh_bound(uint32_t sample_count, uint32_t triangle_count, uint32_t attributes);

/* The same for mlod_build_points with point_count points (about 100 bytes
   per point, 132 with every attribute).  0 when the build refuses the
   count (0, above MANYLODS_MAX_LEAVES).  Pure. */
MANYLODS_DEF size_t mlod_build_points_bound(uint32_t point_count, uint32_t attributes);

/* Sample desc->sample_count points on the mesh and build the tree.  O(N log N
   + triangles).  On success *out_tree owns its memory (mlod_tree_destroy);
   on failure *out_tree is NULL.  Reentrant: no shared state. */
MANYLODS_DEF mlod_result mlod_build_mesh(const mlod_mesh *mesh, const mlod_build_desc *desc,
                                         mlod_tree **out_tree, mlod_error *error);

/* Build a tree whose leaves are the points.  desc->sample_count is ignored.
   Without radii, each point's radius is radius_scale * R * sqrt(pi / L),
   where R is the radius and L >= 8 the leaf count of the lowest node above
   the point with at least 8 leaves (the point's share of a disc of radius R,
   as for mesh samples; the whole tree when N < 8).  The area of a point
   leaf is (radius / radius_scale)^2; area_unit is their mean. */
MANYLODS_DEF mlod_result mlod_build_points(const mlod_points *points, const mlod_build_desc *desc,
                                           mlod_tree **out_tree, mlod_error *error);

/* Recompute the leaves from the deformed mesh (same triangles, same vertex
   count, new positions, normals, colours) and merge bounds bottom-up, with
   the build's containment guarantees.  Needs MLOD_ATTR_REFIT.  No
   allocation.  On error the tree is unchanged.  Cost: the leaves and their
   merges, plus light passes over the indices and vertices (validation and
   a bound on every triangle's growth); with at least as many leaves as
   triangles, one pass over the triangles computes what their samples share
   (with fewer, each leaf computes its own triangle's, and the triangles get
   a pass of their own only when the bound cannot rule out a growth out of
   float range).  Results are the same bits either way.  Each leaf whose
   sphere, cone, area or colour bits change (compared before and after)
   gets the new revision in mlod_tree.changes, and so does each node above
   it; the others keep theirs, so that an incremental or lazy cut of
   unchanged views re-evaluates only what moved (THE CUT).  Internal nodes
   are merged again only where a child changed (the others would get the
   same bits): with the top eighth of a mesh moving, a refit of 1.3 M
   leaves takes 20 ms where the whole mesh twisting takes 45 (2 threads).
   A tree built with MLOD_ATTR_REFIT_CACHE keeps every triangle's corners
   as the refit read them (positions; normals where the tree has cones and
   the mesh has normals; colours) and computes again only the leaves of
   triangles whose corners differ, bit for bit (a leaf is a function of
   its triangle's corners, barycentrics and area at build): the same
   bits, for one pass over the corners (the same mesh: 10.7 ms with its
   top eighth moving, 4.4 ms with one vertex moving, 48 ms with all of it
   twisting; the tree holds 21.5 MB more, 142.5 MB).  The first refit
   after the build, one with normals where the last had none or the other
   way round, and one after a failed refit compute every leaf.  When the
   revision was counted up by other code since the last refit (arrays
   written otherwise, mlodvk_tree_download), every leaf is computed and
   every node merged and marked. */
MANYLODS_DEF mlod_result mlod_refit_mesh(mlod_tree *tree, const mlod_mesh *mesh,
                                         const mlod_parallel *parallel, mlod_error *error);

/* The same for a tree built from points: same count, new positions (and
   normals, radii, colours when the tree has them).  Without radii (each
   leaf's radius estimated again from the new density) every node is
   marked as changed. */
MANYLODS_DEF mlod_result mlod_refit_points(mlod_tree *tree, const mlod_points *points,
                                           const mlod_parallel *parallel, mlod_error *error);

/* Free the tree and everything it owns.  NULL is fine. */
MANYLODS_DEF void mlod_tree_destroy(mlod_tree *tree);

/* For refits done elsewhere (manylods_vk.h): the internal nodes at one
   depth of the implicit tree of leaf_count leaves are first .. last
   (returns 1), or there are none (returns 0; also for NULL outputs).
   Merging depth by depth, deepest first, is the refit's order.  Pure. */
MANYLODS_DEF int mlod_tree_depth_nodes(uint32_t leaf_count, uint32_t depth, uint32_t *first, uint32_t *last);

/* The refit's range check: a sampled triangle grown `growth` times its
   area at build must keep radii (radius_scale sqrt(area_unit growth)) and
   summed areas (growth x leaf_count, in build units) within float range;
   MLOD_OK or MLOD_ERROR_RANGE with a message.  Pure. */
MANYLODS_DEF mlod_result mlod_refit_check_growth(float radius_scale, double area_unit, uint32_t leaf_count,
                                                 double growth, mlod_error *error);

/* ------------------------------------------------------------------ views */

typedef enum mlod_view_kind {
    MLOD_VIEW_PERSPECTIVE = 0,
    MLOD_VIEW_PARABOLOID = 1,
    MLOD_VIEW_DUAL_PARABOLOID = 2,
    MLOD_VIEW_ORTHOGRAPHIC = 3,
    MLOD_VIEW_CUBE = 4
} mlod_view_kind;

enum { MLOD_VIEW_CULL_BACKFACES = 1u << 0 };

/* The most sub-projections a view has (a cube map's six faces). */
#define MLOD_VIEW_MAX_SUBS 6

/* One view.  World units; angles in radians.  forward and up need not be
   unit length but must not be parallel: the sine of their angle must
   exceed 1e-6; right = forward x up.  position, forward and up must be
   finite.  A kind reads only the fields marked for it below; the others
   are never read and may hold anything (NaN and infinities included).
   In a field a kind reads, NaN is MLOD_ERROR_NON_FINITE, and so is an
   infinity in a field that must be finite (far_plane may be +inf). */
typedef struct mlod_view {
    mlod_view_kind kind;
    float position[3];   /* eye; orthographic: a point on the box's axis, depth 0 */
    float forward[3];    /* viewing direction; paraboloids: the hemisphere axis */
    float up[3];
    uint32_t width;      /* tile size in pixels, >= 1 each; cube: 3s x 2s */
    uint32_t height;
    float fov_y;         /* perspective: vertical field of view, (0, pi) */
    float near_plane;    /* perspective, cube: > 0; orthographic: any finite value */
    float far_plane;     /* perspective, cube, orthographic: > near, may be +inf */
    float half_width;    /* orthographic: half-extents of the box, > 0 */
    float half_height;
    uint32_t flags;      /* MLOD_VIEW_* */
} mlod_view;

/* c(node, view) in pixels, as defined above: 0 when culled, +inf when
   unbounded.  Returns NaN when node >= node_count or the view is invalid.
   Pure, thread-safe.  Costs one view set-up: use the cut for bulk work. */
MANYLODS_DEF double mlod_criterion(const mlod_tree *tree, uint32_t node, const mlod_view *view);

/* Check a view: MLOD_OK or MLOD_ERROR_BAD_VIEW / NON_FINITE with a message. */
MANYLODS_DEF mlod_result mlod_view_check(const mlod_view *view, mlod_error *error);

/* One sub-projection of a view, in double (see VIEWS AND THE CRITERION).
   right, up, forward: its unit frame (u, v, w); kind: MLOD_VIEW_PERSPECTIVE,
   _PARABOLOID or _ORTHOGRAPHIC; scale: pixels per unit of the projection
   (perspective: the focal length f; paraboloid: half the larger side of
   its sub-tile; orthographic: the larger of scale_x, scale_y, pixels per
   world unit along u and v); x, y, width, height: its sub-tile within the
   view's tile (pixels from the tile's top-left corner; it draws columns
   floor(x) .. floor(x + width) - 1 and the rows likewise).  A sphere (c, r)
   reaches it unless, for one of its plane_count planes (n, k, l),
   n.c + l r < k exactly.  Unused planes are 0. */
typedef struct mlod_view_sub {
    double right[3], up[3], forward[3];
    double kind, scale, scale_x, scale_y;
    double x, y, width, height;
    double plane_count;
    double planes[6][5];
} mlod_view_sub;

/* What the criterion and the splat derive from a view, in double: for
   other backends of the same formulas (manylods_vk.h uploads it) and for
   tools.  eye: the view's position, which all its sub-projections share
   (an orthographic one looks along its forward from the box's plane
   through it); width, height: the tile; kind: the mlod_view_kind;
   sub_count: 1 to MLOD_VIEW_MAX_SUBS sub-projections in subs (unused ones
   are 0); cull_backfaces: 1 when MLOD_VIEW_CULL_BACKFACES is set.  One
   representation serves the CPU's criterion and splat and is the
   device's: 296 doubles, which manylods_vk.h uploads as they are (the
   small integers are stored as doubles for that reason). */
typedef struct mlod_view_frame {
    double eye[3], width, height;
    double kind, sub_count, cull_backfaces;
    mlod_view_sub subs[MLOD_VIEW_MAX_SUBS];
} mlod_view_frame;

/* Fill *frame from a view; MLOD_OK, or the error of mlod_view_check.
   Pure, thread-safe. */
MANYLODS_DEF mlod_result mlod_view_frame_of(const mlod_view *view, mlod_view_frame *frame, mlod_error *error);

/* The cut's float filter of a view (see "Fast paths" below), as floats for
   other backends (manylods_vk.h uploads it beside the frame): its
   thresholds hold for the cut's epsilon.  MLOD_FILTER_FLOATS floats at
   the offsets below, in groups of four that start on a multiple of four
   (a shader reads each group as one vec4); OK 0 where the view has no
   filter (every node-view then takes the exact path); small integers
   stored as floats; unused entries 0.  A sub-projection s starts at
   MLOD_FILTER_SUBS + s * MLOD_FILTER_SUB_STRIDE: its kind, plane count,
   thresholds (valid, invalid: pixels' inverse scale over epsilon, widened
   by 2^-12), axis w, then its planes, plane j at MLOD_FILTER_S_PLANES + j
   * MLOD_FILTER_PLANE_STRIDE: n, l, k' = k - n.eye, its slope and its
   error.  EYE holds the eye in floats; FLOAT_EYE is 1 when those are the
   eye exactly (the filter needs it on other backends). */
enum {
    MLOD_FILTER_OK = 0,
    MLOD_FILTER_BACKFACES = 1,
    MLOD_FILTER_ORTHO = 2,
    MLOD_FILTER_SUB_COUNT = 3,
    MLOD_FILTER_EYE = 4, /* 3 */
    MLOD_FILTER_FLOAT_EYE = 7,
    MLOD_FILTER_SUBS = 8,
    MLOD_FILTER_SUB_STRIDE = 56,
    MLOD_FILTER_S_KIND = 0,
    MLOD_FILTER_S_PLANE_COUNT = 1,
    MLOD_FILTER_S_VALID = 2,
    MLOD_FILTER_S_INVALID = 3,
    MLOD_FILTER_S_W = 4,       /* 3 */
    MLOD_FILTER_S_PLANES = 8,  /* 6 planes */
    MLOD_FILTER_PLANE_STRIDE = 8,
    MLOD_FILTER_P_N = 0,       /* 3, then l and k' */
    MLOD_FILTER_P_SLOPE = 5,
    MLOD_FILTER_P_ERR = 6,
    MLOD_FILTER_FLOATS = 344   /* 8 + 6 x 56 */
};

/* Fill out[0 .. MLOD_FILTER_FLOATS - 1] with the float filter of a view
   for a cut's epsilon (pixels, > 0, may be +inf); MLOD_OK, or the error
   of mlod_view_check (MLOD_ERROR_INVALID_ARGUMENT for a bad epsilon or a
   NULL out).  Pure, thread-safe. */
MANYLODS_DEF mlod_result mlod_view_filter_of(const mlod_view *view, float epsilon, float *out, mlod_error *error);

/* -------------------------------------------------------------------- cut */

typedef enum mlod_cut_mode {
    MLOD_CUT_BASIC = 0,
    MLOD_CUT_INCREMENTAL = 1,
    MLOD_CUT_LAZY = 2
} mlod_cut_mode;

/* Status of a node in a cut. */
enum {
    MLOD_STATUS_DRAWN = 1,    /* valid and not culled */
    MLOD_STATUS_CULLED = 2,   /* culled: never drawn */
    MLOD_STATUS_OVERSIZE = 3, /* a leaf above epsilon: drawn */
    MLOD_STATUS_COARSE = 4    /* lazy mode only: an internal node above epsilon
                                 not yet split: drawn */
};

typedef struct mlod_cut_params {
    mlod_cut_mode mode;
    float epsilon;               /* pixels, > 0, may be +inf */
    uint32_t lazy_steps;         /* lazy mode: moves per node-view and call, >= 1 */
    const mlod_parallel *parallel; /* optional */
    uint64_t budget;             /* lazy mode: at most this many node-views evaluated by an
                                    update from the previous cuts, 0 for no limit (THE CUT,
                                    "A budget"); 0 in the other modes */
} mlod_cut_params;

/* One view's cut, valid until the next mlod_cut_update or mlod_cut_destroy. */
typedef struct mlod_cut_view {
    const uint32_t *nodes;  /* count node indices, left to right */
    const uint8_t *status;  /* count MLOD_STATUS_* values */
    uint32_t count;
    uint32_t drawn, culled, oversize, coarse; /* counts by status (drawn: MLOD_STATUS_DRAWN only) */
    uint64_t evaluated;     /* criterion evaluations in the last update */
    uint64_t steps;         /* splits and merges in the last update */
    uint32_t splatted;      /* the nodes mlod_splat draws: drawn + oversize + coarse */
    uint64_t version;       /* changes exactly when an update or a reset changes the view or the
                               entries mlod_splat draws for it (their nodes and order, or which
                               are culled); no two cuts of the process share a value.  With the
                               tree's record of changes it tells what a tile shows (mlod_splat
                               keeps the tiles whose version and drawn nodes did not change) */
    int deferred;           /* 1: a lazy update's budget left the view out of the last update, so its
                               list is the one before, computed for an earlier view or tree (its
                               statuses may be out of date); 0: evaluated, or skipped unchanged */
} mlod_cut_view;

typedef struct mlod_cut mlod_cut;

/* Sizing, before a cut: the most bytes a cut of view_count views holds,
   between and during its updates, while its views' cuts average at most
   mean_cut_nodes nodes, in any mode.  A cut holds each view's list (5
   bytes per entry: 4 for the node, 1 for its status) in chunks, each the
   lists of a run of consecutive views, with at most an eighth to spare;
   about 255 bytes per view (offsets, counts, statistics, versions, the view its
   list was computed for; 16 more during an update with a budget, for
   its order); and, during an update, the buffers it works
   in, sized for one window of views: an update goes through the views a
   window at a time (a chunk's views, about 2^18 entries) and writes each
   window's lists back into its chunk.  The buffers take 3 to 16 MB
   whatever the cut's total size, and are given back at the end of each
   update unless mlod_cut_reserve grew them.  Between updates a cut of
   4.1 M entries over 1024 views holds 5.4 bytes per entry (7.2 while
   reserved or during an update).  The bound counts the buffers, windows
   of up to 2^19 entries and one chunk replaced during an update.  (Not covered: a window whose cuts grow past that
   within one update, as a single view's cut above 2^19 entries, cuts
   that multiply from one update to the next, or, in a cut's first
   update, views whose cuts are far above those of the views before
   them; its buffers then grow to its size.  Nor a round that leaves more
   than one entry in 16 of its input to split, which the tests never
   saw.)  0 for view_count 0, (size_t)-1 beyond size_t.  Pure. */
MANYLODS_DEF size_t mlod_cut_bound(uint32_t view_count, uint32_t mean_cut_nodes);

/* Grow the buffers an update works in now, to what windows of cuts
   averaging mean_cut_nodes nodes need (all mlod_cut_bound counts but the
   lists and the chunks' records), and keep them between updates, so
   that updates allocate only the chunks that hold the lists: in the
   first update, and where a window's lists outgrow their chunk or fall
   below 8/9 of it (a chunk is allocated with a sixteenth to spare).
   Frames whose cuts change by a few percent allocate nothing: 3 to 16
   MB held for allocation-free frames.  Buffers that already hold more
   keep it.  An update that runs out of memory gives them back and ends
   the reservation.  MLOD_OK, or MLOD_ERROR_OUT_OF_MEMORY /
   MLOD_ERROR_OVERFLOW with the cut as it was.  Not thread-safe for one
   cut. */
MANYLODS_DEF mlod_result mlod_cut_reserve(mlod_cut *cut, uint32_t mean_cut_nodes, mlod_error *error);

/* Create an empty cut for view_count >= 1 views (it keeps the lists that
   incremental and lazy modes start from).  allocator may be NULL. */
MANYLODS_DEF mlod_result mlod_cut_create(uint32_t view_count, const mlod_allocator *allocator,
                                         mlod_cut **out_cut, mlod_error *error);

/* Compute the cuts of all views (views[0 .. view_count-1]) in the tree.
   Incremental and lazy modes start from the previous update's cuts when the
   previous update used a tree of the same node count, else from the root.
   All views and params are checked before any work; when they are
   refused the previous cuts stay, and so does the cut's memory
   (mlod_cut_bytes and the allocator's live bytes as before the call).
   The update goes through the views a window at a time, writing each
   window's lists over its previous ones (mlod_cut_bound), so an update
   that runs out of memory midway has no previous cuts left to keep: it
   resets the cut (as mlod_cut_reset: no entries, every version new; the
   next update starts from the root) and gives back all it held beyond
   what mlod_cut_create allocated.  A view whose view, tree and epsilon
   did not change since the previous update is not evaluated (THE CUT,
   above), and a window of such views is not touched: an update where
   none changed costs about 4 ns per view.  Memory grows with the cut
   sizes, not with views x N. */
MANYLODS_DEF mlod_result mlod_cut_update(mlod_cut *cut, const mlod_tree *tree, const mlod_view *views,
                                         const mlod_cut_params *params, mlod_error *error);

/* The checks mlod_cut_update makes of its parameters alone (mode,
   epsilon, lazy_steps): MLOD_OK, MLOD_ERROR_INVALID_ARGUMENT or
   MLOD_ERROR_BAD_EPSILON with a message.  Pure. */
MANYLODS_DEF mlod_result mlod_cut_params_check(const mlod_cut_params *params, mlod_error *error);

/* Forget the previous cuts: the next update starts from the root and
   evaluates every view. */
MANYLODS_DEF void mlod_cut_reset(mlod_cut *cut);

MANYLODS_DEF uint32_t mlod_cut_view_count(const mlod_cut *cut);
/* view < view_count; before any update every view has count 0. */
MANYLODS_DEF mlod_cut_view mlod_cut_get(const mlod_cut *cut, uint32_t view);
/* Bytes the cut object holds now. */
MANYLODS_DEF size_t mlod_cut_bytes(const mlod_cut *cut);
/* Free the cut and its lists.  NULL is fine. */
MANYLODS_DEF void mlod_cut_destroy(mlod_cut *cut);

/* ------------------------------------------------------------ projection */

/* Where a world point lands in a view's tile.  pixel[0] grows to the right,
   pixel[1] downwards; pixel (i, j) covers [i, i+1) x [j, j+1).  The point
   is projected by the sub-projection whose axis w is closest to its
   direction (the largest (p - eye).w; on a tie the first: a dual
   paraboloid's front, a cube's lower face); depth as in SPLATTING:
   perspective, cube faces and orthographic, z = (p - eye).w along that
   axis; paraboloids, |p - eye|.  Returns 1 when the point is inside the
   view (it reaches a sub-projection: in the frustum, box, front
   hemisphere; for dual paraboloids always; for cube maps outside the near
   cube and inside the far one), else 0 with the outputs still written
   where the projection is defined.  Pure, thread-safe; views are checked
   (0 for an invalid view). */
MANYLODS_DEF int mlod_view_project(const mlod_view *view, const float point[3], float pixel[2], float *depth);

/* The ray through pixel position (x, y) of the tile (continuous, pixel
   centres at i + 0.5): origin and unit direction in world units, through
   the sub-projection whose sub-tile holds the position.  Returns 0 when the
   position has no ray (outside a paraboloid's disc, or outside the tile),
   for an invalid view and for NULL outputs.  The origin is the eye (perspective, cube, paraboloids) or the point of
   depth 0 on the pixel's line (orthographic; not the near plane).  The
   depth (as in mlod_view_project) of origin + t direction is
   t * (direction . w) + (origin - eye) . w for perspective, cube and
   orthographic views, w the axis of the sub-projection, and t for
   paraboloids.  Pure, thread-safe. */
MANYLODS_DEF int mlod_view_pixel_ray(const mlod_view *view, float x, float y, float origin[3], float direction[3]);

/* ----------------------------------------------------------------- atlas */

/* Channels of an atlas beyond depth. */
enum {
    MLOD_ATLAS_NORMAL = 1u << 0, /* the drawn node's cone axis (trees with cones) */
    MLOD_ATLAS_COLOR = 1u << 1   /* the drawn node's mean colour (trees with colours) */
};

/* What a drawn node becomes in a tile (mlod_atlas_desc.splat; see
   SPLATTING in the manual). */
enum {
    MLOD_SPLAT_AUTO = 0,    /* MLOD_SPLAT_TANGENT with a tree that has cones, else MLOD_SPLAT_SPHERES */
    MLOD_SPLAT_SPHERES = 1, /* the disc of the sphere's image at the centre's depth; at disc_scale 1 a
                               disc covering no pixel centre sets the pixel holding its centre */
    MLOD_SPLAT_TANGENT = 2  /* the node's tangent disc (through the sphere's centre, normal the cone's
                               axis, the sphere's radius) sampled at pixel centres, at the depth where
                               each centre's ray meets it; needs a tree with cones */
};

/* Zero-initialise it (memset or = {0}): a zero field means its default. */
typedef struct mlod_atlas_desc {
    uint32_t columns;  /* tiles per row; 0: ceil(sqrt(views)) */
    uint32_t channels; /* MLOD_ATLAS_* */
    float disc_scale;  /* drawn disc radius / sphere image radius, in (0, 1];
                          0: 1 (see mlod_splat) */
    const uint32_t *order; /* NULL: view v in cell v; else order[k] is the view in cell k
                              (row by row), a permutation of 0 .. view_count - 1, read
                              only during mlod_atlas_create.  Which cell holds which view
                              changes no tile's pixels, only where they lie: give the
                              view tree's leaf order (mlod_view_tree.eyes->leaf_sources)
                              and mlod_megaviews_render writes the tiles in sequence,
                              not scattered over the atlas (docs/GUIDE.md measures it) */
    uint32_t splat;        /* MLOD_SPLAT_*; 0: MLOD_SPLAT_AUTO */
    uint32_t fill_holes;   /* 1: mlod_splat fills the holes of each tile it draws, as
                              mlod_atlas_fill_holes does (allocating its scratch for those
                              tiles in the call), so that the tiles it keeps stay filled;
                              0: it leaves holes */
} mlod_atlas_desc;

/* One image holding a tile per view, laid out as a grid of equal cells (the
   largest tile's size), row by row in view order (or desc->order); each
   view's tile sits at the top-left of its cell (mlod_splat keeps a record
   per tile of what it shows).  depth[y * width + x] is
   +inf where nothing was drawn; normal and colour have 3 floats per pixel
   (0 where nothing was drawn) or are NULL.  All arrays are owned by the
   atlas. */
typedef struct mlod_atlas {
    uint32_t width, height;   /* pixels */
    uint32_t view_count;
    uint32_t channels;
    uint32_t cell_width, cell_height, columns;
    float disc_scale;         /* as given in mlod_atlas_desc (0 became 1) */
    uint32_t splat;           /* as given in mlod_atlas_desc (MLOD_SPLAT_*) */
    uint32_t fill_holes;      /* as given in mlod_atlas_desc */
    float *depth;
    float *normal;
    float *color;
    uint32_t *tiles;          /* per view: x, y, width, height of its tile */
    uint32_t *ids;            /* private: per pixel, the node mlod_splat or mlod_splat_ism drew there
                                 (equal depths: the lower node index wins); NULL until the first */
    uint32_t *bands;          /* private: per view, first row band (splat tasks) */
    size_t bytes;
    mlod_allocator allocator;
    uint32_t redrawn;         /* the tiles the last mlod_splat drew whole */
    uint32_t patched;         /* the tiles it patched (cleared and drew only the pixels that could
                                 change); the others kept their pixels */
    uint64_t *shown;          /* private: per view, what its tile shows (mlod_splat): the cut's
                                 version, the tree's revision and the cut's basis it was drawn from
                                 (the basis 0: the list was not the basic cut of that revision);
                                 version 0: unknown */
    uint8_t *dirty;           /* private: per pixel, mlod_splat's mask of the pixels a patch draws;
                                 NULL until the first patch */
    uint32_t *redraw;         /* private: mlod_splat's band tasks (the bands of the tiles it draws) */
    float shown_scale;        /* private: the disc_scale, splat and fill_holes the known tiles were */
    uint32_t shown_splat, shown_fill; /* drawn with */
} mlod_atlas;

/* Sizing, before an atlas: the bytes mlod_atlas_create allocates for these
   views and desc (the atlas's bytes, exactly): 4 bytes per pixel of depth,
   12 more per channel, the per-view tables (44 bytes per view and 4 per
   64 rows of its tile).  0 when mlod_atlas_create
   would refuse them (no views, an empty tile, a bad desc, a size that
   overflows; desc->order is not read: it changes no byte count, and
   mlod_atlas_create checks it), (size_t)-1 beyond size_t.
   mlod_atlas_fill_holes allocates for its call, on top, about a third of
   the tiles' pixels times 4 (values + 1) bytes, values = 1 + 3 per
   channel.  Pure. */
MANYLODS_DEF size_t mlod_atlas_bound(const mlod_view *views, uint32_t view_count, const mlod_atlas_desc *desc);

/* Create an atlas for view_count >= 1 views (their tile sizes fix the
   layout).  Sizes that overflow return MLOD_ERROR_OVERFLOW; a disc_scale
   outside (0, 1] (other than 0), or NaN, or a desc->order that is not a
   permutation of the views (a view out of range, or twice),
   MLOD_ERROR_INVALID_ARGUMENT. */
MANYLODS_DEF mlod_result mlod_atlas_create(const mlod_view *views, uint32_t view_count, const mlod_atlas_desc *desc,
                                           const mlod_allocator *allocator, mlod_atlas **out_atlas,
                                           mlod_error *error);
MANYLODS_DEF void mlod_atlas_destroy(mlod_atlas *atlas);

/* Draw every drawn node (status DRAWN, OVERSIZE or COARSE) of every
   view's cut into its cleared tile, in each sub-projection the
   node's sphere reaches, clipped to that sub-projection's sub-tile: its
   disc there is the disc around the exact image of the sphere (the
   image's diameter, centred on the image's centre; paraboloids use the
   larger of their two pixel scales) with its radius times the atlas's
   disc_scale.  A pixel is drawn when its centre lies in the disc and, with
   tangent discs (mlod_atlas_desc.splat, by default for a tree with cones),
   when its centre's ray meets the node's tangent disc, at the depth where
   it does; with sphere discs at the depth of the sphere's centre (as in
   mlod_view_project), and at disc_scale 1 a sphere disc covering no pixel
   centre sets the pixel holding its centre.  See SPLATTING in the manual.
   Nearest depth wins; of equal depths the lower node index, whatever
   order the nodes are drawn in (mlod_splat_ism and mlod_megaviews_render
   keep the same rule); for it the first mlod_splat or mlod_splat_ism on
   an atlas allocates a record of the node drawn at each pixel, 4 bytes
   per pixel that the atlas holds (atlas->bytes counts them, not
   mlod_atlas_bound; MLOD_ERROR_OUT_OF_MEMORY when they do not fit).  A node is
   not drawn in a sub-projection where its image is unbounded.  The views
   must be those of the cut's last update, byte for byte: a view moved
   since is MLOD_ERROR_MISMATCH (a cut never updated, or reset, draws
   nothing for any views).  MLOD_ERROR_MISMATCH also for
   MLOD_SPLAT_TANGENT and a tree without cones.  A tile that shows what
   this call would draw is kept as it is (the same bits): one this atlas's
   last mlod_splat drew or kept, whose view and drawn entries did not
   change since (mlod_cut_view.version) and none of whose drawn nodes a
   refit changed (sphere, cone or colour bits; a tree without
   MLOD_ATTR_REFIT: any refit), with the same disc_scale and splat.  A
   tile that does not is patched where that gives the same bits: it
   showed the basic cut of its view at an earlier revision of this tree,
   refitted since with its record of changes (MLOD_ATTR_REFIT; not
   written by hand since the last refit), the cut holds the basic cut of
   the same view bytes and epsilon for the tree as it is (a basic or
   incremental update, or a lazy one that made no move, each update since
   of the same view and epsilon), the atlas does not fill holes, and the
   last refit changed at most half of the tree's internal nodes at depth
   10 (more, and a patch costs more than a redraw).  A
   patch empties the pixels whose node's parent a refit changed since,
   draws the entries whose parent changed over the whole tile and the
   others over those pixels only (see SPLATTING); the first patch
   allocates a mask of 1 byte per pixel (atlas->bytes counts it, not
   mlod_atlas_bound; without it tiles are drawn whole).  The others are
   cleared and drawn whole (and, with mlod_atlas_desc.fill_holes, their
   holes filled).  atlas->redrawn counts the tiles drawn whole,
   atlas->patched those patched.  What else writes the pixels (mlod_splat_ism,
   mlod_atlas_fill_holes, mlod_megaviews_render, mlodvk_atlas_download)
   makes the next mlod_splat draw every tile; code of yours that writes
   them calls mlod_atlas_invalidate.  Parallel over tiles and row bands;
   results are identical for any thread count. */
MANYLODS_DEF mlod_result mlod_splat(mlod_atlas *atlas, const mlod_tree *tree, const mlod_cut *cut,
                                    const mlod_view *views, const mlod_parallel *parallel, mlod_error *error);

/* Forget what the tiles show: the next mlod_splat clears and draws every
   tile (a full redraw).  Call it after writing an atlas's pixels yourself.
   NULL is fine.  Not thread-safe for one atlas. */
MANYLODS_DEF void mlod_atlas_invalidate(mlod_atlas *atlas);

/* The Imperfect Shadow Maps baseline (Ritschel et al. 2008): clear the
   atlas, then draw into each view points_per_view leaves of the tree chosen
   at random for that view (with replacement, from (seed, view, k): the same
   subset every call), each as the disc of its own sphere, as mlod_splat
   draws nodes with MLOD_SPLAT_SPHERES whatever the atlas's splat setting
   (disc_scale included; a point covering no pixel centre sets its pixel,
   as ISM splats points), unless the cut's criterion culls it
   (outside the view, or back-facing where the view culls back faces).
   The points go through the same float filters as the cut and the splat,
   64 at a time: the atlas is the one drawing them one by one in double
   would give, bit for bit.  Equal depths and memory as mlod_splat.
   Parallel as mlod_splat. */
MANYLODS_DEF mlod_result mlod_splat_ism(mlod_atlas *atlas, const mlod_tree *tree, const mlod_view *views,
                                        uint32_t points_per_view, uint64_t seed, const mlod_parallel *parallel,
                                        mlod_error *error);

/* Pull-push hole filling, tile by tile, on depth and every channel.  Pull:
   a pyramid of 2x2 reductions, each coarser pixel the plain mean of its
   non-empty children (empty if all are).  Push: from coarse to fine, every
   empty pixel takes its parent's value; so an empty tile pixel gets the
   value of its nearest non-empty ancestor in the pyramid.  Pixels that
   were drawn keep their values; a tile with nothing drawn stays empty.
   Allocates its scratch once per call.  The next mlod_splat draws every
   tile again, unless the atlas has fill_holes: its tiles that mlod_splat
   drew or kept are filled already and left as they are (the others are
   filled). */
MANYLODS_DEF mlod_result mlod_atlas_fill_holes(mlod_atlas *atlas, const mlod_parallel *parallel, mlod_error *error);

/* -------------------------------------------------------- shadow lookups */

/* The widest percentage-closer filter of mlod_atlas_shadow, in pixels. */
#define MLOD_SHADOW_MAX_FILTER 16u
/* The largest slope mlod_atlas_shadow scales its slope bias by (tan 82.9 degrees). */
#define MLOD_SHADOW_MAX_SLOPE 8.0

/* How mlod_atlas_shadow tests a point against a tile (zero-initialise:
   one pixel, no bias). */
typedef struct mlod_shadow_params {
    uint32_t filter;  /* percentage-closer filter width k, in pixels, 0 .. MLOD_SHADOW_MAX_FILTER: 0 tests
                         the pixel holding the point; k >= 1 averages the tests of the pixels under the
                         k x k-pixel square centred on the point, each weighted by the area of it that
                         lies in the square (k = 1: bilinear weights over the 2 x 2 nearest pixels);
                         pixels past the point's sub-tile (a dual paraboloid's half, a cube face) are
                         read at its nearest edge pixel */
    float bias;       /* world units of depth, >= 0, finite: added to the map's depth */
    float slope_bias; /* pixel footprints, >= 0, finite: times the footprint at the point (the world
                         distance between the rays of its pixel's centre and of the horizontal neighbour's,
                         at the point's distance from the first), times tan of the angle between the
                         normal and the direction to the eye (at most MLOD_SHADOW_MAX_SLOPE), or times 1
                         without a normal; added to the map's depth */
} mlod_shadow_params;

/* Where a world point lands in view `view`'s tile of the atlas (frame:
   that view's, from mlod_view_frame_of; the tile must be the frame's
   size): pixel (tile pixels from its top-left, as mlod_view_project),
   *depth the point's depth as the view measures it (perspective, cube,
   orthographic: along the sub-projection's axis; paraboloids: distance
   from the eye) and *map_depth the depth the tile holds at the pixel
   under the point (+inf where nothing was drawn).  The point is projected
   by the sub-projection whose axis is closest to its direction, with the
   arithmetic of mlod_view_project (the same bits).  Returns 1 when the
   point lies inside the view as mlod_view_project says and its pixel in
   the tile, else 0 (outputs then undefined); 0 for NULL atlas, frame or
   point, view >= view_count, or a tile of another size.  Outputs may be
   NULL.  Pure, thread-safe; no allocation; the frame spares the view's
   set-up that mlod_view_project makes on every call. */
MANYLODS_DEF int mlod_atlas_lookup(const mlod_atlas *atlas, uint32_t view, const mlod_view_frame *frame,
                                   const float point[3], float pixel[2], float *depth, float *map_depth);

/* The lit fraction, in [0, 1], of a world point in view `view`'s tile
   (a shadow map; frame as for mlod_atlas_lookup): the point counts as lit
   by a map pixel when its depth is at most the pixel's depth plus the
   bias of params (bias + slope_bias x footprint x slope); params->filter
   averages such tests (percentage-closer filtering).  normal (any length,
   not 0; may be NULL) gives the slope: tan of the angle between it and
   the direction to the eye (an orthographic view's: -axis), either side.
   A point outside the view (mlod_atlas_lookup returns 0 for it) is lit: 1.
   NaN for NULL atlas, frame, point or params, view >= view_count, a tile
   of another size than the frame, or params out of range.  Doubles
   throughout; the result does not depend on the build's SIMD level.
   Pure, thread-safe; no allocation.  On a Vulkan device, shaders/lookup.glsl
   gives the same results bit for bit (this and mlod_atlas_lookup, with
   the device's doubles or emulated ones): #include it in your shader after
   declaring the frames and the atlas depth as its top comment says. */
MANYLODS_DEF float mlod_atlas_shadow(const mlod_atlas *atlas, uint32_t view, const mlod_view_frame *frame,
                                     const float point[3], const float normal[3], const mlod_shadow_params *params);

/* ------------------------------------------------------- choosing N */

/* Surface area of a mesh in world units^2 (0 for invalid input). Pure. */
MANYLODS_DEF double mlod_mesh_area(const mlod_mesh *mesh);

/* The smallest N (samples) whose leaves, of radius radius_scale * sqrt(A/N),
   are at most epsilon pixels across in every view wherever they appear in
   its tile (in every sub-projection: a cube map's face, a dual
   paraboloid's half), for surface at least `closest` world units from the eye
   (orthographic views: at any depth).  Sample only what the views can
   resolve.  radius_scale <= 0 means 1, as in mlod_build_desc.  Returns 0
   for invalid input (A <= 0 or not finite, epsilon <= 0, closest <= 0 or
   not finite, an invalid view), MANYLODS_MAX_LEAVES when more would be
   needed.  Pure. */
MANYLODS_DEF uint32_t mlod_suggest_sample_count(double surface_area, const mlod_view *views, uint32_t view_count,
                                                float epsilon, float radius_scale, double closest);

/* ------------------------------------------------- choosing the views */

/* How mlod_sample draws (CHOOSING THE VIEWS, above). */
typedef enum mlod_sampler {
    MLOD_SAMPLER_INVERSE_TRANSFORM = 0, /* cumulative importance and a binary search */
    MLOD_SAMPLER_METROPOLIS = 1         /* independent Metropolis-Hastings chains */
} mlod_sampler;

typedef struct mlod_sample_params {
    mlod_sampler method;
    uint32_t chain_length;           /* MLOD_SAMPLER_METROPOLIS: proposals per chain, M >= 1 (0: 8) */
    uint64_t seed;                   /* picks the random numbers; keep it from frame to frame */
    const mlod_parallel *parallel;   /* optional */
    const mlod_allocator *allocator; /* optional: the inverse transform's table */
} mlod_sample_params;

/* Bytes mlod_sample allocates (and frees before it returns) for a domain
   of domain_size candidates: (domain_size + 1) doubles for the inverse
   transform ((size_t)-1 where that does not fit), none for Metropolis,
   (size_t)-1 for an unknown method (mlod_sample refuses it).  Pure. */
MANYLODS_DEF size_t mlod_sample_bound(uint32_t domain_size, mlod_sampler method);

/* sample_count (N >= 1) samples of the domain [0, domain_size) (D >= 1)
   drawn by importance[0 .. D) (finite, >= 0) into samples[0 .. N), and
   their weights, finite and >= 0, into weights[0 .. N): (1 / N) sum_j
   weights[j] g(samples[j]) estimates sum_i g(i) for any g that is 0 where
   the importance is (see CHOOSING THE VIEWS for how well).  Where every
   importance is 0, samples are uniform and weights 0.  Deterministic for a
   seed, for any thread count.  Errors: NULL arrays, N or D 0, a negative
   or non-finite importance, an unknown method
   (MLOD_ERROR_INVALID_ARGUMENT / EMPTY / NON_FINITE), a table beyond
   size_t (MLOD_ERROR_OVERFLOW, 32-bit systems), importances whose
   weights could exceed float range (the total, or D times the largest,
   over the smallest positive one above FLT_MAX / 2: MLOD_ERROR_RANGE), no memory;
   samples and weights are then untouched.  Thread-safe. */
MANYLODS_DEF mlod_result mlod_sample(const float *importance, uint32_t domain_size, uint32_t sample_count,
                                      const mlod_sample_params *params, uint32_t *samples, float *weights,
                                      mlod_error *error);

/* ------------------------------------------ many views at once: MegaViews */

/* Views for a view tree (MANY VIEWS AT ONCE in the manual).  eyes: 3
   floats per view (world units, finite, |x| <= 1e36); strides as in
   mlod_points.  directions (optional): each view's axis, finite, not of
   zero length; with them a view sees the directions within its half field
   of view of its axis, without them every direction.  half_fovs (optional,
   with directions): one per view, radians in (0, pi]; NULL: half_fov for
   every view, 0 meaning pi/2 (a virtual point light's hemisphere). */
typedef struct mlod_view_set {
    const float *eyes;
    size_t eye_stride;
    uint32_t count;            /* views, 1 .. MANYLODS_MAX_LEAVES */
    const float *directions;
    size_t direction_stride;
    const float *half_fovs;
    size_t half_fov_stride;
    float half_fov;
} mlod_view_set;

/* A bounding sphere hierarchy over views: the scene tree's layout and
   build over the eyes (mlod_build_points with radius-0 points; with
   directions, the leaves in the order of median splits by eyes and
   directions: MANY VIEWS AT ONCE in the manual), so node i
   of `eyes` bounds the eyes below it by its sphere (exactly, with the
   scene tree's slack) and their directions by its cone (cones NULL
   without directions); leaf j holds view eyes->leaf_sources[j].
   half_fovs[2i], half_fovs[2i + 1]: the smallest and the largest half
   field of view below node i, or NULL without directions.  floors[2i]:
   the least height of node i's eyes along its cone's unit axis, above the
   node's centre (world units, a lower bound; -inf where the cone or a
   field of view below reaches pi), and floors[2i + 1]: 2 sin(alpha / 2)
   of the cone's half-angle alpha, plus sin(phi - pi/2) of the largest
   half field of view phi below where it passes pi/2 (an upper bound), or
   NULL without directions: MegaViews culls with them what lies behind
   every eye's field of view (mlod_megaviews_render).  Owned by the view
   tree. */
typedef struct mlod_view_tree {
    mlod_tree *eyes;
    float *half_fovs;
    float *floors;
    float *radii;              /* private: the leaves' radii, 0 (for refits) */
    uint32_t view_count;
    size_t bytes;              /* everything the view tree allocated */
    mlod_allocator allocator;
} mlod_view_tree;

/* Build the view tree of the views: O(V log V), deterministic; parallel
   through the hook (NULL: the calling thread), memory from the allocator
   (NULL: the default); mlod_build_points_bound(count, MLOD_ATTR_REFIT |
   (directions ? MLOD_ATTR_CONE : 0)) bounds its peak, plus
   sizeof(mlod_view_tree), 4 bytes per view for the radii and, with
   directions, 32 per view.  On error *out is
   NULL.  Reentrant. */
MANYLODS_DEF mlod_result mlod_view_tree_build(const mlod_view_set *views, const mlod_allocator *allocator,
                                              const mlod_parallel *parallel, mlod_view_tree **out,
                                              mlod_error *error);

/* The views moved: refit the bounds to the same count of views (new eyes,
   directions, fields of view; the leaves keep their views), with the
   build's containment.  No allocation; on error the tree is unchanged. */
MANYLODS_DEF mlod_result mlod_view_tree_refit(mlod_view_tree *tree, const mlod_view_set *views,
                                              const mlod_parallel *parallel, mlod_error *error);

/* Free the view tree.  NULL is fine. */
MANYLODS_DEF void mlod_view_tree_destroy(mlod_view_tree *tree);

/* The map every view gets from mlod_megaviews_render with the default
   orientation (params.forward and up 0): a dual paraboloid of one global
   orientation (front half: directions towards +z, in the tile's left
   half; back half: -z, in the right; forward (0, 0, 1), up (0, 1, 0)),
   at the eye, resolution x resolution pixels per half (tile 2 resolution
   x resolution), with `flags` (MLOD_VIEW_*).  Use it to create the atlas
   and to look up pixels (mlod_view_project).  Pure. */
MANYLODS_DEF mlod_view mlod_megaviews_view(const float eye[3], uint32_t resolution, uint32_t flags);

/* The same map in another orientation, the one params.forward and up
   give the render: the front half (the tile's left) looks along forward,
   the back half (the right) along -forward, up as mlod_view's (made
   perpendicular to forward).  forward and up both NULL or 0:
   mlod_megaviews_view's, forward (0, 0, 1), up (0, 1, 0); otherwise
   copied as given, for mlod_view_check (or mlod_megaviews_check) to
   judge.  A direction on the seam between the halves (perpendicular to
   forward) lands on the rim of both discs, the map's least sharp place:
   choose forward along what the views look at most (-y, down, for
   ceiling lights in a y-up scene).  Pure. */
MANYLODS_DEF mlod_view mlod_megaviews_view_oriented(const float eye[3], uint32_t resolution, uint32_t flags,
                                                    const float forward[3], const float up[3]);

/* The sharing suggested for delta: half a pixel. */
#define MLOD_MEGAVIEWS_DELTA 0.5f

typedef struct mlod_megaviews_params {
    float epsilon;             /* pixels, > 0 (+inf allowed): the cut's epsilon */
    float delta;               /* pixels, >= 0, finite: how far a shared node's image may move
                                  between the views that share it; 0 gives the per-view
                                  cut and splat (but for exact depth ties: MANY VIEWS AT ONCE)
                                  (MLOD_MEGAVIEWS_DELTA: the suggested sharing) */
    uint32_t resolution;       /* pixels per side of each half of the map, >= 1 */
    uint32_t flags;            /* MLOD_VIEW_CULL_BACKFACES (with a scene tree that has cones) */
    float group_radius;        /* world units, >= 0, finite: a view node whose eyes lie within this of
                                  its centre renders one map, from its centre, for all its views
                                  (an approximation: see MANY VIEWS AT ONCE); 0: none */
    const mlod_parallel *parallel;   /* optional */
    const mlod_allocator *allocator; /* the call's scratch; NULL: the atlas's allocator */
    float forward[3];          /* the maps' front axis and up (mlod_megaviews_view_oriented); both 0:
                                  forward +z, up +y (the default, mlod_megaviews_view); otherwise as
                                  mlod_view's forward and up: finite, nonzero, not parallel */
    float up[3];
} mlod_megaviews_params;

/* What a render did. */
typedef struct mlod_megaviews_stats {
    uint64_t pairs;            /* (scene node, view node) pairs classified */
    uint64_t culled;           /* pairs culled for every view below the view node */
    uint64_t shared_draws;     /* scene nodes drawn into an inner view node's map (shared) */
    uint64_t leaf_draws;       /* scene nodes drawn into a view leaf's map */
    uint64_t shared_views;     /* views below the inner nodes of shared draws, summed */
    uint64_t shared_leaves;    /* of shared_draws: scene leaves above epsilon for some eye (MegaViews 3.2.4) */
    uint32_t levels;           /* depth of the view tree + 1 */
    size_t peak_bytes;         /* the most the call held at once from its allocator (a zero-size array counts
                                  the byte it takes; mlod_megaviews_render_maps: the maps it returns included) */
    uint64_t node_pairs;       /* the most pairs classified at one view node (mlod_megaviews_bound) */
} mlod_megaviews_stats;

/* Sizing, before a render: an upper bound on the bytes that
   mlod_megaviews_render holds at once from its allocator (its
   stats.peak_bytes) for this view tree at this resolution, when no view
   node classifies more than node_pairs pairs.  The pairs depend on the
   scene and the views: stats.node_pairs reports them after a render (the
   next frames of a moving scene need a margin: 6 317 to 7 060 in
   docs/GUIDE.md's benchmark, 1 k to 1 M lights), and the scene tree's node
   count holds for any render (each scene node meets a view node at most
   once) at the price of a far larger bound.  Maps and tables are counted
   as allocated, the pair lists at their worst for node_pairs: 3.9 to 5.4
   times the peak in that benchmark.  (mlod_megaviews_render_maps keeps
   every view node's map: up to 16 R^2 bytes per view tree node, beside
   its level-by-level lists.)  0 for views NULL or a resolution the render
   refuses (0, above 2^31 - 1), (size_t)-1 beyond size_t.  Pure,
   thread-safe. */
MANYLODS_DEF size_t mlod_megaviews_bound(const mlod_view_tree *views, uint32_t resolution, uint64_t node_pairs);

/* The maps of every view node, unfused (mlod_megaviews_render_maps). */
typedef struct mlod_megaviews_maps mlod_megaviews_maps;

/* Check the parameters alone: epsilon > 0, delta and group_radius finite
   and >= 0, resolution in 1 .. 2^31 - 1, no flag but
   MLOD_VIEW_CULL_BACKFACES (MLOD_ERROR_BAD_VIEW), forward and up both 0
   or a frame mlod_view_check takes (MLOD_ERROR_NON_FINITE: NaN or
   infinite; MLOD_ERROR_BAD_VIEW: one of zero length, the two parallel)
   (what mlod_megaviews_render and mlodvk_megaviews_render refuse first).
   Pure, thread-safe. */
MANYLODS_DEF mlod_result mlod_megaviews_check(const mlod_megaviews_params *params, mlod_error *error);

/* Render every view's map into the atlas (MANY VIEWS AT ONCE): the pair
   traversal of the scene tree and the view tree, drawing into shared maps
   of inner view nodes and fusing them down into each view's tile of the
   atlas (created for the views of mlod_megaviews_view at the same
   resolution: view i has tile i), in the orientation of params.forward
   and up (mlod_megaviews_view_oriented).  Depth as for paraboloids:
   distance from the view's eye.  Every tile is cleared first.  stats may
   be NULL.  Parallel through the hook, with the same atlas for any
   thread count.  The atlas's views give only the tiles' sizes and
   places: the maps are those of the view tree's eyes, whatever eyes the
   atlas was created for (so one atlas serves a view tree refitted to
   moving views; look its pixels up with mlod_megaviews_view_oriented of
   the view tree's eyes and the params' forward and up).
   Errors: NULLs, parameters mlod_megaviews_check refuses, an atlas of
   another view count or tile size, channels the scene lacks (the atlas
   is then untouched); maps whose bytes do not fit size_t
   (MLOD_ERROR_OVERFLOW, untouched too); no memory
   (MLOD_ERROR_OUT_OF_MEMORY, every tile then empty, nothing held).  Not
   thread-safe for one atlas. */
MANYLODS_DEF mlod_result mlod_megaviews_render(mlod_atlas *atlas, const mlod_tree *scene, const mlod_view_tree *views,
                                               const mlod_megaviews_params *params, mlod_megaviews_stats *stats,
                                               mlod_error *error);

/* The same traversal without fusion, for programs that look up a few
   pixels: every view node keeps its own map (what was drawn there, 8
   bytes per pixel for each node that drew anything; drawn with disc
   scale 1, as an atlas created without a disc_scale), and
   mlod_megaviews_query descends to a view's pixel.  On success *out
   owns the maps (mlod_megaviews_maps_destroy; their bytes:
   mlod_megaviews_maps_bytes); on error *out is NULL.  Errors as
   mlod_megaviews_render's, without an atlas. */
MANYLODS_DEF mlod_result mlod_megaviews_render_maps(const mlod_tree *scene, const mlod_view_tree *views,
                                                    const mlod_megaviews_params *params, mlod_megaviews_maps **out,
                                                    mlod_megaviews_stats *stats, mlod_error *error);

/* Pixel (x, y) of view `view`'s map (x < 2 resolution, y < resolution,
   in the render's orientation, which the maps keep): down the view tree
   from the root to the view's leaf, each node's pixel taken where it is
   nearer (from that node's centre) than what the nodes above left there,
   as the fusion does.  Returns 1 and writes the depth
   (distance from the view's eye) and the scene node, equal to the fused
   atlas's pixel of mlod_megaviews_render with the same arguments, or 0
   where nothing was drawn, for arguments out of range, and for a view tree
   or a scene that cannot be the render's (the maps record the view count
   and the scene's node count; a tree of the same counts is not told
   apart: pass those of the render).  Pure, thread-safe. */
MANYLODS_DEF int mlod_megaviews_query(const mlod_megaviews_maps *maps, const mlod_tree *scene,
                                      const mlod_view_tree *views, uint32_t view, uint32_t x, uint32_t y, float *depth,
                                      uint32_t *node);

/* Bytes the maps hold.  Free them with mlod_megaviews_maps_destroy (NULL
   is fine). */
MANYLODS_DEF size_t mlod_megaviews_maps_bytes(const mlod_megaviews_maps *maps);
MANYLODS_DEF void mlod_megaviews_maps_destroy(mlod_megaviews_maps *maps);

/* ------------------------------------------------------ vector lanes ---- */
/* The vector instructions the float filters run on (the cut's, the
   splat's, MegaViews' pair filter; see VECTOR LANES in the manual).  Every
   level computes the same bits: a level is a speed, never a result. */
typedef enum mlod_simd {
    MLOD_SIMD_NONE = 0, /* scalar code */
    MLOD_SIMD_SSE2 = 1, /* x86: 4 float lanes, the x86-64 baseline */
    MLOD_SIMD_NEON = 2, /* AArch64: 4 float lanes */
    MLOD_SIMD_AVX2 = 3, /* x86: 8 float lanes, where the processor and the OS have AVX2 */
    MLOD_SIMD_AVX512 = 4 /* x86: the same 8 lanes compiled for AVX-512 (F, VL, DQ, BW: 32 registers, masks) */
} mlod_simd;

/* The level the library's calls run at now: the highest that the build
   compiled (MANYLODS_NO_SIMD: none; the build's own flags' level, and
   AVX2 beside an SSE2 build with gcc or clang), that the processor and
   its OS support (cpuid and xgetbv, read once), and that mlod_simd_limit
   allows.  Thread-safe. */
MANYLODS_DEF mlod_simd mlod_simd_level(void);
/* Run the calls that start from now on at no level above `highest` (any
   mlod_simd; MLOD_SIMD_AVX512 or above lifts the limit); returns the level
   now in use (mlod_simd_level).  MLOD_SIMD_NONE turns the float filters'
   lanes off (the splat's exact path keeps its two double lanes: only
   MANYLODS_NO_SIMD removes every vector instruction).  For comparisons
   and benchmarks: the results do not change.  Thread-safe; a call in
   flight may finish at either level. */
MANYLODS_DEF mlod_simd mlod_simd_limit(mlod_simd highest);

/* --------------------------------------------------- built-in thread pool */
#ifdef MANYLODS_PTHREADS
typedef struct mlod_pool mlod_pool;
/* threads >= 1 workers in all, counting the calling thread (threads - 1 are
   started).  Returns NULL on failure.  Uses malloc. */
MANYLODS_DEF mlod_pool *mlod_pool_create(uint32_t threads);
MANYLODS_DEF void mlod_pool_destroy(mlod_pool *pool);
/* A hook that runs tasks on the pool; valid while the pool lives. One call
   at a time per pool.  For a NULL pool (mlod_pool_create failed) a hook
   that runs every task on the calling thread. */
MANYLODS_DEF mlod_parallel mlod_pool_parallel(mlod_pool *pool);
#endif

#endif /* MANYLODS_H */

/* ======================================================================== */
/*                             IMPLEMENTATION                               */
/* ======================================================================== */
#ifdef MANYLODS_IMPLEMENTATION
#ifndef MANYLODS_IMPLEMENTATION_DONE
#define MANYLODS_IMPLEMENTATION_DONE

/* Flags that change what a floating-point operation computes, refused
   where the compiler says it was given them (see FLOATING POINT above):
   finite-only math drops the NaN and infinity checks that bad input needs,
   reassociation, reciprocals and unsigned zeros change the bits. */
#if defined(__FAST_MATH__)
#error "manylods: compile the implementation without -ffast-math (or -Ofast): its results need IEEE arithmetic as written"
#endif
#if defined(__FINITE_MATH_ONLY__) && __FINITE_MATH_ONLY__
#error "manylods: compile the implementation without -ffinite-math-only: it must see NaN and infinite input to refuse it"
#endif
#if defined(__ASSOCIATIVE_MATH__) || defined(__RECIPROCAL_MATH__) || defined(__NO_SIGNED_ZEROS__)
#error "manylods: compile the implementation without -funsafe-math-optimizations, -fassociative-math, -freciprocal-math or -fno-signed-zeros: they change its results"
#endif

#include <math.h>
#include <string.h>
#include <stdio.h>
#include <stdarg.h>
#include <float.h>
#if defined(__linux__) && !defined(MANYLODS_NO_HUGE_PAGES)
#include <sys/mman.h>
#endif

#if defined(MANYLODS_MALLOC) != defined(MANYLODS_FREE)
#error "manylods: define both MANYLODS_MALLOC and MANYLODS_FREE, or neither"
#endif
#ifndef MANYLODS_MALLOC
#include <stdlib.h>
#define MANYLODS_MALLOC(size, user) ((void)(user), malloc(size))
#define MANYLODS_FREE(pointer, user) ((void)(user), free(pointer))
#endif
#ifndef MANYLODS_ASSERT
#include <assert.h>
#define MANYLODS_ASSERT(x) assert(x)
#endif
#ifdef MANYLODS_PTHREADS
#include <pthread.h>
#endif

/* ---------------------------------------------------- vector lanes ---- */
/* The one place that decides which vector code the implementation holds:
     MLOD__BASE_LEVEL     the level (an mlod_simd) the build's own flags
                          give: none with MANYLODS_NO_SIMD or on other
                          processors; AVX2 where the compiler targets it
                          (-mavx2, -march=haswell or later); else SSE2 on
                          x86 (every x86-64 compiler), NEON on AArch64;
     MLOD__SIMD_X86       SSE2 instructions usable (the box lanes, the
                          splat's double lanes);
     MLOD__SIMD_NEON      NEON instructions usable;
     MLOD__DISPATCH_AVX2  AVX2 lanes compiled beside an SSE2 build, for the
                          processors that have them (x86-64, gcc 5 or
                          later, clang 9 or later but not where it
                          targets FMA without AVX2, which the code below
                          builds for a target without FMA; none with
                          MANYLODS_NO_AVX2);
     MLOD__DISPATCH_AVX512  the same lanes compiled for AVX-512 too (gcc
                          only: clang fuses a * b + c under
                          -ffp-contract=fast whatever a pragma says, and
                          AVX-512 has FMA; none with MANYLODS_NO_AVX512).
   The lanes' code is compiled once per level (VECTOR LANES, at the end). */
#if defined(MANYLODS_NO_SIMD)
#define MLOD__BASE_LEVEL 0
#elif defined(__AVX2__) && !defined(MANYLODS_NO_AVX2) && defined(__AVX512F__) && defined(__AVX512VL__) &&              \
    defined(__AVX512DQ__) && defined(__AVX512BW__)
#define MLOD__BASE_LEVEL 4
#elif defined(__AVX2__) && !defined(MANYLODS_NO_AVX2)
#define MLOD__BASE_LEVEL 3
#elif defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2)
#define MLOD__BASE_LEVEL 1
#elif defined(__aarch64__) && defined(__ARM_NEON)
#define MLOD__BASE_LEVEL 2
#else
#define MLOD__BASE_LEVEL 0
#endif
#define MLOD__SIMD_X86 (MLOD__BASE_LEVEL == 1 || MLOD__BASE_LEVEL >= 3)
#define MLOD__SIMD_NEON (MLOD__BASE_LEVEL == 2)
#if MLOD__BASE_LEVEL == 1 && !defined(MANYLODS_NO_AVX2) && (defined(__x86_64__) || defined(_M_X64)) &&                \
    ((defined(__clang__) && __clang_major__ >= 9 && !defined(__FMA__)) ||                                               \
     (!defined(__clang__) && defined(__GNUC__) && __GNUC__ >= 5))
#define MLOD__DISPATCH_AVX2 1
#else
#define MLOD__DISPATCH_AVX2 0
#endif
#if MLOD__DISPATCH_AVX2 && !defined(__clang__) && !defined(MANYLODS_NO_AVX512)
#define MLOD__DISPATCH_AVX512 1
#else
#define MLOD__DISPATCH_AVX512 0
#endif
#if MLOD__SIMD_X86
#include <emmintrin.h>
#endif
#if MLOD__BASE_LEVEL >= 3 || MLOD__DISPATCH_AVX2
#include <immintrin.h> /* before the AVX2 pass's target: its functions keep their own */
#endif
#if MLOD__SIMD_NEON
#include <arm_neon.h>
#endif
#if MLOD__DISPATCH_AVX2
#include <cpuid.h>
#endif
/* The file the implementation includes again for each level's lanes: this
   one, looked up first in its own directory ("manylods.h"); define it
   where the file has another name. */
#ifndef MANYLODS_SELF
#define MANYLODS_SELF "manylods.h"
#endif

/* Every a * b + c here is rounded twice, as written: the shaders compute
   the same bits only so (where the device's doubles are IEEE), and the
   error bounds assume it.  gcc fuses such sums into one multiply-add in
   its GNU modes (the default) once the target has FMA (-march=native),
   clang within an expression: the implementation turns that off for its
   own code and restores the caller's setting at its end.
   clang defines no macro for -funsafe-math-optimizations (or its parts)
   nor for -ffp-contract=fast, so they cannot be refused above: its
   float_control(precise) turns the first off for the code below, and
   since -ffp-contract=fast fuses in the code generator whatever a pragma
   says, the code below is compiled for a target without FMA instructions
   where the caller's target has them (x86); nothing else changes. */
#if defined(__clang__)
#if __clang_major__ >= 11
#pragma float_control(precise, on, push)
#endif
#pragma STDC FP_CONTRACT OFF
#if defined(__FMA__) || defined(__AVX512F__)
#define MLOD__NO_FMA_TARGET 1
#pragma clang attribute push(__attribute__((target("no-fma"))), apply_to = function)
#endif
#elif defined(__GNUC__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")
#endif

/* What the public functions' definitions start with.  Compiled without
   FMA, they are never inlined into the caller's code, where the code
   generator would fuse them again (MANYLODS_STATIC, link-time
   optimisation). */
#ifdef MLOD__NO_FMA_TARGET
#define MLOD__PUBLIC MANYLODS_DEF __attribute__((noinline))
#else
#define MLOD__PUBLIC MANYLODS_DEF
#endif

/* ------------------------------------------------------ vector lanes ---- */

/* A word every thread may read while one writes it (the level in use):
   relaxed atomics where the compiler has them. */
#if defined(__GNUC__) || defined(__clang__)
#define MLOD__LOAD_WORD(p) __atomic_load_n(p, __ATOMIC_RELAXED)
#define MLOD__STORE_WORD(p, v) __atomic_store_n(p, v, __ATOMIC_RELAXED)
#else
#define MLOD__LOAD_WORD(p) (*(volatile int *)(p))
#define MLOD__STORE_WORD(p, v) (*(volatile int *)(p) = (v))
#endif

/* The level in use (-1: not chosen yet), mlod_simd_limit's limit and
   mlod__cpu_level's answer (-1: not asked yet). */
static int mlod__simd_in_use = -1, mlod__simd_cap = MLOD_SIMD_AVX512, mlod__simd_cpu = -1;

/* The highest dispatched level the processor runs with its OS keeping
   the registers: MLOD_SIMD_AVX512, MLOD_SIMD_AVX2, else 0. */
static int mlod__cpu_level(void)
{
#if MLOD__DISPATCH_AVX2
    unsigned a, b, c, d, lo, hi;
    const unsigned avx512 = 1u << 16 | 1u << 17 | 1u << 30 | 1u << 31; /* F, DQ, BW, VL */
    if (__get_cpuid_max(0, NULL) < 7) return 0;
    __cpuid(1, a, b, c, d);
    if (!(c >> 27 & 1u) || !(c >> 28 & 1u)) return 0; /* OSXSAVE, AVX */
    __asm__ __volatile__(".byte 0x0f, 0x01, 0xd0" : "=a"(lo), "=d"(hi) : "c"(0)); /* xgetbv: XCR0 */
    (void)hi;
    if ((lo & 6u) != 6u) return 0; /* the OS saves the SSE and AVX registers */
    __cpuid_count(7, 0, a, b, c, d);
    if (!(b >> 5 & 1u)) return 0; /* AVX2 */
    /* AVX-512: the four subsets, and the OS saving the mask and upper registers */
    return (b & avx512) == avx512 && (lo & 0xE0u) == 0xE0u ? MLOD_SIMD_AVX512 : MLOD_SIMD_AVX2;
#else
    return 0;
#endif
}

/* Whether the build compiled the lanes of this level. */
static int mlod__simd_compiled(int level)
{
    return level == MLOD_SIMD_NONE || level == MLOD__BASE_LEVEL || (level == MLOD_SIMD_AVX2 && MLOD__DISPATCH_AVX2) ||
           (level == MLOD_SIMD_AVX512 && MLOD__DISPATCH_AVX512);
}

/* Choose the level in use: the highest compiled one that the processor
   runs and the limit allows. */
static int mlod__simd_choose(void)
{
    int cap = MLOD__LOAD_WORD(&mlod__simd_cap), cpu = MLOD__LOAD_WORD(&mlod__simd_cpu), best = MLOD__BASE_LEVEL, level;
    if (cpu < 0) MLOD__STORE_WORD(&mlod__simd_cpu, cpu = mlod__cpu_level()); /* cpuid and xgetbv once */
    if (cpu > best) best = cpu;
    for (level = cap < best ? cap : best; level > MLOD_SIMD_NONE && !mlod__simd_compiled(level); level--) continue;
    MLOD__STORE_WORD(&mlod__simd_in_use, level);
    return level;
}

/* The level in use, which names the lanes' pass a call takes (VECTOR
   LANES). */
static inline int mlod__simd_pass(void)
{
    int level = MLOD__LOAD_WORD(&mlod__simd_in_use);
    return level >= 0 ? level : mlod__simd_choose();
}

MLOD__PUBLIC mlod_simd mlod_simd_level(void) { return (mlod_simd)mlod__simd_pass(); }

MLOD__PUBLIC mlod_simd mlod_simd_limit(mlod_simd highest)
{
    int cap = (int)highest < 0 ? 0 : (int)highest > MLOD_SIMD_AVX512 ? MLOD_SIMD_AVX512 : (int)highest;
    MLOD__STORE_WORD(&mlod__simd_cap, cap);
    return (mlod_simd)mlod__simd_choose();
}

/* ------------------------------------------------------------ errors ---- */

MLOD__PUBLIC const char *mlod_result_name(mlod_result result)
{
    switch (result) {
    case MLOD_OK: return "MLOD_OK";
    case MLOD_ERROR_INVALID_ARGUMENT: return "MLOD_ERROR_INVALID_ARGUMENT";
    case MLOD_ERROR_NON_FINITE: return "MLOD_ERROR_NON_FINITE";
    case MLOD_ERROR_INDEX_OUT_OF_RANGE: return "MLOD_ERROR_INDEX_OUT_OF_RANGE";
    case MLOD_ERROR_EMPTY: return "MLOD_ERROR_EMPTY";
    case MLOD_ERROR_BAD_EPSILON: return "MLOD_ERROR_BAD_EPSILON";
    case MLOD_ERROR_BAD_VIEW: return "MLOD_ERROR_BAD_VIEW";
    case MLOD_ERROR_OVERFLOW: return "MLOD_ERROR_OVERFLOW";
    case MLOD_ERROR_OUT_OF_MEMORY: return "MLOD_ERROR_OUT_OF_MEMORY";
    case MLOD_ERROR_MISMATCH: return "MLOD_ERROR_MISMATCH";
    case MLOD_ERROR_RANGE: return "MLOD_ERROR_RANGE";
    case MLOD_ERROR_CANCELLED: return "MLOD_ERROR_CANCELLED";
    case MLOD_ERROR_DEVICE: return "MLOD_ERROR_DEVICE";
    }
    return "MLOD_ERROR_UNKNOWN";
}

/* printf-style arguments checked where the compiler can */
#if defined(__GNUC__) || defined(__clang__)
#define MLOD__PRINTF(format_index) __attribute__((format(printf, format_index, format_index + 1)))
#else
#define MLOD__PRINTF(format_index)
#endif
static mlod_result mlod__fail(mlod_error *error, mlod_result code, const char *format, ...) MLOD__PRINTF(3);
static mlod_result mlod__fail(mlod_error *error, mlod_result code, const char *format, ...)
{
    if (error) {
        va_list args;
        error->code = code;
        va_start(args, format);
        vsnprintf(error->message, sizeof error->message, format, args);
        va_end(args);
    }
    return code;
}

static mlod_result mlod__succeed(mlod_error *error)
{
    if (error) {
        error->code = MLOD_OK;
        error->message[0] = '\0';
    }
    return MLOD_OK;
}

/* -------------------------------------------------------- allocation ---- */

static void *mlod__default_alloc(void *user, size_t bytes) { return MANYLODS_MALLOC(bytes, user); }
static void mlod__default_free(void *user, void *pointer) { MANYLODS_FREE(pointer, user); }

MLOD__PUBLIC mlod_allocator mlod_default_allocator(void)
{
    mlod_allocator a;
    a.alloc = mlod__default_alloc;
    a.free = mlod__default_free;
    a.user = NULL;
    return a;
}

static mlod_allocator mlod__allocator(const mlod_allocator *given)
{
    if (given && given->alloc && given->free) return *given;
    return mlod_default_allocator();
}

/* Large buffers on Linux (x86-64, AArch64): ask the kernel for
   transparent huge pages over the 2 MiB pages inside [p, p + bytes), so
   that touching them costs one page fault per 2 MiB instead of one per
   4 KiB (a build of 1.3 M leaves touched 256 MB in 65 k faults, a quarter
   of its time on a virtual machine).  Advice only: a system that leaves
   huge pages off (or memory that cannot have them) ignores it.
   MANYLODS_NO_HUGE_PAGES turns it off. */
#if defined(__linux__) && !defined(MANYLODS_NO_HUGE_PAGES) && \
    (defined(MADV_HUGEPAGE) || (!defined(__cplusplus) && (defined(__x86_64__) || defined(__aarch64__))))
#ifdef MADV_HUGEPAGE
#define MLOD__MADV_HUGEPAGE MADV_HUGEPAGE
#else
/* <sys/mman.h> hides madvise under -std=c99; its Linux value there */
#define MLOD__MADV_HUGEPAGE 14
int madvise(void *address, size_t length, int advice);
#endif
static void mlod__advise_huge(void *p, size_t bytes)
{
    const uintptr_t huge = (uintptr_t)1 << 21;
    uintptr_t begin = ((uintptr_t)p + huge - 1) & ~(huge - 1), end = ((uintptr_t)p + bytes) & ~(huge - 1);
    if (bytes >= 4 * huge && end > begin) (void)madvise((void *)begin, (size_t)(end - begin), MLOD__MADV_HUGEPAGE);
}
#else
static void mlod__advise_huge(void *p, size_t bytes)
{
    (void)p;
    (void)bytes;
}
#endif

/* count * size bytes, or NULL when that overflows or the allocator fails;
   *bytes_total grows by what was allocated. */
static void *mlod__alloc_array(const mlod_allocator *a, size_t count, size_t size, size_t *bytes_total)
{
    void *p;
    size_t bytes;
    if (size != 0 && count > (size_t)-1 / size) return NULL;
    bytes = count * size;
    p = a->alloc(a->user, bytes ? bytes : 1);
    if (p) mlod__advise_huge(p, bytes);
    if (p && bytes_total) *bytes_total += bytes;
    return p;
}

static void mlod__free(const mlod_allocator *a, void *p)
{
    if (p) a->free(a->user, p);
}

/* -------------------------------------------------- float helpers ---- */

#define MLOD__PI 3.14159265358979323846
/* Relative slack of a parent sphere over its children: 2^-20. */
#define MLOD__SPHERE_SLACK (1.0 + 1.0 / 1048576.0)
/* Angular margin of a parent cone over its children: 2^-20 rad. */
#define MLOD__CONE_MARGIN (1.0 / 1048576.0)

/* The smallest float >= x, for x >= 0 (finite or +inf).  Rounding to
   nearest rounds down about half the time, at random: stepping up without
   a branch spares each merge two mispredicted branches (a merge of spheres
   and cones took 18 % less time). */
/* GLSL twin: float_up */
static float mlod__float_up(double x)
{
    float f = (float)x;
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    bits += (uint32_t)((double)f < x); /* rounded down: the next float up */
    memcpy(&f, &bits, sizeof f);
    return f;
}

static int mlod__finite3(const float *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

static const float *mlod__at(const float *base, size_t stride, size_t index)
{
    return (const float *)((const char *)base + index * (stride ? stride : 3 * sizeof(float)));
}

/* Element `index` of a strided array of single floats (stride 0: packed). */
static float mlod__scalar_at(const float *base, size_t stride, size_t index)
{
    return *(const float *)((const char *)base + index * (stride ? stride : sizeof(float)));
}

/* The box around count >= 1 strided positions (mlod__at): lo and hi. */
static inline void mlod__box_of(const float *base, size_t stride, uint32_t count, double lo[3], double hi[3])
{
    /* six scalars, not arrays, so that they stay in registers (the build's
       splits box every node along three axes: their hottest loop) */
    float x0 = base[0], x1 = x0, y0 = base[1], y1 = y0, z0 = base[2], z1 = z0;
    uint32_t i;
    for (i = 1; i < count; i++) {
        const float *p = mlod__at(base, stride, i);
        x0 = p[0] < x0 ? p[0] : x0;
        x1 = p[0] > x1 ? p[0] : x1;
        y0 = p[1] < y0 ? p[1] : y0;
        y1 = p[1] > y1 ? p[1] : y1;
        z0 = p[2] < z0 ? p[2] : z0;
        z1 = p[2] > z1 ? p[2] : z1;
    }
    lo[0] = x0;
    lo[1] = y0;
    lo[2] = z0;
    hi[0] = x1;
    hi[1] = y1;
    hi[2] = z1;
}

/* GLSL twin: dot3 */
static double mlod__dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* GLSL twin: cross_d */
static void mlod__cross3(const double *a, const double *b, double *out)
{
    double x = a[1] * b[2] - a[2] * b[1];
    double y = a[2] * b[0] - a[0] * b[2];
    double z = a[0] * b[1] - a[1] * b[0];
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

/* GLSL twin: length_d */
static double mlod__length3(const double *a) { return sqrt(mlod__dot3(a, a)); }

/* Distance between two float points, in double. */
/* GLSL twin: distance_f */
static double mlod__distance_f(const float *a, const float *b)
{
    double dx = (double)a[0] - b[0], dy = (double)a[1] - b[1], dz = (double)a[2] - b[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* sin and cos of a in [0, pi], to a few ulps (absolute error ~1e-16),
   with + and * only: the Taylor series of cos and sin around pi/2
   (|x| = |a - pi/2| <= pi/2, terms up to degree 22 and 21: truncation
   below 1e-17), each split into its even and odd powers of x^2 and summed
   as Horner chains in x^4 of at most 6 terms, so that four short chains
   run side by side.  Written out the same way in shaders/common.glsl, so
   that the CPU and the Vulkan path compute the same bits wherever the
   device's double arithmetic is IEEE (lavapipe). */
/* 1 / (4i)! and 1 / (4i + 2)! (cos), 1 / (4i + 1)! and 1 / (4i + 3)! (sin),
   highest i first, and 1 / (4i + 1) and 1 / (4i + 3) for i = 5 .. 0 (atan,
   its even and odd powers of u^2): the same decimal literals, so the same
   doubles, in shaders/common.glsl. */
/* GLSL twin: COS_EVEN (and the five arrays after it) */
static const double mlod__cos_even[6] = {4.110317623312165e-19, 4.779477332387385e-14, 2.08767569878681e-09,
                                         2.48015873015873e-05,  0.041666666666666664, 1.0};
static const double mlod__cos_odd[6] = {8.896791392450574e-22, 1.5619206968586225e-16, 1.1470745597729725e-11,
                                        2.755731922398589e-07, 0.001388888888888889,   0.5};
static const double mlod__sin_even[6] = {1.9572941063391263e-20, 2.8114572543455206e-15, 1.6059043836821613e-10,
                                         2.7557319223985893e-06, 0.008333333333333333,   1.0};
static const double mlod__sin_odd[5] = {8.22063524662433e-18, 7.647163731819816e-13, 2.505210838544172e-08,
                                        0.0001984126984126984, 0.16666666666666666};
static const double mlod__atan_even[6] = {0.047619047619047616, 0.058823529411764705, 0.07692307692307693,
                                          0.1111111111111111,   0.2,                  1.0};
static const double mlod__atan_odd[6] = {0.043478260869565216, 0.05263157894736842, 0.06666666666666667,
                                         0.09090909090909091,  0.14285714285714285, 0.3333333333333333};

/* GLSL twin: sin_cos */
static inline void mlod__sin_cos(double a, double *sin_a, double *cos_a)
{
    double x = a - 1.57079632679489661923, y = x * x, z = y * y;
    double ce = mlod__cos_even[0], co = mlod__cos_odd[0], se = mlod__sin_even[0], so = mlod__sin_odd[0];
    int k;
    for (k = 1; k < 6; k++) {
        ce = mlod__cos_even[k] + z * ce;
        co = mlod__cos_odd[k] + z * co;
        se = mlod__sin_even[k] + z * se;
    }
    for (k = 1; k < 5; k++) so = mlod__sin_odd[k] + z * so;
    *sin_a = ce - y * co;         /* sin(pi/2 + x) = cos x */
    *cos_a = -x * (se - y * so); /* cos(pi/2 + x) = -sin x */
}

/* atan2(y, x) for y >= 0, in [0, pi], within 1e-11 rad, with + - * /
   only: reduced to t = min/max in [0, 1], then to |u| <= tan(pi/8) by
   atan t = pi/4 + atan((t - 1) / (t + 1)), then the Taylor series of atan u
   to degree 23 (alternating: truncation below u^25 / 25 < 1.1e-11), its
   even and odd powers of u^2 summed as two Horner chains of half the
   length.  Its one use, the cone merge, allows 2^-22 rad of error.
   Written out the same way in shaders/common.glsl (atan2_d), so that the
   CPU and the Vulkan refit compute the same bits. */
/* GLSL twin: atan2_d */
static double mlod__atan2(double y, double x)
{
    double ax = fabs(x), t, u, u2, w, even, odd, base = 0.0, a;
    int swap = y > ax, k;
    if (!(y > 0.0) && !(ax > 0.0)) return x < 0.0 ? 3.14159265358979323846 : 0.0;
    t = swap ? ax / y : y / ax;
    u = t;
    if (t > 0.41421356237309504880) {
        u = (t - 1.0) / (t + 1.0);
        base = 0.78539816339744830962;
    }
    u2 = u * u;
    w = u2 * u2;
    even = mlod__atan_even[0];
    odd = mlod__atan_odd[0];
    for (k = 1; k < 6; k++) {
        even = mlod__atan_even[k] + w * even;
        odd = mlod__atan_odd[k] + w * odd;
    }
    a = base + u * (even - u2 * odd);
    if (swap) a = 1.57079632679489661923 - a;
    return x < 0.0 ? 3.14159265358979323846 - a : a;
}

/* Angle between two (not necessarily unit) directions, within 1e-11 rad
   everywhere (mlod__atan2). */
/* GLSL twin: angle_d */
static double mlod__angle(const double *a, const double *b)
{
    double c[3];
    mlod__cross3(a, b, c);
    return mlod__atan2(mlod__length3(c), mlod__dot3(a, b));
}

/* ------------------------------------------------ sphere and cone merge -- */

/* Merges take up to MLOD__LANES node pairs at once, step by step across
   them: each lane's arithmetic is what one merge alone computes, and the
   lanes' long chains of square roots and divisions overlap. */
#define MLOD__LANES 4u

/* For each lane l < n: the smallest sphere around spheres a[l] and b[l]
   (x, y, z, r), rounded to floats so that it contains both exactly, with
   the relative slack of the tree, into out[l] (which may alias a[l] or
   b[l]). */
/* GLSL twin: sphere_enclose */
static void mlod__sphere_enclose(const float *const *a, const float *const *b, float *const *out, uint32_t n)
{
    double d[MLOD__LANES];
    float c[MLOD__LANES][3];
    uint32_t l;
    int k;
    for (l = 0; l < n; l++) d[l] = mlod__distance_f(a[l], b[l]);
    for (l = 0; l < n; l++) {
        double ra = a[l][3], rb = b[l][3];
        if (d[l] + rb <= ra) {
            for (k = 0; k < 3; k++) c[l][k] = a[l][k];
        } else if (d[l] + ra <= rb) {
            for (k = 0; k < 3; k++) c[l][k] = b[l][k];
        } else {
            double t = ((d[l] + ra + rb) * 0.5 - ra) / d[l];
            for (k = 0; k < 3; k++) c[l][k] = (float)((double)a[l][k] + ((double)b[l][k] - (double)a[l][k]) * t);
        }
    }
    for (l = 0; l < n; l++) {
        double need_a = mlod__distance_f(c[l], a[l]) + a[l][3], need_b = mlod__distance_f(c[l], b[l]) + b[l][3];
        /* (1 + 2^-50) covers the rounding of the double sums, which may even
           drop a child radius far below the distance */
        out[l][3] =
            mlod__float_up((need_a > need_b ? need_a : need_b) * MLOD__SPHERE_SLACK * (1.0 + 1.0 / 1125899906842624.0));
        for (k = 0; k < 3; k++) out[l][k] = c[l][k];
    }
}

/* GLSL twin: cone_full */
static void mlod__cone_full(const float *axis, float *out)
{
    out[0] = axis[0];
    out[1] = axis[1];
    out[2] = axis[2];
    out[3] = mlod__float_up(MLOD__PI);
}

/* Rounding a unit axis to float turns it by at most 2^-24 rad (round to
   nearest moves each component by at most 2^-24 of it); 2^-22 bounds that
   and the error of the double arithmetic before it, as long as the two
   axes are not nearly opposite: the direction from A towards B is then
   the difference of nearly equal vectors, its error ~1e-16 over its length
   (the sine of their angle), and the axis turns by nearly pi/2 along it
   (nearly equal axes turn by as little: no harm).  Below
   MLOD__CONE_OPPOSITE of that length, for axes more than pi/2 apart, the
   merge measures the stored axis against both cones instead. */
#define MLOD__CONE_ROUNDING (1.0 / 4194304.0)
#define MLOD__CONE_OPPOSITE (1.0 / 1024.0)

/* For each lane l < n: the smallest cone of directions around cones a[l]
   and b[l] (axis x, y, z, half-angle), rounded so that it contains both
   with the angular margin of the tree, into out[l] (which may alias a[l]
   or b[l]).  The merged axis X lies on the arc from A to B, at angle phi
   from A and theta - phi from B, both at most the merged half-angle
   alpha; the axis as stored (float) is within MLOD__CONE_ROUNDING of X, so
   alpha plus that bound contains both cones without measuring the stored
   axis again (but for nearly opposite axes, see MLOD__CONE_OPPOSITE). */
/* GLSL twin: cone_enclose */
static void mlod__cone_enclose(const float *const *a, const float *const *b, float *const *out, uint32_t n)
{
    enum { DONE, AXIS, ROTATE }; /* per lane: written; X and alpha known; X to rotate */
    double A[MLOD__LANES][3], B[MLOD__LANES][3], X[MLOD__LANES][3], theta[MLOD__LANES], alpha[MLOD__LANES];
    double phi[MLOD__LANES], sin_phi[MLOD__LANES], cos_phi[MLOD__LANES];
    int state[MLOD__LANES], measure[MLOD__LANES], k;
    uint32_t l;
    for (l = 0; l < n; l++) {
        state[l] = a[l][3] >= MLOD__PI || b[l][3] >= MLOD__PI ? DONE : AXIS;
        measure[l] = 0;
        if (state[l] == DONE) {
            mlod__cone_full(a[l], out[l]);
            continue;
        }
        for (k = 0; k < 3; k++) {
            A[l][k] = a[l][k];
            B[l][k] = b[l][k];
        }
        /* equal axes (leaves of one flat triangle, often): their cross
           product is exactly 0, so mlod__angle's atan2(0, |A|^2) is 0 */
        theta[l] = A[l][0] == B[l][0] && A[l][1] == B[l][1] && A[l][2] == B[l][2] ? 0.0 : mlod__angle(A[l], B[l]);
    }
    for (l = 0; l < n; l++) {
        if (state[l] == DONE) continue;
        if (theta[l] + b[l][3] <= a[l][3]) {
            for (k = 0; k < 3; k++) X[l][k] = A[l][k];
            alpha[l] = a[l][3];
        } else if (theta[l] + a[l][3] <= b[l][3]) {
            for (k = 0; k < 3; k++) X[l][k] = B[l][k];
            alpha[l] = b[l][3];
        } else {
            alpha[l] = (theta[l] + a[l][3] + b[l][3]) * 0.5;
            if (alpha[l] >= MLOD__PI) {
                mlod__cone_full(a[l], out[l]);
                state[l] = DONE;
                continue;
            }
            phi[l] = alpha[l] - a[l][3]; /* rotate A towards B by phi */
            state[l] = ROTATE;
        }
    }
    for (l = 0; l < n; l++)
        if (state[l] == ROTATE) mlod__sin_cos(phi[l], &sin_phi[l], &cos_phi[l]);
    for (l = 0; l < n; l++) {
        double la, an[3], ab, t[3], len;
        if (state[l] != ROTATE) continue;
        la = mlod__length3(A[l]);
        for (k = 0; k < 3; k++) an[k] = A[l][k] / la;
        ab = mlod__dot3(an, B[l]);
        for (k = 0; k < 3; k++) t[k] = B[l][k] - an[k] * ab;
        len = mlod__length3(t);
        measure[l] = !(len >= MLOD__CONE_OPPOSITE) && !(ab > 0.0); /* nearly opposite, not nearly equal */
        if (!(len > 0.0)) { /* antiparallel: any direction orthogonal to A */
            double helper[3] = {0.0, 0.0, 0.0};
            helper[fabs(an[0]) < 0.5 ? 0 : 1] = 1.0;
            mlod__cross3(an, helper, t);
            len = mlod__length3(t);
        }
        for (k = 0; k < 3; k++) X[l][k] = an[k] * cos_phi[l] + t[k] / len * sin_phi[l];
    }
    for (l = 0; l < n; l++) {
        double len, stored;
        /* volatile: a measured margin must start from the axis as rounded
           to float (gcc 12 -O2 otherwise may reuse the unrounded doubles) */
        volatile float rounded[3];
        float axis[3];
        if (state[l] == DONE) continue;
        len = mlod__length3(X[l]);
        for (k = 0; k < 3; k++) {
            rounded[k] = (float)(X[l][k] / len);
            if (rounded[k] == 0.0f) rounded[k] = 0.0f; /* +0, however the zero was reached (as the shader) */
            axis[k] = rounded[k];
        }
        if (measure[l]) { /* the stored axis against both cones (the atan2 error is within the rounding bound) */
            double S[3], need_a, need_b;
            for (k = 0; k < 3; k++) S[k] = rounded[k];
            need_a = mlod__angle(S, A[l]) + a[l][3];
            need_b = mlod__angle(S, B[l]) + b[l][3];
            alpha[l] = need_a > need_b ? need_a : need_b;
        }
        stored = alpha[l] + MLOD__CONE_ROUNDING + MLOD__CONE_MARGIN;
        if (stored >= MLOD__PI) {
            mlod__cone_full(axis, out[l]);
            continue;
        }
        for (k = 0; k < 3; k++) out[l][k] = axis[k];
        out[l][3] = mlod__float_up(stored);
    }
}

/* A leaf's cone from a normal: half-angle 0, or the full sphere when the
   normal has no direction. */
static void mlod__cone_from_normal(const double *n, float *out)
{
    double len = mlod__length3(n);
    int k;
    if (!(len > 0.0) || !isfinite(len)) {
        static const float up[3] = {0.0f, 0.0f, 1.0f};
        mlod__cone_full(up, out);
        return;
    }
    for (k = 0; k < 3; k++) out[k] = (float)(n[k] / len);
    out[3] = 0.0f;
}

/* ------------------------------------------------------- tree shape ---- */

/* GLSL twin: depth_of */
static uint32_t mlod__depth_of(uint64_t node)
{
#if defined(__GNUC__) || defined(__clang__)
    return 63u - (uint32_t)__builtin_clzll(node + 1);
#else
    uint32_t depth = 0;
    uint64_t x = node + 1;
    while (x > 1) {
        x >>= 1;
        depth++;
    }
    return depth;
#endif
}

/* Number of leaves below node i in the implicit tree of n leaves. */
/* GLSL twin: leaves_below */
static uint32_t mlod__leaves_below(uint32_t i, uint32_t n)
{
    uint64_t last = 2 * (uint64_t)n - 2;
    uint32_t k = mlod__depth_of(i), deepest = mlod__depth_of(last);
    uint32_t span = deepest - k;
    uint64_t lo = (((uint64_t)i + 1) << span) - 1, hi = (((uint64_t)i + 2) << span) - 2;
    uint64_t at_deepest = lo > last ? 0 : (hi < last ? hi : last) - lo + 1;
    uint64_t nodes = (((uint64_t)1 << span) - 1) + at_deepest;
    return (uint32_t)((nodes + 1) / 2);
}

/* The 4-float records of nodes first .. first + n - 1 of a per-node array,
   and of their left and right children. */
static void mlod__lane_pointers(float *base, uint32_t first, uint32_t n, const float **left, const float **right,
                                float **parent)
{
    uint32_t j;
    for (j = 0; j < n; j++) {
        size_t i = (size_t)first + j;
        left[j] = base + 4 * (2 * i + 1);
        right[j] = base + 4 * (2 * i + 2);
        parent[j] = base + 4 * i;
    }
}

/* Merge the bounds of nodes first .. first + n - 1 (n <= MLOD__LANES, one
   depth) from their children. */
static void mlod__merge_nodes(mlod_tree *tree, uint32_t first, uint32_t n)
{
    const float *left[MLOD__LANES], *right[MLOD__LANES];
    float *parent[MLOD__LANES];
    uint32_t j;
    mlod__lane_pointers(tree->spheres, first, n, left, right, parent);
    mlod__sphere_enclose(left, right, parent, n);
    if (tree->cones) {
        mlod__lane_pointers(tree->cones, first, n, left, right, parent);
        mlod__cone_enclose(left, right, parent, n);
    }
    for (j = 0; j < n; j++) {
        uint32_t i = first + j, l = 2 * i + 1, r = 2 * i + 2;
        if (tree->areas) tree->areas[i] = tree->areas[l] + tree->areas[r];
        if (tree->colors) {
            double wl = mlod__leaves_below(l, tree->leaf_count), wr = mlod__leaves_below(r, tree->leaf_count);
            int k;
            for (k = 0; k < 3; k++)
                tree->colors[3 * (size_t)i + k] =
                    (float)((wl * tree->colors[3 * (size_t)l + k] + wr * tree->colors[3 * (size_t)r + k]) / (wl + wr));
        }
    }
}

MLOD__PUBLIC int mlod_tree_depth_nodes(uint32_t leaf_count, uint32_t depth, uint32_t *first, uint32_t *last)
{
    uint64_t lo, hi;
    if (!first || !last || leaf_count < 2 || depth >= 32) return 0; /* depth 32 starts at node 2^32 - 1 > leaf_count - 2 */
    lo = ((uint64_t)1 << depth) - 1;
    hi = ((uint64_t)1 << (depth + 1)) - 2;
    if (lo > (uint64_t)leaf_count - 2) return 0;
    if (hi > (uint64_t)leaf_count - 2) hi = (uint64_t)leaf_count - 2;
    *first = (uint32_t)lo;
    *last = (uint32_t)hi;
    return 1;
}


/* A hint that the cache line at p is wanted soon (nothing where the
   compiler has no way to say it). */
#if defined(__GNUC__) || defined(__clang__)
#define MLOD__PREFETCH(p) __builtin_prefetch(p)
#define MLOD__PREFETCH_WRITE(p) __builtin_prefetch(p, 1)
#else
#define MLOD__PREFETCH(p) ((void)(p))
#define MLOD__PREFETCH_WRITE(p) ((void)(p))
#endif

/* ------------------------------------------------------- parallel run -- */

static void mlod__run(const mlod_parallel *parallel, uint32_t count, mlod_task_fn *task, void *context)
{
    uint32_t i;
    if (parallel && parallel->run && count > 1) {
        parallel->run(parallel->user, count, task, context);
        return;
    }
    for (i = 0; i < count; i++) task(context, i);
}

/* ------------------------------------------------------ input checks ---- */

/* Coordinates beyond this magnitude could overflow float bounds. */
#define MLOD__MAX_COORDINATE 1.0e36
/* Leaf radii and summed areas beyond this could overflow float bounds. */
#define MLOD__MAX_MEASURE 1.0e37

static mlod_result mlod__check_floats(const float *base, size_t stride, uint32_t count, int limit,
                                      const char *what, mlod_error *error)
{
    uint32_t i;
    if (stride && (stride < 3 * sizeof(float) || stride % sizeof(float)))
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "%s stride %lu is not 0 or a multiple of 4 of at least 12",
                          what, (unsigned long)stride);
    for (i = 0; i < count; i++) {
        const float *p = mlod__at(base, stride, i);
        int k;
        if (!mlod__finite3(p))
            return mlod__fail(error, MLOD_ERROR_NON_FINITE, "%s %u is not finite (%g, %g, %g)", what, i, p[0], p[1], p[2]);
        for (k = 0; limit && k < 3; k++)
            if (fabs(p[k]) > MLOD__MAX_COORDINATE)
                return mlod__fail(error, MLOD_ERROR_RANGE, "%s %u has a coordinate beyond 1e36 (%g)", what, i, p[k]);
    }
    return MLOD_OK;
}

static mlod_result mlod__check_mesh(const mlod_mesh *mesh, mlod_error *error)
{
    mlod_result res;
    uint32_t i;
    if (!mesh) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "mesh is NULL");
    if (mesh->index_count % 3 != 0)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "index_count %u is not a multiple of 3", mesh->index_count);
    if (mesh->index_count == 0 || mesh->vertex_count == 0)
        return mlod__fail(error, MLOD_ERROR_EMPTY, "the mesh has no triangles");
    if (!mesh->positions || !mesh->indices)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "mesh positions or indices are NULL");
    for (i = 0; i < mesh->index_count; i++)
        if (mesh->indices[i] >= mesh->vertex_count)
            return mlod__fail(error, MLOD_ERROR_INDEX_OUT_OF_RANGE, "indices[%u] = %u is not below vertex_count %u", i,
                              mesh->indices[i], mesh->vertex_count);
    res = mlod__check_floats(mesh->positions, mesh->position_stride, mesh->vertex_count, 1, "position", error);
    if (res == MLOD_OK && mesh->normals)
        res = mlod__check_floats(mesh->normals, mesh->normal_stride, mesh->vertex_count, 0, "normal", error);
    if (res == MLOD_OK && mesh->colors)
        res = mlod__check_floats(mesh->colors, mesh->color_stride, mesh->vertex_count, 0, "colour", error);
    return res;
}

static mlod_result mlod__check_points(const mlod_points *points, mlod_error *error)
{
    mlod_result res;
    uint32_t i;
    if (!points) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "points is NULL");
    if (points->count == 0) return mlod__fail(error, MLOD_ERROR_EMPTY, "the point cloud has no points");
    if (points->count > MANYLODS_MAX_LEAVES)
        return mlod__fail(error, MLOD_ERROR_OVERFLOW, "%u points exceed MANYLODS_MAX_LEAVES", points->count);
    if (!points->positions) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "point positions are NULL");
    res = mlod__check_floats(points->positions, points->position_stride, points->count, 1, "point", error);
    if (res == MLOD_OK && points->normals)
        res = mlod__check_floats(points->normals, points->normal_stride, points->count, 0, "normal", error);
    if (res == MLOD_OK && points->colors)
        res = mlod__check_floats(points->colors, points->color_stride, points->count, 0, "colour", error);
    if (res == MLOD_OK && points->radii && points->radius_stride % sizeof(float))
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "radius stride %lu is not a multiple of 4",
                          (unsigned long)points->radius_stride);
    for (i = 0; res == MLOD_OK && points->radii && i < points->count; i++) {
        float r = mlod__scalar_at(points->radii, points->radius_stride, i);
        if (!isfinite(r)) return mlod__fail(error, MLOD_ERROR_NON_FINITE, "radius %u is not finite", i);
        if (r < 0.0f || r > MLOD__MAX_COORDINATE)
            return mlod__fail(error, MLOD_ERROR_RANGE, "radius %u = %g is negative or beyond 1e36", i, r);
    }
    return res;
}

static mlod_result mlod__check_desc(const mlod_build_desc *desc, mlod_tree **out, mlod_error *error)
{
    if (!out) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "out_tree is NULL");
    *out = NULL;
    if (!desc) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "desc is NULL");
    if (!(desc->radius_scale >= 0.0f) || !isfinite(desc->radius_scale))
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "radius_scale %g is not finite and >= 0", desc->radius_scale);
    if (desc->attributes &
        ~(uint32_t)(MLOD_ATTR_CONE | MLOD_ATTR_AREA | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT | MLOD_ATTR_REFIT_CACHE))
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "unknown attribute bits 0x%x", desc->attributes);
    if ((desc->attributes & MLOD_ATTR_REFIT_CACHE) && !(desc->attributes & MLOD_ATTR_REFIT))
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "MLOD_ATTR_REFIT_CACHE needs MLOD_ATTR_REFIT");
    return MLOD_OK;
}

/* ------------------------------------------------- tree allocation ---- */

/* Every array of a tree lies in one block that starts with its spheres
   (mlod__tree_layout). */
static void mlod__tree_free_arrays(mlod_tree *t) { mlod__free(&t->allocator, t->spheres); }

MLOD__PUBLIC void mlod_tree_destroy(mlod_tree *tree)
{
    mlod_allocator a;
    if (!tree) return;
    a = tree->allocator;
    mlod__tree_free_arrays(tree);
    a.free(a.user, tree);
}

/* What the samples of one triangle share: the growth of its area since the
   build (area now / at build), the leaf radius and area that follow, and
   the cone of its face normal (with cones).  Where the tree has
   mlod_tree.triangle_leaves, the build and refit compute it once per
   triangle into it, else once per sample. */
typedef struct mlod__triangle_leaf {
    double growth;
    float radius, area, cone[4];
} mlod__triangle_leaf;

/* Offsets in a block and sizes: the next multiple of 16 bytes (any
   array's alignment, the 8 of a double or uint64 included). */
#define MLOD__BLOCK_ALIGN 16u
static uint64_t mlod__block_round(uint64_t bytes) { return (bytes + MLOD__BLOCK_ALIGN - 1) / MLOD__BLOCK_ALIGN * MLOD__BLOCK_ALIGN; }

/* The arrays of a tree of `leaves` leaves, in its one block: spheres,
   cones, areas, colors, leaf_sources, leaf_barycentrics, triangle_areas,
   triangle_leaves (MLOD__TREE_* below), each at offsets[i] bytes from the
   block's start, a multiple of 16, or offsets[i] = UINT64_MAX for an
   array the attributes do not ask for.  Returns the block's bytes.  A
   build lends the block to its ordering's scratch before it writes the
   arrays (mlod__order_layout). */
enum {
    MLOD__TREE_SPHERES, MLOD__TREE_CONES, MLOD__TREE_AREAS, MLOD__TREE_COLORS, MLOD__TREE_SOURCES,
    MLOD__TREE_BARYCENTRICS, MLOD__TREE_TRIANGLE_AREAS, MLOD__TREE_TRIANGLE_LEAVES, MLOD__TREE_CHANGES,
    MLOD__TREE_CORNERS, MLOD__TREE_CORNERS_CHANGED, MLOD__TREE_ARRAYS
};

/* Floats per triangle in mlod_tree.corners (MLOD_ATTR_REFIT_CACHE): 3
   corners' positions, then their normals with cones, then their colours
   with colours. */
static uint32_t mlod__corner_floats(uint32_t attributes)
{
    return 9u * (1u + ((attributes & MLOD_ATTR_CONE) ? 1u : 0u) + ((attributes & MLOD_ATTR_COLOR) ? 1u : 0u));
}
static uint64_t mlod__tree_layout(uint64_t leaves, uint32_t attributes, int mesh, uint64_t triangles,
                                  uint64_t offsets[MLOD__TREE_ARRAYS])
{
    uint64_t nodes = 2 * leaves - 1, size[MLOD__TREE_ARRAYS], at = 0;
    int i, refit_mesh = (attributes & MLOD_ATTR_REFIT) && mesh;
    size[MLOD__TREE_SPHERES] = nodes * 4 * sizeof(float);
    size[MLOD__TREE_CONES] = attributes & MLOD_ATTR_CONE ? nodes * 4 * sizeof(float) : 0;
    size[MLOD__TREE_AREAS] = attributes & MLOD_ATTR_AREA ? nodes * sizeof(float) : 0;
    size[MLOD__TREE_COLORS] = attributes & MLOD_ATTR_COLOR ? nodes * 3 * sizeof(float) : 0;
    size[MLOD__TREE_SOURCES] = attributes & MLOD_ATTR_REFIT ? leaves * sizeof(uint32_t) : 0;
    size[MLOD__TREE_BARYCENTRICS] = refit_mesh ? leaves * 2 * sizeof(float) : 0;
    size[MLOD__TREE_TRIANGLE_AREAS] = refit_mesh ? triangles * sizeof(double) : 0;
    /* refit shares each triangle's work among its samples */
    size[MLOD__TREE_TRIANGLE_LEAVES] = refit_mesh && leaves >= triangles ? triangles * sizeof(mlod__triangle_leaf) : 0;
    /* which nodes each refit changed (the cut skips the others) */
    size[MLOD__TREE_CHANGES] = attributes & MLOD_ATTR_REFIT ? nodes * sizeof(uint32_t) : 0;
    /* refit's copy of the corners it read, and which triangles' changed */
    size[MLOD__TREE_CORNERS] =
        refit_mesh && (attributes & MLOD_ATTR_REFIT_CACHE) ? triangles * mlod__corner_floats(attributes) * sizeof(float) : 0;
    size[MLOD__TREE_CORNERS_CHANGED] = refit_mesh && (attributes & MLOD_ATTR_REFIT_CACHE) ? triangles : 0;
    for (i = 0; i < MLOD__TREE_ARRAYS; i++) {
        int present = i == MLOD__TREE_SPHERES || size[i] > 0 ||
                      (i == MLOD__TREE_TRIANGLE_AREAS && refit_mesh); /* a mesh without triangles is refused earlier */
        offsets[i] = present ? at : UINT64_MAX;
        if (present) at += mlod__block_round(size[i]);
    }
    return at;
}

/* mlod_tree.bytes of a tree of `leaves` leaves: what mlod__tree_create
   allocates (the tree and its block). */
static uint64_t mlod__tree_bytes(uint64_t leaves, uint32_t attributes, int mesh, uint64_t triangles)
{
    uint64_t offsets[MLOD__TREE_ARRAYS];
    return sizeof(mlod_tree) + mlod__tree_layout(leaves, attributes, mesh, triangles, offsets);
}

/* A 64-bit mixing function (splitmix64's finaliser). */
static uint64_t mlod__mix64(uint64_t x)
{
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    x ^= x >> 31;
    return x;
}

/* Trees built so far by this copy of the implementation. */
static uint64_t mlod__trees_built;

/* A tree's first revision: (a serial number) x 2^32, unique among the trees
   this process builds, so that a cut never takes a new tree for a
   destroyed one at the same address; refits count up from it.  The serial
   mixes the counter's own address in, so copies of the implementation
   (MANYLODS_STATIC) number differently.  Without atomics, two builds at
   the same instant may share a number; both trees are then alive at once,
   so at different addresses, and the counter never goes back. */
static uint64_t mlod__first_revision(void)
{
    uint64_t n;
#if defined(__GNUC__) || defined(__clang__)
    n = __atomic_add_fetch(&mlod__trees_built, 1, __ATOMIC_RELAXED);
#else
    n = ++mlod__trees_built;
#endif
    return (n + mlod__mix64((uint64_t)(uintptr_t)&mlod__trees_built)) << 32;
}

/* A tree with every array its attributes need; NULL when out of memory. */
static mlod_tree *mlod__tree_create(const mlod_allocator *a, uint32_t leaves, uint32_t attributes, int mesh,
                                    uint32_t triangles)
{
    size_t nodes = 2 * (size_t)leaves - 1, per_node;
    uint64_t offsets[MLOD__TREE_ARRAYS], block;
    unsigned char *base;
    mlod_tree *t = (mlod_tree *)a->alloc(a->user, sizeof(mlod_tree));
    if (!t) return NULL;
    memset(t, 0, sizeof *t);
    t->allocator = *a;
    t->bytes = sizeof *t;
    t->revision = mlod__first_revision();
    t->leaf_count = leaves;
    t->node_count = (uint32_t)nodes;
    t->attributes = attributes;
    block = mlod__tree_layout(leaves, attributes, mesh, triangles, offsets);
    base = block <= (uint64_t)(size_t)-1 ? (unsigned char *)mlod__alloc_array(a, (size_t)block, 1, &t->bytes) : NULL;
    if (!base) {
        mlod_tree_destroy(t);
        return NULL;
    }
#define MLOD__TREE_ARRAY(i) (offsets[i] == UINT64_MAX ? NULL : (void *)(base + offsets[i]))
    t->spheres = (float *)MLOD__TREE_ARRAY(MLOD__TREE_SPHERES);
    t->cones = (float *)MLOD__TREE_ARRAY(MLOD__TREE_CONES);
    t->areas = (float *)MLOD__TREE_ARRAY(MLOD__TREE_AREAS);
    t->colors = (float *)MLOD__TREE_ARRAY(MLOD__TREE_COLORS);
    t->leaf_sources = (uint32_t *)MLOD__TREE_ARRAY(MLOD__TREE_SOURCES);
    t->leaf_barycentrics = (float *)MLOD__TREE_ARRAY(MLOD__TREE_BARYCENTRICS);
    t->triangle_areas = (double *)MLOD__TREE_ARRAY(MLOD__TREE_TRIANGLE_AREAS);
    t->triangle_leaves = MLOD__TREE_ARRAY(MLOD__TREE_TRIANGLE_LEAVES);
    t->changes = (uint32_t *)MLOD__TREE_ARRAY(MLOD__TREE_CHANGES);
    t->corners = (float *)MLOD__TREE_ARRAY(MLOD__TREE_CORNERS);
    t->corners_changed = (unsigned char *)MLOD__TREE_ARRAY(MLOD__TREE_CORNERS_CHANGED);
#undef MLOD__TREE_ARRAY
    per_node = 4 * sizeof(float) + (t->cones ? 4 * sizeof(float) : 0) + (t->areas ? sizeof(float) : 0) +
               (t->colors ? 3 * sizeof(float) : 0) + (t->changes ? sizeof(uint32_t) : 0);
    t->bytes_per_node = per_node;
    MANYLODS_ASSERT(t->bytes == mlod__tree_bytes(leaves, attributes, mesh, triangles));
    return t;
}

/* How a pass that writes nodes records the ones it changed in
   mlod_tree.changes: not at all (changes NULL: a build, which clears the
   array after), with value (the refit's revision, low 32 bits) on each
   leaf whose sphere, cone, colour or area bits (what a cut's status, a
   tile and the merges above read) differ before and after and on each
   internal node a child of which got it (a refit that knows changes[]), or on every node written (`all`: a refit
   after the arrays were written otherwise).  An internal node neither of
   whose children changed keeps its bits: it holds the merge of its
   children (mlod__merge_all, the last writer of every internal node in
   builds and refits), which are the same bits, merged the same way. */
typedef struct mlod__stamp {
    uint32_t *changes;
    uint32_t value;
    int all;
} mlod__stamp;

/* Store count floats of leaf `node` (its sphere, cone, colour or area),
   recording a change of their bits as `stamp` says (NULL: not at all;
   `all`: every leaf written).  The areas count too: they weigh the
   colours of the nodes above, and a refit merges only above what changed
   (mlod__merge_task); a mesh leaf's radius, rounded from the square root
   of its area, may keep its bits where the area does not. */
static inline void mlod__store_leaf_floats(float *to, const float *from, size_t count, uint32_t node,
                                           const mlod__stamp *stamp)
{
    if (stamp && stamp->changes && (stamp->all || memcmp(to, from, count * sizeof(float)) != 0))
        stamp->changes[node] = stamp->value;
    memcpy(to, from, count * sizeof(float));
}

/* Store leaf `node`'s sphere (bounds[0..3]) and, in a tree with cones,
   its cone (bounds[4..7]), as mlod__store_leaf_floats. */
static void mlod__store_leaf(mlod_tree *tree, uint32_t node, const float bounds[8], const mlod__stamp *stamp)
{
    mlod__store_leaf_floats(tree->spheres + 4 * (size_t)node, bounds, 4, node, stamp);
    if (tree->cones) mlod__store_leaf_floats(tree->cones + 4 * (size_t)node, bounds + 4, 4, node, stamp);
}

typedef struct mlod__merge_job {
    mlod_tree *tree;
    uint32_t first, last;
    const mlod__stamp *stamp;
} mlod__merge_job;

#define MLOD__MERGE_CHUNK 2048u

static void mlod__merge_task(void *context, uint32_t index)
{
    mlod__merge_job *job = (mlod__merge_job *)context;
    uint32_t i = job->first + index * MLOD__MERGE_CHUNK, end = i + MLOD__MERGE_CHUNK - 1;
    if (end > job->last || end < i) end = job->last;
    for (;;) {
        uint32_t n = end - i + 1 < MLOD__LANES ? end - i + 1 : MLOD__LANES, j, changed = 0;
        const mlod__stamp *stamp = job->stamp;
        if (stamp->changes && !stamp->all) {
            /* only where a child changed: the others hold the merge of
               their children's bits already (mlod__stamp), and merging
               them again would write the same bits; a lane group merges
               whole when one of its nodes changed */
            for (j = 0; j < n; j++) {
                uint32_t node = i + j;
                uint32_t child = (uint32_t)(stamp->changes[2 * node + 1] == stamp->value) |
                                 (uint32_t)(stamp->changes[2 * node + 2] == stamp->value);
                if (child) stamp->changes[node] = stamp->value;
                changed |= child;
            }
            if (changed) mlod__merge_nodes(job->tree, i, n);
        } else {
            mlod__merge_nodes(job->tree, i, n);
            if (stamp->changes)
                for (j = 0; j < n; j++) stamp->changes[i + j] = stamp->value;
        }
        if (end - i < MLOD__LANES) break;
        i += MLOD__LANES;
    }
}

/* A built tree's record of changes: every node as built (revision's low
   bits are 0 at build), MLOD__CHANGES_CHUNK nodes a task (at N = 1.3 M on
   2 threads, 1 to 9 ms in one task: its first touch in a build, where its
   pages may be fresh). */
#define MLOD__CHANGES_CHUNK 65536u
static void mlod__changes_zero_task(void *context, uint32_t index)
{
    mlod_tree *tree = (mlod_tree *)context;
    size_t first = (size_t)index * MLOD__CHANGES_CHUNK, count = tree->node_count - first;
    memset(tree->changes + first, 0, (count < MLOD__CHANGES_CHUNK ? count : MLOD__CHANGES_CHUNK) * sizeof(uint32_t));
}

static void mlod__changes_built(mlod_tree *tree, const mlod_parallel *parallel)
{
    if (tree->changes)
        mlod__run(parallel, (tree->node_count - 1) / MLOD__CHANGES_CHUNK + 1, mlod__changes_zero_task, tree);
    tree->changes_revision = tree->revision;
    tree->changes_share = 0.0f;
}

/* A refit's stamp (tree->revision not yet counted up): compare where
   changes[] describes the tree as it is, else mark every node. */
static mlod__stamp mlod__refit_stamp(const mlod_tree *tree)
{
    mlod__stamp stamp;
    stamp.changes = tree->changes;
    stamp.value = (uint32_t)(tree->revision + 1);
    stamp.all = tree->changes_revision != tree->revision;
    return stamp;
}

/* After a refit stamped with mlod__refit_stamp: the new revision, and
   the share of the nodes at depth 10 it changed (what a cut's views look
   like: the cut skips looking at the record when most of it changed). */
static void mlod__refit_done(mlod_tree *tree)
{
    uint32_t first = 0, last = 0, i, changed = 0, depth = mlod__depth_of(2 * (uint64_t)tree->leaf_count - 2);
    tree->revision++; /* cuts recompute the views, each node that changed */
    tree->changes_revision = tree->revision;
    if (!tree->changes) return;
    if (depth > 10) depth = 10;
    while (depth > 0 && !mlod_tree_depth_nodes(tree->leaf_count, depth, &first, &last)) depth--;
    if (depth == 0) first = last = 0; /* the root (a leaf when it is the only node) */
    for (i = first; i <= last; i++) changed += tree->changes[i] == (uint32_t)tree->revision;
    tree->changes_share = (float)changed / (float)(last - first + 1);
}

/* Merge all internal bounds bottom-up, one depth at a time (in parallel
   within a depth), recording changes as `stamp` says (NULL: not at all). */
static void mlod__merge_all(mlod_tree *tree, const mlod_parallel *parallel, const mlod__stamp *stamp)
{
    static const mlod__stamp none = {NULL, 0, 0};
    uint32_t depth, deepest = mlod__depth_of(2 * (uint64_t)tree->leaf_count - 2);
    for (depth = deepest; depth-- > 0;) {
        mlod__merge_job job;
        if (!mlod_tree_depth_nodes(tree->leaf_count, depth, &job.first, &job.last)) continue;
        job.tree = tree;
        job.stamp = stamp ? stamp : &none;
        mlod__run(parallel, (job.last - job.first) / MLOD__MERGE_CHUNK + 1, mlod__merge_task, &job);
    }
}

/* ------------------------------------------------------------ sampling -- */


/* A uniform number in [0, 1) from (seed, stream, index). */
static double mlod__hash01(uint64_t seed, uint64_t stream, uint64_t index)
{
    uint64_t h = mlod__mix64(seed + 0x9e3779b97f4a7c15ull * (stream + 1));
    h = mlod__mix64(h ^ (index * 0xd1b54a32d192ed03ull + 0x8cb92ba72f3d8dd7ull));
    return (double)(h >> 11) * (1.0 / 9007199254740992.0);
}

static void mlod__triangle(const mlod_mesh *mesh, uint32_t tri, double v[3][3])
{
    int c, k;
    for (c = 0; c < 3; c++) {
        const float *p = mlod__at(mesh->positions, mesh->position_stride, mesh->indices[3 * (size_t)tri + c]);
        for (k = 0; k < 3; k++) v[c][k] = p[k];
    }
}

/* The triangle's face normal, (v1 - v0) x (v2 - v0): twice its area long. */
static void mlod__face_normal(const mlod_mesh *mesh, uint32_t tri, double *n)
{
    double v[3][3], e1[3], e2[3];
    int k;
    mlod__triangle(mesh, tri, v);
    for (k = 0; k < 3; k++) {
        e1[k] = v[1][k] - v[0][k];
        e2[k] = v[2][k] - v[0][k];
    }
    mlod__cross3(e1, e2, n);
}

static double mlod__triangle_area(const mlod_mesh *mesh, uint32_t tri)
{
    double n[3];
    mlod__face_normal(mesh, tri, n);
    return 0.5 * mlod__length3(n);
}

/* Interpolate a per-vertex attribute of the mesh at (s, t). */
static void mlod__interpolate(const float *base, size_t stride, const uint32_t *corner, double s, double t, double *out)
{
    const float *a = mlod__at(base, stride, corner[0]), *b = mlod__at(base, stride, corner[1]),
                *c = mlod__at(base, stride, corner[2]);
    int k;
    for (k = 0; k < 3; k++) out[k] = (double)a[k] + s * ((double)b[k] - a[k]) + t * ((double)c[k] - a[k]);
}

/* What the samples of a triangle of face normal n (mlod__face_normal)
   share, its area grown `growth` times since the build. */
static void mlod__triangle_leaf_of(const mlod_tree *tree, const double *n, double growth, mlod__triangle_leaf *out)
{
    out->growth = growth;
    out->radius = mlod__float_up(tree->radius_scale * sqrt(tree->area_unit * growth));
    out->area = (float)growth;
    if (tree->cones)
        mlod__cone_from_normal(n, out->cone);
    else /* never read then, but gcc -O3 cannot see that */
        memset(out->cone, 0, sizeof out->cone);
}

/* Write leaf `node` of the tree from the mesh sample (tri, s, t) and what
   its triangle's samples share: the one function build and refit share
   (stamp: see mlod__store_leaf). */
static void mlod__mesh_leaf(mlod_tree *tree, uint32_t node, const mlod_mesh *mesh, uint32_t tri, float s, float t,
                            const mlod__triangle_leaf *shared, const mlod__stamp *stamp)
{
    const uint32_t *corner = mesh->indices + 3 * (size_t)tri;
    double p[3];
    float bounds[8];
    int k;
    mlod__interpolate(mesh->positions, mesh->position_stride, corner, s, t, p);
    for (k = 0; k < 3; k++) bounds[k] = (float)p[k];
    bounds[3] = shared->radius;
    if (tree->cones) {
        double n[3] = {0.0, 0.0, 0.0};
        if (mesh->normals) mlod__interpolate(mesh->normals, mesh->normal_stride, corner, s, t, n);
        if (mlod__dot3(n, n) > 0.0)
            mlod__cone_from_normal(n, bounds + 4);
        else
            for (k = 0; k < 4; k++) bounds[4 + k] = shared->cone[k];
    } else { /* never read then, but a compiler may not see that */
        bounds[4] = bounds[5] = bounds[6] = bounds[7] = 0.0f;
    }
    mlod__store_leaf(tree, node, bounds, stamp);
    if (tree->areas) mlod__store_leaf_floats(tree->areas + node, &shared->area, 1, node, stamp);
    if (tree->colors) {
        double c[3];
        float color[3];
        mlod__interpolate(mesh->colors, mesh->color_stride, corner, s, t, c);
        for (k = 0; k < 3; k++) color[k] = (float)c[k];
        mlod__store_leaf_floats(tree->colors + 3 * (size_t)node, color, 3, node, stamp);
    }
}

/* The stratified samples: sample i sits at u_i = (i + h_i) / n * A along
   the running sums of the triangles' areas (h_i a hash in [0, 1), A the
   total), in triangle tri(i), the first whose running sum passes u_i
   (the last with area at most; u_i never decreases, so neither does
   tri(i)).  Its (s, t) follow a jittered rank-1 lattice over the samples
   that share the triangle, run(i) = i - (the first sample in tri(i)).
   Each task places MLOD__SAMPLE_CHUNK consecutive samples; the result
   does not depend on how they are shared out. */
#define MLOD__SAMPLE_CHUNK 65536u
typedef struct mlod__mesh_sample_job {
    const double *cumulative; /* triangles + 1 running sums */
    uint32_t last_with_area;  /* the last triangle of nonzero area */
    uint32_t n;
    uint64_t seed;
    uint32_t *tri_out;        /* n */
    float *st_out;            /* 2n */
    const mlod_mesh *mesh;    /* positions of the samples into pos_out */
    float *pos_out;           /* 3n */
} mlod__mesh_sample_job;

static double mlod__mesh_sample_u(const mlod__mesh_sample_job *job, uint32_t i)
{
    return ((double)i + mlod__hash01(job->seed, 0, i)) / job->n * job->cumulative[job->last_with_area + 1];
}

/* tri(i) for the sample at u: the first triangle whose running sum exceeds
   u, or the last with area. */
static uint32_t mlod__mesh_sample_triangle(const mlod__mesh_sample_job *job, double u)
{
    uint32_t lo = 0, hi = job->last_with_area; /* the answer lies in [lo, hi] */
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (job->cumulative[mid + 1] > u)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

static void mlod__mesh_sample_task(void *context, uint32_t index)
{
    const mlod__mesh_sample_job *job = (const mlod__mesh_sample_job *)context;
    const double golden = 0.6180339887498948482, *cumulative = job->cumulative;
    uint32_t i = index * MLOD__SAMPLE_CHUNK, end = i + MLOD__SAMPLE_CHUNK, tri, first = 0, lo, run;
    double u = mlod__mesh_sample_u(job, i), offset;
    if (end > job->n || end < i) end = job->n;
    tri = mlod__mesh_sample_triangle(job, u);
    lo = i; /* the first sample in tri: the least j <= i with tri(j) >= tri */
    while (first < lo) {
        uint32_t mid = first + (lo - first) / 2;
        if (mlod__mesh_sample_triangle(job, mlod__mesh_sample_u(job, mid)) >= tri)
            lo = mid;
        else
            first = mid + 1;
    }
    run = i - first;
    offset = mlod__hash01(job->seed, 1, tri);
    for (;;) {
        double area = cumulative[tri + 1] - cumulative[tri], x = (u - cumulative[tri]) / area, y, r, p[3];
        float *st = job->st_out + 2 * (size_t)i;
        int k;
        if (x < 0.0) x = 0.0;
        if (x > 1.0) x = 1.0;
        y = offset + run * golden;
        y -= floor(y);
        r = sqrt(x);
        job->tri_out[i] = tri;
        st[0] = (float)(r * (1.0 - y));
        st[1] = (float)(r * y);
        mlod__interpolate(job->mesh->positions, job->mesh->position_stride, job->mesh->indices + 3 * (size_t)tri, st[0],
                          st[1], p);
        for (k = 0; k < 3; k++) job->pos_out[3 * (size_t)i + k] = (float)p[k];
        if (++i >= end) break;
        u = mlod__mesh_sample_u(job, i);
        run++;
        if (tri < job->last_with_area && cumulative[tri + 1] <= u) { /* on to the triangle of u */
            while (tri < job->last_with_area && cumulative[tri + 1] <= u) tri++;
            run = 0;
            offset = mlod__hash01(job->seed, 1, tri);
        }
    }
}

/* Triangle areas into out[0 .. count - 1], MLOD__AREA_CHUNK a task. */
#define MLOD__AREA_CHUNK 16384u
typedef struct mlod__areas_job {
    const mlod_mesh *mesh;
    double *out;
    uint32_t count;
} mlod__areas_job;

static void mlod__areas_task(void *context, uint32_t index)
{
    const mlod__areas_job *job = (const mlod__areas_job *)context;
    uint32_t i = index * MLOD__AREA_CHUNK, end = i + MLOD__AREA_CHUNK;
    if (end > job->count || end < i) end = job->count;
    for (; i < end; i++) job->out[i] = mlod__triangle_area(job->mesh, i);
}

static void mlod__triangle_areas(const mlod_mesh *mesh, uint32_t count, double *out, const mlod_parallel *parallel)
{
    mlod__areas_job job;
    job.mesh = mesh;
    job.out = out;
    job.count = count;
    if (count > 0) mlod__run(parallel, (count - 1) / MLOD__AREA_CHUNK + 1, mlod__areas_task, &job);
}

/* ---------------------------------------------------------- the build -- */

static uint32_t mlod__sort_key(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    if (f == 0.0f) u = 0; /* -0 and +0 sort together */
    return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

/* Stable LSD radix sort of n (key << 32 | item) pairs by key, 11 bits a
   pass: the three passes read the pairs front to back.  The result lands
   in scratch (n more). */
static void mlod__radix_sort(uint64_t *pairs, uint64_t *scratch, uint32_t n)
{
    static const int shift[3] = {32, 43, 54};
    uint32_t count[2048];
    int pass;
    for (pass = 0; pass < 3; pass++) {
        const uint64_t *from = pass == 1 ? scratch : pairs;
        uint64_t *to = pass == 1 ? pairs : scratch;
        uint32_t i, sum = 0;
        memset(count, 0, sizeof count);
        for (i = 0; i < n; i++) count[(from[i] >> shift[pass]) & 2047u]++;
        for (i = 0; i < 2048; i++) {
            uint32_t c = count[i];
            count[i] = sum;
            sum += c;
        }
        for (i = 0; i < n; i++) to[count[(from[i] >> shift[pass]) & 2047u]++] = from[i];
    }
}

/* The box around count >= 1 packed points (3 floats each, consecutive),
   as mlod__box_of but four points at a time in vector lanes where the
   build has them (SSE2, NEON): their 12 floats are three vectors, each
   lane always the same coordinate.  Minima and maxima are exact, so the
   box is mlod__box_of's (a zero's sign aside, which no difference of two
   bounds sees). */
#ifdef MLOD__NO_FMA_TARGET
#pragma clang attribute pop
#endif
#if MLOD__SIMD_X86
#define MLOD__BOX_LANES 1
typedef __m128 mlod__box_vf;
#define MLOD__BOX_LOAD _mm_loadu_ps
#define MLOD__BOX_MIN _mm_min_ps
#define MLOD__BOX_MAX _mm_max_ps
#define MLOD__BOX_STORE _mm_storeu_ps
#elif MLOD__SIMD_NEON
#define MLOD__BOX_LANES 1
typedef float32x4_t mlod__box_vf;
#define MLOD__BOX_LOAD vld1q_f32
#define MLOD__BOX_MIN vminq_f32
#define MLOD__BOX_MAX vmaxq_f32
#define MLOD__BOX_STORE vst1q_f32
#endif
#ifdef MLOD__BOX_LANES
static void mlod__box_packed_lanes(const float *pts, uint32_t quads, float lo[12], float hi[12])
{
    mlod__box_vf a0 = MLOD__BOX_LOAD(pts), b0 = MLOD__BOX_LOAD(pts + 4), c0 = MLOD__BOX_LOAD(pts + 8);
    mlod__box_vf a1 = a0, b1 = b0, c1 = c0;
    uint32_t q;
    for (q = 1; q < quads; q++) {
        const float *p = pts + 12 * (size_t)q;
        mlod__box_vf a = MLOD__BOX_LOAD(p), b = MLOD__BOX_LOAD(p + 4), c = MLOD__BOX_LOAD(p + 8);
        a0 = MLOD__BOX_MIN(a0, a);
        b0 = MLOD__BOX_MIN(b0, b);
        c0 = MLOD__BOX_MIN(c0, c);
        a1 = MLOD__BOX_MAX(a1, a);
        b1 = MLOD__BOX_MAX(b1, b);
        c1 = MLOD__BOX_MAX(c1, c);
    }
    MLOD__BOX_STORE(lo, a0);
    MLOD__BOX_STORE(lo + 4, b0);
    MLOD__BOX_STORE(lo + 8, c0);
    MLOD__BOX_STORE(hi, a1);
    MLOD__BOX_STORE(hi + 4, b1);
    MLOD__BOX_STORE(hi + 8, c1);
}
#endif
#ifdef MLOD__NO_FMA_TARGET
#pragma clang attribute push(__attribute__((target("no-fma"))), apply_to = function)
#endif

static void mlod__box_packed(const float *pts, uint32_t count, double lo[3], double hi[3])
{
#ifdef MLOD__BOX_LANES
    if (count >= 8) {
        float l[12], h[12];
        uint32_t quads = count / 4, j;
        int k;
        mlod__box_packed_lanes(pts, quads, l, h);
        if (count > 4 * quads) /* the last points, one by one */
            mlod__box_of(pts + 12 * (size_t)quads, 3 * sizeof(float), count - 4 * quads, lo, hi);
        else
            for (k = 0; k < 3; k++) lo[k] = hi[k] = l[k];
        for (j = 0; j < 12; j++) { /* float j of a quad is coordinate j % 3 */
            lo[j % 3] = l[j] < lo[j % 3] ? l[j] : lo[j % 3];
            hi[j % 3] = h[j] > hi[j % 3] ? h[j] : hi[j % 3];
        }
        return;
    }
#endif
    mlod__box_of(pts, 3 * sizeof(float), count, lo, hi);
}

/* d^3 for the diagonal d of the box around count points (3 floats each,
   consecutive): proportional to the volume of the box's sphere. */
static double mlod__box_volume_of(const float *pts, uint32_t count)
{
    double lo[3], hi[3], dx, dy, dz, d2;
    mlod__box_packed(pts, count, lo, hi);
    dx = hi[0] - lo[0];
    dy = hi[1] - lo[1];
    dz = hi[2] - lo[2];
    d2 = dx * dx + dy * dy + dz * dz;
    return d2 * sqrt(d2);
}

/* The top depths, of fewer than MLOD__SPLIT_FINE nodes, are split in
   pieces (mlod__split_fine): each node's halves' boxes, a task each, then
   each of its other axes' items in MLOD__SPLIT_PARTS parts at once, so
   that the first splits, each of a half or more of the items, take all
   the threads too.  (Measured, N = 1.3 M: on 2 threads the root's split
   from 18 to 11 ms, the next depth's, two nodes, as fast as a task per
   node; on one thread that depth about 1 ms slower in pieces, which move
   the right items back one by one.) */
#define MLOD__SPLIT_FINE 4u
#define MLOD__SPLIT_PARTS 8u

/* The items in the order of each axis, each with its position alongside
   (so that a node's boxes are read front to back), split node by node. */
typedef struct mlod__order_ctx {
    uint32_t n;
    uint32_t *order[3];  /* per axis: items, sorted along it within each node */
    float *pts[3];       /* per axis: the positions of order[axis], 3 floats each */
    uint32_t *scratch;   /* n items, and scratch_pts 3n floats, at the node's slots */
    float *scratch_pts;
    uint32_t *begin;     /* per node: its first slot */
    uint32_t first, last;           /* the nodes of one depth (or of a batch of it) */
    int subtrees;                   /* split each of them with its subtree */
    uint32_t *leaf_item;            /* at the end: the item of each leaf */
    /* mlod__split_fine, per node of the depth (node - first): */
    double volumes[MLOD__SPLIT_FINE][3][2]; /* of the halves' boxes, per axis */
    int axis[MLOD__SPLIT_FINE];
    uint64_t pivot[MLOD__SPLIT_FINE];
    uint32_t lefts[MLOD__SPLIT_FINE][MLOD__SPLIT_PARTS]; /* left items per part of the axis being moved */
    int other, step; /* which of a node's other axes is moved; 0 boxes, 1 into the scratch, 2 back */
} mlod__order_ctx;

/* Node `node`'s first slot b, its count items, nl of them its left
   child's (the halves by leaf count). */
static void mlod__split_slots(const mlod__order_ctx *c, uint32_t node, uint32_t *b, uint32_t *count, uint32_t *nl)
{
    *b = c->begin[node];
    *count = mlod__leaves_below(node, c->n);
    *nl = mlod__leaves_below(2 * node + 1, c->n);
}

/* The volume of the box of a node's half (right: 1 the right one) along
   axis k; the node's slots from mlod__split_slots. */
static double mlod__half_volume(const mlod__order_ctx *c, uint32_t b, uint32_t count, uint32_t nl, int k, int right)
{
    const float *p = c->pts[k] + 3 * (size_t)b;
    return right ? mlod__box_volume_of(p + 3 * (size_t)nl, count - nl) : mlod__box_volume_of(p, nl);
}

/* The axis whose two halves' boxes have the smaller summed volume, the
   first on a tie. */
static int mlod__split_axis(const double volumes[3][2])
{
    double best = 0.0;
    int axis = 0, k;
    for (k = 0; k < 3; k++) {
        double v = volumes[k][0] + volumes[k][1];
        if (k == 0 || v < best) {
            best = v;
            axis = k;
        }
    }
    return axis;
}

/* The left child takes the first nl items of the node along the axis,
   which is sorted by (key, item): those below the (nl + 1)-th, found from
   each item's own position (no lookup by item). */
static uint64_t mlod__split_pivot(const mlod__order_ctx *c, uint32_t b, uint32_t nl, int axis)
{
    return (uint64_t)mlod__sort_key(c->pts[axis][3 * ((size_t)b + nl) + (size_t)axis]) << 32 | c->order[axis][b + nl];
}

/* Axis k's slots i .. end of the node at slot b into the scratch, the
   left ones (by the pivot along `axis`) at slots l, l + 1, ..., the right
   ones at r, r + step, ... (step 1, or -1 as an unsigned); returns how
   many are left. */
static uint32_t mlod__split_move(mlod__order_ctx *c, uint32_t b, int k, int axis, uint64_t pivot, uint32_t i,
                                 uint32_t end, uint32_t l, uint32_t r, uint32_t step)
{
    const uint32_t *o = c->order[k] + b;
    const float *p = c->pts[k] + 3 * (size_t)b;
    uint32_t first = l;
    uint32_t *so = c->scratch + b;
    float *sp = c->scratch_pts + 3 * (size_t)b;
    for (; i < end; i++) { /* branch-free: left and right are a coin toss */
        uint32_t item = o[i], to;
        uint32_t is_left = ((uint64_t)mlod__sort_key(p[3 * (size_t)i + (size_t)axis]) << 32 | item) < pivot;
        to = is_left ? l : r;
        l += is_left;
        r += step & (is_left - 1u);
        so[to] = item;
        sp[3 * (size_t)to] = p[3 * (size_t)i];
        sp[3 * (size_t)to + 1] = p[3 * (size_t)i + 1];
        sp[3 * (size_t)to + 2] = p[3 * (size_t)i + 2];
    }
    return l - first;
}

/* Split node `node` (slots b .. b+count of every axis) between its
   children: along mlod__split_axis's axis, halves by leaf count; the
   other axes keep their order within each half. */
static void mlod__split_node(mlod__order_ctx *c, uint32_t node)
{
    uint32_t b, count, nl;
    double volumes[3][2];
    uint64_t pivot;
    int axis, k, right;
    mlod__split_slots(c, node, &b, &count, &nl);
    for (k = 0; k < 3; k++)
        for (right = 0; right < 2; right++) volumes[k][right] = mlod__half_volume(c, b, count, nl, k, right);
    axis = mlod__split_axis((const double(*)[2])volumes);
    pivot = mlod__split_pivot(c, b, nl, axis);
    for (k = 0; k < 3; k++) {
        if (k == axis) continue;
        mlod__split_move(c, b, k, axis, pivot, 0, count, 0, nl, 1);
        memcpy(c->order[k] + b, c->scratch + b, count * sizeof(uint32_t));
        memcpy(c->pts[k] + 3 * (size_t)b, c->scratch_pts + 3 * (size_t)b, 3 * (size_t)count * sizeof(float));
    }
    c->begin[2 * node + 1] = b;
    c->begin[2 * node + 2] = b + nl;
}

/* One piece of mlod__split_fine (c->step): a half's box (index 6 j + 2 k
   + right, node first + j), or part `part` of node first + j (index
   MLOD__SPLIT_PARTS j + part) of its other axis c->other moved into the
   scratch (the right ones last first, from the part's end), or back:
   its left ones after the parts' before it (left of the lo items
   before it), its right ones after nl and theirs (the lo - left
   others).  The same slots as mlod__split_node's. */
static void mlod__split_fine_task(void *context, uint32_t index)
{
    mlod__order_ctx *c = (mlod__order_ctx *)context;
    uint32_t j, part, b, count, nl, lo, hi, at, left, right, q, i;
    int axis, k;
    if (c->step == 0) {
        int right = (int)(index % 2);
        j = index / 6;
        k = (int)(index % 6 / 2);
        mlod__split_slots(c, c->first + j, &b, &count, &nl);
        c->volumes[j][k][right] = mlod__half_volume(c, b, count, nl, k, right);
        return;
    }
    j = index / MLOD__SPLIT_PARTS;
    part = index % MLOD__SPLIT_PARTS;
    axis = c->axis[j];
    k = (axis + 1 + c->other) % 3;
    mlod__split_slots(c, c->first + j, &b, &count, &nl);
    lo = (uint32_t)((uint64_t)count * part / MLOD__SPLIT_PARTS);
    hi = (uint32_t)((uint64_t)count * (part + 1) / MLOD__SPLIT_PARTS);
    if (c->step == 1) {
        c->lefts[j][part] = mlod__split_move(c, b, k, axis, c->pivot[j], lo, hi, lo, hi - 1, 0xffffffffu);
        return;
    }
    for (q = 0, left = 0; q < part; q++) left += c->lefts[j][q];
    right = nl + (lo - left);
    memcpy(c->order[k] + b + left, c->scratch + b + lo, c->lefts[j][part] * sizeof(uint32_t));
    memcpy(c->pts[k] + 3 * ((size_t)b + left), c->scratch_pts + 3 * ((size_t)b + lo),
           3 * (size_t)c->lefts[j][part] * sizeof(float));
    for (i = lo + c->lefts[j][part], at = hi; i < hi; i++) { /* the right ones, last first in the scratch */
        size_t to = (size_t)b + right++, from = (size_t)b + --at;
        c->order[k][to] = c->scratch[from];
        c->pts[k][3 * to] = c->scratch_pts[3 * from];
        c->pts[k][3 * to + 1] = c->scratch_pts[3 * from + 1];
        c->pts[k][3 * to + 2] = c->scratch_pts[3 * from + 2];
    }
}

/* Split the count < MLOD__SPLIT_FINE nodes of one depth (c->first on) as
   mlod__split_node does, in pieces: the halves' boxes, each node's axis,
   pivot and children's first slots, then each other axis into the
   scratch and back. */
static void mlod__split_fine(mlod__order_ctx *c, const mlod_parallel *parallel, uint32_t count)
{
    uint32_t j, b, n, nl;
    c->step = 0;
    mlod__run(parallel, 6 * count, mlod__split_fine_task, c);
    for (j = 0; j < count; j++) { /* the children's first slots too: the pieces read only this depth's */
        mlod__split_slots(c, c->first + j, &b, &n, &nl);
        c->axis[j] = mlod__split_axis((const double(*)[2])c->volumes[j]);
        c->pivot[j] = mlod__split_pivot(c, b, nl, c->axis[j]);
        c->begin[2 * (c->first + j) + 1] = b;
        c->begin[2 * (c->first + j) + 2] = b + nl;
    }
    for (c->other = 0; c->other < 2; c->other++)
        for (c->step = 1; c->step <= 2; c->step++)
            mlod__run(parallel, MLOD__SPLIT_PARTS * count, mlod__split_fine_task, c);
}

/* Once a depth has this many internal nodes, each task splits whole
   subtrees below them depth first: a subtree's slots then stay in the
   cache while it is split down to its leaves, where a pass per depth
   would stream every slot through memory at every depth. */
#define MLOD__SPLIT_SUBTREES 256u
/* The subtrees are split in this many batches, progress reported between. */
#define MLOD__SPLIT_BATCHES 16u

/* Split every internal node below and including `root`, depth first (a
   node's split reads only its own slots: the order does not change the
   result). */
static void mlod__split_subtree(mlod__order_ctx *c, uint32_t root)
{
    uint32_t stack[2 * 33], top = 0; /* at most one pending right child per depth, depth <= 32 */
    stack[top++] = root;
    while (top > 0) {
        uint32_t node = stack[--top];
        if (node >= c->n - 1) continue; /* a leaf */
        mlod__split_node(c, node);
        stack[top++] = 2 * node + 2;
        stack[top++] = 2 * node + 1;
    }
}

/* Split node first + index of one depth, or with c->subtrees its whole
   subtree: disjoint slots and items. */
static void mlod__split_task(void *context, uint32_t index)
{
    mlod__order_ctx *c = (mlod__order_ctx *)context;
    if (c->subtrees)
        mlod__split_subtree(c, c->first + index);
    else
        mlod__split_node(c, c->first + index);
}

/* The item of each leaf into leaf_item, MLOD__LEAF_ITEMS leaves a task. */
#define MLOD__LEAF_ITEMS 65536u
static void mlod__leaf_items_task(void *context, uint32_t index)
{
    const mlod__order_ctx *c = (const mlod__order_ctx *)context;
    uint32_t i = index * MLOD__LEAF_ITEMS, end = i + MLOD__LEAF_ITEMS;
    if (end > c->n || end < i) end = c->n;
    for (; i < end; i++) c->leaf_item[i] = c->order[0][c->begin[(size_t)c->n - 1 + i]];
}

/* Sort axis k's items by their coordinate along it (ties by item), and
   lay out their positions. */
typedef struct mlod__sort_job {
    mlod__order_ctx *c;
    const float *pos;
    uint64_t *scratch[3];
} mlod__sort_job;

static void mlod__sort_axis_task(void *context, uint32_t k)
{
    mlod__sort_job *job = (mlod__sort_job *)context;
    mlod__order_ctx *c = job->c;
    uint64_t *pairs = (uint64_t *)(void *)c->pts[k]; /* 12 bytes per item: room for the 8 of a pair */
    uint32_t i;
    for (i = 0; i < c->n; i++) pairs[i] = (uint64_t)mlod__sort_key(job->pos[3 * (size_t)i + k]) << 32 | i;
    mlod__radix_sort(pairs, job->scratch[k], c->n);
}

/* Once sorted (the pairs in job->scratch[k]): axis k's items, and their
   positions gathered, MLOD__SORT_PARTS tasks per axis (the gather, a read
   at random per item, is most of the time). */
#define MLOD__SORT_PARTS 8u
static void mlod__sort_gather_task(void *context, uint32_t index)
{
    mlod__sort_job *job = (mlod__sort_job *)context;
    mlod__order_ctx *c = job->c;
    uint32_t k = index / MLOD__SORT_PARTS, part = index % MLOD__SORT_PARTS, i, end;
    i = (uint32_t)((uint64_t)c->n * part / MLOD__SORT_PARTS);
    end = (uint32_t)((uint64_t)c->n * (part + 1) / MLOD__SORT_PARTS);
    for (; i < end; i++) {
        uint32_t item = (uint32_t)job->scratch[k][i];
        const float *p = job->pos + 3 * (size_t)item;
        c->order[k][i] = item;
        c->pts[k][3 * (size_t)i] = p[0];
        c->pts[k][3 * (size_t)i + 1] = p[1];
        c->pts[k][3 * (size_t)i + 2] = p[2];
    }
}

static int mlod__report(const mlod_build_desc *desc, float fraction)
{
    return desc->progress && desc->progress(desc->progress_user, fraction);
}

/* The ordering's scratch for n items, seven pieces: a phase block of 24n
   bytes (the sort's three arrays of n pairs, then the split's scratch_pts
   (12n), scratch (4n) and begin (4 (2n - 1))), positions along each axis
   (12n each), items along each axis (4n each).  In this order, each piece
   that fits in what is left of `lent` bytes (the tree's block, which the
   build has not written yet) takes the next multiple of 16 there
   (offsets[i]); the others are allocated (offsets[i] = UINT64_MAX).
   Returns the bytes allocated. */
static uint64_t mlod__order_piece(uint64_t n, int i) { return (i == 0 ? 24 : i <= 3 ? 12 : 4) * n; }

static uint64_t mlod__order_layout(uint64_t n, uint64_t lent, uint64_t offsets[7])
{
    uint64_t at = 0, allocated = 0;
    int i;
    for (i = 0; i < 7; i++) {
        uint64_t size = mlod__order_piece(n, i);
        if (at + mlod__block_round(size) <= lent) {
            offsets[i] = at;
            at += mlod__block_round(size);
        } else {
            offsets[i] = UINT64_MAX;
            allocated += size;
        }
    }
    return allocated;
}

/* Order n items (positions pos) into the leaves: leaf_item[j] is the item
   of leaf j, its scratch in the `lent` bytes at `block` where they suffice
   (mlod__order_layout).  Nodes of one depth are split in parallel; the
   result does not depend on the hook.  Returns MLOD_ERROR_OUT_OF_MEMORY
   or MLOD_ERROR_CANCELLED. */
static mlod_result mlod__order_items(const mlod_allocator *a, const mlod_build_desc *desc, const float *pos, uint32_t n,
                                     uint32_t *leaf_item, float progress_from, float progress_to, unsigned char *block,
                                     uint64_t lent)
{
    mlod__order_ctx c;
    mlod__sort_job sort;
    uint32_t depth;
    uint64_t offsets[7];
    unsigned char *piece[7];
    mlod_result res = MLOD_OK;
    int k, ok = 1;
    memset(&c, 0, sizeof c);
    memset(&sort, 0, sizeof sort);
    c.n = n;
    mlod__order_layout(n, lent, offsets);
    for (k = 0; k < 7; k++) {
        piece[k] = offsets[k] != UINT64_MAX ? block + offsets[k] : NULL;
        if (!piece[k] && ok)
            ok = (piece[k] = (unsigned char *)mlod__alloc_array(a, (size_t)mlod__order_piece(n, k), 1, NULL)) != NULL;
    }
    if (!ok) {
        res = MLOD_ERROR_OUT_OF_MEMORY;
        goto done;
    }
    for (k = 0; k < 3; k++) {
        sort.scratch[k] = (uint64_t *)(void *)(piece[0] + 8 * (size_t)n * k);
        c.pts[k] = (float *)(void *)piece[1 + k];
        c.order[k] = (uint32_t *)(void *)piece[4 + k];
    }
    sort.c = &c;
    sort.pos = pos;
    mlod__run(desc->parallel, 3, mlod__sort_axis_task, &sort);
    mlod__run(desc->parallel, 3 * MLOD__SORT_PARTS, mlod__sort_gather_task, &sort);
    /* the sort is done with the phase block: the split's scratch */
    c.scratch_pts = (float *)(void *)piece[0];
    c.scratch = (uint32_t *)(void *)(piece[0] + 12 * (size_t)n);
    c.begin = (uint32_t *)(void *)(piece[0] + 16 * (size_t)n);
    c.begin[0] = 0;
    for (depth = 0; mlod_tree_depth_nodes(n, depth, &c.first, &c.last); depth++) {
        uint32_t count = c.last - c.first + 1;
        if (depth > 0 && desc->progress &&
            desc->progress(desc->progress_user, progress_from + (progress_to - progress_from) * (float)c.first / (float)n)) {
            res = MLOD_ERROR_CANCELLED;
            goto done;
        }
        if (count >= MLOD__SPLIT_SUBTREES) { /* the rest, subtree by subtree, in batches between reports */
            uint32_t first = c.first, batch;
            float from = (float)first / (float)n;
            c.subtrees = 1;
            for (batch = 0; batch < MLOD__SPLIT_BATCHES; batch++) {
                c.first = first + (uint32_t)((uint64_t)count * batch / MLOD__SPLIT_BATCHES);
                c.last = first + (uint32_t)((uint64_t)count * (batch + 1) / MLOD__SPLIT_BATCHES) - 1;
                if (batch > 0 &&
                    mlod__report(desc, progress_from + (progress_to - progress_from) *
                                                           (from + (1.0f - from) * (float)batch / MLOD__SPLIT_BATCHES))) {
                    res = MLOD_ERROR_CANCELLED;
                    goto done;
                }
                mlod__run(desc->parallel, c.last - c.first + 1, mlod__split_task, &c);
            }
            break;
        }
        if (count < MLOD__SPLIT_FINE)
            mlod__split_fine(&c, desc->parallel, count);
        else
            mlod__run(desc->parallel, count, mlod__split_task, &c);
    }
    c.leaf_item = leaf_item;
    mlod__run(desc->parallel, (n - 1) / MLOD__LEAF_ITEMS + 1, mlod__leaf_items_task, &c);
done:
    for (k = 0; k < 7; k++)
        if (offsets[k] == UINT64_MAX) mlod__free(a, piece[k]);
    return res;
}

/* A build's tree and its leaves' order: the tree first, its block (which
   starts with the spheres, and is not written yet) lending the ordering
   its scratch.  *out_tree is the tree, the caller's to destroy, also when
   the ordering fails; NULL when there is no memory for it. */
static mlod_result mlod__tree_ordered(const mlod_allocator *a, const mlod_build_desc *desc, const float *pos, uint32_t n,
                                      int mesh, uint32_t triangles, uint32_t *leaf_item, float progress_from,
                                      mlod_tree **out_tree)
{
    mlod_tree *tree = mlod__tree_create(a, n, desc->attributes, mesh, triangles);
    *out_tree = tree;
    if (!tree) return MLOD_ERROR_OUT_OF_MEMORY;
    return mlod__order_items(a, desc, pos, n, leaf_item, progress_from, 0.9f, (unsigned char *)tree->spheres,
                             tree->bytes - sizeof(mlod_tree));
}

/* A build's peak: its own arrays (`held`), the tree, and the ordering's
   scratch beyond the tree's block. */
static size_t mlod__build_peak(uint64_t held, uint64_t n, uint32_t attributes, int mesh, uint64_t triangles)
{
    uint64_t offsets[MLOD__TREE_ARRAYS], order[7];
    uint64_t block = mlod__tree_layout(n, attributes, mesh, triangles, offsets);
    uint64_t peak = held + sizeof(mlod_tree) + block + mlod__order_layout(n, block, order);
    return peak > (uint64_t)(size_t)-1 ? (size_t)-1 : (size_t)peak;
}

MLOD__PUBLIC size_t mlod_build_mesh_bound(uint32_t sample_count, uint32_t triangle_count, uint32_t attributes)
{
    uint64_t n = sample_count, held;
    if (n == 0 || n > MANYLODS_MAX_LEAVES) return 0;
    /* cumulative areas, then per sample: triangle, (s, t), position, leaf order */
    held = ((uint64_t)triangle_count + 1) * sizeof(double) +
           n * (sizeof(uint32_t) + 2 * sizeof(float) + 3 * sizeof(float) + sizeof(uint32_t));
    return mlod__build_peak(held, n, attributes, 1, triangle_count);
}

MLOD__PUBLIC size_t mlod_build_points_bound(uint32_t point_count, uint32_t attributes)
{
    uint64_t n = point_count;
    if (n == 0 || n > MANYLODS_MAX_LEAVES) return 0;
    /* per point: position, leaf order, radius */
    return mlod__build_peak(n * (3 * sizeof(float) + sizeof(uint32_t) + sizeof(double)), n, attributes, 0, 0);
}

#define MLOD__LEAF_CHUNK 4096u

/* The leaves of a mesh build, MLOD__LEAF_CHUNK per task. */
typedef struct mlod__build_leaves_job {
    mlod_tree *tree;
    const mlod_mesh *mesh;
    const uint32_t *leaf_item, *tri;
    const float *st;
} mlod__build_leaves_job;

/* What the samples of triangle t share at build (growth 1). */
static void mlod__build_triangle(const mlod_tree *tree, const mlod_mesh *mesh, uint32_t t, mlod__triangle_leaf *out)
{
    double normal[3];
    mlod__face_normal(mesh, t, normal);
    mlod__triangle_leaf_of(tree, normal, 1.0, out);
}

/* A tree with mlod_tree.triangle_leaves: each triangle's share, once (the
   leaves then read it), MLOD__LEAF_CHUNK triangles per task.  Refit
   overwrites them with its own. */
static void mlod__build_triangles_task(void *context, uint32_t index)
{
    const mlod__build_leaves_job *job = (const mlod__build_leaves_job *)context;
    const mlod_tree *tree = job->tree;
    mlod__triangle_leaf *shared = (mlod__triangle_leaf *)tree->triangle_leaves;
    uint32_t t = index * MLOD__LEAF_CHUNK, end = t + MLOD__LEAF_CHUNK;
    if (end > tree->triangle_count || end < t) end = tree->triangle_count;
    for (; t < end; t++) mlod__build_triangle(tree, job->mesh, t, &shared[t]);
}

static void mlod__build_leaves_task(void *context, uint32_t index)
{
    const mlod__build_leaves_job *job = (const mlod__build_leaves_job *)context;
    mlod_tree *tree = job->tree;
    const mlod__triangle_leaf *shared = (const mlod__triangle_leaf *)tree->triangle_leaves;
    uint32_t i = index * MLOD__LEAF_CHUNK, end = i + MLOD__LEAF_CHUNK, n = tree->leaf_count;
    if (end > n) end = n;
    for (; i < end; i++) {
        uint32_t item = job->leaf_item[i], tri = job->tri[item];
        float s = job->st[2 * (size_t)item], t = job->st[2 * (size_t)item + 1];
        mlod__triangle_leaf own;
        if (!shared) mlod__build_triangle(tree, job->mesh, tri, &own);
        mlod__mesh_leaf(tree, n - 1 + i, job->mesh, tri, s, t, shared ? &shared[tri] : &own, NULL);
        if (tree->leaf_sources) {
            tree->leaf_sources[i] = tri;
            tree->leaf_barycentrics[2 * (size_t)i] = s;
            tree->leaf_barycentrics[2 * (size_t)i + 1] = t;
        }
    }
}


/* The spacing of floats below 2^-126 (denormals): 2^-149. */
#define MLOD__FLOAT_DENORMAL_SPACING 1.4012984643248171e-45

/* Flag a tree whose float positions are quantised coarser than a quarter of
   its typical leaf radius (see MLOD_PRECISION_COARSE_POSITIONS): the
   spacing of floats at its largest coordinate, never finer than the
   denormals' 2^-149. */
static void mlod__set_precision(mlod_tree *tree, double typical_radius)
{
    const float *root = tree->spheres;
    double reach = fabs(root[0]) + root[3];
    int k;
    for (k = 1; k < 3; k++)
        if (fabs(root[k]) + root[3] > reach) reach = fabs(root[k]) + root[3];
    double spacing = reach * (1.0 / 8388608.0);
    if (spacing < MLOD__FLOAT_DENORMAL_SPACING) spacing = MLOD__FLOAT_DENORMAL_SPACING;
    tree->precision = spacing > 0.25 * typical_radius ? (uint32_t)MLOD_PRECISION_COARSE_POSITIONS : 0u;
}

static mlod_result mlod__build_error(mlod_error *error, mlod_result res)
{
    if (res == MLOD_ERROR_CANCELLED) return mlod__fail(error, res, "the build was cancelled by the progress callback");
    return mlod__fail(error, res, "out of memory while building the tree");
}

MLOD__PUBLIC mlod_result mlod_build_mesh(const mlod_mesh *mesh, const mlod_build_desc *desc, mlod_tree **out_tree,
                                         mlod_error *error)
{
    mlod_allocator a;
    mlod_result res = mlod__check_desc(desc, out_tree, error);
    uint32_t triangles, n, i, *tri = NULL, *leaf_item = NULL;
    double *cumulative = NULL;
    float *st = NULL, *pos = NULL;
    mlod_tree *tree = NULL;
    if (res != MLOD_OK) return res;
    if ((res = mlod__check_mesh(mesh, error)) != MLOD_OK) return res;
    n = desc->sample_count;
    if (n == 0) return mlod__fail(error, MLOD_ERROR_EMPTY, "sample_count is 0");
    if (n > MANYLODS_MAX_LEAVES)
        return mlod__fail(error, MLOD_ERROR_OVERFLOW, "sample_count %u exceeds MANYLODS_MAX_LEAVES (%u)", n,
                          MANYLODS_MAX_LEAVES);
    if (desc->attributes & MLOD_ATTR_COLOR && !mesh->colors)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "MLOD_ATTR_COLOR asks for colours the mesh lacks");
    a = mlod__allocator(desc->allocator);
    triangles = mesh->index_count / 3;
    cumulative = (double *)mlod__alloc_array(&a, (size_t)triangles + 1, sizeof(double), NULL);
    tri = (uint32_t *)mlod__alloc_array(&a, n, sizeof(uint32_t), NULL);
    st = (float *)mlod__alloc_array(&a, n, 2 * sizeof(float), NULL);
    pos = (float *)mlod__alloc_array(&a, n, 3 * sizeof(float), NULL);
    leaf_item = (uint32_t *)mlod__alloc_array(&a, n, sizeof(uint32_t), NULL);
    if (!cumulative || !tri || !st || !pos || !leaf_item) {
        res = mlod__build_error(error, MLOD_ERROR_OUT_OF_MEMORY);
        goto done;
    }
    /* each triangle's area, then their running sums in order */
    cumulative[0] = 0.0;
    mlod__triangle_areas(mesh, triangles, cumulative + 1, desc->parallel);
    for (i = 0; i < triangles; i++) cumulative[i + 1] += cumulative[i];
    if (!(cumulative[triangles] > 0.0)) {
        double reach = 0.0;
        for (i = 0; i < mesh->vertex_count; i++) {
            const float *p = mlod__at(mesh->positions, mesh->position_stride, i);
            int k;
            for (k = 0; k < 3; k++)
                if (fabs(p[k]) > reach) reach = fabs(p[k]);
        }
        res = mlod__fail(error, MLOD_ERROR_EMPTY,
                         "every triangle of the mesh has zero area (vertices reach %g from the origin, where float "
                         "precision is %g: a scene far from the origin may have collapsed)",
                         reach, reach * (1.0 / 8388608.0));
        goto done;
    }
    {
        double scale = desc->radius_scale > 0.0f ? desc->radius_scale : 1.0;
        if (!(scale * sqrt(cumulative[triangles] / n) <= MLOD__MAX_MEASURE)) {
            res = mlod__fail(error, MLOD_ERROR_RANGE, "leaf radius radius_scale * sqrt(A/N) = %g overflows float bounds",
                             scale * sqrt(cumulative[triangles] / n));
            goto done;
        }
    }
    {
        mlod__mesh_sample_job job;
        job.cumulative = cumulative;
        job.last_with_area = 0;
        for (i = 0; i < triangles; i++)
            if (cumulative[i + 1] > cumulative[i]) job.last_with_area = i;
        job.n = n;
        job.seed = desc->seed;
        job.tri_out = tri;
        job.st_out = st;
        job.mesh = mesh;
        job.pos_out = pos;
        mlod__run(desc->parallel, (n - 1) / MLOD__SAMPLE_CHUNK + 1, mlod__mesh_sample_task, &job);
    }
    if (mlod__report(desc, 0.1f)) {
        res = mlod__build_error(error, MLOD_ERROR_CANCELLED);
        goto done;
    }
    res = mlod__tree_ordered(&a, desc, pos, n, 1, triangles, leaf_item, 0.1f, &tree);
    if (res != MLOD_OK) {
        res = mlod__build_error(error, res);
        goto done;
    }
    tree->radius_scale = desc->radius_scale > 0.0f ? desc->radius_scale : 1.0f;
    tree->area_unit = cumulative[triangles] / n;
    tree->triangle_count = triangles;
    tree->vertex_count = mesh->vertex_count;
    {
        mlod__build_leaves_job job;
        job.tree = tree;
        job.mesh = mesh;
        job.leaf_item = leaf_item;
        job.tri = tri;
        job.st = st;
        if (tree->triangle_leaves)
            mlod__run(desc->parallel, (triangles - 1) / MLOD__LEAF_CHUNK + 1, mlod__build_triangles_task, &job);
        mlod__run(desc->parallel, (n - 1) / MLOD__LEAF_CHUNK + 1, mlod__build_leaves_task, &job);
    }
    if (tree->triangle_areas) {
        double smallest = INFINITY;
        /* each its own area, as refit will compute it: a difference of the
           running sums loses a triangle far smaller than the total */
        mlod__triangle_areas(mesh, triangles, tree->triangle_areas, desc->parallel);
        for (i = 0; i < triangles; i++) {
            double area = tree->triangle_areas[i];
            if (area > 0.0 && area < smallest) smallest = area;
        }
        tree->smallest_area = smallest; /* finite: the mesh has area */
    }
    mlod__merge_all(tree, desc->parallel, NULL);
    mlod__changes_built(tree, desc->parallel);
    mlod__set_precision(tree, tree->radius_scale * sqrt(tree->area_unit));
    if (mlod__report(desc, 1.0f)) {
        res = mlod__build_error(error, MLOD_ERROR_CANCELLED);
        goto done;
    }
    *out_tree = tree;
    tree = NULL;
    res = mlod__succeed(error);
done:
    mlod_tree_destroy(tree);
    mlod__free(&a, cumulative);
    mlod__free(&a, tri);
    mlod__free(&a, st);
    mlod__free(&a, pos);
    mlod__free(&a, leaf_item);
    return res;
}

static float mlod__point_radius(const mlod_points *points, uint32_t i)
{
    return mlod__scalar_at(points->radii, points->radius_stride, i);
}

/* Write leaf `node` from point `item`.  radius: before radius_scale. */
static void mlod__point_leaf(mlod_tree *tree, uint32_t node, const mlod_points *points, uint32_t item, double radius,
                             const mlod__stamp *stamp)
{
    const float *p = mlod__at(points->positions, points->position_stride, item);
    float bounds[8];
    int k;
    for (k = 0; k < 3; k++) bounds[k] = p[k];
    bounds[3] = mlod__float_up(tree->radius_scale * radius);
    if (tree->cones) {
        double n[3] = {0.0, 0.0, 0.0};
        if (points->normals) {
            const float *q = mlod__at(points->normals, points->normal_stride, item);
            for (k = 0; k < 3; k++) n[k] = q[k];
        }
        mlod__cone_from_normal(n, bounds + 4);
    } else { /* never read then, but a compiler may not see that */
        bounds[4] = bounds[5] = bounds[6] = bounds[7] = 0.0f;
    }
    mlod__store_leaf(tree, node, bounds, stamp);
    if (tree->areas) {
        float area = (float)(radius * radius / tree->area_unit);
        mlod__store_leaf_floats(tree->areas + node, &area, 1, node, stamp);
    }
    if (tree->colors)
        mlod__store_leaf_floats(tree->colors + 3 * (size_t)node, mlod__at(points->colors, points->color_stride, item), 3,
                                node, stamp);
}

/* Density-based radius of leaf j (before radius_scale), from the lowest
   node above it with at least 8 leaves (the root when N < 8). */
static double mlod__density_radius(const mlod_tree *tree, uint32_t j)
{
    uint32_t n = tree->leaf_count, node = n - 1 + j, leaves = 1;
    while (node > 0 && leaves < 8) {
        node = (node - 1) / 2;
        leaves = mlod__leaves_below(node, n);
    }
    return tree->spheres[4 * (size_t)node + 3] * sqrt(MLOD__PI / leaves);
}

/* The leaves of a points build, MLOD__LEAF_CHUNK per task, in one of its
   passes over them (step): 0 each leaf's radius from its point, 1 the
   leaves bare (radius 0: a first tree, whose density gives the radii), 2
   each leaf's radius from that density, 3 the leaves with their radii
   (and their points). */
typedef struct mlod__point_leaves_job {
    mlod_tree *tree;
    const mlod_points *points;
    const uint32_t *leaf_item;
    double *radius;
    int step;
} mlod__point_leaves_job;

static void mlod__point_leaves_task(void *context, uint32_t index)
{
    const mlod__point_leaves_job *job = (const mlod__point_leaves_job *)context;
    mlod_tree *tree = job->tree;
    uint32_t n = tree->leaf_count, i = index * MLOD__LEAF_CHUNK, end = i + MLOD__LEAF_CHUNK;
    if (end > n || end < i) end = n;
    for (; i < end; i++) {
        if (job->step == 0)
            job->radius[i] = mlod__point_radius(job->points, job->leaf_item[i]);
        else if (job->step == 2)
            job->radius[i] = mlod__density_radius(tree, i);
        else
            mlod__point_leaf(tree, n - 1 + i, job->points, job->leaf_item[i], job->step == 1 ? 0.0 : job->radius[i],
                             NULL);
        if (job->step == 3 && tree->leaf_sources) tree->leaf_sources[i] = job->leaf_item[i];
    }
}

/* Run step `step` of mlod__point_leaves_task over every leaf. */
static void mlod__point_leaves(mlod__point_leaves_job *job, int step, const mlod_parallel *parallel)
{
    job->step = step;
    mlod__run(parallel, (job->tree->leaf_count - 1) / MLOD__LEAF_CHUNK + 1, mlod__point_leaves_task, job);
}

/* mlod_build_points with the leaves' order given (order[j]: the point of
   leaf j, a permutation of the points), or NULL: the median splits'. */
static mlod_result mlod__build_points_in(const mlod_points *points, const mlod_build_desc *desc, const uint32_t *order,
                                         mlod_tree **out_tree, mlod_error *error)
{
    mlod_allocator a;
    mlod_result res = mlod__check_desc(desc, out_tree, error);
    uint32_t n, i, *leaf_item = NULL;
    float *pos = NULL;
    double *radius = NULL, mean_area = 0.0;
    mlod_tree *tree = NULL;
    mlod__point_leaves_job leaves;
    if (res != MLOD_OK) return res;
    if ((res = mlod__check_points(points, error)) != MLOD_OK) return res;
    if (desc->attributes & MLOD_ATTR_COLOR && !points->colors)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "MLOD_ATTR_COLOR asks for colours the points lack");
    n = points->count;
    a = mlod__allocator(desc->allocator);
    if (!order) { /* the median splits' order, from the positions */
        pos = (float *)mlod__alloc_array(&a, n, 3 * sizeof(float), NULL);
        leaf_item = (uint32_t *)mlod__alloc_array(&a, n, sizeof(uint32_t), NULL);
    }
    radius = (double *)mlod__alloc_array(&a, n, sizeof(double), NULL);
    if ((!order && (!pos || !leaf_item)) || !radius) {
        res = mlod__build_error(error, MLOD_ERROR_OUT_OF_MEMORY);
        goto done;
    }
    if (order) {
        tree = mlod__tree_create(&a, n, desc->attributes, 0, 0);
        res = tree ? MLOD_OK : MLOD_ERROR_OUT_OF_MEMORY;
    } else {
        for (i = 0; i < n; i++)
            memcpy(pos + 3 * (size_t)i, mlod__at(points->positions, points->position_stride, i), 3 * sizeof(float));
        res = mlod__tree_ordered(&a, desc, pos, n, 0, 0, leaf_item, 0.0f, &tree);
    }
    if (res != MLOD_OK) {
        res = mlod__build_error(error, res);
        goto done;
    }
    tree->radius_scale = desc->radius_scale > 0.0f ? desc->radius_scale : 1.0f;
    tree->area_unit = 1.0;
    leaves.tree = tree;
    leaves.points = points;
    leaves.leaf_item = order ? order : leaf_item;
    leaves.radius = radius;
    if (points->radii) {
        mlod__point_leaves(&leaves, 0, desc->parallel);
    } else {
        float scale = tree->radius_scale;
        tree->radius_scale = 0.0f; /* a first tree of bare points gives the density */
        mlod__point_leaves(&leaves, 1, desc->parallel);
        mlod__merge_all(tree, desc->parallel, NULL);
        mlod__point_leaves(&leaves, 2, desc->parallel);
        tree->radius_scale = scale;
    }
    for (i = 0; i < n; i++) {
        mean_area += radius[i] * radius[i] / n;
        if (!(tree->radius_scale * radius[i] <= MLOD__MAX_MEASURE)) {
            res = mlod__fail(error, MLOD_ERROR_RANGE, "point radius %g times radius_scale %g overflows float bounds",
                             radius[i], tree->radius_scale);
            goto done;
        }
    }
    tree->area_unit = mean_area > 0.0 ? mean_area : 1.0;
    mlod__point_leaves(&leaves, 3, desc->parallel);
    mlod__merge_all(tree, desc->parallel, NULL);
    mlod__changes_built(tree, desc->parallel);
    mlod__set_precision(tree, tree->radius_scale * sqrt(mean_area));
    if (mlod__report(desc, 1.0f)) {
        res = mlod__build_error(error, MLOD_ERROR_CANCELLED);
        goto done;
    }
    *out_tree = tree;
    tree = NULL;
    res = mlod__succeed(error);
done:
    mlod_tree_destroy(tree);
    mlod__free(&a, pos);
    mlod__free(&a, leaf_item);
    mlod__free(&a, radius);
    return res;
}

MLOD__PUBLIC mlod_result mlod_build_points(const mlod_points *points, const mlod_build_desc *desc, mlod_tree **out_tree,
                                           mlod_error *error)
{
    return mlod__build_points_in(points, desc, NULL, out_tree, error);
}


/* --------------------------------------------------------------- refit -- */

/* Triangle t's area now over its area at build, from its face normal n
   (mlod__face_normal); triangles of zero area at build have no samples:
   growth 0. */
static double mlod__triangle_growth(const mlod_tree *tree, uint32_t t, const double *n)
{
    return tree->triangle_areas[t] > 0.0 ? 0.5 * mlod__length3(n) / tree->triangle_areas[t] : 0.0;
}

/* What refit gives the samples of triangle t of the deformed mesh. */
static void mlod__refit_triangle(const mlod_tree *tree, const mlod_mesh *mesh, uint32_t t, mlod__triangle_leaf *out)
{
    double normal[3];
    mlod__face_normal(mesh, t, normal); /* one cross product for the area and the cone */
    mlod__triangle_leaf_of(tree, normal, mlod__triangle_growth(tree, t, normal), out);
}

/* Refit's first pass, MLOD__REFIT_SLICES tasks over the triangles: with
   the per-triangle scratch, each triangle's shared leaf data; without,
   only the largest growth (the range check looks at every triangle either
   way, as the Vulkan path does).  slice_growth[i]: task i's largest. */
#define MLOD__REFIT_SLICES 64u
typedef struct mlod__refit_job {
    mlod_tree *tree;
    const mlod_mesh *mesh;
    const mlod_points *points;
    mlod__stamp stamp; /* the leaves' writes recorded */
    int normals;       /* the leaves read the mesh's normals (a tree with cones, a mesh with them) */
    int cached;        /* only triangles with corners_changed[] set are computed again */
    double slice_growth[MLOD__REFIT_SLICES];
} mlod__refit_job;

/* Triangle t's corners as a refit reads them, in mlod_tree.corners'
   layout (mlod__corner_floats): positions, normals (zeros where the
   leaves do not read them), colours. */
static void mlod__corners_of(const mlod_tree *tree, const mlod_mesh *mesh, uint32_t t, int normals, float *out)
{
    const uint32_t *corner = mesh->indices + 3 * (size_t)t;
    int k;
    for (k = 0; k < 3; k++) memcpy(out + 3 * k, mlod__at(mesh->positions, mesh->position_stride, corner[k]), 12);
    out += 9;
    if (tree->cones) {
        for (k = 0; k < 3; k++)
            if (normals)
                memcpy(out + 3 * k, mlod__at(mesh->normals, mesh->normal_stride, corner[k]), 12);
            else
                memset(out + 3 * k, 0, 12);
        out += 9;
    }
    if (tree->colors)
        for (k = 0; k < 3; k++) memcpy(out + 3 * k, mlod__at(mesh->colors, mesh->color_stride, corner[k]), 12);
}

/* The triangles of refit slice `index` (of MLOD__REFIT_SLICES). */
static void mlod__refit_slice(const mlod_tree *tree, uint32_t index, uint32_t *first, uint32_t *end)
{
    *first = (uint32_t)((uint64_t)tree->triangle_count * index / MLOD__REFIT_SLICES);
    *end = (uint32_t)((uint64_t)tree->triangle_count * (index + 1) / MLOD__REFIT_SLICES);
}

/* MLOD_ATTR_REFIT_CACHE, before the leaves: which triangles' corners
   differ, bit for bit, from those the last refit read, those kept in
   their place.  A leaf's bits are a function of its triangle's corners
   (with its barycentrics, the triangle's area at build and the tree's
   constants, which no refit changes), so the leaves of the others would
   be written with the same bits.  (A refit that fails after this marks
   the cache unknown: mlod_refit_mesh.) */
static void mlod__corners_compare_task(void *context, uint32_t index)
{
    const mlod__refit_job *job = (const mlod__refit_job *)context;
    mlod_tree *tree = job->tree;
    uint32_t floats = mlod__corner_floats(tree->attributes), t, end;
    float now[27];
    mlod__refit_slice(tree, index, &t, &end);
    for (; t < end; t++) {
        float *kept = tree->corners + (size_t)floats * t;
        mlod__corners_of(tree, job->mesh, t, job->normals, now);
        tree->corners_changed[t] = memcmp(now, kept, floats * sizeof(float)) != 0;
        if (tree->corners_changed[t]) memcpy(kept, now, floats * sizeof(float));
    }
}

/* A refit that computed every leaf, after them: the corners it read. */
static void mlod__corners_store_task(void *context, uint32_t index)
{
    const mlod__refit_job *job = (const mlod__refit_job *)context;
    mlod_tree *tree = job->tree;
    uint32_t floats = mlod__corner_floats(tree->attributes), t, end;
    mlod__refit_slice(tree, index, &t, &end);
    for (; t < end; t++) mlod__corners_of(tree, job->mesh, t, job->normals, tree->corners + (size_t)floats * t);
}

static void mlod__refit_triangles_task(void *context, uint32_t index)
{
    mlod__refit_job *job = (mlod__refit_job *)context;
    const mlod_tree *tree = job->tree;
    mlod__triangle_leaf *shared = (mlod__triangle_leaf *)tree->triangle_leaves;
    uint32_t t, end;
    double largest = 0.0;
    mlod__refit_slice(tree, index, &t, &end);
    for (; t < end; t++) {
        double growth;
        if (shared) {
            /* a triangle whose corners did not change keeps its share */
            if (!job->cached || tree->corners_changed[t]) mlod__refit_triangle(tree, job->mesh, t, &shared[t]);
            growth = shared[t].growth;
        } else {
            double normal[3];
            mlod__face_normal(job->mesh, t, normal);
            growth = mlod__triangle_growth(tree, t, normal);
        }
        if (growth > largest) largest = growth;
    }
    job->slice_growth[index] = largest;
}

/* An upper bound on every triangle's growth without visiting the
   triangles: one inside a box of diagonal D has area at most D^2 / 2, so
   grows at most D^2 / (2 a), a the smallest area at build of a triangle
   that had area (kept by the build: mlod_tree.smallest_area); 2^-30 of
   slack covers the rounding of this bound and of each growth as refit
   computes it.  +inf (no bound: the triangles' own pass decides) when the
   tree does not know a. */
static double mlod__growth_bound(const mlod_tree *tree, const mlod_mesh *mesh)
{
    double lo[3], hi[3], d2 = 0.0, smallest = tree->smallest_area;
    int k;
    if (!(smallest > 0.0 && smallest < INFINITY)) return INFINITY;
    mlod__box_of(mesh->positions, mesh->position_stride, mesh->vertex_count, lo, hi);
    for (k = 0; k < 3; k++) d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    return d2 / (2.0 * smallest) * (1.0 + 1.0 / 1073741824.0);
}

static void mlod__refit_mesh_task(void *context, uint32_t index)
{
    mlod__refit_job *job = (mlod__refit_job *)context;
    mlod_tree *tree = job->tree;
    const mlod__triangle_leaf *shared = (const mlod__triangle_leaf *)tree->triangle_leaves;
    uint32_t j = index * MLOD__LEAF_CHUNK, end = j + MLOD__LEAF_CHUNK;
    if (end > tree->leaf_count) end = tree->leaf_count;
    for (; j < end; j++) {
        uint32_t tri = tree->leaf_sources[j], node = tree->leaf_count - 1 + j;
        mlod__triangle_leaf own;
        if (job->cached && !tree->corners_changed[tri]) continue; /* the same bits (mlod__corners_compare_task) */
        if (!shared) mlod__refit_triangle(tree, job->mesh, tri, &own); /* fewer leaves than triangles */
        mlod__mesh_leaf(tree, node, job->mesh, tri, tree->leaf_barycentrics[2 * (size_t)j],
                        tree->leaf_barycentrics[2 * (size_t)j + 1], shared ? &shared[tri] : &own, &job->stamp);
    }
}

static mlod_result mlod__check_refit_tree(const mlod_tree *tree, int mesh, mlod_error *error)
{
    if (!tree) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "tree is NULL");
    if (!tree->leaf_sources)
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "the tree was built without MLOD_ATTR_REFIT");
    if (mesh != (tree->leaf_barycentrics != NULL))
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "the tree was built from %s", mesh ? "points" : "a mesh");
    return MLOD_OK;
}

MLOD__PUBLIC mlod_result mlod_refit_check_growth(float radius_scale, double area_unit, uint32_t leaf_count,
                                                 double growth, mlod_error *error)
{
    if (!(radius_scale * sqrt(area_unit * growth) <= MLOD__MAX_MEASURE) || !(growth * leaf_count <= MLOD__MAX_MEASURE))
        return mlod__fail(error, MLOD_ERROR_RANGE, "a triangle grew %g times its build area: radii or areas would overflow",
                          growth);
    return MLOD_OK;
}

MLOD__PUBLIC mlod_result mlod_refit_mesh(mlod_tree *tree, const mlod_mesh *mesh, const mlod_parallel *parallel,
                                         mlod_error *error)
{
    mlod__refit_job job;
    mlod_result res = mlod__check_refit_tree(tree, 1, error);
    if (res != MLOD_OK) return res;
    if ((res = mlod__check_mesh(mesh, error)) != MLOD_OK) return res;
    if (mesh->index_count / 3 != tree->triangle_count || mesh->vertex_count != tree->vertex_count)
        return mlod__fail(error, MLOD_ERROR_MISMATCH,
                          "the mesh has %u triangles and %u vertices, the tree was built from %u and %u",
                          mesh->index_count / 3, mesh->vertex_count, tree->triangle_count, tree->vertex_count);
    if (tree->colors && !mesh->colors)
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "the tree has colours and the mesh has none");
    job.tree = tree;
    job.mesh = mesh;
    job.points = NULL;
    job.stamp = mlod__refit_stamp(tree);
    job.normals = tree->cones && mesh->normals;
    /* only what changed, where the corners cached are those of the last
       writer of the leaves (a tree whose arrays were written otherwise
       is marked and computed whole) */
    job.cached = tree->corners && tree->corners_state == 1u + (uint32_t)job.normals && !job.stamp.all;
    if (job.cached) mlod__run(parallel, MLOD__REFIT_SLICES, mlod__corners_compare_task, &job);
    if (!tree->triangle_leaves &&
        mlod_refit_check_growth(tree->radius_scale, tree->area_unit, tree->leaf_count, mlod__growth_bound(tree, mesh),
                                NULL) == MLOD_OK) {
        /* fewer leaves than triangles, and no triangle can have grown out
           of range: the triangles need no pass of their own */
    } else {
        /* the largest growth of a triangle must keep radii and summed
           areas (in build units) within float range; the scratch this
           pass writes is all that was written so far */
        double growth = 0.0;
        uint32_t i;
        mlod__run(parallel, MLOD__REFIT_SLICES, mlod__refit_triangles_task, &job);
        for (i = 0; i < MLOD__REFIT_SLICES; i++)
            if (job.slice_growth[i] > growth) growth = job.slice_growth[i];
        res = mlod_refit_check_growth(tree->radius_scale, tree->area_unit, tree->leaf_count, growth, error);
        if (res != MLOD_OK) {
            /* the scratch holds shares of this mesh's corners, the cache
               some of them: neither is the last writer's */
            tree->corners_state = 0;
            return res;
        }
    }
    mlod__run(parallel, (tree->leaf_count - 1) / MLOD__LEAF_CHUNK + 1, mlod__refit_mesh_task, &job);
    mlod__merge_all(tree, parallel, &job.stamp);
    if (tree->corners) { /* (a cached refit stored the changed ones as it compared) */
        if (!job.cached) mlod__run(parallel, MLOD__REFIT_SLICES, mlod__corners_store_task, &job);
        tree->corners_state = 1u + (uint32_t)job.normals;
    }
    mlod__set_precision(tree, tree->radius_scale * sqrt(tree->area_unit));
    mlod__refit_done(tree);
    return mlod__succeed(error);
}

/* How many leaves ahead refit asks for a point's position and normal. */
#define MLOD__POINT_AHEAD 8u
static void mlod__refit_points_task(void *context, uint32_t index)
{
    mlod__refit_job *job = (mlod__refit_job *)context;
    mlod_tree *tree = job->tree;
    uint32_t j = index * MLOD__LEAF_CHUNK, end = j + MLOD__LEAF_CHUNK;
    if (end > tree->leaf_count) end = tree->leaf_count;
    for (; j < end; j++) {
        uint32_t item = tree->leaf_sources[j], node = tree->leaf_count - 1 + j;
        double radius;
        if (j + MLOD__POINT_AHEAD < end) { /* the points come in tree order, scattered in memory */
            uint32_t ahead = tree->leaf_sources[j + MLOD__POINT_AHEAD];
            MLOD__PREFETCH(mlod__at(job->points->positions, job->points->position_stride, ahead));
            if (tree->cones && job->points->normals)
                MLOD__PREFETCH(mlod__at(job->points->normals, job->points->normal_stride, ahead));
        }
        radius = job->points->radii ? mlod__point_radius(job->points, item) : 0.0;
        mlod__point_leaf(tree, node, job->points, item, radius, &job->stamp);
    }
}

MLOD__PUBLIC mlod_result mlod_refit_points(mlod_tree *tree, const mlod_points *points, const mlod_parallel *parallel,
                                           mlod_error *error)
{
    mlod__refit_job job;
    mlod_result res = mlod__check_refit_tree(tree, 0, error);
    uint32_t chunks;
    if (res != MLOD_OK) return res;
    if ((res = mlod__check_points(points, error)) != MLOD_OK) return res;
    if (points->count != tree->leaf_count)
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "%u points, the tree was built from %u", points->count,
                          tree->leaf_count);
    if (tree->colors && !points->colors)
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "the tree has colours and the points have none");
    {
        /* the largest radius (given, or at most the points' extent when
           estimated) must keep radii and areas within float range */
        double largest = 0.0, lo[3], hi[3];
        uint32_t i;
        int k;
        if (points->radii)
            for (i = 0; i < points->count; i++)
                if (mlod__point_radius(points, i) > largest) largest = mlod__point_radius(points, i);
        if (!points->radii) {
            mlod__box_of(points->positions, points->position_stride, points->count, lo, hi);
            for (k = 0; k < 3; k++) largest += hi[k] - lo[k];
        }
        if (!(tree->radius_scale * largest <= MLOD__MAX_MEASURE) ||
            (tree->areas && !(largest * largest / tree->area_unit * points->count <= MLOD__MAX_MEASURE)))
            return mlod__fail(error, MLOD_ERROR_RANGE, "point radii up to %g would overflow float bounds", largest);
    }
    job.tree = tree;
    job.mesh = NULL;
    job.points = points;
    job.stamp = mlod__refit_stamp(tree);
    chunks = (tree->leaf_count - 1) / MLOD__LEAF_CHUNK + 1;
    if (!points->radii) {
        /* radii from the density of the new positions, as at build: a tree
           of bare points first; each leaf then reads only nodes above it */
        uint32_t j, n = tree->leaf_count;
        float scale = tree->radius_scale;
        /* every node is written twice (bare, then with its radius): each
           marked as changed */
        job.stamp.all = 1;
        tree->radius_scale = 0.0f;
        mlod__run(parallel, chunks, mlod__refit_points_task, &job);
        mlod__merge_all(tree, parallel, NULL);
        tree->radius_scale = scale;
        for (j = 0; j < n; j++)
            mlod__point_leaf(tree, n - 1 + j, points, tree->leaf_sources[j], mlod__density_radius(tree, j), NULL);
    } else {
        mlod__run(parallel, chunks, mlod__refit_points_task, &job);
    }
    mlod__merge_all(tree, parallel, &job.stamp);
    mlod__set_precision(tree, tree->radius_scale * sqrt(tree->area_unit));
    mlod__refit_done(tree);
    return mlod__succeed(error);
}

/* ---------------------------------------------- exact plane predicate -- */

/* GLSL twin: two_sum */
static void mlod__two_sum(double a, double b, double *sum, double *err)
{
    double s = a + b, bv = s - a, av = s - bv;
    *err = (a - av) + (b - bv);
    *sum = s;
}

/* GLSL twin: split_double */
static void mlod__split(double a, double *hi, double *lo)
{
    double c = 134217729.0 * a, big = c - a;
    *hi = c - big;
    *lo = a - *hi;
}

/* GLSL twin: two_product */
static void mlod__two_product(double a, double b, double *product, double *err)
{
    double p = a * b, ah, al, bh, bl;
    mlod__split(a, &ah, &al);
    mlod__split(b, &bh, &bl);
    *err = al * bl - (((p - ah * bh) - al * bh) - ah * bl);
    *product = p;
}

/* Sign of the exact sum of count doubles (an expansion grown term by term,
   as in Shewchuk's robust predicates). */
/* GLSL twin: exact_sign9 */
static int mlod__exact_sign(const double *terms, int count)
{
    double e[24];
    int len = 0, i, j;
    for (i = 0; i < count; i++) {
        double q = terms[i], h;
        int out = 0;
        for (j = 0; j < len; j++) {
            mlod__two_sum(q, e[j], &q, &h);
            if (h != 0.0) e[out++] = h;
        }
        e[out++] = q;
        len = out;
    }
    for (i = len - 1; i >= 0; i--)
        if (e[i] != 0.0) return e[i] > 0.0 ? 1 : -1;
    return 0;
}

/* A half-space {x : n.x >= k}, l >= |n}: five doubles n0 n1 n2 k l (a row
   of mlod_view_frame.planes). */
static void mlod__plane_set(double *p, const double *n, const double *point, double offset)
{
    int j;
    for (j = 0; j < 3; j++) p[j] = n[j];
    p[3] = mlod__dot3(n, point) + offset;
    p[4] = mlod__length3(n) * (1.0 + 1.0 / 1125899906842624.0);
}

/* mlod__outside when rounding leaves the sign in doubt: the sign of
   n.c + l r - k from exact products and an exact sum. */
static int mlod__outside_exact(const double *p, const float *sphere)
{
    double t[9];
    int j;
    for (j = 0; j < 3; j++) mlod__two_product(p[j], sphere[j], &t[2 * j], &t[2 * j + 1]);
    mlod__two_product(p[4], sphere[3], &t[6], &t[7]);
    t[8] = -p[3];
    return mlod__exact_sign(t, 9) < 0;
}

/* Is the sphere wholly outside the half-space: n.c + l r < k, exactly?
   The rounded sum decides unless it lies within its error bound of 0 (the
   criterion's hot path: kept small enough to inline). */
/* GLSL twin: plane_outside */
static inline int mlod__outside(const double *p, const float *sphere)
{
    double t0 = p[0] * sphere[0], t1 = p[1] * sphere[1], t2 = p[2] * sphere[2], t3 = p[4] * sphere[3];
    double s = t0 + t1 + t2 + t3 - p[3];
    double bound = (fabs(t0) + fabs(t1) + fabs(t2) + fabs(t3) + fabs(p[3])) * (1.0 / 281474976710656.0);
    if (s < -bound) return 1;
    if (s > bound) return 0;
    return mlod__outside_exact(p, sphere);
}

/* --------------------------------------------------------------- views -- */

/* The float filter's copy of one sub-projection (see mlod__fast_status):
   the axis w, the planes as n0 n1 n2 l k' with k' = k - n.eye (so that
   they apply to x = centre - eye), each plane's margin slope * reach +
   err (slope = 2^-20 l; err = 2^-20 |k'|, the rounding of k' and 2^-100
   for float underflow), and the thresholds on the diameter in projection
   units, S / epsilon times 1 + 2^-12 (valid) and 1 - 2^-12 (invalid). */
typedef struct mlod__fsub {
    float w[3], valid, invalid;
    int kind, plane_count;
    float planes[6][5], slope[6], err[6];
} mlod__fsub;

typedef struct mlod__fview {
    int ok; /* 0: every node-view takes the exact path */
    int sub_count, backfaces, ortho;
    int float_eye; /* eye[] holds floats: centre - eye subtracted in float (the same bound) */
    double eye[3];
    float eye_f[3];
    mlod__fsub subs[MLOD_VIEW_MAX_SUBS];
} mlod__fview;

/* A prepared view: its frame (the one representation, see mlod_view_frame)
   and, for the hot paths, the sub-projection count, the back-face flag and
   each sub-projection's kind and plane count as integers; the float
   filter's copy when mlod__fast_prepare made one. */
typedef struct mlod__pview {
    int sub_count, backfaces;
    int kind[MLOD_VIEW_MAX_SUBS];
    int plane_count[MLOD_VIEW_MAX_SUBS];
    uint32_t columns[MLOD_VIEW_MAX_SUBS][2], rows[MLOD_VIEW_MAX_SUBS][2]; /* each sub-tile's pixels, [begin, end) */
    mlod_view_frame f;
    mlod__fview fast;
} mlod__pview;

static int mlod__finite_positive(float x) { return isfinite(x) && x > 0.0f; }

/* Append a sub-projection of this kind, frame (u, v, w) and sub-tile to the
   view; its scale and planes are the caller's. */
static mlod_view_sub *mlod__sub_add(mlod__pview *pv, mlod_view_kind kind, const double *u, const double *v,
                                    const double *w, double x, double y, double width, double height)
{
    int s = pv->sub_count++, k;
    mlod_view_sub *sub = &pv->f.subs[s];
    for (k = 0; k < 3; k++) {
        sub->right[k] = u[k];
        sub->up[k] = v[k];
        sub->forward[k] = w[k];
    }
    pv->kind[s] = (int)kind;
    sub->kind = kind;
    sub->x = x;
    sub->y = y;
    sub->width = width;
    sub->height = height;
    return sub;
}

/* Append the half-space n.p >= n.eye + offset to the last sub-projection. */
static void mlod__sub_plane(mlod__pview *pv, const double *n, double offset)
{
    int s = pv->sub_count - 1;
    mlod__plane_set(pv->f.subs[s].planes[pv->plane_count[s]++], n, pv->f.eye, offset);
}

/* The same half-space with -n and -offset. */
static void mlod__sub_plane_neg(mlod__pview *pv, const double *n, double offset)
{
    double m[3];
    int k;
    for (k = 0; k < 3; k++) m[k] = -n[k];
    mlod__sub_plane(pv, m, -offset);
}

/* A perspective sub-projection: tan of its half vertical field of view ty,
   depth range [near_plane, far_plane]; culled outside its frustum. */
static void mlod__perspective_sub(mlod__pview *pv, const double *u, const double *v, const double *w, double x,
                                  double y, double width, double height, double ty, float near_plane, float far_plane)
{
    mlod_view_sub *sub = mlod__sub_add(pv, MLOD_VIEW_PERSPECTIVE, u, v, w, x, y, width, height);
    double tx, n[3];
    int k;
    sub->scale = 0.5 * height / ty;
    tx = 0.5 * width / sub->scale;
    mlod__sub_plane(pv, w, near_plane);
    if (isfinite(far_plane)) mlod__sub_plane_neg(pv, w, far_plane);
    for (k = 0; k < 3; k++) n[k] = tx * w[k] - u[k];
    mlod__sub_plane(pv, n, 0.0);
    for (k = 0; k < 3; k++) n[k] = tx * w[k] + u[k];
    mlod__sub_plane(pv, n, 0.0);
    for (k = 0; k < 3; k++) n[k] = ty * w[k] - v[k];
    mlod__sub_plane(pv, n, 0.0);
    for (k = 0; k < 3; k++) n[k] = ty * w[k] + v[k];
    mlod__sub_plane(pv, n, 0.0);
}

/* A paraboloid sub-projection: the hemisphere around w; culled behind it. */
static void mlod__paraboloid_sub(mlod__pview *pv, const double *u, const double *v, const double *w, double x,
                                 double y, double width, double height)
{
    mlod_view_sub *sub = mlod__sub_add(pv, MLOD_VIEW_PARABOLOID, u, v, w, x, y, width, height);
    sub->scale = 0.5 * (width > height ? width : height);
    mlod__sub_plane(pv, w, 0.0);
}

/* An orthographic sub-projection of the view's box over the whole tile;
   culled outside the box. */
static void mlod__orthographic_sub(mlod__pview *pv, const mlod_view *view, const double *u, const double *v,
                                   const double *w)
{
    mlod_view_sub *sub = mlod__sub_add(pv, MLOD_VIEW_ORTHOGRAPHIC, u, v, w, 0.0, 0.0, view->width, view->height);
    double sx = view->width / (2.0 * view->half_width), sy = view->height / (2.0 * view->half_height);
    sub->scale = sx > sy ? sx : sy;
    sub->scale_x = sx;
    sub->scale_y = sy;
    mlod__sub_plane(pv, w, view->near_plane);
    if (isfinite(view->far_plane)) mlod__sub_plane_neg(pv, w, view->far_plane);
    mlod__sub_plane(pv, u, -(double)view->half_width);
    mlod__sub_plane_neg(pv, u, view->half_width);
    mlod__sub_plane(pv, v, -(double)view->half_height);
    mlod__sub_plane_neg(pv, v, view->half_height);
}

/* The six faces of a cube map in the frame (u, v, w) of its view, in the
   order and orientation of Vulkan's cube maps over X = u, Y = v, Z = -w:
   for each face, its axis, its pixel x and its pixel y (upwards), each as
   +-1 times u, v or w (1, 2, 3). */
static const signed char mlod__cube_faces[6][3] = {
    {1, 3, 2}, {-1, -3, 2}, {2, 1, 3}, {-2, 1, -3}, {-3, 1, 2}, {3, -1, 2}};

/* The cube map's faces: perspective sub-projections of 90 degrees. */
static void mlod__cube_subs(mlod__pview *pv, const mlod_view *view, const double *const axes[3])
{
    double side = view->height / 2, frame[3][3];
    int face, j, k;
    for (face = 0; face < 6; face++) {
        for (j = 0; j < 3; j++) {
            int a = mlod__cube_faces[face][j];
            for (k = 0; k < 3; k++) frame[j][k] = a < 0 ? -axes[-a - 1][k] : axes[a - 1][k];
        }
        mlod__perspective_sub(pv, frame[1], frame[2], frame[0], side * (face % 3), side * (face / 3), side, side, 1.0,
                              view->near_plane, view->far_plane);
    }
}

/* Check that the fields the view's kind reads hold numbers where they must
   (see mlod_view), and the kind, tile and flags. */
static mlod_result mlod__view_fields_check(const mlod_view *view, mlod_error *error)
{
    mlod_view_kind kind = view->kind;
    if ((unsigned)kind > (unsigned)MLOD_VIEW_CUBE)
        return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "unknown view kind %d", (int)kind);
    if (!mlod__finite3(view->position) || !mlod__finite3(view->forward) || !mlod__finite3(view->up))
        return mlod__fail(error, MLOD_ERROR_NON_FINITE, "the view's position, forward or up is not finite");
    if (view->width == 0 || view->height == 0)
        return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "tile size %ux%u: both must be >= 1", view->width, view->height);
    /* a paraboloid accepts anything, NaN included, in fov_y, near_plane,
       far_plane, half_width and half_height */
    if (kind == MLOD_VIEW_PERSPECTIVE &&
        (!isfinite(view->fov_y) || !isfinite(view->near_plane) || isnan(view->far_plane)))
        return mlod__fail(error, MLOD_ERROR_NON_FINITE,
                          "perspective fov_y %g and near_plane %g must be finite, far_plane %g not NaN", view->fov_y,
                          view->near_plane, view->far_plane);
    if (kind == MLOD_VIEW_CUBE && (!isfinite(view->near_plane) || isnan(view->far_plane)))
        return mlod__fail(error, MLOD_ERROR_NON_FINITE, "cube map near_plane %g must be finite, far_plane %g not NaN",
                          view->near_plane, view->far_plane);
    if (kind == MLOD_VIEW_ORTHOGRAPHIC &&
        (!isfinite(view->near_plane) || !isfinite(view->half_width) || !isfinite(view->half_height) ||
         isnan(view->far_plane)))
        return mlod__fail(error, MLOD_ERROR_NON_FINITE,
                          "orthographic near_plane %g, half_width %g and half_height %g must be finite, far_plane %g "
                          "not NaN",
                          view->near_plane, view->half_width, view->half_height, view->far_plane);
    if (view->flags & ~(uint32_t)MLOD_VIEW_CULL_BACKFACES)
        return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "unknown view flags 0x%x", view->flags);
    return MLOD_OK;
}

/* Check the ranges of the fields the view's kind reads, once they are
   known to be numbers. */
static mlod_result mlod__view_ranges_check(const mlod_view *view, mlod_error *error)
{
    mlod_view_kind kind = view->kind;
    if (kind == MLOD_VIEW_PERSPECTIVE && !(view->fov_y > 0.0f && view->fov_y < MLOD__PI))
        return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "fov_y %g is not in (0, pi)", view->fov_y);
    if ((kind == MLOD_VIEW_PERSPECTIVE || kind == MLOD_VIEW_CUBE) && !(view->near_plane > 0.0f))
        return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "%s near_plane %g must be finite and > 0",
                          kind == MLOD_VIEW_CUBE ? "cube map" : "perspective", view->near_plane);
    if ((kind == MLOD_VIEW_PERSPECTIVE || kind == MLOD_VIEW_CUBE) && !(view->far_plane > view->near_plane))
        return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "far_plane %g must be > near_plane %g", view->far_plane,
                          view->near_plane);
    /* 3s in 64 bits: it may pass 2^32 where 2s does not */
    if (kind == MLOD_VIEW_CUBE && (view->height % 2 != 0 || view->width != (uint64_t)(view->height / 2) * 3))
        return mlod__fail(error, MLOD_ERROR_BAD_VIEW,
                          "cube map tile %ux%u: must be 3s x 2s pixels, six s x s faces (for example %llux%u)",
                          view->width, view->height, 3ull * (view->height / 2 ? view->height / 2 : 1u),
                          view->height / 2 ? view->height / 2 * 2 : 2u);
    if (kind == MLOD_VIEW_ORTHOGRAPHIC && (!mlod__finite_positive(view->half_width) ||
                                           !mlod__finite_positive(view->half_height)))
        return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "orthographic half_width %g and half_height %g must be > 0",
                          view->half_width, view->half_height);
    if (kind == MLOD_VIEW_ORTHOGRAPHIC && !(view->far_plane > view->near_plane))
        return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "orthographic near_plane %g must be finite and < far_plane %g",
                          view->near_plane, view->far_plane);
    return MLOD_OK;
}

/* Validate a view and derive its frame: the unit frame (u, v, w), then its
   sub-projections, each with its scale, sub-tile and planes.  A view kind
   is this function's case and nothing else. */
static mlod_result mlod__view_prepare(const mlod_view *view, mlod__pview *pv, mlod_error *error)
{
    double f[3], up[3], u[3], v[3], w[3], back_u[3], back_w[3], len_f, len_up, right_len;
    const double *axes[3];
    mlod_result res;
    int k;
    if (!view) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "view is NULL");
    res = mlod__view_fields_check(view, error);
    if (res != MLOD_OK) return res;
    memset(pv, 0, sizeof *pv);
    for (k = 0; k < 3; k++) {
        pv->f.eye[k] = view->position[k];
        f[k] = view->forward[k];
        up[k] = view->up[k];
    }
    len_f = mlod__length3(f);
    len_up = mlod__length3(up);
    if (!(len_f > 0.0) || !(len_up > 0.0))
        return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "the view's forward or up vector has zero length");
    for (k = 0; k < 3; k++) {
        w[k] = f[k] / len_f;
        up[k] /= len_up;
    }
    mlod__cross3(w, up, u);
    right_len = mlod__length3(u);
    if (!(right_len > 1e-6))
        return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "the view's forward and up vectors are parallel");
    for (k = 0; k < 3; k++) u[k] /= right_len;
    mlod__cross3(u, w, v);
    res = mlod__view_ranges_check(view, error);
    if (res != MLOD_OK) return res;
    pv->f.width = view->width;
    pv->f.height = view->height;
    pv->f.kind = view->kind;
    pv->backfaces = (view->flags & MLOD_VIEW_CULL_BACKFACES) != 0;
    switch (view->kind) {
    case MLOD_VIEW_PERSPECTIVE:
        mlod__perspective_sub(pv, u, v, w, 0.0, 0.0, view->width, view->height, tan(0.5 * view->fov_y),
                              view->near_plane, view->far_plane);
        break;
    case MLOD_VIEW_PARABOLOID:
        mlod__paraboloid_sub(pv, u, v, w, 0.0, 0.0, view->width, view->height);
        break;
    case MLOD_VIEW_DUAL_PARABOLOID:
        for (k = 0; k < 3; k++) {
            back_u[k] = -u[k];
            back_w[k] = -w[k];
        }
        mlod__paraboloid_sub(pv, u, v, w, 0.0, 0.0, 0.5 * view->width, view->height);
        mlod__paraboloid_sub(pv, back_u, v, back_w, 0.5 * view->width, 0.0, 0.5 * view->width, view->height);
        break;
    case MLOD_VIEW_ORTHOGRAPHIC:
        mlod__orthographic_sub(pv, view, u, v, w);
        break;
    case MLOD_VIEW_CUBE:
        axes[0] = u;
        axes[1] = v;
        axes[2] = w;
        mlod__cube_subs(pv, view, axes);
        break;
    }
    pv->f.sub_count = pv->sub_count;
    for (k = 0; k < pv->sub_count; k++) {
        const mlod_view_sub *sub = &pv->f.subs[k];
        pv->f.subs[k].plane_count = pv->plane_count[k];
        pv->columns[k][0] = (uint32_t)sub->x;
        pv->columns[k][1] = (uint32_t)(sub->x + sub->width);
        pv->rows[k][0] = (uint32_t)sub->y;
        pv->rows[k][1] = (uint32_t)(sub->y + sub->height);
    }
    pv->f.cull_backfaces = pv->backfaces;
    return MLOD_OK;
}

MLOD__PUBLIC mlod_result mlod_view_check(const mlod_view *view, mlod_error *error)
{
    mlod__pview pv;
    mlod_result res = mlod__view_prepare(view, &pv, error);
    return res == MLOD_OK ? mlod__succeed(error) : res;
}

MLOD__PUBLIC mlod_result mlod_view_frame_of(const mlod_view *view, mlod_view_frame *frame, mlod_error *error)
{
    mlod__pview pv;
    mlod_result res;
    if (!frame) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "frame is NULL");
    res = mlod__view_prepare(view, &pv, error);
    if (res != MLOD_OK) return res;
    *frame = pv.f;
    return mlod__succeed(error);
}

/* Does every point of the sphere, with every normal of the cone, face away
   from the eye?  x = centre - eye, d2 = |x|^2, tangent = sqrt(d^2 - r^2)
   when d2 > r^2.  With g the angle between the axis and the direction to
   the eye, a the cone's half-angle and b = asin(r/d) the sphere's angular
   radius, culled when g > pi/2 + a + b (< pi), i.e. cos g < -sin(a + b):
   axis.(e - c) / |axis| < -(sin a t + cos a r), and cos(a + b) > 0, i.e.
   cos a t - sin a r > 0, with (t, r) = (sqrt(d^2 - r^2), r); no inverse
   trigonometry.  An orthographic eye (a view's sub-projections share their
   eye, so the first one tells) is at -w with b = 0: (t, r) = (1, 0)
   turns the same two tests into cos a > 0 and axis.(-w) / |axis| < -sin a,
   bit for bit. */
/* GLSL twin: backfacing */
static int mlod__backfacing(const mlod__pview *pv, const double *x, double d2, double r, double tangent,
                            const float *cone)
{
    double a = cone[3], sa, ca, away, len, cos_g, t = tangent, s = r;
    /* a half-angle of pi/2 or more, or an axis not turned away from the eye
       (g <= pi/2), always has a normal facing it: those return before the
       square root and the series (half the nodes of a closed surface) */
    if (!(a < 0.5 * MLOD__PI)) return 0;
    if (pv->kind[0] == MLOD_VIEW_ORTHOGRAPHIC) {
        const double *w = pv->f.subs[0].forward;
        away = -(cone[0] * w[0] + cone[1] * w[1] + cone[2] * w[2]);
        t = 1.0;
        s = 0.0;
    } else {
        if (d2 <= r * r) return 0;
        away = -(cone[0] * x[0] + cone[1] * x[1] + cone[2] * x[2]);
    }
    if (!(away < 0.0)) return 0;
    len = sqrt((double)cone[0] * cone[0] + (double)cone[1] * cone[1] + (double)cone[2] * cone[2]);
    cos_g = away / len; /* |x| cos g, or cos g when orthographic */
    /* Nine nodes in ten are decided without the series (measured on the
       bench's object): on [0, pi/2), a - a^3/6 <= sin a <= a and
       1 - a^2/2 <= cos a <= 1, and mlod__sin_cos is within 1e-16 of sin and
       cos; past a margin of 2^-30 (t + s), far above that error and the
       rounding of either side, these bounds settle both tests as the
       series' values would. */
    if (a >= 0.0) {
        double a2 = a * a, margin = (t + s) * (1.0 / 1073741824.0) + 1e-300;
        if (cos_g > margin - ((a - a2 * a * (1.0 / 6.0)) * t + (1.0 - 0.5 * a2) * s)) return 0;
        if ((1.0 - 0.5 * a2) * t - a * s > margin && cos_g < -(a * t + s) - margin) return 1;
    }
    mlod__sin_cos(a, &sa, &ca);
    return ca * t - sa * s > 0.0 && cos_g < -(sa * t + ca * s);
}

/* Diameter of the paraboloid image of a sphere, in projection units, for
   the hemisphere whose axis has component xw along x (+inf if unbounded). */
/* GLSL twin: paraboloid_diameter */
static double mlod__paraboloid_diameter(double r, double xw, double tangent)
{
    double den = xw + tangent;
    return den > 0.0 ? 2.0 * r / den : (double)INFINITY;
}

/* The diameter of the sphere's image in one sub-projection, in pixels:
   x = centre - eye, d2 = |x|^2, tangent = sqrt(max(d2 - r^2, 0)) (0 for
   orthographic views). */
/* GLSL twin: sub_diameter */
static inline double mlod__sub_diameter(const mlod_view_sub *sub, int kind, const double *x, double d2, double r,
                                 double tangent)
{
    double xw = mlod__dot3(x, sub->forward);
    switch (kind) {
    case MLOD_VIEW_PERSPECTIVE:
        if (xw <= r) return INFINITY;
        return sub->scale * 2.0 * r * tangent / ((xw - r) * (xw + r));
    case MLOD_VIEW_PARABOLOID:
        if (d2 <= r * r) return INFINITY;
        return sub->scale * mlod__paraboloid_diameter(r, xw, tangent);
    }
    return sub->scale * 2.0 * r;
}

/* Which sub-projections the sphere reaches: bit s for sub-projection s. */
/* GLSL twin: reached_subs */
static inline unsigned mlod__reached(const mlod__pview *pv, const float *sphere)
{
    unsigned reached = 0;
    int s, k;
    for (s = 0; s < pv->sub_count; s++) {
        for (k = 0; k < pv->plane_count[s]; k++)
            if (mlod__outside(pv->f.subs[s].planes[k], sphere)) break;
        if (k == pv->plane_count[s]) reached |= 1u << s;
    }
    return reached;
}

/* What every sub-projection's diameter needs: x = centre - eye, d2 = |x|^2
   and the tangent length (0 for an orthographic eye); 1 when back-face
   culling culls the sphere. */
static inline int mlod__sphere_setup(const mlod__pview *pv, const float *sphere, const float *cone, double *x,
                                     double *d2, double *tangent)
{
    double r = sphere[3], t2;
    int k;
    for (k = 0; k < 3; k++) x[k] = (double)sphere[k] - pv->f.eye[k];
    *d2 = mlod__dot3(x, x);
    t2 = *d2 - r * r; /* > 0 exactly when d2 > r^2 */
    *tangent = pv->kind[0] == MLOD_VIEW_ORTHOGRAPHIC ? 0.0 : sqrt(t2 > 0.0 ? t2 : 0.0);
    return pv->backfaces && cone && mlod__backfacing(pv, x, *d2, r, *tangent, cone);
}

/* c(node, view) of the documentation; *culled = 1 when culled. */
/* GLSL twin: evaluate */
static double mlod__evaluate(const mlod__pview *pv, const float *sphere, const float *cone, int *culled)
{
    double x[3], d2, tangent, c = 0.0;
    unsigned reached;
    int k;
    *culled = 1;
    if (pv->sub_count == 1) { /* the hot path (most views): mlod__reached inline */
        for (k = 0; k < pv->plane_count[0]; k++)
            if (mlod__outside(pv->f.subs[0].planes[k], sphere)) return 0.0;
        if (mlod__sphere_setup(pv, sphere, cone, x, &d2, &tangent)) return 0.0;
        *culled = 0;
        return mlod__sub_diameter(&pv->f.subs[0], pv->kind[0], x, d2, sphere[3], tangent);
    }
    /* culled either way (the order changes no result): several
       sub-projections cost more plane tests than the back-face test, and
       seldom cull all together */
    if (mlod__sphere_setup(pv, sphere, cone, x, &d2, &tangent)) return 0.0;
    reached = mlod__reached(pv, sphere);
    if (!reached) return 0.0;
    *culled = 0;
    for (k = 0; k < pv->sub_count; k++)
        if (reached >> k & 1u) {
            double sub = mlod__sub_diameter(&pv->f.subs[k], pv->kind[k], x, d2, sphere[3], tangent);
            if (sub > c) c = sub;
        }
    return c;
}

static const float *mlod__cone_of(const mlod_tree *tree, uint32_t node)
{
    return tree->cones ? tree->cones + 4 * (size_t)node : NULL;
}

MLOD__PUBLIC double mlod_criterion(const mlod_tree *tree, uint32_t node, const mlod_view *view)
{
    mlod__pview pv;
    int culled;
    if (!tree || node >= tree->node_count || mlod__view_prepare(view, &pv, NULL) != MLOD_OK) return NAN;
    return mlod__evaluate(&pv, tree->spheres + 4 * (size_t)node, mlod__cone_of(tree, node), &culled);
}


/* ------------------------------------------------------- float filter -- */

/* The cut's decisions in float, proven to agree with the exact path
   (THE CUT, "Fast paths decide exactly").  mlod__fast_status gives the
   status mlod__classify would give (MLOD_STATUS_COARSE standing for
   "not valid"), or MLOD__UNSURE when it cannot prove it; only then does
   the exact path run.  The proof, with u = 2^-24 (float rounding):

   - x = centre - eye is subtracted in double and rounded to float (in
     float, one rounding, where the eye's coordinates are floats), so
     each component is within u |x_k| (the eye may be far from the origin
     and x small).  Guards keep every float value normal and finite:
     2^-40 <= |x|^2 <= 2^80, r = 0 or 2^-40 <= r <= 2^40, the thresholds
     within [2^-40, 2^40] (else the view has no filter); whatever fails a
     guard is UNSURE.  Then x.w errs by at most 4.01 u |x| (|w| = 1),
     |x|^2 by 5.01 u |x|^2.
   - Planes: s = n.x + l r - k' errs by at most 7.01 u M, M = |n0 x0| +
     |n1 x1| + |n2 x2| + l r + |k'| <= l (|x| + r) + |k'| (l >= |n|), plus
     err (k' rounded in double; 2^-100 for the plane's components and k'
     rounded to float below 2^-126, times |x_k| <= 2^40); with |x| + r <=
     reach = t + 2 r (|x|^2 = t^2 + r^2; sqrt(|x|^2) + r orthographic),
     |s| > 2^-20 (l reach + |k'|) + err decides.
   - Diameters, with t^2 = |x|^2 - r^2 >= |x|^2 / 4 (so t errs by at most
     13.6 u t): perspective 2 r t S / ((x.w - r)(x.w + r)) with
     (x.w - r)^2 >= |x|^2 / 256: each factor errs by at most 65.3 u, the
     two sides of 2 r t (S / eps) <= (x.w - r)(x.w + r) by 17 u and 132 u;
     paraboloid 2 r S / (x.w + t) with (x.w + t)^2 >= |x|^2 / 256: the
     denominator errs by 283 u; orthographic 2 r S: 3 u.  The thresholds'
     margin 2^-12 = 4096 u exceeds every sum by 3700 u, far above the
     exact path's own rounding (about 2^-45 relative under these guards):
     a decided side is the exact path's side.
   - Back faces (mlod__backfacing): sin a and cos a by their Taylor
     polynomials to a^5 and a^6, within a^7 / 5040 + 32 u for a < pi/2;
     Z1 = cos a t - sin a r and Z2 = axis.(eye - centre) + |axis| (sin a t
     + cos a r) then err by at most (a^7/5040 + 28 u)(t + r) and
     |axis| times that ((t, r) = (1, 0) orthographic; |x| <= t + r);
     culled when Z1 > 0 and Z2 < 0, decided past (a^7/5040 + 40 u)(t + r).
   The tests compare every decision with the exact path, at thresholds
   placed exactly on node-views' criteria (tests/test_cut.c). */
#define MLOD__UNSURE 0u
#define MLOD__FAST_U (1.0f / 16777216.0f)

/* Whether v is a float: *out = v rounded to float, equal to v. */
static int mlod__float_exact(double v, float *out)
{
    *out = (float)v;
    return (double)*out == v;
}

/* Fill pv->fast for the cut's epsilon (pv from mlod__view_prepare): no
   filter (ok = 0) where a value leaves the guarded range. */
static void mlod__fast_prepare(mlod__pview *pv, double epsilon)
{
    mlod__fview *fv = &pv->fast;
    const double lo = 1.0 / 1099511627776.0, hi = 1099511627776.0; /* 2^-40, 2^40 */
    int s, k, j;
    fv->ok = 0;
    fv->sub_count = pv->sub_count;
    fv->backfaces = pv->backfaces;
    fv->ortho = pv->kind[0] == MLOD_VIEW_ORTHOGRAPHIC;
    fv->float_eye = 1;
    for (k = 0; k < 3; k++) {
        fv->eye[k] = pv->f.eye[k];
        if (!(fabs(fv->eye[k]) <= 18446744073709551616.0)) return; /* 2^64: centre - eye rounds into float range */
        if (!mlod__float_exact(fv->eye[k], &fv->eye_f[k])) fv->float_eye = 0;
    }
    for (s = 0; s < pv->sub_count; s++) {
        const mlod_view_sub *sub = &pv->f.subs[s];
        mlod__fsub *fs = &fv->subs[s];
        double inv = sub->scale / epsilon;
        if (!(inv >= lo && inv <= hi)) return;
        fs->kind = pv->kind[s];
        fs->plane_count = pv->plane_count[s];
        fs->valid = (float)(inv * (1.0 + 1.0 / 4096.0));
        fs->invalid = (float)(inv * (1.0 - 1.0 / 4096.0));
        for (k = 0; k < 3; k++) fs->w[k] = (float)sub->forward[k];
        for (j = 0; j < fs->plane_count; j++) {
            const double *p = sub->planes[j];
            double ne = 0.0, mag = fabs(p[3]), kp;
            for (k = 0; k < 3; k++) {
                ne += p[k] * fv->eye[k];
                mag += fabs(p[k]) * fabs(fv->eye[k]);
            }
            kp = p[3] - ne;
            if (!(fabs(kp) <= 1e30 && mag <= 1e30 && p[4] <= 1e30)) return; /* l >= |n_k| */
            for (k = 0; k < 3; k++) fs->planes[j][k] = (float)p[k];
            fs->planes[j][3] = (float)p[4];
            fs->planes[j][4] = (float)kp;
            /* the margin 2^-20 (l (|x| + r) + |k'|) + err: 2^-48, 2^-100 */
            fs->slope[j] = mlod__float_up(p[4] * (1.0 / 1048576.0));
            fs->err[j] = mlod__float_up(fabs(kp) * (1.0 / 1048576.0) + mag * (1.0 / 281474976710656.0)) +
                         7.88860905e-31f;
        }
    }
    fv->ok = 1;
}

/* The back-face test of mlod__backfacing in float: 1 culled, 0 not,
   -1 unsure.  x = centre - eye (float), t the tangent length, r the radius
   ((t, r) = (1, 0) and x unused for an orthographic view, w its axis). */
/* GLSL twin: fast_backfacing */
static int mlod__fast_backfacing(const mlod__fview *fv, const float *x, float t, float r, const float *cone)
{
    float a = cone[3], a2, sa, ca, away, len, e, m1, z1, z2;
    /* no float lies between pi/2 and its float rounding: the same test as
       the double one */
    if (!(a < (float)(0.5 * MLOD__PI))) return 0;
    if (!(a >= 0.0f)) return -1;
    if (fv->ortho) {
        const float *w = fv->subs[0].w;
        away = -(cone[0] * w[0] + cone[1] * w[1] + cone[2] * w[2]);
    } else {
        away = -(cone[0] * x[0] + cone[1] * x[1] + cone[2] * x[2]);
    }
    len = sqrtf(cone[0] * cone[0] + cone[1] * cone[1] + cone[2] * cone[2]);
    a2 = a * a;
    sa = a * (1.0f - a2 * (1.0f / 6.0f - a2 * (1.0f / 120.0f)));
    ca = 1.0f - a2 * (0.5f - a2 * (1.0f / 24.0f - a2 * (1.0f / 720.0f)));
    e = a2 * a2 * a2 * a * (1.0f / 5040.0f) + 40.0f * MLOD__FAST_U;
    m1 = (t + r) * e;
    z2 = away + len * (sa * t + ca * r);
    if (z2 > len * m1) return 0;
    z1 = ca * t - sa * r;
    if (z1 < -m1) return 0;
    if (z1 > m1 && z2 < -len * m1) return 1;
    return -1;
}

/* The status of a node-view in float (see above): MLOD_STATUS_CULLED,
   _DRAWN, _COARSE (not valid: the caller tells an oversize leaf) or
   MLOD__UNSURE.  fv->ok must be set. */
/* GLSL twin: fast_status */
static inline uint8_t mlod__fast_status(const mlod__fview *fv, const float *sphere, const float *cone)
{
    float x[3], r = sphere[3], d2, t = 1.0f, twice = r + r, reach;
    unsigned reached = 0;
    int s, j, all_valid = 1;
    if (fv->float_eye) {
        x[0] = sphere[0] - fv->eye_f[0];
        x[1] = sphere[1] - fv->eye_f[1];
        x[2] = sphere[2] - fv->eye_f[2];
    } else {
        x[0] = (float)((double)sphere[0] - fv->eye[0]);
        x[1] = (float)((double)sphere[1] - fv->eye[1]);
        x[2] = (float)((double)sphere[2] - fv->eye[2]);
    }
    d2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    if (!(d2 >= 9.09494702e-13f && d2 <= 1.20892582e24f)) return MLOD__UNSURE; /* 2^-40, 2^80 */
    if (!(r == 0.0f || (r >= 9.09494702e-13f && r <= 1.09951163e12f))) return MLOD__UNSURE;
    if (!fv->ortho) {
        float t2 = d2 - r * r;
        if (!(4.0f * t2 >= d2)) return MLOD__UNSURE;
        t = sqrtf(t2);
        reach = t + twice; /* >= |x| + r: |x|^2 = t^2 + r^2 */
    } else {
        reach = sqrtf(d2) + r;
    }
    for (s = 0; s < fv->sub_count; s++) {
        const mlod__fsub *fs = &fv->subs[s];
        for (j = 0; j < fs->plane_count; j++) {
            const float *p = fs->planes[j];
            float a0 = p[0] * x[0], a1 = p[1] * x[1], a2 = p[2] * x[2], a3 = p[3] * r;
            float v = a0 + a1 + a2 + a3 - p[4];
            float m = fs->slope[j] * reach + fs->err[j];
            if (v < -m) break;
            if (!(v > m)) return MLOD__UNSURE;
        }
        if (j == fs->plane_count) reached |= 1u << s;
    }
    if (!reached) return MLOD_STATUS_CULLED;
    if (fv->backfaces && cone) {
        int b = mlod__fast_backfacing(fv, x, t, fv->ortho ? 0.0f : r, cone);
        if (b) return b > 0 ? (uint8_t)MLOD_STATUS_CULLED : (uint8_t)MLOD__UNSURE;
    }
    for (s = 0; s < fv->sub_count; s++) {
        const mlod__fsub *fs = &fv->subs[s];
        float xw, lhs, rhs;
        if (!(reached >> s & 1u)) continue;
        xw = x[0] * fs->w[0] + x[1] * fs->w[1] + x[2] * fs->w[2];
        if (fs->kind == MLOD_VIEW_PERSPECTIVE) {
            float near_side = xw - r;
            if (!(near_side > 0.0f && 256.0f * near_side * near_side >= d2)) return MLOD__UNSURE;
            lhs = twice * t;
            rhs = near_side * (xw + r);
        } else if (fs->kind == MLOD_VIEW_PARABOLOID) {
            rhs = xw + t;
            if (!(rhs > 0.0f && 256.0f * rhs * rhs >= d2)) return MLOD__UNSURE;
            lhs = twice;
        } else {
            lhs = twice;
            rhs = 1.0f;
        }
        if (lhs * fs->invalid > rhs) return MLOD_STATUS_COARSE;
        if (!(lhs * fs->valid <= rhs)) all_valid = 0;
    }
    return all_valid ? (uint8_t)MLOD_STATUS_DRAWN : (uint8_t)MLOD__UNSURE;
}

MLOD__PUBLIC mlod_result mlod_view_filter_of(const mlod_view *view, float epsilon, float *out, mlod_error *error)
{
    mlod__pview pv;
    mlod_result res;
    int s, j, k;
    if (!out) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "out is NULL");
    if (!(epsilon > 0.0f))
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "epsilon must be > 0 (got %g)", epsilon);
    res = mlod__view_prepare(view, &pv, error);
    if (res != MLOD_OK) return res;
    mlod__fast_prepare(&pv, epsilon);
    memset(out, 0, MLOD_FILTER_FLOATS * sizeof(float));
    if (!pv.fast.ok) return mlod__succeed(error);
    out[MLOD_FILTER_OK] = 1.0f;
    out[MLOD_FILTER_BACKFACES] = (float)pv.fast.backfaces;
    out[MLOD_FILTER_ORTHO] = (float)pv.fast.ortho;
    out[MLOD_FILTER_SUB_COUNT] = (float)pv.fast.sub_count;
    for (k = 0; k < 3; k++) out[MLOD_FILTER_EYE + k] = pv.fast.eye_f[k];
    out[MLOD_FILTER_FLOAT_EYE] = (float)pv.fast.float_eye;
    for (s = 0; s < pv.fast.sub_count; s++) {
        const mlod__fsub *fs = &pv.fast.subs[s];
        float *o = out + MLOD_FILTER_SUBS + s * MLOD_FILTER_SUB_STRIDE;
        o[MLOD_FILTER_S_KIND] = (float)fs->kind;
        o[MLOD_FILTER_S_PLANE_COUNT] = (float)fs->plane_count;
        o[MLOD_FILTER_S_VALID] = fs->valid;
        o[MLOD_FILTER_S_INVALID] = fs->invalid;
        for (k = 0; k < 3; k++) o[MLOD_FILTER_S_W + k] = fs->w[k];
        for (j = 0; j < fs->plane_count; j++) {
            float *plane = o + MLOD_FILTER_S_PLANES + j * MLOD_FILTER_PLANE_STRIDE;
            for (k = 0; k < 5; k++) plane[MLOD_FILTER_P_N + k] = fs->planes[j][k];
            plane[MLOD_FILTER_P_SLOPE] = fs->slope[j];
            plane[MLOD_FILTER_P_ERR] = fs->err[j];
        }
    }
    return mlod__succeed(error);
}

/* ------------------------------------------------ vector float filter -- */

/* A function the compiler must inline where it has a way to be told: the
   float filter's lanes, so that a caller holding a view whose counts are
   constants gets them unrolled (mlod__classify_list). */
#if defined(__GNUC__) || defined(__clang__)
#define MLOD__FORCE_INLINE static inline __attribute__((always_inline))
#elif defined(_MSC_VER)
#define MLOD__FORCE_INLINE static __forceinline
#else
#define MLOD__FORCE_INLINE static inline
#endif


/* ----------------------------------------------------------------- cut -- */

/* Working status of a list entry: 0 = not evaluated yet, else MLOD_STATUS_*.
   Outside lazy mode, COARSE marks an entry still to be split. */
#define MLOD__PENDING 0u
/* Lazy rounds of one call: this valid node's parent was found invalid; the
   views do not change within a call, so later rounds need not look again.
   Or-ed into the status between rounds, cleared by the last round. */
#define MLOD__PARENT_INVALID 8u
#define MLOD__STATUS_MASK 7u
/* A merge hint (never a list status): the parent is known invalid without
   an evaluation (an entry of the pair is unchanged, MLOD__STAMPED). */
#define MLOD__KNOWN_INVALID 5u
/* A segment (a run of one view's list handled by one task) holds at most
   this many input entries. */
#define MLOD__SEGMENT_INPUT 1024u
/* Scratch entries a round may spend on splits, shared among the entries to
   split (at least MLOD__MIN_SHARE each, at most MLOD__SEGMENT_GROWTH).
   Internal; tests/compile/matrix.sh builds the cut's tests with smaller
   ones, where small trees take every path of the planning. */
#ifndef MLOD__ROUND_BUDGET
#define MLOD__ROUND_BUDGET ((size_t)1 << 19)
#endif
#define MLOD__MIN_SHARE 16u
#ifndef MLOD__SEGMENT_GROWTH
#define MLOD__SEGMENT_GROWTH 8192u
#endif

typedef struct mlod__list {
    uint32_t *nodes;
    uint8_t *status;
    size_t capacity; /* entries */
    size_t *offset;  /* per view: first entry */
    uint32_t *count; /* per view: entries */
} mlod__list;

typedef struct mlod__view_stats {
    uint64_t evaluated, steps;
    uint32_t drawn, culled, oversize, coarse;
} mlod__view_stats;

typedef struct mlod__segment {
    uint32_t view;
    uint32_t in_count;
    size_t in_begin;
    size_t out_begin;
    uint32_t out_capacity;
    uint32_t out_count;
    uint8_t ends_unchanged; /* bit 0: the first output entry is an unchanged input entry (see
                               mlod__classify_input), bit 1: the last one is */
    uint8_t from_input;     /* every entry unchanged (mlod__all_unchanged): the output is the input,
                               which the join copies from the input list (no room in scratch) */
    uint32_t depth_room;    /* 0, or: an entry with more leaves below it than this is split at most
                               log2(depth_room) levels deep this round (mlod__depth_limit) */
    uint64_t evaluated, steps;
} mlod__segment;

/* The work buffers an update may grow, by index: the entries (nodes and
   statuses) of lists[0 .. 2], those of the scratch, the segments, the
   tasks.  One or two arrays of `capacity` elements, sizes[0] and sizes[1]
   bytes each (sizes[1] = 0: no second array). */
enum { MLOD__WORK_SCRATCH = 3, MLOD__WORK_SEGMENTS = 4, MLOD__WORK_TASKS = 5, MLOD__WORK_COUNT = 6 };
typedef struct mlod__work_buffer {
    void *first, *second;
    size_t capacity;
    size_t sizes[2];
} mlod__work_buffer;

/* The committed lists live in chunks, each the lists of a run of
   consecutive views (first .. first + views - 1), nodes then statuses in
   one allocation of `capacity` entries (none for capacity 0);
   lists[MLOD__COMMITTED].offset[v] is view v's first entry in its chunk
   and count[v] its entries.  An update goes through the views a window at a time: the
   views of a chunk, or, where the cut has no chunks, windows of about
   MLOD__WINDOW entries by the cuts computed so far (one view first, then
   at most as many views as those done, and MLOD__WINDOW_VIEWS; a chunk
   whose cuts shrank below MLOD__WINDOW / 4 entries first takes in the
   chunks after it, mlod__merge_chunks).  A window runs the
   rounds on a cut restricted to its views (mlod__window_enter), its work
   lists sized to it; its result goes back into its chunk where that fits
   (mlod__commit_window), in runs of about MLOD__WINDOW entries where the
   result holds more than twice that.  A window whose views are all
   skipped is not touched.  Internal; tests/compile/matrix.sh builds the
   cut's tests with a small one. */
#ifndef MLOD__WINDOW
#define MLOD__WINDOW ((size_t)1 << 18)
#endif
/* A window of a cut without chunks takes at most this many views (a
   round's scratch gives each of its views' roots a share). */
#define MLOD__WINDOW_VIEWS ((uint32_t)(MLOD__WINDOW / MLOD__MIN_SHARE))
#define MLOD__COMMITTED 2
typedef struct mlod__chunk {
    uint32_t first, views;
    uint32_t *nodes;
    size_t capacity;
} mlod__chunk;

struct mlod_cut {
    mlod_allocator allocator;
    uint32_t view_count;
    uint32_t tree_nodes; /* node count the committed lists belong to; 0: none */
    int committed;       /* which of lists[] holds the result: MLOD__COMMITTED (a window's
                            restriction reads it; its nodes and statuses are a chunk's) */
    mlod__list lists[3];
    mlod__chunk *chunks; /* chunk_count chunks in view order, covering every view, or none */
    uint32_t chunk_count, chunk_capacity;
    mlod__chunk *fresh; /* during an update: the chunks of the windows done */
    uint32_t fresh_capacity;
    int reserved; /* mlod_cut_reserve succeeded: the work buffers stay between updates */
    mlod__view_stats *stats[2]; /* [0] committed, [1] work */
    uint32_t *scratch_nodes;
    uint8_t *scratch_status;
    size_t scratch_capacity;
    mlod__segment *segments;
    size_t segment_capacity;
    uint32_t *tasks; /* first segment of each task, then the end */
    size_t task_capacity;
    uint32_t *view_segment; /* per view: first segment, then the end */
    uint8_t *view_done;     /* per view: nothing to split this round (copied as it is), or
                               MLOD__SKIPPED: not evaluated at all in this update */
    size_t *view_work;      /* planning, per view: entries to split, then its segments' scratch */
    /* What the committed lists were computed for, to skip the views that
       did not change (see mlod__skip_views).  Written only when an update
       succeeds, so a failed one leaves them as they were. */
    mlod_view *seen;            /* per view: the view of its committed list (when MLOD__SEEN) */
    uint8_t *known;             /* per view: MLOD__SEEN, MLOD__EXACT */
    const mlod_tree *seen_tree; /* the tree, by address, and the revision, arrays and epsilon it */
    uint64_t seen_revision;     /* had then; seen_tree NULL: none (tree_nodes is its node count) */
    const float *seen_spheres, *seen_cones;
    float seen_epsilon;
    uint64_t *version; /* per view: mlod_cut_view.version */
    uint64_t *basis;   /* per view: changes when an update's list is not the basic cut of the view
                          bytes, epsilon and tree (object, arrays) of the update before (a reset, a
                          failed update, another view, epsilon or tree, a lazy list that moved),
                          so that two lists of one basis are the basic cuts of one view (mlod_splat
                          patches tiles by it) */
    uint64_t *touched; /* per view: the serial of the last update that evaluated it (or of the
                          cut's creation or reset): a budget goes to the oldest first */
    uint64_t serial;   /* the last version given out */
    mlod__work_buffer kept[MLOD__WORK_COUNT]; /* during an update: what its growth replaced */
    uint8_t grown[MLOD__WORK_COUNT];          /* during an update: kept[i] holds buffer i's old arrays */
    size_t bytes;
};

/* cut->known[v]: seen[v] holds the view of the committed list (a view an
   update accepted, so a valid one); the committed list is the basic cut
   of seen[v] in seen_tree at seen_epsilon. */
#define MLOD__SEEN 1u
#define MLOD__EXACT 2u
/* For this update (set by mlod__skip_views): the view and epsilon are
   those of its exact committed list, and the tree is the same but was
   refitted since, with its record of changes kept (mlod_tree.changes): an
   entry whose node and parent no refit changed since keeps its status, and
   its parent stays invalid (mlod__unchanged). */
#define MLOD__STAMPED 4u
/* ... only where the last refit changed at most this share of the tree
   (mlod_tree.changes_share) */
#define MLOD__STAMPED_SHARE 0.5f
/* For this update, set by the first round's join of a MLOD__STAMPED view
   (mlod__join_view): its list differs from the committed one in what the
   splat draws (mlod__same_drawn). */
#define MLOD__DIFFERS 8u
/* Set by mlod__budget_views: the view is left out of a lazy update with
   a budget; its list stays as it is (not evaluated).  Kept after the
   update (mlod_cut_view.deferred) until the next one starts. */
#define MLOD__DEFERRED 16u
/* For this window (mlod__keep_in_place): a skipped view whose list the
   commit leaves where it is in its chunk, neither copied out nor back. */
#define MLOD__KEPT 32u
/* cut->view_done[v] for a view the update skips. */
#define MLOD__SKIPPED 2u

/* GLSL twin: status_valid */
static int mlod__is_valid(uint8_t status) { return status == MLOD_STATUS_DRAWN || status == MLOD_STATUS_CULLED; }

/* The status of an invalid node: a leaf is oversize. */
static uint8_t mlod__invalid_status(const mlod_tree *tree, uint32_t node)
{
    return (uint8_t)(node >= tree->leaf_count - 1 ? MLOD_STATUS_OVERSIZE : MLOD_STATUS_COARSE);
}

/* The status of a node-view by the definition (mlod__evaluate). */
static uint8_t mlod__classify_exact(const mlod__pview *pv, const mlod_tree *tree, uint32_t node, double epsilon)
{
    int culled;
    double c = mlod__evaluate(pv, tree->spheres + 4 * (size_t)node, mlod__cone_of(tree, node), &culled);
    if (culled) return MLOD_STATUS_CULLED;
    return c <= epsilon ? (uint8_t)MLOD_STATUS_DRAWN : mlod__invalid_status(tree, node);
}

/* The same status, by the float filter where pv has one and it is sure. */
/* GLSL twin: classify */
static inline uint8_t mlod__classify(const mlod__pview *pv, const mlod_tree *tree, uint32_t node, double epsilon)
{
    if (pv->fast.ok) {
        uint8_t st = mlod__fast_status(&pv->fast, tree->spheres + 4 * (size_t)node, mlod__cone_of(tree, node));
        if (st != MLOD__UNSURE) return st == MLOD_STATUS_COARSE ? mlod__invalid_status(tree, node) : st;
    }
    return mlod__classify_exact(pv, tree, node, epsilon);
}

typedef struct mlod__cut_job {
    const mlod_tree *tree;
    const mlod_view *views;
    double epsilon;
    int trust;  /* statuses of the input are current */
    int merge;  /* look for sibling pairs to merge */
    int lazy;   /* one step per entry */
    int last;   /* the call's last round: clear MLOD__PARENT_INVALID */
    uint32_t age; /* refits since the committed lists (low 32 bits), for MLOD__STAMPED views */
    uint64_t serial; /* the version a view gets whose view or drawn entries changed */
    int again;  /* a later pass of a budgeted update: the views skipped keep their counts */
    const mlod__list *in;
    mlod__list *out;
    const mlod__list *done_in; /* where the views done this round are copied from: in, or in
                                  the first round the committed list (skipped views: their
                                  counts only, until mlod__copy_skipped_task) */
    mlod_cut *cut;
} mlod__cut_job;

/* Output of one segment while it is produced. */
typedef struct mlod__emitter {
    uint32_t *nodes;
    uint8_t *status;
    uint32_t count, capacity;
} mlod__emitter;

static void mlod__emit(mlod__emitter *out, uint32_t node, uint8_t status)
{
    MANYLODS_ASSERT(out->count < out->capacity); /* the segment's room was planned for this */
    out->nodes[out->count] = node;
    out->status[out->count] = status;
    out->count++;
}

/* 1 when x (status xs, without lazy marks) is the right sibling of node
   `left`, both valid (left_valid: 1 when left is): their parent is worth a
   look.  Without branches, for the loops where pairs come and go
   unpredictably. */
static inline uint32_t mlod__valid_pair(uint32_t left, uint32_t left_valid, uint32_t x, uint8_t xs)
{
    return (uint32_t)mlod__is_valid(xs) & (x > 0) & ((x & 1u) == 0) & (left == x - 1) & left_valid;
}

/* Whether x (status xs) and the entry on top of the output (nodes, status,
   count entries) are valid siblings, x the right one (mlod__valid_pair):
   the usual answer, no sibling on top, first and with a branch, where the
   merges' loops meet it after a merge or at a segment's boundary. */
static inline int mlod__mergeable(const uint32_t *nodes, const uint8_t *status, uint32_t count, uint32_t x, uint8_t xs)
{
    return count > 0 && nodes[count - 1] == x - 1 &&
           mlod__valid_pair(nodes[count - 1], (uint32_t)mlod__is_valid(status[count - 1]), x, xs);
}

/* Merge x with its left sibling on top of the output while their parent
   is valid (the merge goes through the left child).  hint: the status of
   x's parent when the caller classified it already (mlod__merge_hints),
   else MLOD__PENDING.  Returns x's replacement and its status. */
MLOD__FORCE_INLINE uint32_t mlod__reduce(const mlod__cut_job *job, const mlod__pview *pv, uint32_t *nodes,
                                         uint8_t *status, uint32_t *count, uint32_t x, uint8_t *xs, uint8_t hint,
                                         uint64_t *evaluated, uint64_t *steps)
{
    while (mlod__mergeable(nodes, status, *count, x, *xs)) {
        uint32_t parent = (x - 1) / 2;
        uint8_t ps;
        if (hint == MLOD__KNOWN_INVALID) break;
        ps = hint != MLOD__PENDING ? hint : mlod__classify(pv, job->tree, parent, job->epsilon);
        hint = MLOD__PENDING; /* a merge's own parent is not hinted */
        ++*evaluated;
        if (!mlod__is_valid(ps)) break;
        --*count;
        x = parent;
        *xs = ps;
        ++*steps;
    }
    return x;
}

/* Entries split together in the depth-first search of mlod__refine_segment:
   up to this many coarse entries on top of its stack, their children
   classified in one call (independent loads and arithmetic for the
   processor, whole vectors for mlod__classify_list). */
#define MLOD__BATCH 32u
#define MLOD__STACK 1024u
/* Room for the padding of a batch of children (below): a vector's lanes. */
#define MLOD__BATCH_PAD 8u

/* The view shapes whose float filter the vector paths take with its
   counts as constants: one sub-projection, eye in floats, and either a
   paraboloid hemisphere (one plane: the views of virtual point lights) or
   a perspective frustum (six planes). */
enum { MLOD__SHAPE_OTHER, MLOD__SHAPE_PARABOLOID, MLOD__SHAPE_PERSPECTIVE };

/* Whether the vector paths track which nodes lie wholly inside every
   plane of fv's view (mlod__vstatus_known): one sub-projection of more
   than one plane (a frustum or a box; a paraboloid's one plane is not
   worth it); the scalar path ignores it. */
MLOD__FORCE_INLINE int mlod__known_planes(const mlod__fview *fv)
{
    return fv->sub_count == 1 && fv->subs[0].plane_count > 1;
}

/* The statuses of nodes[0 .. count - 1] into status[] (the float filter
   in vector lanes at the level in use, the exact path where it is
   unsure), and the statuses of the children of a batch of parents
   (below, with the vector lanes: VECTOR LANES at the end). */
static void mlod__classify_list(const mlod__pview *pv, const mlod_tree *tree, const uint32_t *nodes, uint32_t count,
                                double epsilon, uint8_t *status);
static void mlod__classify_children(const mlod__pview *pv, const mlod_tree *tree, uint32_t *parents, uint32_t count,
                                    double epsilon, uint8_t *status, uint8_t *known, uint8_t *inside);


/* Whether node x lies strictly below node a. */
static inline int mlod__below(uint32_t x, uint32_t a)
{
    uint32_t dx = mlod__depth_of(x), da = mlod__depth_of(a);
    return dx > da && ((x + 1u) >> (dx - da)) == a + 1u;
}

/* Whether a refit of the last `age` (the tree's record of changes) may
   have changed a node's entry in a basic cut or its disc: it changed the
   node's parent (the root: the root).  A refit that changes a node marks
   every node above it, so this takes the node's own changes too; a node
   whose parent did not change keeps its status and its parent's, so it
   is an entry of the basic cut before the refits exactly when it is one
   after (mlod__patch_task).  The entries of a list that are not suspect
   are those mlod__unchanged_run finds. */
static int mlod__suspect(const mlod_tree *tree, uint32_t age, uint32_t node)
{
    return (uint32_t)tree->revision - tree->changes[node ? (node - 1) / 2 : 0] < age;
}

/* Unchanged entries.  An entry of a MLOD__STAMPED view's list is
   unchanged when no refit of the last `age` changed its parent (the root
   entry: itself; mlod__suspect).  Changes mark every node above a changed
   one, so the nodes no refit changed are whole subtrees, and the entries
   below one of them are a run of the list (left to right): a run costs one
   climb to its highest unchanged node (through the top of the tree, which
   stays in cache) and a search for its end, rather than one look at a
   scattered record per entry.

   The highest node above x, a strict ancestor, that no refit of the last
   `age` changed, or MLOD__CHANGED when one changed x's parent (or x is
   the root). */
#define MLOD__CHANGED ((uint32_t)-1)
static uint32_t mlod__unchanged_top(const mlod_tree *tree, uint32_t age, uint32_t x)
{
    uint32_t top;
    if (x == 0 || mlod__suspect(tree, age, x)) return MLOD__CHANGED;
    top = (x - 1) / 2;
    while (top > 0 && !mlod__suspect(tree, age, top)) top = (top - 1) / 2;
    return top;
}

/* The end of the run of unchanged entries from nodes[k] (k < n): k when
   entry k is changed. */
static uint32_t mlod__unchanged_run(const mlod_tree *tree, uint32_t age, const uint32_t *nodes, uint32_t k, uint32_t n)
{
    uint32_t x = nodes[k], top = mlod__unchanged_top(tree, age, x), lo, hi;
    if (top == MLOD__CHANGED) return x == 0 && !mlod__suspect(tree, age, 0) ? k + 1 : k;
    /* the usual case, where a run is long, at once: the entries are not
       in cache, and each step of the search below loads one more line */
    if (mlod__below(nodes[n - 1], top)) return n;
    /* entries k .. k + lo - 1 lie below top, entry k + hi does not (or
       hi = n - k): the run ends between, found by doubling then halving */
    lo = 1;
    hi = 2;
    while (k + hi < n && mlod__below(nodes[k + hi], top)) {
        lo = hi + 1;
        hi *= 2;
    }
    if (k + hi > n) hi = n - k;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (mlod__below(nodes[k + mid], top))
            lo = mid + 1;
        else
            hi = mid;
    }
    return k + lo;
}

/* unchanged[k] for each of n consecutive entries of a view's list. */
static void mlod__unchanged_runs(const mlod_tree *tree, uint32_t age, const uint32_t *nodes, uint32_t n,
                                 uint8_t *unchanged)
{
    uint32_t k = 0;
    while (k < n) {
        uint32_t end = mlod__unchanged_run(tree, age, nodes, k, n);
        if (end == k) {
            unchanged[k++] = 0;
        } else {
            memset(unchanged + k, 1, end - k);
            k = end;
        }
    }
}

/* Whether each of the n consecutive entries of a view's list from
   nodes[0] is unchanged (mlod__unchanged_runs), run by run. */
static int mlod__all_unchanged(const mlod_tree *tree, uint32_t age, const uint32_t *nodes, uint32_t n)
{
    uint32_t k = 0;
    while (k < n) {
        uint32_t end = mlod__unchanged_run(tree, age, nodes, k, n);
        if (end == k) return 0;
        k = end;
    }
    return 1;
}

/* The end of the run of entries from k (< n) whose flag equals flags[k]. */
static inline uint32_t mlod__run_end(const uint8_t *flags, uint32_t k, uint32_t n)
{
    const void *other = memchr(flags + k, flags[k] ? 0 : 1, n - k);
    return other ? (uint32_t)((const uint8_t *)other - flags) : n;
}

/* The statuses of a segment's input entries into status[]: those whose
   status is not current (all, unless the job trusts the input; else the
   pending ones) classified, in vector lanes together, the others copied
   (with their lazy marks).  In the first round of a MLOD__STAMPED view,
   an entry whose node and parent no refit changed since the committed
   lists (job->age refits ago: their spheres and cones hold the bits they
   held then) keeps its committed status unevaluated, and unchanged[k] = 1
   says so (its parent, invalid in an exact cut, is still invalid); else
   unchanged[k] = 0.  The parent's record says it for both: a refit marks
   an internal node whenever it marks a child.  A node unchanged for 2^32
   refits or more may read as changed: only more work.  Returns how many
   were classified. */
static uint32_t mlod__classify_input(const mlod__cut_job *job, const mlod__segment *seg, const mlod__pview *pv,
                                     uint8_t *status, uint8_t *unchanged)
{
    const uint32_t *in_nodes = job->in->nodes + seg->in_begin;
    const uint8_t *in_status = job->in->status + seg->in_begin;
    uint32_t todo[MLOD__SEGMENT_INPUT], count = 0, k;
    uint8_t found[MLOD__SEGMENT_INPUT], kept[MLOD__SEGMENT_INPUT];
    MANYLODS_ASSERT(seg->in_count <= MLOD__SEGMENT_INPUT);
    memset(unchanged, 0, seg->in_count);
    if (!job->trust && !(job->cut->known[seg->view] & MLOD__STAMPED)) {
        mlod__classify_list(pv, job->tree, in_nodes, seg->in_count, job->epsilon, status);
        return seg->in_count;
    }
    if (!job->trust) { /* the committed lists hold no lazy marks: runs of
                          unchanged entries copied whole, the rest classified */
        uint32_t end;
        mlod__unchanged_runs(job->tree, job->age, in_nodes, seg->in_count, unchanged);
        for (k = 0; k < seg->in_count; k = end) {
            end = mlod__run_end(unchanged, k, seg->in_count);
            if (unchanged[k]) {
                memcpy(status + k, in_status + k, end - k);
                continue;
            }
            for (; k < end; k++) todo[count++] = in_nodes[k];
        }
        if (count) mlod__classify_list(pv, job->tree, todo, count, job->epsilon, found);
        for (k = 0, count = 0; k < seg->in_count; k = end) {
            end = mlod__run_end(unchanged, k, seg->in_count);
            if (!unchanged[k]) {
                memcpy(status + k, found + count, end - k);
                count += end - k;
            }
        }
        return count;
    }
    /* a later round: the pending entries classified, the others' statuses
       (with their lazy marks) stand */
    for (k = 0; k < seg->in_count; k++) kept[k] = (uint8_t)((in_status[k] & MLOD__STATUS_MASK) != MLOD__PENDING);
    for (k = 0; k < seg->in_count; k++) {
        todo[count] = in_nodes[k];
        count += !kept[k];
    }
    if (count) mlod__classify_list(pv, job->tree, todo, count, job->epsilon, found);
    for (k = 0, count = 0; k < seg->in_count; k++) status[k] = kept[k] ? in_status[k] : found[count++];
    return count;
}

/* The statuses of the parents a segment's merges will ask for first, in
   vector lanes together rather than one by one as the merges meet them:
   hint[k] for each input entry k that is a right child whose left sibling
   is entry k - 1, both valid (and the left one not marked
   MLOD__PARENT_INVALID), else MLOD__PENDING.  Such a pair's parent is
   evaluated exactly once by either mode's merge step, so the counts do
   not change; statuses (from mlod__classify_input) may carry lazy marks.
   Unchanged entries get MLOD__KNOWN_INVALID, unevaluated: a pair of them
   has an unchanged parent, still invalid. */
static void mlod__merge_hints(const mlod__cut_job *job, const mlod__segment *seg, const mlod__pview *pv,
                              const uint8_t *fresh, const uint8_t *unchanged, uint8_t *hint)
{
    const uint32_t *in_nodes = job->in->nodes + seg->in_begin;
    uint32_t parents[MLOD__SEGMENT_INPUT / 2 + 1], at[MLOD__SEGMENT_INPUT / 2 + 1], count = 0, k, n = seg->in_count;
    uint8_t found[MLOD__SEGMENT_INPUT / 2];
    uint32_t end;
    hint[0] = MLOD__PENDING;
    /* siblings share their parent, and so whether it changed: a pair is
       unchanged whole or not at all, and a run of unchanged entries is
       known at once */
    for (k = 0; k < n; k = end) {
        end = mlod__run_end(unchanged, k, n);
        if (unchanged[k]) {
            memset(hint + k, MLOD__KNOWN_INVALID, end - k);
            continue;
        }
        for (k = k > 0 ? k : 1; k < end; k++) { /* without branches: the pairs come and go unpredictably */
            uint32_t x = in_nodes[k];
            uint32_t pair = mlod__valid_pair(in_nodes[k - 1],
                                             (uint32_t)mlod__is_valid(fresh[k - 1] & MLOD__STATUS_MASK) &
                                                 !(fresh[k - 1] & MLOD__PARENT_INVALID),
                                             x, fresh[k] & MLOD__STATUS_MASK);
            hint[k] = MLOD__PENDING;
            parents[count] = (x - 1) / 2; /* pairs do not overlap: at most in_count / 2, and one slot to spare */
            at[count] = k;
            count += (uint32_t)pair;
        }
    }
    if (count == 0) return;
    mlod__classify_list(pv, job->tree, parents, count, job->epsilon, found);
    for (k = 0; k < count; k++) hint[at[k]] = found[k];
}

/* The depth below which the split of an input entry of the segment stops
   this round (MLOD__NO_LIMIT: none): where its room may not hold the cut
   below it, so few levels that the frontier fits the room (2^levels <=
   depth_room), rather than a depth-first search that fills the room on
   the left and leaves the nodes beside its path, each larger than the
   last, to the next rounds.  The frontier's nodes are alike in size, so
   the next round's shares fit them. */
#define MLOD__NO_LIMIT ((uint32_t)-1)
static uint32_t mlod__depth_limit(const mlod__segment *seg, const mlod_tree *tree, uint32_t node)
{
    if (!seg->depth_room || mlod__leaves_below(node, tree->leaf_count) <= seg->depth_room) return MLOD__NO_LIMIT;
    /* levels: floor(log2(depth_room)), the depth of node depth_room - 1 */
    return mlod__depth_of(node) + mlod__depth_of(seg->depth_room - 1);
}

/* The split of one coarse input entry (node, status st) of a segment down
   to the cut, into out, a depth-first search whose stack holds classified
   entries, the next one left to right on top; the run of coarse entries
   on top is split together.  remaining: the segment's input entries after
   it, whose room it keeps.  track (a constant in each copy): the stack
   keeps which nodes lie wholly inside every plane (mlod__vstatus_known),
   so that their children skip the plane tests. */
MLOD__FORCE_INLINE void mlod__split_down(const mlod__cut_job *job, const mlod__segment *seg, const mlod__pview *pv,
                                         mlod__emitter *out, uint32_t node, uint8_t st, uint32_t remaining, int track,
                                         uint64_t *evaluated, uint64_t *steps)
{
    const mlod_tree *tree = job->tree;
    uint32_t stack[MLOD__STACK], parents[MLOD__BATCH + MLOD__BATCH_PAD], top = 1, n, i;
    uint32_t limit = mlod__depth_limit(seg, tree, node);
    uint8_t stack_status[MLOD__STACK], children[2 * (MLOD__BATCH + MLOD__BATCH_PAD)];
    uint8_t stack_inside[MLOD__STACK], parent_inside[MLOD__BATCH + MLOD__BATCH_PAD];
    uint8_t child_inside[2 * (MLOD__BATCH + MLOD__BATCH_PAD)];
    stack[0] = node;
    stack_status[0] = st;
    stack_inside[0] = 0; /* an input entry: not known */
    while (top > 0) {
        if (stack_status[top - 1] != MLOD_STATUS_COARSE) {
            --top;
            mlod__emit(out, stack[top], stack_status[top]);
            continue;
        }
        /* the run of coarse entries on top, up to MLOD__BATCH of them,
           split together (their children's loads overlap) while the
           output still has room for every entry pending (a coarse entry
           without room waits for the next round) and the stack for the
           children */
        n = 0;
        while (n < MLOD__BATCH && n < top && stack_status[top - 1 - n] == MLOD_STATUS_COARSE &&
               out->count + top + n + 1 + remaining <= seg->out_capacity && top + n + 1 <= MLOD__STACK &&
               (limit == MLOD__NO_LIMIT || mlod__depth_of(stack[top - 1 - n]) < limit)) {
            parents[n] = stack[top - 1 - n];
            if (track) parent_inside[n] = stack_inside[top - 1 - n];
            n++;
        }
        if (n == 0) {
            --top;
            mlod__emit(out, stack[top], stack_status[top]);
            continue;
        }
        mlod__classify_children(pv, tree, parents, n, job->epsilon, children, track ? parent_inside : NULL,
                                track ? child_inside : NULL);
        top -= n;
        for (i = n; i-- > 0;) { /* a split entry becomes its right child with its left one above */
            stack[top] = 2 * parents[i] + 2;
            if (track) stack_inside[top] = child_inside[2 * i + 1];
            stack_status[top++] = children[2 * i + 1];
            stack[top] = 2 * parents[i] + 1;
            if (track) stack_inside[top] = child_inside[2 * i];
            stack_status[top++] = children[2 * i];
        }
        *evaluated += 2 * n;
        *steps += n;
    }
}

/* Basic and incremental rounds: split invalid nodes down to the cut within
   the segment's capacity (and mlod__depth_limit, mlod__split_down), merge
   valid sibling pairs. */
static void mlod__refine_segment(const mlod__cut_job *job, mlod__segment *seg, const mlod__pview *pv)
{
    const uint32_t *in_nodes = job->in->nodes + seg->in_begin;
    mlod__emitter out;
    uint32_t k;
    uint8_t fresh[MLOD__SEGMENT_INPUT], hint[MLOD__SEGMENT_INPUT], unchanged[MLOD__SEGMENT_INPUT];
    /* the nodes wholly inside every plane, where the vector filter tracks them */
    const int track = pv->fast.ok && mlod__known_planes(&pv->fast);
    uint64_t evaluated = 0, steps = 0; /* locals: neighbouring segments are other threads' */
    /* the entry on top of the output, kept in registers rather than read
       back from where it was just stored (UINT32_MAX: none) */
    uint32_t top_node = UINT32_MAX, top_valid = 0;
    out.nodes = job->cut->scratch_nodes + seg->out_begin;
    out.status = job->cut->scratch_status + seg->out_begin;
    out.count = 0;
    out.capacity = seg->out_capacity;
    evaluated += mlod__classify_input(job, seg, pv, fresh, unchanged);
    if (job->merge) mlod__merge_hints(job, seg, pv, fresh, unchanged, hint);
    /* an unchanged entry is never split, nor merged: the first and last
       input entries, unchanged, are the first and last output entries */
    seg->ends_unchanged = (uint8_t)(seg->in_count ? (unchanged[0] ? 1u : 0u) | (unchanged[seg->in_count - 1] ? 2u : 0u) : 0u);
    for (k = 0; k < seg->in_count; k++) {
        uint32_t node = in_nodes[k], remaining = seg->in_count - 1 - k;
        uint8_t st = fresh[k];
        if (unchanged[k]) {
            /* a run of unchanged entries: none splits or merges, nor
               merges with the output before it (its first entry's left
               sibling, unchanged too, is in the run or before the
               segment), so the run is copied */
            uint32_t end = mlod__run_end(unchanged, k, seg->in_count);
            MANYLODS_ASSERT(out.count + (end - k) <= out.capacity);
            memcpy(out.nodes + out.count, in_nodes + k, (end - k) * sizeof(uint32_t));
            memcpy(out.status + out.count, fresh + k, end - k);
            out.count += end - k;
            k = end - 1;
            top_node = in_nodes[k];
            top_valid = (uint32_t)mlod__is_valid(fresh[k]);
            continue;
        }
        if (st != MLOD_STATUS_COARSE) {
            if (job->merge) {
                /* whether x and the output's top are valid siblings, and
                   whether their parent may be valid, without branches:
                   pairs come and go unpredictably, merges are rare */
                uint8_t h = hint[k];
                uint32_t pair = mlod__valid_pair(top_node, top_valid, node, st);
                if (pair & ((h == MLOD__PENDING) | (uint32_t)mlod__is_valid(h)))
                    node = mlod__reduce(job, pv, out.nodes, out.status, &out.count, node, &st, h, &evaluated,
                                        &steps);
                else /* the parent is invalid: mlod__reduce would stop at once, counting the hint's evaluation */
                    evaluated += pair & (h != MLOD__PENDING) & (h != MLOD__KNOWN_INVALID);
            }
            mlod__emit(&out, node, st);
            top_node = node;
            top_valid = (uint32_t)mlod__is_valid(st);
        } else {
            if (track)
                mlod__split_down(job, seg, pv, &out, node, st, remaining, 1, &evaluated, &steps);
            else
                mlod__split_down(job, seg, pv, &out, node, st, remaining, 0, &evaluated, &steps);
            top_node = out.nodes[out.count - 1]; /* a split emits at least one entry */
            top_valid = (uint32_t)mlod__is_valid(out.status[out.count - 1]);
        }
    }
    seg->out_count = out.count;
    seg->evaluated = evaluated;
    seg->steps = steps;
}

/* Lazy rounds: at most one split or merge per entry. */
static void mlod__lazy_segment(const mlod__cut_job *job, mlod__segment *seg, const mlod__pview *pv)
{
    const mlod_tree *tree = job->tree;
    size_t view_begin = job->in->offset[seg->view], view_end = view_begin + job->in->count[seg->view];
    mlod__emitter out;
    uint32_t k;
    uint64_t evaluated = 0, steps = 0; /* locals: neighbouring segments are other threads' */
    out.nodes = job->cut->scratch_nodes + seg->out_begin;
    out.status = job->cut->scratch_status + seg->out_begin;
    out.count = 0;
    out.capacity = seg->out_capacity;
    uint8_t fresh[MLOD__SEGMENT_INPUT], hint[MLOD__SEGMENT_INPUT], split[2 * MLOD__SEGMENT_INPUT];
    uint8_t unchanged[MLOD__SEGMENT_INPUT];
    uint32_t children[2 * MLOD__SEGMENT_INPUT], splits = 0;
    evaluated += mlod__classify_input(job, seg, pv, fresh, unchanged);
    mlod__merge_hints(job, seg, pv, fresh, unchanged, hint);
    for (k = 0; k < seg->in_count; k++) /* the children of the entries to split, classified together */
        if ((fresh[k] & MLOD__STATUS_MASK) == MLOD_STATUS_COARSE) {
            children[splits++] = 2 * job->in->nodes[seg->in_begin + k] + 1;
            children[splits++] = 2 * job->in->nodes[seg->in_begin + k] + 2;
        }
    if (splits) mlod__classify_list(pv, tree, children, splits, job->epsilon, split);
    splits = 0;
    for (k = 0; k < seg->in_count; k++) {
        size_t at = seg->in_begin + k;
        uint32_t node = job->in->nodes[at];
        uint8_t raw = fresh[k], st = raw & MLOD__STATUS_MASK;
        if (st == MLOD_STATUS_COARSE) {
            mlod__emit(&out, 2 * node + 1, split[splits++]);
            mlod__emit(&out, 2 * node + 2, split[splits++]);
            evaluated += 2;
            steps++;
            continue;
        }
        if (mlod__is_valid(st) && node > 0) {
            uint32_t parent = (node - 1) / 2;
            int left = (node & 1u) != 0;
            /* a left child merges with its right sibling; a right child at
               the start of a segment defers to its left sibling before it;
               a parent found invalid this call stays invalid (the left
               child carries the mark) */
            if (left ? (!(raw & MLOD__PARENT_INVALID) && at + 1 < view_end && job->in->nodes[at + 1] == node + 1)
                     : (k == 0 && at > view_begin && job->in->nodes[at - 1] == node - 1 &&
                        !(job->trust && (job->in->status[at - 1] & MLOD__PARENT_INVALID)))) {
                /* an unchanged entry's parent is still invalid */
                uint8_t ps = unchanged[k]                                                     ? MLOD__KNOWN_INVALID
                             : left && k + 1 < seg->in_count && hint[k + 1] != MLOD__PENDING ? hint[k + 1]
                                                                                             : mlod__classify(pv, tree, parent, job->epsilon);
                evaluated += ps != MLOD__KNOWN_INVALID;
                if (mlod__is_valid(ps)) {
                    if (left) {
                        mlod__emit(&out, parent, ps);
                        steps++;
                        k++;
                    }
                    continue;
                }
                if (left) raw |= MLOD__PARENT_INVALID;
            }
        }
        mlod__emit(&out, node, raw);
    }
    seg->out_count = out.count;
    seg->evaluated = evaluated;
    seg->steps = steps;
}

static void mlod__segment_task(void *context, uint32_t index)
{
    const mlod__cut_job *job = (const mlod__cut_job *)context;
    mlod_cut *cut = job->cut;
    uint32_t s, prepared = (uint32_t)-1;
    mlod__pview pv;
    for (s = cut->tasks[index]; s < cut->tasks[index + 1]; s++) {
        mlod__segment *seg = &cut->segments[s];
        if (seg->from_input) continue; /* the join copies it */
        if (seg->view != prepared) {
            mlod__view_prepare(&job->views[seg->view], &pv, NULL);
            mlod__fast_prepare(&pv, job->epsilon);
            prepared = seg->view;
        }
        if (job->lazy)
            mlod__lazy_segment(job, seg, &pv);
        else
            mlod__refine_segment(job, seg, &pv);
    }
}

/* Whether entries a and b (count each) draw the same nodes in the same
   order: equal nodes, and equal in which are culled (lazy marks aside). */
static int mlod__same_drawn(const uint32_t *a_nodes, const uint8_t *a_status, const uint32_t *b_nodes,
                            const uint8_t *b_status, uint32_t count)
{
    uint32_t i;
    if (count && memcmp(a_nodes, b_nodes, count * sizeof(uint32_t)) != 0) return 0;
    if (count && memcmp(a_status, b_status, count) == 0) return 1; /* the usual case, at once */
    for (i = 0; i < count; i++)
        if (((a_status[i] & MLOD__STATUS_MASK) == MLOD_STATUS_CULLED) !=
            ((b_status[i] & MLOD__STATUS_MASK) == MLOD_STATUS_CULLED))
            return 0;
    return 1;
}

/* Adds how many of status[0 .. count) are drawn, culled and oversize
   (their lazy marks aside) to by_status[MLOD_STATUS_DRAWN ..
   MLOD_STATUS_OVERSIZE], after clearing the marks where unmark is set
   (the last round of a lazy update): eight at a time, without branches
   (the statuses alternate unpredictably).  A byte of t = w ^ (s * ones) is zero exactly
   where w's byte is s; ~(((t & low) + low) | t | low) holds 0x80 in those
   bytes and nothing else (no carry crosses a byte), so each byte of the
   running sum counts one position, emptied before it can pass 255. */
typedef char mlod__statuses_in_a_row[MLOD_STATUS_CULLED == MLOD_STATUS_DRAWN + 1 &&
                                     MLOD_STATUS_OVERSIZE == MLOD_STATUS_DRAWN + 2 ? 1 : -1];
static void mlod__count_statuses(uint8_t *status, uint32_t count, int unmark, uint32_t *by_status)
{
    const uint64_t ones = 0x0101010101010101u, low = 0x7f7f7f7f7f7f7f7fu;
    uint64_t sums[3] = {0, 0, 0};
    uint32_t i = 0, s;
    if (unmark)
        for (i = 0; i < count; i++) status[i] &= MLOD__STATUS_MASK;
    i = 0;
    while (i + 8 <= count) {
        uint64_t part[3] = {0, 0, 0};
        uint32_t end = count - i >= 8 * 255u ? i + 8 * 255u : i + ((count - i) & ~7u);
        for (; i < end; i += 8) {
            uint64_t w;
            memcpy(&w, status + i, 8);
            w &= ones * MLOD__STATUS_MASK;
            for (s = 0; s < 3; s++) {
                uint64_t t = w ^ (ones * (MLOD_STATUS_DRAWN + s));
                part[s] += ~(((t & low) + low) | t | low) >> 7;
            }
        }
        for (s = 0; s < 3; s++) /* the bytes' sum: pairs, then fours, then all */
        {
            uint64_t x = (part[s] & 0x00ff00ff00ff00ffu) + ((part[s] >> 8) & 0x00ff00ff00ff00ffu);
            x = (x & 0x0000ffff0000ffffu) + ((x >> 16) & 0x0000ffff0000ffffu);
            sums[s] += (x & 0xffffffffu) + (x >> 32);
        }
    }
    for (; i < count; i++) {
        uint32_t st = status[i] & MLOD__STATUS_MASK;
        for (s = 0; s < 3; s++) sums[s] += st == MLOD_STATUS_DRAWN + s;
    }
    for (s = 0; s < 3; s++) by_status[MLOD_STATUS_DRAWN + s] += (uint32_t)sums[s];
}

/* Concatenate one view's segment outputs into the output list, merging
   sibling pairs that meet at segment boundaries, and count (a finished
   view: copy its list). */
static void mlod__join_view(const mlod__cut_job *job, uint32_t view, const mlod__pview *pv)
{
    mlod_cut *cut = job->cut;
    mlod__view_stats *stats = &cut->stats[1][view];
    uint32_t *nodes = job->out->nodes + job->out->offset[view], count = 0, s, i;
    uint8_t *status = job->out->status + job->out->offset[view];
    uint64_t evaluated, steps;
    int left_unchanged = 0; /* the entry on top of the output is an unchanged input entry */
    /* The first round over a stamped view's committed list: the segments
       copied from the input (from_input) stay as they are (no merge
       reaches an unchanged entry), so the counts are the committed list's
       less its other segments' input plus their output, and the list
       differs exactly where one of those segments or a merge between
       them changed something.  counted: the output before it is counted
       (or copied from the input). */
    const int stamped = (cut->known[view] & MLOD__STAMPED) && job->in == &cut->lists[cut->committed];
    const int unmark = job->lazy && job->last; /* only lazy rounds leave marks (the input holds none) */
    uint32_t counted = 0, differs = 0, was[MLOD__STATUS_MASK + 1], now[MLOD__STATUS_MASK + 1];
    memset(was, 0, sizeof was);
    memset(now, 0, sizeof now);
    if (cut->view_done[view]) { /* nothing to split this round: copied as it is, its counts stand */
        const mlod__list *in = job->done_in;
        count = in->count[view];
        if (cut->view_done[view] != MLOD__SKIPPED) { /* a skipped view's list is copied once, at the end */
            memcpy(nodes, in->nodes + in->offset[view], count * sizeof(uint32_t));
            memcpy(status, in->status + in->offset[view], count);
        }
        job->out->count[view] = count;
        return;
    }
    /* later rounds add to the first round's counts; summed in locals, as
       the neighbouring views' counts are other threads' */
    evaluated = job->trust ? stats->evaluated : 0;
    steps = job->trust ? stats->steps : 0;
    for (s = cut->view_segment[view]; s < cut->view_segment[view + 1]; s++) {
        const mlod__segment *seg = &cut->segments[s];
        const uint32_t *src = seg->from_input ? job->in->nodes + seg->in_begin : cut->scratch_nodes + seg->out_begin;
        const uint8_t *src_status =
            seg->from_input ? job->in->status + seg->in_begin : cut->scratch_status + seg->out_begin;
        if (stamped && !seg->from_input) {
            const uint32_t *in_nodes = job->in->nodes + seg->in_begin;
            uint8_t *in_status = job->in->status + seg->in_begin;
            mlod__count_statuses(in_status, seg->in_count, 0, was);
            differs |= seg->out_count != seg->in_count ||
                       !mlod__same_drawn(src, src_status, in_nodes, in_status, seg->out_count);
        }
        if (seg->from_input) /* (stamped) the output before it stays as it is */
            mlod__count_statuses(status + counted, count - counted, unmark, now);
        i = 0;
        if (job->merge && count > 0) {
            for (; i < seg->out_count; i++) {
                /* a pair across the boundary with an unchanged entry: its
                   parent is still invalid */
                uint8_t xs = src_status[i], hint = i == 0 && ((seg->ends_unchanged & 1u) || left_unchanged)
                                                       ? (uint8_t)MLOD__KNOWN_INVALID
                                                       : (uint8_t)MLOD__PENDING;
                uint32_t x = mlod__reduce(job, pv, nodes, status, &count, src[i], &xs, hint, &evaluated, &steps);
                nodes[count] = x;
                status[count] = xs;
                count++;
                if (x == src[i]) { /* unchanged: the rest was reduced already */
                    i++;
                    break;
                }
                differs = 1; /* a merge across the boundary */
            }
        }
        memcpy(nodes + count, src + i, (seg->out_count - i) * sizeof(uint32_t));
        memcpy(status + count, src_status + i, seg->out_count - i);
        count += seg->out_count - i;
        if (seg->from_input) counted = count;
        left_unchanged = (seg->ends_unchanged & 2u) && seg->out_count > 0 && nodes[count - 1] == src[seg->out_count - 1];
        evaluated += seg->evaluated;
        steps += seg->steps;
    }
    stats->evaluated = evaluated;
    stats->steps = steps;
    job->out->count[view] = count;
    /* what is not counted yet (a view not stamped: all of it); a stamped
       view's counts start from the committed list's, less was */
    mlod__count_statuses(status + counted, count - counted, unmark, now);
    if (stamped) {
        const mlod__view_stats *old = &cut->stats[0][view];
        now[MLOD_STATUS_DRAWN] += old->drawn - was[MLOD_STATUS_DRAWN];
        now[MLOD_STATUS_CULLED] += old->culled - was[MLOD_STATUS_CULLED];
        now[MLOD_STATUS_OVERSIZE] += old->oversize - was[MLOD_STATUS_OVERSIZE];
        cut->known[view] = (uint8_t)((cut->known[view] & ~MLOD__DIFFERS) | (differs ? MLOD__DIFFERS : 0u));
    }
    stats->drawn = now[MLOD_STATUS_DRAWN];
    stats->culled = now[MLOD_STATUS_CULLED];
    stats->oversize = now[MLOD_STATUS_OVERSIZE];
    stats->coarse = count - stats->drawn - stats->culled - stats->oversize;
}

/* Per-view work of a cut (joining, planning) runs MLOD__VIEW_CHUNK views a
   task: mlod__view_chunks tasks; task `index` takes views first .. *end - 1. */
#define MLOD__VIEW_CHUNK 16u
static uint32_t mlod__view_chunks(const mlod_cut *cut) { return (cut->view_count - 1) / MLOD__VIEW_CHUNK + 1; }

static uint32_t mlod__view_chunk(const mlod_cut *cut, uint32_t index, uint32_t *end)
{
    uint32_t first = index * MLOD__VIEW_CHUNK;
    *end = (uint64_t)first + MLOD__VIEW_CHUNK > cut->view_count ? cut->view_count : first + MLOD__VIEW_CHUNK;
    return first;
}

/* After the last round: the skipped views' lists, from the committed list
   (which no round writes) into the room every round kept for them. */
static void mlod__copy_skipped_task(void *context, uint32_t index)
{
    const mlod__cut_job *job = (const mlod__cut_job *)context;
    const mlod__list *from = job->done_in;
    uint32_t end, v = mlod__view_chunk(job->cut, index, &end);
    for (; v < end; v++) {
        uint32_t count = job->out->count[v];
        if (job->cut->view_done[v] != MLOD__SKIPPED || (job->cut->known[v] & MLOD__KEPT)) continue;
        MANYLODS_ASSERT(count == from->count[v]); /* every round kept the room of its list */
        memcpy(job->out->nodes + job->out->offset[v], from->nodes + from->offset[v], count * sizeof(uint32_t));
        memcpy(job->out->status + job->out->offset[v], from->status + from->offset[v], count);
    }
}

/* After the last round, before the commit (job->out the new lists,
   job->done_in the committed ones, cut->seen their views): a view
   evaluated in this update gets the new version (job->serial) when its
   view bytes or its drawn entries differ from the committed list's
   (node indices alone, whatever the tree: the atlas asks the tree; a
   reset left no entries). */
static void mlod__version_task(void *context, uint32_t index)
{
    const mlod__cut_job *job = (const mlod__cut_job *)context;
    mlod_cut *cut = job->cut;
    const mlod__list *old = job->done_in, *now = job->out;
    uint32_t end, v = mlod__view_chunk(cut, index, &end);
    for (; v < end; v++) {
        uint32_t count = now->count[v];
        if (cut->view_done[v] == MLOD__SKIPPED) continue;
        if (cut->known[v] & MLOD__STAMPED) { /* the join compared what could differ */
            if (cut->known[v] & MLOD__DIFFERS) cut->version[v] = job->serial;
            continue;
        }
        if ((cut->known[v] & MLOD__SEEN) &&
            memcmp(&job->views[v], &cut->seen[v], sizeof(mlod_view)) == 0 && old->count[v] == count &&
            mlod__same_drawn(now->nodes + now->offset[v], now->status + now->offset[v], old->nodes + old->offset[v],
                             old->status + old->offset[v], count))
            continue;
        cut->version[v] = job->serial;
    }
}

static void mlod__join_task(void *context, uint32_t index)
{
    const mlod__cut_job *job = (const mlod__cut_job *)context;
    uint32_t end, v = mlod__view_chunk(job->cut, index, &end);
    mlod__pview pv;
    for (; v < end; v++) {
        if (job->merge && !job->cut->view_done[v]) {
            mlod__view_prepare(&job->views[v], &pv, NULL);
            mlod__fast_prepare(&pv, job->epsilon);
        }
        mlod__join_view(job, v, &pv);
    }
}

static mlod__work_buffer mlod__work_get(const mlod_cut *cut, int which)
{
    mlod__work_buffer b;
    b.second = NULL;
    b.sizes[1] = 0;
    if (which < MLOD__WORK_SCRATCH) {
        b.first = cut->lists[which].nodes;
        b.second = cut->lists[which].status;
        b.capacity = cut->lists[which].capacity;
        b.sizes[0] = sizeof(uint32_t);
        b.sizes[1] = sizeof(uint8_t);
    } else if (which == MLOD__WORK_SCRATCH) {
        b.first = cut->scratch_nodes;
        b.second = cut->scratch_status;
        b.capacity = cut->scratch_capacity;
        b.sizes[0] = sizeof(uint32_t);
        b.sizes[1] = sizeof(uint8_t);
    } else if (which == MLOD__WORK_SEGMENTS) {
        b.first = cut->segments;
        b.capacity = cut->segment_capacity;
        b.sizes[0] = sizeof(mlod__segment);
    } else {
        b.first = cut->tasks;
        b.capacity = cut->task_capacity;
        b.sizes[0] = sizeof(uint32_t);
    }
    return b;
}

static void mlod__work_set(mlod_cut *cut, int which, const mlod__work_buffer *b)
{
    if (which < MLOD__WORK_SCRATCH) {
        cut->lists[which].nodes = (uint32_t *)b->first;
        cut->lists[which].status = (uint8_t *)b->second;
        cut->lists[which].capacity = b->capacity;
    } else if (which == MLOD__WORK_SCRATCH) {
        cut->scratch_nodes = (uint32_t *)b->first;
        cut->scratch_status = (uint8_t *)b->second;
        cut->scratch_capacity = b->capacity;
    } else if (which == MLOD__WORK_SEGMENTS) {
        cut->segments = (mlod__segment *)b->first;
        cut->segment_capacity = b->capacity;
    } else {
        cut->tasks = (uint32_t *)b->first;
        cut->task_capacity = b->capacity;
    }
}

static void mlod__work_free(mlod_cut *cut, const mlod__work_buffer *b)
{
    mlod__free(&cut->allocator, b->first);
    mlod__free(&cut->allocator, b->second);
    cut->bytes -= b->capacity * (b->sizes[0] + b->sizes[1]);
}

/* Grow work buffer `which` to hold `need` elements (contents are not
   kept), an eighth more when `spare` is set and the allocator gives it.
   The arrays the update began with are kept, not freed, until
   mlod__work_end: a failed update puts them back and leaves the cut's
   memory as it found it.  Returns 0 when out of memory, with the buffer as
   it was. */
static int mlod__work_grow(mlod_cut *cut, int which, size_t need, int spare)
{
    mlod__work_buffer old = mlod__work_get(cut, which), b = old;
    int attempt;
    if (need <= old.capacity) return 1;
    for (attempt = 0; attempt < 2; attempt++) {
        b.capacity = spare && attempt == 0 && need + need / 8 > need ? need + need / 8 : need;
        b.first = mlod__alloc_array(&cut->allocator, b.capacity, b.sizes[0], NULL);
        b.second = b.first && b.sizes[1] ? mlod__alloc_array(&cut->allocator, b.capacity, b.sizes[1], NULL) : NULL;
        if (b.first && (b.second || !b.sizes[1])) break;
        mlod__free(&cut->allocator, b.first);
        b.first = NULL;
    }
    if (!b.first) return 0;
    if (cut->grown[which]) {
        mlod__work_free(cut, &old); /* grown earlier in this update */
    } else {
        cut->kept[which] = old;
        cut->grown[which] = 1;
    }
    cut->bytes += b.capacity * (b.sizes[0] + b.sizes[1]);
    mlod__work_set(cut, which, &b);
    return 1;
}

static int mlod__work_reserve(mlod_cut *cut, int which, size_t need) { return mlod__work_grow(cut, which, need, 1); }

/* End an update: on success free the arrays its growth replaced; on
   failure free what it grew and put those arrays back. */
static void mlod__work_end(mlod_cut *cut, int success)
{
    int which;
    for (which = 0; which < MLOD__WORK_COUNT; which++) {
        mlod__work_buffer now;
        if (!cut->grown[which]) continue;
        cut->grown[which] = 0;
        if (success) {
            mlod__work_free(cut, &cut->kept[which]);
            continue;
        }
        now = mlod__work_get(cut, which);
        mlod__work_free(cut, &now);
        mlod__work_set(cut, which, &cut->kept[which]);
    }
}

/* The bytes of a chunk of `capacity` entries. */
static size_t mlod__chunk_bytes(size_t capacity) { return capacity * (sizeof(uint32_t) + 1); }

static void mlod__chunk_free(mlod_cut *cut, mlod__chunk *c)
{
    if (!c->nodes) return;
    mlod__free(&cut->allocator, c->nodes);
    cut->bytes -= mlod__chunk_bytes(c->capacity);
    c->nodes = NULL;
    c->capacity = 0;
}

/* Free every chunk's entries (cut->chunks and, during an update, the
   fresh ones) and forget them: the cut has no chunks. */
static void mlod__chunks_drop(mlod_cut *cut, uint32_t fresh_count)
{
    uint32_t i;
    for (i = 0; i < cut->chunk_count; i++) mlod__chunk_free(cut, &cut->chunks[i]);
    for (i = 0; i < fresh_count; i++) mlod__chunk_free(cut, &cut->fresh[i]);
    cut->chunk_count = 0;
}

/* Give back the buffers an update works in. */
static void mlod__work_release(mlod_cut *cut)
{
    int which;
    for (which = 0; which < MLOD__WORK_COUNT; which++) {
        mlod__work_buffer b = mlod__work_get(cut, which);
        mlod__work_free(cut, &b);
        b.first = b.second = NULL;
        b.capacity = 0;
        mlod__work_set(cut, which, &b);
    }
}

/* Give back all a cut holds beyond what mlod_cut_create gave it: its
   chunks (the fresh ones, fresh_count, too) and work buffers. */
static void mlod__cut_release(mlod_cut *cut, uint32_t fresh_count)
{
    mlod__chunks_drop(cut, fresh_count);
    mlod__free(&cut->allocator, cut->chunks);
    mlod__free(&cut->allocator, cut->fresh);
    cut->bytes -= ((size_t)cut->chunk_capacity + cut->fresh_capacity) * sizeof(mlod__chunk);
    cut->chunks = cut->fresh = NULL;
    cut->chunk_capacity = cut->fresh_capacity = 0;
    mlod__work_release(cut);
    cut->reserved = 0;
}

MLOD__PUBLIC void mlod_cut_destroy(mlod_cut *cut)
{
    int i;
    if (!cut) return;
    mlod__cut_release(cut, 0);
    for (i = 0; i < 3; i++) {
        mlod__free(&cut->allocator, cut->lists[i].offset);
        mlod__free(&cut->allocator, cut->lists[i].count);
    }
    mlod__free(&cut->allocator, cut->stats[0]);
    mlod__free(&cut->allocator, cut->stats[1]);
    mlod__free(&cut->allocator, cut->view_segment);
    mlod__free(&cut->allocator, cut->view_done);
    mlod__free(&cut->allocator, cut->view_work);
    mlod__free(&cut->allocator, cut->seen);
    mlod__free(&cut->allocator, cut->known);
    mlod__free(&cut->allocator, cut->version);
    mlod__free(&cut->allocator, cut->basis);
    mlod__free(&cut->allocator, cut->touched);
    cut->allocator.free(cut->allocator.user, cut);
}

/* A new version for every view (a created or reset cut). */
static void mlod__new_versions(mlod_cut *cut)
{
    uint32_t v;
    cut->serial++;
    for (v = 0; v < cut->view_count; v++) cut->version[v] = cut->basis[v] = cut->touched[v] = cut->serial;
}

MLOD__PUBLIC mlod_result mlod_cut_create(uint32_t view_count, const mlod_allocator *allocator, mlod_cut **out_cut,
                                         mlod_error *error)
{
    mlod_allocator a = mlod__allocator(allocator);
    mlod_cut *cut;
    int i, ok = 1;
    if (!out_cut) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "out_cut is NULL");
    *out_cut = NULL;
    if (view_count == 0) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "view_count is 0");
    if (view_count == (uint32_t)-1) return mlod__fail(error, MLOD_ERROR_OVERFLOW, "view_count is too large");
    cut = (mlod_cut *)a.alloc(a.user, sizeof(mlod_cut));
    if (!cut) return mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "out of memory creating a cut");
    memset(cut, 0, sizeof *cut);
    cut->allocator = a;
    cut->view_count = view_count;
    cut->committed = MLOD__COMMITTED;
    cut->bytes = sizeof *cut;
    for (i = 0; i < 3; i++) {
        ok = ok && (cut->lists[i].offset = (size_t *)mlod__alloc_array(&a, view_count, sizeof(size_t), &cut->bytes));
        ok = ok && (cut->lists[i].count = (uint32_t *)mlod__alloc_array(&a, view_count, sizeof(uint32_t), &cut->bytes));
    }
    for (i = 0; i < 2; i++)
        ok = ok && (cut->stats[i] = (mlod__view_stats *)mlod__alloc_array(&a, view_count, sizeof(mlod__view_stats), &cut->bytes));
    ok = ok && (cut->view_segment = (uint32_t *)mlod__alloc_array(&a, (size_t)view_count + 1, sizeof(uint32_t), &cut->bytes));
    ok = ok && (cut->view_done = (uint8_t *)mlod__alloc_array(&a, view_count, 1, &cut->bytes));
    ok = ok && (cut->view_work = (size_t *)mlod__alloc_array(&a, view_count, sizeof(size_t), &cut->bytes));
    ok = ok && (cut->seen = (mlod_view *)mlod__alloc_array(&a, view_count, sizeof(mlod_view), &cut->bytes));
    ok = ok && (cut->known = (uint8_t *)mlod__alloc_array(&a, view_count, 1, &cut->bytes));
    ok = ok && (cut->version = (uint64_t *)mlod__alloc_array(&a, view_count, sizeof(uint64_t), &cut->bytes));
    ok = ok && (cut->basis = (uint64_t *)mlod__alloc_array(&a, view_count, sizeof(uint64_t), &cut->bytes));
    ok = ok && (cut->touched = (uint64_t *)mlod__alloc_array(&a, view_count, sizeof(uint64_t), &cut->bytes));
    if (!ok) {
        mlod_cut_destroy(cut);
        return mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "out of memory creating a cut for %u views", view_count);
    }
    for (i = 0; i < 3; i++) {
        memset(cut->lists[i].offset, 0, view_count * sizeof(size_t));
        memset(cut->lists[i].count, 0, view_count * sizeof(uint32_t));
    }
    memset(cut->stats[0], 0, view_count * sizeof(mlod__view_stats));
    memset(cut->known, 0, view_count);
    cut->serial = mlod__first_revision(); /* unique in the process, as a tree's revision */
    mlod__new_versions(cut);
    *out_cut = cut;
    return mlod__succeed(error);
}

MLOD__PUBLIC void mlod_cut_reset(mlod_cut *cut)
{
    uint32_t v;
    if (!cut) return;
    cut->tree_nodes = 0;
    cut->seen_tree = NULL; /* nothing skipped: the views stay known to be valid */
    memset(cut->lists[cut->committed].count, 0, cut->view_count * sizeof(uint32_t));
    memset(cut->stats[0], 0, cut->view_count * sizeof(mlod__view_stats));
    for (v = 0; v < cut->view_count; v++) cut->known[v] &= (uint8_t)~(MLOD__DEFERRED | MLOD__KEPT);
    mlod__new_versions(cut);
}

MLOD__PUBLIC uint32_t mlod_cut_view_count(const mlod_cut *cut) { return cut ? cut->view_count : 0; }

MLOD__PUBLIC size_t mlod_cut_bytes(const mlod_cut *cut) { return cut ? cut->bytes : 0; }

MLOD__PUBLIC mlod_cut_view mlod_cut_get(const mlod_cut *cut, uint32_t view)
{
    mlod_cut_view r;
    memset(&r, 0, sizeof r);
    if (cut && view < cut->view_count) {
        const mlod__list *list = &cut->lists[cut->committed];
        const mlod__view_stats *s = &cut->stats[0][view];
        r.count = list->count[view];
        if (r.count) { /* its chunk: the last that starts at or before it */
            uint32_t lo = 0, hi = cut->chunk_count;
            const mlod__chunk *c;
            while (hi - lo > 1) {
                uint32_t mid = lo + (hi - lo) / 2;
                if (cut->chunks[mid].first <= view) lo = mid; else hi = mid;
            }
            c = &cut->chunks[lo];
            r.nodes = c->nodes + list->offset[view];
            r.status = (const uint8_t *)(c->nodes + c->capacity) + list->offset[view];
        }
        r.drawn = s->drawn;
        r.culled = s->culled;
        r.oversize = s->oversize;
        r.coarse = s->coarse;
        r.evaluated = s->evaluated;
        r.steps = s->steps;
        r.splatted = s->drawn + s->oversize + s->coarse;
        r.deferred = (cut->known[view] & MLOD__DEFERRED) != 0;
        r.version = cut->version[view];
    }
    return r;
}

/* What mlod_cut_bound counts, for views whose cuts average at most
   mean_cut_nodes: the capacity, in elements, of each work buffer
   (MLOD__WORK_*; none for the committed lists), the entries of the chunks
   (*committed), and the bytes of the per-view arrays a cut holds from its
   creation with two chunk records per view (their most).  Doubles: the
   caller checks the range.  The work buffers serve one window at a time,
   of at most 2 MLOD__WINDOW entries (mlod__commit_window) and
   MLOD__WINDOW_VIEWS views.  A round's scratch holds its input and the room of its splits.
   A first round splits the roots with a share of the round's budget each
   (at least MLOD__MIN_SHARE, at most MLOD__SEGMENT_GROWTH), plus, for a
   basic cut, 1.25 times each view's previous cut and MLOD__MIN_SHARE; an
   incremental one reads the previous cuts with a quarter more and
   MLOD__MIN_SHARE per segment; later rounds give their splits max(budget,
   input) in all (the leaves below each, or rooms from the previous cut,
   where those fit it, else equal shares; see mlod__plan_round; a wide
   view's roots take less in the first round, see mlod__root_room); a
   lazy round at most doubles its input.  Segments: one per view, per
   MLOD__SEGMENT_INPUT / 4 entries, per MLOD__SEGMENT_GROWTH entries of
   the budget's room.  Each buffer with the eighth it grows by; chunks
   with at most an eighth to spare, and a window's new chunk while it
   replaces the old one. */
static double mlod__cut_capacities(uint32_t view_count, uint32_t mean_cut_nodes, double capacity[MLOD__WORK_COUNT],
                                   double *committed)
{
    double v = view_count, total = v * mean_cut_nodes, most = total > v ? total : v;
    double window = most < 2.0 * MLOD__WINDOW ? most : 2.0 * MLOD__WINDOW;
    double wv = v < window ? v : window, wt = total < window ? total : window;
    if (wv > MLOD__WINDOW_VIEWS) wv = MLOD__WINDOW_VIEWS;
    double budget = (double)MLOD__ROUND_BUDGET;
    double roots, first, later, segments;
    roots = MLOD__MIN_SHARE * wv > budget ? MLOD__MIN_SHARE * wv : budget;
    if (roots > MLOD__SEGMENT_GROWTH * wv) roots = MLOD__SEGMENT_GROWTH * wv;
    first = wv + roots + 1.25 * wt + MLOD__MIN_SHARE * (wv + wt / 64);
    later = window + (budget > window ? budget : window);
    segments = wv + wt / (MLOD__SEGMENT_INPUT / 4) + budget / MLOD__SEGMENT_GROWTH;
    capacity[0] = capacity[1] = ceil(1.125 * window);
    capacity[MLOD__COMMITTED] = 0.0;
    capacity[MLOD__WORK_SCRATCH] = ceil(1.125 * (first > later ? first : later));
    capacity[MLOD__WORK_SEGMENTS] = ceil(1.125 * segments);
    capacity[MLOD__WORK_TASKS] = capacity[MLOD__WORK_SEGMENTS] + 1.0;
    *committed = floor(1.125 * total + 1.0625 * window);
    return (double)sizeof(mlod_cut) + 4.0 * (v + 1) +
           v * (3 * (sizeof(size_t) + sizeof(uint32_t)) + 2 * sizeof(mlod__view_stats) + 1 + sizeof(size_t) +
                sizeof(mlod_view) + 1 + 3 * sizeof(uint64_t) /* version, basis, touched */ +
                2 * sizeof(uint64_t) /* a budget's order, during an update */ + 2 * sizeof(mlod__chunk));
}

MLOD__PUBLIC size_t mlod_cut_bound(uint32_t view_count, uint32_t mean_cut_nodes)
{
    double capacity[MLOD__WORK_COUNT], bytes, committed;
    mlod_cut empty;
    int i;
    if (view_count == 0) return 0;
    memset(&empty, 0, sizeof empty);
    bytes = mlod__cut_capacities(view_count, mean_cut_nodes, capacity, &committed);
    for (i = 0; i < MLOD__WORK_COUNT; i++) {
        mlod__work_buffer b = mlod__work_get(&empty, i);
        bytes += capacity[i] * (double)(b.sizes[0] + b.sizes[1]);
    }
    bytes += committed * (double)mlod__chunk_bytes(1);
    return bytes >= (double)(size_t)-1 ? (size_t)-1 : (size_t)bytes;
}

MLOD__PUBLIC mlod_result mlod_cut_reserve(mlod_cut *cut, uint32_t mean_cut_nodes, mlod_error *error)
{
    double capacity[MLOD__WORK_COUNT], committed;
    int i, ok = 1;
    if (!cut) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "cut is NULL");
    if (mlod_cut_bound(cut->view_count, mean_cut_nodes) == (size_t)-1)
        return mlod__fail(error, MLOD_ERROR_OVERFLOW, "a cut of %u views of %u nodes each does not fit in memory",
                          cut->view_count, mean_cut_nodes);
    mlod__cut_capacities(cut->view_count, mean_cut_nodes, capacity, &committed);
    for (i = 0; i < MLOD__WORK_COUNT && ok; i++)
        if (i != MLOD__COMMITTED) ok = mlod__work_grow(cut, i, (size_t)capacity[i], 0);
    mlod__work_end(cut, ok);
    if (ok) cut->reserved = 1;
    return ok ? mlod__succeed(error)
              : mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "out of memory reserving the cut of %u views",
                           cut->view_count);
}

/* Does this entry still have to be split (or evaluated first)? */
static int mlod__to_split(uint8_t status, int lazy, int trust)
{
    return !lazy && (status == MLOD__PENDING || (trust && status == MLOD_STATUS_COARSE));
}

/* Whether none of the 8 statuses at p is to split (mlod__to_split, not
   lazy): no byte is PENDING, nor COARSE when trusted.  A byte is zero
   somewhere in w exactly when (w - 0x01..01) & ~w & 0x80..80 is not zero
   (a borrow can only start at a zero byte). */
static int mlod__none_to_split8(const uint8_t *p, int trust)
{
    const uint64_t ones = 0x0101010101010101ull, highs = 0x8080808080808080ull;
    uint64_t w, c;
    memcpy(&w, p, 8);
    if ((w - ones) & ~w & highs) return 0;
    c = w ^ (ones * MLOD_STATUS_COARSE);
    return !trust || !((c - ones) & ~c & highs);
}

/* The first entry at or after `at`, before `end`, to be split in a round
   that is not lazy (mlod__to_split), else end: runs of 8 statuses with
   nothing to split are passed over at once. */
static size_t mlod__next_to_split(const uint8_t *status, size_t at, size_t end, int trust)
{
    while (at + 8 <= end && mlod__none_to_split8(status + at, trust)) at += 8;
    while (at < end && !mlod__to_split(status[at], 0, trust)) at++;
    return at;
}

/* Leaf order.  A node's key, (node + 1) * 2^(deepest - depth), orders
   the nodes of a cut as their leaves (the order of the lists), and the
   nodes below it (itself included) are those whose keys lie in
   [key, key + 2^(deepest - depth)); deepest: the depth of the last node. */
static uint64_t mlod__order_key(uint32_t node, uint32_t deepest)
{
    return ((uint64_t)node + 1) << (deepest - mlod__depth_of(node));
}

/* The first of the cut entries nodes[at .. end - 1] whose key is key or
   more, else end: a galloping search forward from at. */
static size_t mlod__gallop(const uint32_t *nodes, size_t at, size_t end, uint64_t key, uint32_t deepest)
{
    size_t lo = at, hi, step = 1;
    if (at >= end || mlod__order_key(nodes[at], deepest) >= key) return at;
    /* key(nodes[lo]) < key; hi: end, or an entry whose key is key or more */
    while (lo + step < end && mlod__order_key(nodes[lo + step], deepest) < key) {
        lo += step;
        step *= 2;
    }
    hi = lo + step < end ? lo + step : end;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (mlod__order_key(nodes[mid], deepest) < key)
            lo = mid;
        else
            hi = mid;
    }
    return hi;
}

/* The entries of a split's room, walked along one view's entries to split
   in list order: from the view's previous cut (prev, the committed list of
   the same tree) where the round takes those, else `unit`; never more than
   the leaves below the entry, which bound its cut (the room is then sure
   to hold it). */
typedef struct mlod__room_walk {
    const uint32_t *prev; /* NULL: the share */
    size_t prev_count, cursor;
    size_t unit;
    uint32_t leaf_count, deepest;
} mlod__room_walk;

static size_t mlod__split_room(mlod__room_walk *w, uint32_t node)
{
    size_t room = w->unit, leaves = mlod__leaves_below(node, w->leaf_count);
    if (w->prev) {
        /* the previous cut's entries below node, a quarter more; 1 where
           one entry held it; the next entry to split comes after them */
        uint64_t key = mlod__order_key(node, w->deepest);
        uint64_t span = (uint64_t)1 << (w->deepest - mlod__depth_of(node));
        size_t first = mlod__gallop(w->prev, w->cursor, w->prev_count, key, w->deepest);
        size_t past = mlod__gallop(w->prev, first, w->prev_count, key + span, w->deepest);
        size_t held = past > first ? past - first : 1;
        w->cursor = past;
        room = held + held / 4 + MLOD__MIN_SHARE;
    }
    return room < leaves ? room : leaves;
}

/* The next segment of a view's list from `at`: its length, and in *grow
   the entries its splits may add (mlod__split_room).  A segment closes at
   MLOD__SEGMENT_INPUT entries, or once its splits may produce
   MLOD__SEGMENT_GROWTH entries, so that big expansions spread over many
   tasks.  scan: look for entries to split (not in lazy rounds, which
   split nothing by plan, nor in an exact committed list, which holds
   none). */
static uint32_t mlod__segment_length(const mlod__list *in, size_t at, size_t end, int scan, int trust,
                                     mlod__room_walk *w, size_t *grow)
{
    size_t limit = end - at < MLOD__SEGMENT_INPUT ? end : at + MLOD__SEGMENT_INPUT, next = at, g = 0;
    if (scan)
        while (g < MLOD__SEGMENT_GROWTH) {
            next = mlod__next_to_split(in->status, next, limit, trust);
            if (next == limit) break;
            g += mlod__split_room(w, in->nodes[next]);
            next++; /* the segment ends after this split if its growth is spent */
        }
    *grow = g;
    return (uint32_t)(g < MLOD__SEGMENT_GROWTH ? limit - at : next - at);
}

/* Output room of a segment: lazy steps at most double it; splits may add
   `grow` entries in all; entries of unknown status (the first round from a
   previous cut) get a quarter more. */
static size_t mlod__segment_room(uint32_t n, size_t grow, int lazy, int trust)
{
    if (lazy) return 2 * (size_t)n;
    if (grow) return n + grow;
    return trust ? n : n + n / 4 + MLOD__MIN_SHARE;
}

/* The split room of a view's root in the first round of a cut from the
   root: what its previous cut held, a quarter more, so that the cut is
   found in one round where the views moved little (at least the round's
   share, at most MLOD__ROOT_ROOM entries).  Every later round reads and
   writes every unfinished view's whole list, so a view whose cut does not
   fit pays for it again: the room is not held to MLOD__SEGMENT_GROWTH
   (the room's 1024 views of 13.6 k nodes took four rounds when it was).
   The scratch this takes is 1.25 times the previous cut's.
   But a root's split is one task: a view whose room is more than
   MLOD__SEGMENT_GROWTH and more than 1 / MLOD__WIDE_SHARE of all the
   roots' rooms (one large view beside few or none) is split only
   MLOD__SEGMENT_GROWTH entries wide in the first round, and its entries
   in the next one with rooms sized to hold the cut below each (the
   leaves below, or the previous cut's entries: mlod__plan_round): two
   rounds, the second in many tasks.  Where those rooms do not fit (wide
   views of a few million nodes side by side), the next rounds share the
   budget: more rounds, each in many tasks. */
#define MLOD__WIDE_SHARE 16u
#define MLOD__ROOT_ROOM ((size_t)1 << 26)
static size_t mlod__root_room(size_t unit, uint32_t previous)
{
    size_t room = (size_t)previous + previous / 4 + MLOD__MIN_SHARE;
    if (room > MLOD__ROOT_ROOM) room = MLOD__ROOT_ROOM;
    return room > unit ? room : unit;
}

/* Planning a round, a chunk of views per task: three passes over every
   entry of the input (the entries to split; the segments; their layout),
   run in parallel, with sums over views in between. */
typedef struct mlod__plan_job {
    mlod_cut *cut;
    const mlod__list *in;
    int lazy, trust;
    const uint32_t *hint; /* see mlod__plan_round */
    const mlod__list *prev; /* rooms from the previous cut (mlod__split_room), else NULL */
    uint32_t leaf_count, deepest; /* the tree's, and the depth of its last node */
    size_t unit;
    size_t wide; /* the first round from the roots: root rooms above this are MLOD__SEGMENT_GROWTH */
    int fill;    /* segments pass: 0 counts, 1 writes */
    int committed; /* the input is the committed lists (the first round of an update from them) */
    const mlod_tree *tree;
    uint32_t age; /* for the MLOD__STAMPED views (mlod__cut_job.age); 0: no segment is copied
                     from the input (from_input) */
} mlod__plan_job;

/* Whether this round reads view v's exact committed list (a basic cut:
   no entry to split). */
static int mlod__plan_exact(const mlod__plan_job *job, uint32_t v)
{
    return job->committed && (job->cut->known[v] & MLOD__EXACT);
}

/* The room walk of view v's splits in this round, and the depth room of
   its segments (mlod__segment): the share where the rooms may not hold
   the cuts below them, 0 where they were sized to. */
static mlod__room_walk mlod__plan_walk(const mlod__plan_job *job, uint32_t v, uint32_t *depth_room)
{
    mlod__room_walk w;
    w.prev = NULL;
    w.prev_count = w.cursor = 0;
    w.unit = job->unit;
    w.leaf_count = job->leaf_count;
    w.deepest = job->deepest;
    /* only where a split has a segment's room to itself: where many share
       a segment, its search finishes many small cuts in one pooled room,
       and in long runs of coarse nodes that it classifies together */
    *depth_room = job->unit >= MLOD__SEGMENT_GROWTH ? (uint32_t)job->unit : 0;
    if (job->prev) {
        w.prev = job->prev->nodes + job->prev->offset[v];
        w.prev_count = job->prev->count[v];
        *depth_room = 0;
    } else if (job->hint) {
        w.unit = mlod__root_room(job->unit, job->hint[v]);
        *depth_room = 0;
        if (w.unit > job->wide) *depth_room = (uint32_t)(w.unit = MLOD__SEGMENT_GROWTH);
    }
    return w;
}

/* Pass 1: each view's entries to split (view_work), whether it is done,
   and the leaves below its entries to split (view_segment: a partition's,
   at most the leaf count); with rooms from the previous cut (job->prev),
   only the sum of those rooms (view_segment, at most the leaves). */
static void mlod__plan_splits_task(void *context, uint32_t index)
{
    const mlod__plan_job *job = (const mlod__plan_job *)context;
    mlod_cut *cut = job->cut;
    uint32_t end, v = mlod__view_chunk(cut, index, &end);
    for (; v < end; v++) {
        size_t at = job->in->offset[v], stop = at + job->in->count[v], view_splits = 0, sum = 0;
        uint32_t depth_room;
        mlod__room_walk w = mlod__plan_walk(job, v, &depth_room);
        if (cut->view_done[v] == MLOD__SKIPPED) { /* in every round of the update */
            cut->view_work[v] = 0;
            cut->view_segment[v] = 0;
            continue;
        }
        if (!job->lazy && !mlod__plan_exact(job, v)) /* an exact list has none */
            while ((at = mlod__next_to_split(job->in->status, at, stop, job->trust)) < stop) {
                view_splits++;
                sum += w.prev ? mlod__split_room(&w, job->in->nodes[at])
                              : mlod__leaves_below(job->in->nodes[at], job->leaf_count);
                at++;
            }
        cut->view_segment[v] = (uint32_t)sum;
        if (w.prev) continue;
        cut->view_work[v] = view_splits;
        /* later basic and incremental rounds leave finished views alone */
        cut->view_done[v] = (uint8_t)(job->trust && !job->lazy && view_splits == 0);
    }
}

/* Walk view v's segments: count them and their scratch (fill = 0), or
   write them from segment view_segment[v] and scratch entry view_work[v]. */
static void mlod__plan_view(const mlod__plan_job *job, uint32_t v)
{
    int fill = job->fill;
    mlod_cut *cut = job->cut;
    size_t at = job->in->offset[v], end = cut->view_done[v] ? at : at + job->in->count[v];
    size_t s = fill ? cut->view_segment[v] : 0, capacity = fill ? cut->view_work[v] : 0;
    uint32_t depth_room;
    mlod__room_walk w = mlod__plan_walk(job, v, &depth_room);
    const int exact = mlod__plan_exact(job, v);
    const int stamped = job->committed && job->age && (cut->known[v] & MLOD__STAMPED);
    while (at < end) {
        size_t grow;
        uint32_t n = mlod__segment_length(job->in, at, end, !job->lazy && !exact, job->trust, &w, &grow);
        int copy = stamped && mlod__all_unchanged(job->tree, job->age, job->in->nodes + at, n);
        size_t room = copy ? 0 : mlod__segment_room(n, grow, job->lazy, job->trust);
        if (fill) {
            mlod__segment *seg = &cut->segments[s];
            seg->view = v;
            seg->from_input = (uint8_t)copy;
            seg->in_begin = at;
            seg->in_count = n;
            seg->out_begin = capacity;
            seg->out_capacity = (uint32_t)room;
            seg->out_count = copy ? n : 0;       /* a copied segment's output is its input, */
            seg->ends_unchanged = copy ? 3u : 0u; /* unchanged at both ends */
            seg->depth_room = depth_room;
            seg->evaluated = seg->steps = 0;
        }
        capacity += room;
        at += n;
        s++;
    }
    if (!fill) {
        cut->view_segment[v] = (uint32_t)(s < (uint32_t)-1 ? s : (uint32_t)-1);
        cut->view_work[v] = capacity;
    }
}

/* Pass 2 (fill 0): each view's segment count (view_segment) and scratch
   (view_work); pass 3 (fill 1): its segments, once those are prefix sums. */
static void mlod__plan_segments_task(void *context, uint32_t index)
{
    const mlod__plan_job *job = (const mlod__plan_job *)context;
    uint32_t end, v = mlod__view_chunk(job->cut, index, &end);
    for (; v < end; v++) mlod__plan_view(job, v);
}

/* Cut the input lists into segments and the segments into tasks, place
   every segment's output in scratch.  hint: the previous cut's count per
   view when this round splits the roots, else NULL; prev: in the later
   rounds of a cut from the roots, the previous cut of the same tree, else
   NULL.  Returns 0 when out of memory (or too many segments). */
static int mlod__plan_round(mlod_cut *cut, const mlod__list *in, int lazy, int trust, const uint32_t *hint,
                            const mlod__list *prev, const mlod_tree *tree, uint32_t age,
                            const mlod_parallel *parallel, uint32_t *task_count)
{
    const uint32_t leaf_count = tree->leaf_count;
    mlod__plan_job job;
    size_t total = 0, to_split = 0, leaves = 0, rooms = 0, segments = 0, capacity = 0, work = 0, s, budget;
    uint32_t v, tasks = 0, chunks = mlod__view_chunks(cut);
    job.cut = cut;
    job.in = in;
    job.lazy = lazy;
    job.trust = trust;
    job.hint = hint;
    job.prev = NULL;
    job.leaf_count = leaf_count;
    job.deepest = mlod__depth_of(2 * (uint64_t)leaf_count - 2);
    job.committed = in == &cut->lists[cut->committed];
    job.tree = tree;
    job.age = age;
    job.unit = 0;
    job.wide = (size_t)-1;
    job.fill = 0;
    mlod__run(parallel, chunks, mlod__plan_splits_task, &job);
    for (v = 0; v < cut->view_count; v++) {
        total += in->count[v];
        to_split += cut->view_work[v];
        leaves += cut->view_segment[v];
    }
    /* the entries to split share a budget of scratch, at least the input:
       where the leaves below them fit it, each split's room is its leaves
       (sure to hold its cut) up to a segment's growth; else rooms from the
       previous cut where those fit it; else equal shares */
    budget = MLOD__ROUND_BUDGET > total ? MLOD__ROUND_BUDGET : total;
    if (to_split && leaves <= budget) {
        job.unit = MLOD__SEGMENT_GROWTH;
    } else if (to_split) {
        if (prev && !lazy) {
            /* the previous cuts hold P entries: rooms from them may take
               P + max(budget, P) less the input, so that the round's
               scratch stays within what mlod_cut_bound counts for a later
               round of cuts of P entries (its input and max(budget, it)) */
            size_t held = 0, cap;
            for (v = 0; v < cut->view_count; v++) held += prev->count[v];
            cap = held + (MLOD__ROUND_BUDGET > held ? MLOD__ROUND_BUDGET : held);
            cap = cap > total + budget ? cap - total : budget;
            job.prev = prev;
            mlod__run(parallel, chunks, mlod__plan_splits_task, &job);
            for (v = 0; v < cut->view_count; v++) rooms += cut->view_segment[v];
            if (rooms > cap) job.prev = NULL;
        }
        job.unit = budget / to_split;
        if (job.unit < MLOD__MIN_SHARE) job.unit = MLOD__MIN_SHARE;
        if (job.unit > MLOD__SEGMENT_GROWTH) job.unit = MLOD__SEGMENT_GROWTH;
    }
    if (hint) { /* the wide views (see mlod__root_room) */
        double all = 0.0;
        for (v = 0; v < cut->view_count; v++)
            if (cut->view_done[v] != MLOD__SKIPPED) all += (double)mlod__root_room(job.unit, hint[v]);
        job.wide = all / MLOD__WIDE_SHARE > MLOD__SEGMENT_GROWTH ? (size_t)(all / MLOD__WIDE_SHARE)
                                                                : (size_t)MLOD__SEGMENT_GROWTH;
    }
    mlod__run(parallel, chunks, mlod__plan_segments_task, &job);
    for (v = 0; v < cut->view_count; v++) { /* counts to first segments and scratch entries */
        size_t n = cut->view_segment[v], room = cut->view_work[v];
        if (n >= (uint32_t)-1 - segments) return 0;
        cut->view_segment[v] = (uint32_t)segments;
        cut->view_work[v] = capacity;
        segments += n;
        capacity += room;
    }
    cut->view_segment[cut->view_count] = (uint32_t)segments;
    if (!mlod__work_reserve(cut, MLOD__WORK_SEGMENTS, segments) ||
        !mlod__work_reserve(cut, MLOD__WORK_TASKS, segments + 1))
        return 0;
    job.fill = 1;
    mlod__run(parallel, chunks, mlod__plan_segments_task, &job);
    for (s = 0; s < segments; s++) { /* tasks: consecutive segments worth about one segment of work */
        if (work == 0) cut->tasks[tasks++] = (uint32_t)s;
        work += cut->segments[s].out_capacity;
        if (work >= MLOD__SEGMENT_INPUT) work = 0;
    }
    cut->tasks[tasks] = (uint32_t)segments;
    *task_count = tasks;
    return mlod__work_reserve(cut, MLOD__WORK_SCRATCH, capacity);
}

/* Lay out the output list: each view gets room for all its segments'
   output, a view done this round for its list in done_in.  Returns 0 when
   out of memory. */
static int mlod__place_output(mlod_cut *cut, const mlod__list *done_in, mlod__list *out)
{
    size_t at = 0;
    uint32_t v, s;
    for (v = 0; v < cut->view_count; v++) {
        out->offset[v] = at;
        if (cut->view_done[v]) at += done_in->count[v];
        for (s = cut->view_segment[v]; s < cut->view_segment[v + 1]; s++) at += cut->segments[s].out_count;
    }
    return mlod__work_reserve(cut, (int)(out - cut->lists), at);
}

MLOD__PUBLIC mlod_result mlod_cut_params_check(const mlod_cut_params *params, mlod_error *error)
{
    if (!params) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "params is NULL");
    if ((unsigned)params->mode > (unsigned)MLOD_CUT_LAZY)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "unknown cut mode %d", (int)params->mode);
    if (!(params->epsilon > 0.0f))
        return mlod__fail(error, MLOD_ERROR_BAD_EPSILON, "epsilon %g must be > 0 (pixels)", params->epsilon);
    if (params->mode == MLOD_CUT_LAZY && params->lazy_steps == 0)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "lazy mode needs lazy_steps >= 1");
    if (params->mode != MLOD_CUT_LAZY && params->budget != 0)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "a budget (%llu node-views) needs lazy mode",
                          (unsigned long long)params->budget);
    return mlod__succeed(error);
}

/* The checks of an update.  A view byte for byte equal to the one an
   earlier update accepted for it (cut->seen) is valid: validity depends on
   the bytes alone.  view_done[v] is left 1 for those views, else 0. */
static mlod_result mlod__check_cut_params(mlod_cut *cut, const mlod_tree *tree, const mlod_view *views,
                                          const mlod_cut_params *params, mlod_error *error)
{
    uint32_t v;
    mlod_result res;
    if (!cut || !tree || !views || !params)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "cut, tree, views and params must not be NULL");
    if ((res = mlod_cut_params_check(params, error)) != MLOD_OK) return res;
    if (tree->node_count == 0 || !tree->spheres)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "the tree is empty");
    for (v = 0; v < cut->view_count; v++) {
        mlod__pview pv;
        mlod_error detail;
        mlod_result res;
        /* equal bytes are equal fields (padding, if any, can only make
           equal views differ: they are then checked and computed) */
        cut->view_done[v] =
            (uint8_t)((cut->known[v] & MLOD__SEEN) && memcmp(&views[v], &cut->seen[v], sizeof(mlod_view)) == 0);
        if (cut->view_done[v]) continue;
        res = mlod__view_prepare(&views[v], &pv, &detail);
        if (res != MLOD_OK) return mlod__fail(error, res, "view %u: %.160s", v, detail.message);
    }
    return MLOD_OK;
}

/* The refits of a tree since its revision `since` (1 .. 2^32 - 1) where its
   record of changes (mlod_tree.changes) tells which nodes they changed;
   else 0 (none since, or no such record). */
static uint32_t mlod__record_age(const mlod_tree *tree, uint64_t since)
{
    uint64_t refits = tree->revision - since;
    return tree->changes && tree->changes_revision == tree->revision && refits < ((uint64_t)1 << 32)
               ? (uint32_t)refits
               : 0u;
}

/* Which views this update skips, after mlod__check_cut_params: those whose
   view (every byte), tree (the same object, revision and arrays) and
   epsilon are those of the committed list, when that list is exact (the
   basic cut).  An update of such a view would give the same list: basic
   and incremental updates give the basic cut, and a lazy update makes no
   move on it (it is a partition of valid nodes and oversize leaves with
   no sibling pair under a valid parent).  Sets view_done[v] to
   MLOD__SKIPPED for them and 0 for the others; returns their count.
   Where the tree was refitted since (fewer than 2^32 times) and kept its
   record of changes, an incremental or lazy update marks those views
   MLOD__STAMPED instead, and *age = the refits since. */
static uint32_t mlod__skip_views(mlod_cut *cut, const mlod_tree *tree, const mlod_cut_params *params, uint32_t *age)
{
    uint32_t v, skipped = 0;
    int same_tree = cut->seen_tree == tree && cut->tree_nodes == tree->node_count &&
                    cut->seen_spheres == tree->spheres && cut->seen_cones == tree->cones &&
                    cut->seen_epsilon == params->epsilon;
    int same = same_tree && cut->seen_revision == tree->revision;
    uint32_t refits = mlod__record_age(tree, cut->seen_revision);
    /* where the last refit changed most of the tree, looking at the record
       costs more than it saves (an evaluation costs several record loads;
       the object protocol twisting all over: 40 -> 45 ms per update) */
    int stamped = same_tree && params->mode != MLOD_CUT_BASIC && refits > 0 &&
                  tree->changes_share <= MLOD__STAMPED_SHARE;
    *age = stamped ? refits : 0;
    for (v = 0; v < cut->view_count; v++) {
        /* coarse == 0 follows from MLOD__EXACT; tested again, as the
           rounds end only once no view holds a coarse entry */
        int exact = cut->view_done[v] && (cut->known[v] & MLOD__EXACT) && cut->stats[0][v].coarse == 0;
        int skip = same && exact;
        cut->view_done[v] = (uint8_t)(skip ? MLOD__SKIPPED : 0);
        cut->known[v] = (uint8_t)((cut->known[v] & ~(MLOD__STAMPED | MLOD__DEFERRED)) |
                                  (stamped && exact ? MLOD__STAMPED : 0u));
        skipped += (uint32_t)skip;
    }
    return skipped;
}

/* The most node-views a lazy update of lazy_steps rounds evaluates for a
   view whose list holds n entries: a round evaluates at most 3 per entry
   of its input (the entry, or its parent where it pairs with a sibling,
   or the two children it splits into; an entry is classified at most once
   and either splits or pairs) and at most doubles the entries, so rounds
   1 .. q evaluate at most 3 n (1 + 2 + ... + 2^(q-1)) = 3 n (2^q - 1).
   UINT64_MAX where that does not fit. */
static uint64_t mlod__lazy_bound(uint32_t n, uint32_t lazy_steps)
{
    uint64_t rounds = lazy_steps >= 40 ? UINT64_MAX : ((uint64_t)1 << lazy_steps) - 1;
    uint64_t per = 3 * (uint64_t)n;
    return rounds > UINT64_MAX / (per ? per : 1) ? UINT64_MAX : rounds * per;
}

/* A budget (mlod_cut_params.budget) for a lazy update from the previous
   lists of this tree: of the views to update (the first pass: view_done 0
   after mlod__skip_views; a later pass: those still MLOD__DEFERRED), the
   oldest first (the serial of the update that last evaluated them,
   mlod_cut.touched; equal ones in view order) are chosen while each one's
   bound (mlod__lazy_bound) fits in `left`: view_done 0, their touched the
   update's serial.  The other candidates are MLOD__DEFERRED (view_done
   MLOD__SKIPPED), as is every view in a later pass that is not chosen.
   So a pass evaluates at most `left`.  *chosen and *deferred count them.
   Returns 0, with nothing changed, when out of memory for the order (16
   bytes per view, given back before it returns). */
static int mlod__budget_views(mlod_cut *cut, uint32_t lazy_steps, uint64_t left, int again, uint32_t *chosen,
                              uint32_t *deferred)
{
    const mlod__list *list = &cut->lists[MLOD__COMMITTED];
    uint64_t *order = (uint64_t *)mlod__alloc_array(&cut->allocator, 2 * (size_t)cut->view_count, sizeof(uint64_t), NULL);
    uint32_t v, n = 0, i;
    *chosen = *deferred = 0;
    if (!order) return 0;
    for (v = 0; v < cut->view_count; v++) {
        if (again ? (cut->known[v] & MLOD__DEFERRED) != 0 : cut->view_done[v] != MLOD__SKIPPED) {
            /* oldest first: the key counts down with the updates since */
            uint64_t since = cut->serial - cut->touched[v];
            uint32_t key = since >= 0xffffffffu ? 0u : 0xffffffffu - (uint32_t)since;
            order[n++] = (uint64_t)key << 32 | v;
        }
        cut->view_done[v] = MLOD__SKIPPED; /* unless chosen below */
    }
    mlod__radix_sort(order, order + n, n);
    for (i = 0; i < n; i++) {
        uint64_t bound;
        v = (uint32_t)order[n + i];
        bound = mlod__lazy_bound(list->count[v], lazy_steps);
        if (bound <= left) {
            left -= bound;
            cut->view_done[v] = 0;
            cut->known[v] &= (uint8_t)~MLOD__DEFERRED;
            cut->touched[v] = cut->serial + 1;
            ++*chosen;
        } else {
            cut->known[v] = (uint8_t)((cut->known[v] & ~MLOD__STAMPED) | MLOD__DEFERRED);
            ++*deferred;
        }
    }
    mlod__free(&cut->allocator, order);
    return 1;
}

/* A successful update's record of what its lists were computed for, and
   their bases (mlod_cut.basis; cut->serial the update's). */
static void mlod__remember_views(mlod_cut *cut, const mlod_tree *tree, const mlod_view *views,
                                 const mlod_cut_params *params)
{
    uint32_t v;
    /* the lists before were basic cuts of this tree (the same object and
       arrays, refitted since) at this epsilon */
    const int same_tree = cut->seen_tree == tree && cut->seen_spheres == tree->spheres &&
                          cut->seen_cones == tree->cones && cut->seen_epsilon == params->epsilon &&
                          tree->revision - cut->seen_revision < ((uint64_t)1 << 32);
    for (v = 0; v < cut->view_count; v++) {
        const mlod__view_stats *s = &cut->stats[0][v];
        const int same_view =
            (cut->known[v] & MLOD__SEEN) && memcmp(&cut->seen[v], &views[v], sizeof(mlod_view)) == 0;
        /* lazy: a view that made no move in this call (its first round
           evaluated every entry and every pair's parent afresh) */
        const int exact = params->mode != MLOD_CUT_LAZY || (s->steps == 0 && s->coarse == 0);
        if (cut->known[v] & MLOD__DEFERRED) {
            /* its list stands, computed for what seen[] held then: exact
               for nothing now; the version moves with the view, as the
               splat draws the list with the view it is given */
            if (!same_view) cut->version[v] = cut->serial;
            cut->basis[v] = cut->serial;
            cut->known[v] = MLOD__SEEN | MLOD__DEFERRED; /* (mlod_cut_view.deferred) */
            continue;
        }
        if (cut->view_done[v] != MLOD__SKIPPED) cut->touched[v] = cut->serial;
        if (!(exact && same_tree && (cut->known[v] & MLOD__EXACT) && same_view)) cut->basis[v] = cut->serial;
        cut->known[v] = (uint8_t)(MLOD__SEEN | (exact ? MLOD__EXACT : 0u));
    }
    memcpy(cut->seen, views, cut->view_count * sizeof(mlod_view));
    cut->seen_tree = tree;
    cut->seen_revision = tree->revision;
    cut->seen_spheres = tree->spheres;
    cut->seen_cones = tree->cones;
    cut->seen_epsilon = params->epsilon;
}

/* Whether mlod__commit_window writes a window's total entries back into
   its chunk (nodes, capacity) in place: one run of views (at most twice
   a window), fitting with at most an eighth to spare. */
static int mlod__commits_in_place(const uint32_t *nodes, size_t capacity, size_t total)
{
    return nodes && total <= 2 * (size_t)MLOD__WINDOW && total <= capacity && capacity - total <= total / 8;
}

/* Before a window's skipped views are copied out for the commit (w the
   window, out its result): where the commit goes in place, a skipped
   view whose entries land where they are in the chunk (the same counts
   before it) is marked MLOD__KEPT, and neither copied out
   (mlod__copy_skipped_task) nor back (mlod__commit_task): no other view's
   entries are written over them, each view's going to its own range.
   Returns how many were marked. */
static uint32_t mlod__keep_in_place(mlod_cut *w, const mlod__list *out)
{
    const mlod__list *committed = &w->lists[MLOD__COMMITTED];
    size_t total = 0, at = 0;
    uint32_t v, kept = 0;
    for (v = 0; v < w->view_count; v++) total += out->count[v];
    if (!mlod__commits_in_place(committed->nodes, committed->capacity, total)) return 0;
    for (v = 0; v < w->view_count; v++) {
        if (w->view_done[v] == MLOD__SKIPPED && committed->offset[v] == at && out->count[v]) {
            w->known[v] |= MLOD__KEPT;
            kept++;
        }
        at += out->count[v];
    }
    return kept;
}

/* The rounds of one window (mlod_cut_update), on w, the cut restricted to
   the window's views (mlod__window_enter), job prepared by the update.
   same_tree: the committed lists are cuts of a tree of this node count.
   After the last round: the skipped views' lists copied, the versions
   given, the counts committed (stats[0]).  Returns the list holding the
   window's result, or NULL when out of memory. */
static mlod__list *mlod__window_rounds(mlod_cut *w, const mlod_tree *tree, const mlod_cut_params *params,
                                       mlod__cut_job *job, int same_tree)
{
    mlod__list *in, *out;
    uint32_t v, round, tasks, skipped = 0;
    uint64_t round_steps = 0; /* steps up to the last round */
    int idle = 0;
    const int from_root = params->mode == MLOD_CUT_BASIC || !same_tree;
    /* a basic cut's first round is sized by the previous cut of the tree */
    const uint32_t *hint = params->mode == MLOD_CUT_BASIC && same_tree ? w->lists[w->committed].count : NULL;
    /* ... and its later rounds by the previous cut below each entry to split */
    const mlod__list *hint_list = hint ? &w->lists[w->committed] : NULL;
    job->cut = w;
    in = &w->lists[w->committed];
    if (from_root) {
        in = &w->lists[(w->committed + 1) % 3];
        if (!mlod__work_reserve(w, (int)(in - w->lists), w->view_count)) return NULL;
        for (v = 0; v < w->view_count; v++) {
            in->nodes[v] = 0;
            in->status[v] = MLOD__PENDING;
            in->offset[v] = v;
            in->count[v] = 1;
        }
    }
    for (v = 0; v < w->view_count; v++) {
        if (w->view_done[v] == MLOD__SKIPPED) { /* its counts, with no work */
            w->stats[1][v] = w->stats[0][v];
            if (!job->again) w->stats[1][v].evaluated = w->stats[1][v].steps = 0;
            skipped++;
        } else {
            w->stats[1][v].coarse = 0;
        }
    }
    for (round = 0;; round++) {
        uint64_t coarse = 0, steps = 0;
        out = &w->lists[(w->committed + 1) % 3];
        if (out == in) out = &w->lists[(w->committed + 2) % 3];
        job->trust = round > 0;
        /* lazy: a round without a move leaves a cut the next rounds keep,
           so the round after it is the last whatever lazy_steps says */
        job->last = !job->lazy || round + 1 >= params->lazy_steps || (round > 0 && idle);
        job->merge = params->mode == MLOD_CUT_INCREMENTAL && round == 0 && !from_root;
        job->in = in;
        job->out = out;
        job->done_in = round == 0 ? &w->lists[w->committed] : in;
        /* a lazy round before the last marks the unchanged pairs' parents
           as invalid for the next rounds (MLOD__PARENT_INVALID): its
           segments are not copied from the input, which holds no marks */
        if (!mlod__plan_round(w, in, job->lazy, job->trust, round == 0 ? hint : NULL, round > 0 ? hint_list : NULL,
                              tree, job->lazy && !job->last ? 0u : job->age, params->parallel, &tasks))
            return NULL;
        mlod__run(params->parallel, tasks, mlod__segment_task, job);
        if (!mlod__place_output(w, job->done_in, out)) return NULL;
        mlod__run(params->parallel, mlod__view_chunks(w), mlod__join_task, job);
        in = out;
        for (v = 0; v < w->view_count; v++) {
            coarse += w->stats[1][v].coarse;
            steps += w->stats[1][v].steps;
        }
        if (job->lazy ? job->last : coarse == 0) break;
        idle = steps == round_steps;
        round_steps = steps;
    }
    job->done_in = &w->lists[w->committed];
    job->out = in;
    if (skipped && mlod__keep_in_place(w, in) < skipped)
        mlod__run(params->parallel, mlod__view_chunks(w), mlod__copy_skipped_task, job);
    mlod__run(params->parallel, mlod__view_chunks(w), mlod__version_task, job);
    memcpy(w->stats[0], w->stats[1], w->view_count * sizeof(mlod__view_stats));
    return in;
}

/* w: the cut restricted to views first .. first + n - 1, their committed
   lists in chunk c (NULL: none), sharing the cut's work buffers;
   mlod__window_leave gives the buffers back. */
static void mlod__window_enter(const mlod_cut *cut, mlod_cut *w, uint32_t first, uint32_t n, const mlod__chunk *c)
{
    int i;
    *w = *cut;
    w->view_count = n;
    for (i = 0; i < 3; i++) {
        w->lists[i].offset += first;
        w->lists[i].count += first;
    }
    w->lists[MLOD__COMMITTED].nodes = c && c->capacity ? c->nodes : NULL;
    w->lists[MLOD__COMMITTED].status = c && c->capacity ? (uint8_t *)(c->nodes + c->capacity) : NULL;
    w->lists[MLOD__COMMITTED].capacity = c ? c->capacity : 0;
    w->stats[0] += first;
    w->stats[1] += first;
    w->view_segment += first;
    w->view_done += first;
    w->view_work += first;
    w->seen += first;
    w->known += first;
    w->version += first;
    memset(w->grown, 0, sizeof w->grown);
}

static void mlod__window_leave(mlod_cut *cut, mlod_cut *w, int success)
{
    int which;
    mlod__work_end(w, success);
    for (which = 0; which < MLOD__WORK_COUNT; which++)
        if (which != MLOD__COMMITTED) {
            mlod__work_buffer b = mlod__work_get(w, which);
            mlod__work_set(cut, which, &b);
        }
    cut->bytes = w->bytes;
}

/* Room for chunk record `index` of the fresh ones; NULL when out of memory. */
static mlod__chunk *mlod__fresh_chunk(mlod_cut *cut, uint32_t index)
{
    if (index >= cut->fresh_capacity) {
        uint32_t capacity = cut->fresh_capacity ? 2 * cut->fresh_capacity : 16u;
        mlod__chunk *grown;
        if (capacity > cut->view_count) capacity = cut->view_count;
        grown = (mlod__chunk *)mlod__alloc_array(&cut->allocator, capacity, sizeof(mlod__chunk), NULL);
        if (!grown) return NULL;
        if (index) memcpy(grown, cut->fresh, index * sizeof(mlod__chunk));
        mlod__free(&cut->allocator, cut->fresh);
        cut->bytes += (capacity - cut->fresh_capacity) * sizeof(mlod__chunk);
        cut->fresh = grown;
        cut->fresh_capacity = capacity;
    }
    return &cut->fresh[index];
}

typedef struct mlod__commit_job {
    const mlod__list *res;
    const mlod__list *to;
    const mlod__chunk *chunk;
    const uint8_t *known; /* the window's (MLOD__KEPT: the entries are in place) */
    uint32_t first, start, end;
} mlod__commit_job;

/* Views start + MLOD__VIEW_CHUNK index .. of a window's result into their chunk. */
static void mlod__commit_task(void *context, uint32_t index)
{
    const mlod__commit_job *job = (const mlod__commit_job *)context;
    uint32_t v = job->start + index * MLOD__VIEW_CHUNK, end = v + MLOD__VIEW_CHUNK < job->end ? v + MLOD__VIEW_CHUNK : job->end;
    uint8_t *status;
    if (!job->chunk->nodes) return; /* no entries */
    status = (uint8_t *)(job->chunk->nodes + job->chunk->capacity);
    for (; v < end; v++) {
        uint32_t count = job->res->count[v];
        size_t at = job->to->offset[job->first + v];
        if (!count || (job->known[v] & MLOD__KEPT)) continue;
        memcpy(job->chunk->nodes + at, job->res->nodes + job->res->offset[v], count * sizeof(uint32_t));
        memcpy(status + at, job->res->status + job->res->offset[v], count);
    }
}

/* Commit a window's result (res, restricted to views first .. first + n -
   1 as in mlod__window_enter) as fresh chunks from *fresh_count on: into
   old's entries where it fits them with at most an eighth to spare, else
   into new chunks with a sixteenth to spare; in runs of views of about
   MLOD__WINDOW entries where it holds more than twice that.  old's
   entries are freed or taken (old->nodes NULL after).  Returns 0 when out
   of memory. */
static int mlod__commit_window(mlod_cut *cut, uint32_t first, uint32_t n, const mlod__list *res, mlod__chunk *old,
                               uint32_t *fresh_count, const mlod_parallel *parallel)
{
    mlod__list *to = &cut->lists[MLOD__COMMITTED];
    mlod__commit_job job;
    size_t total = 0;
    uint32_t v, start = 0;
    for (v = 0; v < n; v++) total += res->count[v];
    while (start < n) {
        uint32_t end = n;
        size_t size = total, at = 0;
        mlod__chunk *c = mlod__fresh_chunk(cut, *fresh_count);
        if (!c) return 0;
        if (total > 2 * MLOD__WINDOW)
            for (end = start, size = 0; end < n && (end == start || size < MLOD__WINDOW); end++) size += res->count[end];
        c->first = first + start;
        c->views = end - start;
        if (old && mlod__commits_in_place(old->nodes, old->capacity, total)) {
            c->nodes = old->nodes; /* in place: the result is in a work list (or there, MLOD__KEPT) */
            c->capacity = old->capacity;
            old->nodes = NULL;
        } else {
            c->capacity = size + size / 16;
            c->nodes = c->capacity ? (uint32_t *)mlod__alloc_array(&cut->allocator, c->capacity, sizeof(uint32_t) + 1, NULL)
                                   : NULL;
            if (c->capacity && !c->nodes) return 0;
            cut->bytes += mlod__chunk_bytes(c->capacity);
        }
        ++*fresh_count;
        for (v = start; v < end; v++) {
            to->offset[first + v] = at;
            to->count[first + v] = res->count[v];
            at += res->count[v];
        }
        job.res = res;
        job.to = to;
        job.chunk = c;
        job.known = cut->known + first;
        job.first = first;
        job.start = start;
        job.end = end;
        mlod__run(parallel, (end - start - 1) / MLOD__VIEW_CHUNK + 1, mlod__commit_task, &job);
        start = end;
    }
    for (v = 0; v < n; v++) cut->known[first + v] &= (uint8_t)~MLOD__KEPT;
    if (old) mlod__chunk_free(cut, old);
    return 1;
}

/* The entries of chunk c: its views' counts. */
static size_t mlod__chunk_entries(const mlod_cut *cut, const mlod__chunk *c)
{
    size_t total = 0;
    uint32_t v;
    for (v = c->first; v < c->first + c->views; v++) total += cut->lists[MLOD__COMMITTED].count[v];
    return total;
}

/* Where chunks[at] holds fewer than MLOD__WINDOW / 4 entries (its views'
   cuts shrank), the chunks after it join it, while the whole holds at most
   MLOD__WINDOW entries and MLOD__WINDOW_VIEWS views: their lists are copied
   into one chunk with a sixteenth to spare, which takes chunks[at]'s place,
   and the others' entries are freed.  So a window is never much smaller
   than it need be, whatever the cuts were before.  Returns how many chunks
   joined it (0 also when out of memory: the chunks stay as they are). */
static uint32_t mlod__merge_chunks(mlod_cut *cut, uint32_t at)
{
    mlod__list *list = &cut->lists[MLOD__COMMITTED];
    mlod__chunk merged = cut->chunks[at];
    size_t total = mlod__chunk_entries(cut, &cut->chunks[at]), at_entry = 0;
    uint32_t last = at + 1, i, v;
    uint8_t *status;
    if (total >= MLOD__WINDOW / 4) return 0;
    while (last < cut->chunk_count) {
        size_t more = mlod__chunk_entries(cut, &cut->chunks[last]);
        if (total + more > MLOD__WINDOW || merged.views + cut->chunks[last].views > MLOD__WINDOW_VIEWS) break;
        total += more;
        merged.views += cut->chunks[last].views;
        last++;
    }
    if (last == at + 1) return 0;
    merged.capacity = total + total / 16;
    merged.nodes = merged.capacity
                       ? (uint32_t *)mlod__alloc_array(&cut->allocator, merged.capacity, sizeof(uint32_t) + 1, NULL)
                       : NULL;
    if (merged.capacity && !merged.nodes) return 0;
    cut->bytes += mlod__chunk_bytes(merged.capacity);
    status = merged.nodes ? (uint8_t *)(merged.nodes + merged.capacity) : NULL;
    for (i = at; i < last; i++) {
        mlod__chunk *from = &cut->chunks[i];
        const uint8_t *from_status = from->nodes ? (const uint8_t *)(from->nodes + from->capacity) : NULL;
        for (v = from->first; v < from->first + from->views; v++) {
            uint32_t n = list->count[v];
            if (n) { /* (a chunk without entries has no arrays) */
                memcpy(merged.nodes + at_entry, from->nodes + list->offset[v], n * sizeof(uint32_t));
                memcpy(status + at_entry, from_status + list->offset[v], n);
            }
            list->offset[v] = at_entry;
            at_entry += n;
        }
        mlod__chunk_free(cut, from);
    }
    cut->chunks[at] = merged;
    return last - at - 1;
}

/* Whether every view of first .. first + n - 1 is skipped. */
static int mlod__window_skipped(const mlod_cut *cut, uint32_t first, uint32_t n)
{
    uint32_t v;
    for (v = first; v < first + n; v++)
        if (cut->view_done[v] != MLOD__SKIPPED) return 0;
    return 1;
}

/* The most passes of a budgeted update: each goes through every window,
   and spends about half of what the views before left (their bounds are
   about twice what they cost), so four spend about nine tenths. */
#define MLOD__BUDGET_PASSES 4

/* One pass of an update over the views (mlod_cut_update): each window
   the views not MLOD__SKIPPED take part in goes through its rounds and is
   committed; the others' chunks are kept as they are.  Returns 0 when out
   of memory (the chunks then released: mlod__cut_release). */
static int mlod__update_pass(mlod_cut *cut, const mlod_tree *tree, const mlod_view *views,
                             const mlod_cut_params *params, mlod__cut_job *job, int same_tree)
{
    uint32_t v, next = 0, fresh_count = 0, done_views = 0;
    uint64_t done_entries = 0;
    const int have = cut->chunk_count > 0; /* windows: the chunks */
    for (v = 0; v < cut->view_count;) {
        mlod__chunk *old = have ? &cut->chunks[next++] : NULL;
        uint32_t n;
        if (old) {
            MANYLODS_ASSERT(next <= cut->chunk_count && old->first == v); /* the chunks cover the views in order */
            next += mlod__merge_chunks(cut, next - 1);
            n = old->views;
        } else { /* about MLOD__WINDOW entries by the cuts so far, at most as many views as
                    those: one view, then at most doubling */
            double guess = (double)MLOD__WINDOW * done_views / (double)(done_entries ? done_entries : 1);
            n = done_views == 0 ? 1u : guess < 1.0 ? 1u : guess > (double)done_views ? done_views : (uint32_t)guess;
            if (n > MLOD__WINDOW_VIEWS) n = MLOD__WINDOW_VIEWS;
            if (n > cut->view_count - v) n = cut->view_count - v;
        }
        if (old && mlod__window_skipped(cut, v, n)) { /* kept as it is */
            uint32_t u;
            mlod__chunk *c = mlod__fresh_chunk(cut, fresh_count);
            if (!c) goto out_of_memory;
            *c = *old;
            old->nodes = NULL;
            fresh_count++;
            if (!job->again)
                for (u = v; u < v + n; u++) cut->stats[0][u].evaluated = cut->stats[0][u].steps = 0;
        } else {
            mlod_cut w;
            mlod__list *out;
            uint32_t u;
            mlod__window_enter(cut, &w, v, n, old);
            job->views = views + v;
            out = mlod__window_rounds(&w, tree, params, job, same_tree);
            mlod__window_leave(cut, &w, out != NULL);
            if (!out || !mlod__commit_window(cut, v, n, out, old, &fresh_count, params->parallel)) goto out_of_memory;
            for (u = v; u < v + n; u++) done_entries += cut->lists[MLOD__COMMITTED].count[u];
        }
        done_views += n;
        v += n;
    }
    {
        mlod__chunk *t = cut->chunks;
        uint32_t capacity = cut->chunk_capacity;
        cut->chunks = cut->fresh;
        cut->chunk_capacity = cut->fresh_capacity;
        cut->chunk_count = fresh_count;
        cut->fresh = t;
        cut->fresh_capacity = capacity;
    }
    return 1;
out_of_memory:
    mlod__cut_release(cut, fresh_count);
    return 0;
}

MLOD__PUBLIC mlod_result mlod_cut_update(mlod_cut *cut, const mlod_tree *tree, const mlod_view *views,
                                         const mlod_cut_params *params, mlod_error *error)
{
    mlod__cut_job job;
    uint32_t v, skipped, chosen, deferred = 0;
    int same_tree, budgeted, pass;
    mlod_result res = mlod__check_cut_params(cut, tree, views, params, error);
    if (res != MLOD_OK) return res;
    memset(&job, 0, sizeof job);
    skipped = mlod__skip_views(cut, tree, params, &job.age);
    if (job.age && !mlod__suspect(tree, job.age, 0)) {
        /* the refits since changed no node (a changed leaf marks every
           node above it, the root included): the MLOD__STAMPED views are
           skipped as a whole; their lists are the basic cuts of this
           revision too */
        for (v = 0; v < cut->view_count; v++)
            if (cut->known[v] & MLOD__STAMPED) cut->view_done[v] = MLOD__SKIPPED;
        for (v = 0, skipped = 0; v < cut->view_count; v++) skipped += cut->view_done[v] == MLOD__SKIPPED;
    }
    same_tree = cut->tree_nodes == tree->node_count;
    /* (from the roots, every view needs its list: no budget) */
    budgeted = params->budget && params->mode == MLOD_CUT_LAZY && same_tree && cut->chunk_count > 0 &&
               skipped < cut->view_count;
    if (budgeted && !mlod__budget_views(cut, params->lazy_steps, params->budget, 0, &chosen, &deferred))
        return mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "out of memory ordering %u views for a budget",
                          cut->view_count - skipped);
    if (skipped == cut->view_count) {
        /* nothing changed: the lists stand, and nothing was evaluated */
        for (v = 0; v < cut->view_count; v++) cut->stats[0][v].evaluated = cut->stats[0][v].steps = 0;
        cut->seen_revision = tree->revision;
        return mlod__succeed(error);
    }
    job.tree = tree;
    job.epsilon = params->epsilon;
    job.lazy = params->mode == MLOD_CUT_LAZY;
    job.serial = cut->serial + 1;
    for (pass = 1;; pass++) {
        uint64_t spent = 0;
        if (!mlod__update_pass(cut, tree, views, params, &job, same_tree)) {
            mlod_cut_reset(cut);
            return mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY,
                              "out of memory updating the cut of %u views (the cut is reset)", cut->view_count);
        }
        if (!budgeted || deferred == 0 || pass == MLOD__BUDGET_PASSES) break;
        /* what the views cost below their bounds goes to the deferred
           ones, oldest first, in another pass (the views done so far keep
           their counts) */
        for (v = 0; v < cut->view_count; v++) spent += cut->stats[0][v].evaluated;
        MANYLODS_ASSERT(spent <= params->budget);
        if (!mlod__budget_views(cut, params->lazy_steps, params->budget - spent, 1, &chosen, &deferred) || !chosen)
            break;
        job.again = 1;
    }
    cut->serial++;
    cut->tree_nodes = tree->node_count;
    mlod__remember_views(cut, tree, views, params);
    if (!cut->reserved) mlod__work_release(cut);
    return mlod__succeed(error);
}


/* ---------------------------------------------------------- projection -- */

/* The image of a sphere (centre, radius r) in one sub-projection of a view:
   the disc around it (centre and radius in tile pixels) and the depth of
   its centre.  A point is a sphere of radius 0. */
typedef struct mlod__disc {
    double x, y, radius, depth;
} mlod__disc;

/* Two doubles a vector (SSE2 on x86, NEON on AArch64; none with
   MANYLODS_NO_SIMD) for the images of spheres: each lane computes the
   same operations, in the same order, as mlod__image_discs's scalar steps,
   so the bits are the same.  Not where clang builds for a target with FMA
   (MLOD__NO_FMA_TARGET): an intrinsic cannot be inlined into the code
   built without it, and outside it the code generator may fuse. */
#if MLOD__SIMD_X86 && !defined(MLOD__NO_FMA_TARGET)
#define MLOD__VD 1
typedef __m128d mlod__vd;
#define MLOD__DPAIR(a, b) _mm_set_pd(b, a) /* lane 0: a */
#define MLOD__DSPLAT _mm_set1_pd
#define MLOD__DADD _mm_add_pd
#define MLOD__DSUB _mm_sub_pd
#define MLOD__DMUL _mm_mul_pd
#define MLOD__DDIV _mm_div_pd
#define MLOD__DSQRT _mm_sqrt_pd
#define MLOD__DNEG(a) _mm_xor_pd(a, _mm_set1_pd(-0.0))
#define MLOD__DSTORE _mm_storeu_pd
/* a where mask (all ones, lane by lane), else +0 */
#define MLOD__DKEEP(mask, a) _mm_and_pd(mask, a)
#define MLOD__DGT _mm_cmpgt_pd
#elif MLOD__SIMD_NEON
#define MLOD__VD 1
typedef float64x2_t mlod__vd;
#define MLOD__DPAIR(a, b) vcombine_f64(vdup_n_f64(a), vdup_n_f64(b))
#define MLOD__DSPLAT vdupq_n_f64
#define MLOD__DADD vaddq_f64
#define MLOD__DSUB vsubq_f64
#define MLOD__DMUL vmulq_f64
#define MLOD__DDIV vdivq_f64
#define MLOD__DSQRT vsqrtq_f64
#define MLOD__DNEG vnegq_f64
#define MLOD__DSTORE vst1q_f64
#define MLOD__DKEEP(mask, a) vreinterpretq_f64_u64(vandq_u64(vreinterpretq_u64_f64(mask), vreinterpretq_u64_f64(a)))
#define MLOD__DGT(a, b) vreinterpretq_f64_u64(vcgtq_f64(a, b))
#endif

#ifdef MLOD__VD
/* a . v over three coordinate vectors, as mlod__dot3 sums it */
static mlod__vd mlod__vd_dot(mlod__vd x, mlod__vd y, mlod__vd z, const double *v)
{
    return MLOD__DADD(MLOD__DADD(MLOD__DMUL(x, MLOD__DSPLAT(v[0])), MLOD__DMUL(y, MLOD__DSPLAT(v[1]))),
                      MLOD__DMUL(z, MLOD__DSPLAT(v[2])));
}

/* mlod__image_discs's perspective and paraboloid images for lanes 0 .. 2k
   - 1 (2k <= n), two at a time; returns 2k, the first lane left to the
   scalar steps. */
static uint32_t mlod__image_discs_vd(const mlod__pview *pv, int s, const double (*centre)[3], const double *r,
                                     mlod__disc *out, int *bounded, uint32_t n)
{
    const mlod_view_sub *sub = &pv->f.subs[s];
    const mlod__vd one = MLOD__DSPLAT(1.0), half = MLOD__DSPLAT(0.5), zero = MLOD__DSPLAT(0.0);
    const int perspective = pv->kind[s] == MLOD_VIEW_PERSPECTIVE;
    uint32_t l, j;
    for (l = 0; l + 2 <= n; l += 2) {
        const double *c0 = centre[l], *c1 = centre[l + 1];
        mlod__vd x = MLOD__DSUB(MLOD__DPAIR(c0[0], c1[0]), MLOD__DSPLAT(pv->f.eye[0]));
        mlod__vd y = MLOD__DSUB(MLOD__DPAIR(c0[1], c1[1]), MLOD__DSPLAT(pv->f.eye[1]));
        mlod__vd z = MLOD__DSUB(MLOD__DPAIR(c0[2], c1[2]), MLOD__DSPLAT(pv->f.eye[2]));
        mlod__vd d = MLOD__DSQRT(MLOD__DADD(MLOD__DADD(MLOD__DMUL(x, x), MLOD__DMUL(y, y)), MLOD__DMUL(z, z)));
        mlod__vd a = MLOD__DDIV(mlod__vd_dot(x, y, z, sub->right), d);
        mlod__vd b = MLOD__DDIV(mlod__vd_dot(x, y, z, sub->up), d);
        mlod__vd cos_t = MLOD__DDIV(mlod__vd_dot(x, y, z, sub->forward), d);
        mlod__vd sin_b = MLOD__DDIV(MLOD__DPAIR(r[l], r[l + 1]), d);
        mlod__vd sin_t = MLOD__DSQRT(MLOD__DADD(MLOD__DMUL(a, a), MLOD__DMUL(b, b)));
        mlod__vd cos_b = MLOD__DSQRT(MLOD__DSUB(one, MLOD__DMUL(sin_b, sin_b)));
        mlod__vd turned = MLOD__DGT(sin_t, zero); /* else the direction is (0, 0) */
        mlod__vd dir_x = MLOD__DKEEP(turned, MLOD__DDIV(a, sin_t)), dir_y = MLOD__DKEEP(turned, MLOD__DDIV(b, sin_t));
        mlod__vd s_hi = MLOD__DADD(MLOD__DMUL(sin_t, cos_b), MLOD__DMUL(cos_t, sin_b));
        mlod__vd c_hi = MLOD__DSUB(MLOD__DMUL(cos_t, cos_b), MLOD__DMUL(sin_t, sin_b));
        mlod__vd s_lo = MLOD__DSUB(MLOD__DMUL(sin_t, cos_b), MLOD__DMUL(cos_t, sin_b));
        mlod__vd c_lo = MLOD__DADD(MLOD__DMUL(cos_t, cos_b), MLOD__DMUL(sin_t, sin_b));
        mlod__vd hi, lo, px, py, depth, radius;
        double ox[2], oy[2], od[2], orad[2], dist[2], ch[2], sh[2];
        if (perspective) {
            mlod__vd k;
            hi = MLOD__DDIV(s_hi, c_hi);
            lo = MLOD__DDIV(s_lo, c_lo);
            k = MLOD__DMUL(MLOD__DMUL(MLOD__DSPLAT(sub->scale), half), MLOD__DADD(hi, lo));
            px = MLOD__DADD(MLOD__DSPLAT(sub->x + 0.5 * sub->width), MLOD__DMUL(k, dir_x));
            py = MLOD__DADD(MLOD__DSPLAT(sub->y + 0.5 * sub->height), MLOD__DMUL(k, MLOD__DNEG(dir_y)));
            depth = mlod__vd_dot(x, y, z, sub->forward);
        } else {
            mlod__vd k;
            hi = MLOD__DDIV(s_hi, MLOD__DADD(one, c_hi));
            lo = MLOD__DDIV(s_lo, MLOD__DADD(one, c_lo));
            k = MLOD__DMUL(half, MLOD__DADD(hi, lo));
            px = MLOD__DADD(MLOD__DSPLAT(sub->x), MLOD__DMUL(MLOD__DMUL(half, MLOD__DSPLAT(sub->width)),
                                                             MLOD__DADD(one, MLOD__DMUL(k, dir_x))));
            py = MLOD__DADD(MLOD__DSPLAT(sub->y), MLOD__DMUL(MLOD__DMUL(half, MLOD__DSPLAT(sub->height)),
                                                             MLOD__DSUB(one, MLOD__DMUL(k, dir_y))));
            depth = d;
        }
        radius = MLOD__DMUL(MLOD__DMUL(MLOD__DSPLAT(sub->scale), half), MLOD__DSUB(hi, lo));
        MLOD__DSTORE(ox, px);
        MLOD__DSTORE(oy, py);
        MLOD__DSTORE(od, depth);
        MLOD__DSTORE(orad, radius);
        MLOD__DSTORE(dist, d);
        MLOD__DSTORE(ch, c_hi);
        MLOD__DSTORE(sh, s_hi);
        for (j = 0; j < 2; j++) { /* the scalar steps' tests, lane by lane */
            bounded[l + j] = dist[j] > r[l + j] && (perspective ? ch[j] > 0.0
                                                                : 1.0 + ch[j] > 0.0 && (sh[j] > 0.0 || ch[j] > 0.0));
            if (!bounded[l + j]) continue;
            out[l + j].x = ox[j];
            out[l + j].y = oy[j];
            out[l + j].depth = od[j];
            out[l + j].radius = orad[j];
        }
    }
    return l;
}
#endif

/* The images of n <= MLOD__LANES spheres at once in sub-projection s, step
   by step across them (each lane computes what it would alone):
   bounded[l] says whether out[l] was written (0: the image is unbounded).
   Returns bounded[0]. */
/* GLSL twin: image_disc */
static int mlod__image_discs(const mlod__pview *pv, int s, const double (*centre)[3], const double *r,
                             mlod__disc *out, int *bounded, uint32_t n)
{
    const mlod_view_sub *sub = &pv->f.subs[s];
    double x[MLOD__LANES][3], d[MLOD__LANES], a[MLOD__LANES], b[MLOD__LANES], cos_t[MLOD__LANES];
    double sin_t[MLOD__LANES], sin_b[MLOD__LANES], cos_b[MLOD__LANES];
    double mid_x = sub->x + 0.5 * sub->width, mid_y = sub->y + 0.5 * sub->height;
    uint32_t l, first = 0;
    int k;
#ifdef MLOD__VD
    if (pv->kind[s] != MLOD_VIEW_ORTHOGRAPHIC) first = mlod__image_discs_vd(pv, s, centre, r, out, bounded, n);
#endif
    for (l = first; l < n; l++)
        for (k = 0; k < 3; k++) x[l][k] = centre[l][k] - pv->f.eye[k];
    if (pv->kind[s] == MLOD_VIEW_ORTHOGRAPHIC) {
        for (l = first; l < n; l++) {
            out[l].x = mid_x + sub->scale_x * mlod__dot3(x[l], sub->right);
            out[l].y = mid_y - sub->scale_y * mlod__dot3(x[l], sub->up);
            out[l].radius = r[l] * sub->scale;
            out[l].depth = mlod__dot3(x[l], sub->forward);
            bounded[l] = 1;
        }
        return bounded[0];
    }
    for (l = first; l < n; l++) {
        d[l] = mlod__length3(x[l]);
        bounded[l] = d[l] > r[l];
    }
    for (l = first; l < n; l++) {
        if (!bounded[l]) continue;
        a[l] = mlod__dot3(x[l], sub->right) / d[l];
        b[l] = mlod__dot3(x[l], sub->up) / d[l];
        cos_t[l] = mlod__dot3(x[l], sub->forward) / d[l];
        sin_b[l] = r[l] / d[l];
    }
    for (l = first; l < n; l++) {
        if (!bounded[l]) continue;
        sin_t[l] = sqrt(a[l] * a[l] + b[l] * b[l]);
        cos_b[l] = sqrt(1.0 - sin_b[l] * sin_b[l]);
    }
    for (l = first; l < n; l++) {
        double dir_x = 0.0, dir_y = 0.0, s_hi, c_hi, s_lo, c_lo, hi, lo;
        if (!bounded[l]) continue;
        if (sin_t[l] > 0.0) {
            dir_x = a[l] / sin_t[l];
            dir_y = b[l] / sin_t[l];
        }
        /* the image spans radially from angle t - b to t + b off the axis */
        s_hi = sin_t[l] * cos_b[l] + cos_t[l] * sin_b[l];
        c_hi = cos_t[l] * cos_b[l] - sin_t[l] * sin_b[l];
        s_lo = sin_t[l] * cos_b[l] - cos_t[l] * sin_b[l];
        c_lo = cos_t[l] * cos_b[l] + sin_t[l] * sin_b[l];
        if (pv->kind[s] == MLOD_VIEW_PERSPECTIVE) {
            if (!(c_hi > 0.0)) {
                bounded[l] = 0;
                continue;
            }
            hi = s_hi / c_hi; /* tan(t + b) */
            lo = s_lo / c_lo; /* tan(t - b) */
            /* y as a sum with -dir_y (the same bits as the difference):
               gcc 12 fuses an add beside a subtract into one vector
               multiply-add-subtract even with -ffp-contract=off */
            out[l].x = mid_x + sub->scale * 0.5 * (hi + lo) * dir_x;
            out[l].y = mid_y + sub->scale * 0.5 * (hi + lo) * -dir_y;
            out[l].depth = mlod__dot3(x[l], sub->forward);
        } else {
            /* unbounded once t + b reaches pi (the sphere's cone holds -w):
               1 + cos(t + b) > 0 alone would pass t + b in (pi, 3 pi / 2) */
            if (!(1.0 + c_hi > 0.0) || !(s_hi > 0.0 || c_hi > 0.0)) {
                bounded[l] = 0;
                continue;
            }
            hi = s_hi / (1.0 + c_hi); /* tan((t + b) / 2) */
            lo = s_lo / (1.0 + c_lo);
            out[l].x = sub->x + 0.5 * sub->width * (1.0 + 0.5 * (hi + lo) * dir_x);
            out[l].y = sub->y + 0.5 * sub->height * (1.0 - 0.5 * (hi + lo) * dir_y);
            out[l].depth = d[l];
        }
        out[l].radius = sub->scale * 0.5 * (hi - lo);
    }
    return bounded[0];
}


/* ------------------------------------------------ the splat's float filter -- */

/* Most nodes a cut draws at epsilon ~1 have images smaller than a pixel:
   mlod__raster_disc plots the one pixel holding the disc's centre (below
   a disc scale of 1, where that pixel's centre lies in the disc).  Which
   pixel that is, and whether the disc is small, follow from the disc's
   centre (X, Y) and radius R, which mlod__image_discs computes in double
   (8 divisions and 3 square roots a node).  The filter computes them in
   float by the same formulas, step for step, with a bound on each step's
   distance to the value of the formula in exact arithmetic: whenever the
   float values, widened by their bounds, fall inside one pixel and below
   the small-disc radius, the double path falls there too, and the pixel is
   plotted with the double path's depth (computed as it does: a square
   root, or a dot product, no division).  Otherwise the node takes the
   double path.  So the atlas is the same bit for bit; the filter only
   decides sooner.

   The bounds (u = 2^-24, each float operation off by at most u of its
   result; the basis rounded to float, each component within u of it;
   C - E, the centre less the eye, as floats):
     d = |x|: 5u d; xr = x.right (and x.up, x.forward): 5.2u d, so
     a = xr / d, b, c = cos t: 12u each; rho = r / d: 6u rho (7u taken);
     sin t = sqrt(a^2 + b^2): sqrt2 12u + 3u <= 20u;
     cos b = sqrt(1 - rho^2), rho <= 1/2: 7u;
     s_hi = sin t cos b + c rho (and c_hi, s_lo, c_lo): <= 40u (42u taken);
   then, at run time, for z = x / y: (e_x + |z| e_y) / (|y| - e_y) + u |z|,
   z = x y: |x| e_y + |y| e_x + e_x e_y + u |z|, z = x + y: e_x + e_y +
   u |z|.  The double path follows the same steps, so its own distance to
   the exact values is the same bound with 2^-53 for u: 2^-29 of the
   float's.  The bounds, themselves computed in float (a few roundings
   each), are widened by 2^-8 of themselves, which covers both.  (A
   compiler that fuses a multiply and an add rounds once where the bounds
   count twice: they hold.)  The conditions the bounds need (|x|^2 in
   [2^-100, 2^100], so that the products that count stay normal floats,
   whose rounding is relative; rho <= 1/2, sin t well above its bound, the
   denominators 1 + c (paraboloid) or c (perspective) at least 1/8) also
   give the double path's own tests (the sphere does not hold the eye, the
   image is bounded); a node that fails them takes the double path. */
#define MLOD__DISC_U (1.0f / 16777216.0f)
/* Discs below this radius (times disc_scale, >= 1) cover one pixel (mlod__raster_disc): 0.5 - 2^-30. */
#define MLOD__SMALL_DISC (0.5 - 1.0 / 1073741824.0)

typedef struct mlod__fdisc {
    int kind;                          /* 0: the double path only */
    float right[3], up[3], forward[3]; /* the basis, rounded to float */
    float half_scale;                  /* scale / 2, rounded */
    float x0, y0;                      /* paraboloid: sub.x, sub.y; perspective: the sub-tile's centre (exact) */
    float half_w, half_h;              /* paraboloid: width / 2, height / 2 (exact) */
} mlod__fdisc;

typedef struct mlod__fdiscs {
    float eye[3]; /* exact */
    mlod__fdisc subs[MLOD_VIEW_MAX_SUBS];
} mlod__fdiscs;

/* The filter's constants for the view; 0 (every node takes the double
   path) when its eye or sub-tile origins are not floats, or no
   sub-projection is a paraboloid or perspective one. */
static int mlod__disc_prepare(const mlod__pview *pv, mlod__fdiscs *fd)
{
    int s, k, any = 0;
    for (k = 0; k < 3; k++)
        if (!mlod__float_exact(pv->f.eye[k], &fd->eye[k])) return 0;
    for (s = 0; s < pv->sub_count; s++) {
        const mlod_view_sub *sub = &pv->f.subs[s];
        mlod__fdisc *f = &fd->subs[s];
        int ok;
        f->kind = 0;
        if (pv->kind[s] == MLOD_VIEW_PARABOLOID)
            ok = mlod__float_exact(sub->x, &f->x0) && mlod__float_exact(sub->y, &f->y0) &&
                 mlod__float_exact(0.5 * sub->width, &f->half_w) && mlod__float_exact(0.5 * sub->height, &f->half_h);
        else if (pv->kind[s] == MLOD_VIEW_PERSPECTIVE)
            ok = mlod__float_exact(sub->x + 0.5 * sub->width, &f->x0) &&
                 mlod__float_exact(sub->y + 0.5 * sub->height, &f->y0);
        else
            ok = 0;
        if (!ok || !(sub->scale > 0.0 && sub->scale < 1e30)) continue;
        for (k = 0; k < 3; k++) {
            f->right[k] = (float)sub->right[k];
            f->up[k] = (float)sub->up[k];
            f->forward[k] = (float)sub->forward[k];
        }
        f->half_scale = (float)(0.5 * sub->scale);
        f->kind = pv->kind[s];
        any = 1;
    }
    return any;
}

/* What the filter found for a node: */
enum {
    MLOD__DISC_UNSURE, /* the double path decides */
    MLOD__DISC_PLOT,   /* a small disc: plot pixel (col, row) */
    MLOD__DISC_NONE    /* a small disc whose centre lies outside the clip: nothing drawn */
};

/* A small disc (its radius times the disc scale ds below 0.5 - 2^-30)
   whose centre lies in [xl, xh] x [yl, yh]: the one pixel that can draw
   it (any other pixel's centre lies 0.5 or more away), clipped to columns
   [clip[0], clip[1]) and rows [clip[2], clip[3]) (each below 2^24:
   floats): MLOD__DISC_PLOT with the pixel holding the centre, which
   mlod__raster_disc draws at ds >= 1 (below, see mlod__disc_inside);
   MLOD__DISC_NONE when the centre lies outside the clip; else
   MLOD__DISC_UNSURE (a NAN box is). */
static int mlod__disc_pixel(float xl, float xh, float yl, float yh, const uint32_t *clip, uint32_t *col, uint32_t *row)
{
    if (xh < (float)clip[0] || xl >= (float)clip[1] || yh < (float)clip[2] || yl >= (float)clip[3])
        return MLOD__DISC_NONE;
    if (!(xl >= (float)clip[0] && xh < (float)clip[1] && yl >= (float)clip[2] && yh < (float)clip[3]))
        return MLOD__DISC_UNSURE;
    *col = (uint32_t)xl;
    *row = (uint32_t)yl;
    return *col == (uint32_t)xh && *row == (uint32_t)yh ? MLOD__DISC_PLOT : MLOD__DISC_UNSURE;
}

/* Below a disc scale of 1, whether the pixel (col, row) that
   mlod__disc_pixel found is drawn: whether its centre lies in the disc of
   the filter's box (box[k * stride]: the centre's bounds for k = 0 .. 3,
   as there, the radius times ds within [box[4 stride], box[5 stride]]).
   MLOD__DISC_PLOT, _NONE or _UNSURE; 2^-20 of the squares covers every
   rounding here and in the double path's test. */
static int mlod__disc_inside(const float *box, size_t stride, uint32_t col, uint32_t row)
{
    float dx0 = ((float)col + 0.5f) - box[stride], dx1 = ((float)col + 0.5f) - box[0];
    float dy0 = ((float)row + 0.5f) - box[3 * stride], dy1 = ((float)row + 0.5f) - box[2 * stride];
    float r_lo = box[4 * stride], r_hi = box[5 * stride];
    float far_x = fabsf(dx0) > fabsf(dx1) ? fabsf(dx0) : fabsf(dx1);
    float far_y = fabsf(dy0) > fabsf(dy1) ? fabsf(dy0) : fabsf(dy1);
    float near_x = dx0 > 0.0f ? dx0 : dx1 < 0.0f ? -dx1 : 0.0f;
    float near_y = dy0 > 0.0f ? dy0 : dy1 < 0.0f ? -dy1 : 0.0f;
    if ((far_x * far_x + far_y * far_y) * (1.0f + 1.0f / 1048576.0f) <= r_lo * r_lo) return MLOD__DISC_PLOT;
    if ((near_x * near_x + near_y * near_y) * (1.0f - 1.0f / 1048576.0f) > r_hi * r_hi) return MLOD__DISC_NONE;
    return MLOD__DISC_UNSURE;
}

/* What the filter's box (mlod__fast_disc; box[k * stride], k = 0 .. 5)
   tells of the disc: MLOD__DISC_* and the pixel; strict (a disc scale
   below 1, or tangent discs): only where the pixel's centre lies in the
   disc. */
static int mlod__disc_decide(const float *box, size_t stride, int strict, const uint32_t *clip, uint32_t *col,
                             uint32_t *row)
{
    int code = mlod__disc_pixel(box[0], box[stride], box[2 * stride], box[3 * stride], clip, col, row);
    return code == MLOD__DISC_PLOT && strict ? mlod__disc_inside(box, stride, *col, *row) : code;
}

/* The sub-projection whose sub-tile holds tile position (x, y), or -1. */
static int mlod__sub_at(const mlod__pview *pv, double x, double y)
{
    int s;
    for (s = 0; s < pv->sub_count; s++) {
        const mlod_view_sub *sub = &pv->f.subs[s];
        if (x >= sub->x && x < sub->x + sub->width && y >= sub->y && y < sub->y + sub->height) return s;
    }
    return -1;
}

/* Where world point `point` lands in the view of frame f: in the
   sub-projection whose axis is closest to its direction (mlod__nearest_sub's
   rule), *sub, the tile position (x, y) and depth, with the arithmetic of
   mlod__image_discs for a sphere of radius 0 (the same bits: with r = 0
   its sin b is 0 and cos b 1, so hi = lo = tan t, or tan(t / 2) for
   paraboloids, and the sums below are its own).  Returns 1 when a
   sub-projection reaches the point (mlod__reached), 0 when none does,
   with the outputs written; -1 where the projection is undefined (at the
   eye, or behind a perspective or paraboloid sub-projection), outputs
   unwritten. */
/* GLSL twin: frame_project */
static int mlod__frame_project(const mlod_view_frame *f, const float *point, int *sub, double *x, double *y,
                               double *depth)
{
    double e[3], best = 0.0, d, a, b, cos_t, sin_t, dir_x = 0.0, dir_y = 0.0, hi;
    float sphere[4];
    int s, k, found = 0, subs = (int)f->sub_count;
    const mlod_view_sub *v;
    for (k = 0; k < 3; k++) {
        e[k] = (double)point[k] - f->eye[k];
        sphere[k] = point[k];
    }
    sphere[3] = 0.0f;
    for (s = 0; s < subs; s++) {
        double xw = mlod__dot3(e, f->subs[s].forward);
        if (s == 0 || xw > best) {
            best = xw;
            found = s;
        }
    }
    v = &f->subs[found];
    if ((int)v->kind == MLOD_VIEW_ORTHOGRAPHIC) {
        *x = v->x + 0.5 * v->width + v->scale_x * mlod__dot3(e, v->right);
        *y = v->y + 0.5 * v->height - v->scale_y * mlod__dot3(e, v->up);
        *depth = mlod__dot3(e, v->forward);
    } else {
        d = mlod__length3(e);
        if (!(d > 0.0)) return -1;
        a = mlod__dot3(e, v->right) / d;
        b = mlod__dot3(e, v->up) / d;
        cos_t = mlod__dot3(e, v->forward) / d;
        sin_t = sqrt(a * a + b * b);
        if (sin_t > 0.0) {
            dir_x = a / sin_t;
            dir_y = b / sin_t;
        }
        if ((int)v->kind == MLOD_VIEW_PERSPECTIVE) {
            if (!(cos_t > 0.0)) return -1;
            hi = sin_t / cos_t;
            *x = v->x + 0.5 * v->width + v->scale * 0.5 * (hi + hi) * dir_x;
            *y = v->y + 0.5 * v->height + v->scale * 0.5 * (hi + hi) * -dir_y;
            *depth = mlod__dot3(e, v->forward);
        } else {
            if (!(1.0 + cos_t > 0.0) || !(sin_t > 0.0 || cos_t > 0.0)) return -1;
            hi = sin_t / (1.0 + cos_t);
            *x = v->x + 0.5 * v->width * (1.0 + 0.5 * (hi + hi) * dir_x);
            *y = v->y + 0.5 * v->height * (1.0 - 0.5 * (hi + hi) * dir_y);
            *depth = d;
        }
    }
    *sub = found;
    for (s = 0; s < subs; s++) {
        for (k = 0; k < (int)f->subs[s].plane_count; k++)
            if (mlod__outside(f->subs[s].planes[k], sphere)) break;
        if (k == (int)f->subs[s].plane_count) return 1;
    }
    return 0;
}

MLOD__PUBLIC int mlod_view_project(const mlod_view *view, const float point[3], float pixel[2], float *depth)
{
    mlod__pview pv;
    double x, y, z;
    int s, inside;
    if (!point || mlod__view_prepare(view, &pv, NULL) != MLOD_OK) return 0;
    inside = mlod__frame_project(&pv.f, point, &s, &x, &y, &z);
    if (inside < 0) return 0;
    if (pixel) {
        pixel[0] = (float)x;
        pixel[1] = (float)y;
    }
    if (depth) *depth = (float)z;
    return inside;
}

static int mlod__centre_ray(const mlod_view_sub *sub, int kind, double x, double y, double *o, double *dir,
                            double *depth_per_t);

MLOD__PUBLIC int mlod_view_pixel_ray(const mlod_view *view, float x, float y, float origin[3], float direction[3])
{
    mlod__pview pv;
    double o[3], dir[3], per_t, len;
    int k, s;
    if (!origin || !direction || mlod__view_prepare(view, &pv, NULL) != MLOD_OK) return 0;
    if (!(x >= 0.0f && x < (float)view->width && y >= 0.0f && y < (float)view->height)) return 0;
    s = mlod__sub_at(&pv, x, y);
    if (s < 0 || !mlod__centre_ray(&pv.f.subs[s], pv.kind[s], x, y, o, dir, &per_t)) return 0;
    len = mlod__length3(dir);
    for (k = 0; k < 3; k++) {
        origin[k] = (float)(pv.f.eye[k] + o[k]);
        direction[k] = (float)(dir[k] / len);
    }
    return 1;
}

/* --------------------------------------------------------------- atlas -- */

MLOD__PUBLIC void mlod_atlas_destroy(mlod_atlas *atlas)
{
    mlod_allocator a;
    if (!atlas) return;
    a = atlas->allocator;
    mlod__free(&a, atlas->depth);
    mlod__free(&a, atlas->normal);
    mlod__free(&a, atlas->color);
    mlod__free(&a, atlas->ids);
    mlod__free(&a, atlas->dirty);
    mlod__free(&a, atlas->tiles);
    mlod__free(&a, atlas->bands);
    mlod__free(&a, atlas->shown);
    mlod__free(&a, atlas->redraw);
    a.free(a.user, atlas);
}

/* The grid of an atlas for these views and desc, and its bytes; the error
   mlod_atlas_create returns for them, if any. */
typedef struct mlod__atlas_layout {
    uint32_t columns, cell_w, cell_h, bands;
    uint64_t width, height, pixels;
    size_t bytes;
} mlod__atlas_layout;

static mlod_result mlod__atlas_layout_of(const mlod_view *views, uint32_t view_count, const mlod_atlas_desc *desc,
                                         mlod__atlas_layout *L, mlod_error *error);

#define MLOD__BAND_ROWS 64u
/* mlod_atlas.shown: per view, the cut's version, the tree's revision, the
   cut's basis (mlod__tile_current, mlod__tile_patchable) */
#define MLOD__SHOWN 3u

MLOD__PUBLIC mlod_result mlod_atlas_create(const mlod_view *views, uint32_t view_count, const mlod_atlas_desc *desc,
                                           const mlod_allocator *allocator, mlod_atlas **out_atlas, mlod_error *error)
{
    mlod_allocator a = mlod__allocator(allocator);
    mlod_atlas *atlas;
    mlod__atlas_layout L;
    uint32_t v, columns, cell_w, cell_h;
    uint64_t width, height, pixels;
    mlod_result res;
    int ok;
    if (!out_atlas) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "out_atlas is NULL");
    *out_atlas = NULL;
    if ((res = mlod__atlas_layout_of(views, view_count, desc, &L, error)) != MLOD_OK) return res;
    columns = L.columns;
    cell_w = L.cell_w;
    cell_h = L.cell_h;
    width = L.width;
    height = L.height;
    pixels = L.pixels;
    atlas = (mlod_atlas *)a.alloc(a.user, sizeof(mlod_atlas));
    if (!atlas) return mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "out of memory creating an atlas");
    memset(atlas, 0, sizeof *atlas);
    atlas->allocator = a;
    atlas->bytes = sizeof *atlas;
    atlas->width = (uint32_t)width;
    atlas->height = (uint32_t)height;
    atlas->view_count = view_count;
    atlas->channels = desc->channels;
    atlas->cell_width = cell_w;
    atlas->cell_height = cell_h;
    atlas->columns = columns;
    atlas->disc_scale = desc->disc_scale == 0.0f ? 1.0f : desc->disc_scale;
    atlas->splat = desc->splat;
    atlas->fill_holes = desc->fill_holes;
    atlas->depth = (float *)mlod__alloc_array(&a, (size_t)pixels, sizeof(float), &atlas->bytes);
    ok = atlas->depth != NULL;
    if (desc->channels & MLOD_ATLAS_NORMAL)
        ok = ok && (atlas->normal = (float *)mlod__alloc_array(&a, (size_t)pixels, 3 * sizeof(float), &atlas->bytes));
    if (desc->channels & MLOD_ATLAS_COLOR)
        ok = ok && (atlas->color = (float *)mlod__alloc_array(&a, (size_t)pixels, 3 * sizeof(float), &atlas->bytes));
    ok = ok && (atlas->tiles = (uint32_t *)mlod__alloc_array(&a, view_count, 4 * sizeof(uint32_t), &atlas->bytes));
    ok = ok && (atlas->bands = (uint32_t *)mlod__alloc_array(&a, (size_t)view_count + 1, sizeof(uint32_t), &atlas->bytes));
    ok = ok && (atlas->shown = (uint64_t *)mlod__alloc_array(&a, view_count, MLOD__SHOWN * sizeof(uint64_t), &atlas->bytes));
    ok = ok && (atlas->redraw = (uint32_t *)mlod__alloc_array(&a, L.bands, sizeof(uint32_t), &atlas->bytes));
    if (!ok) {
        mlod_atlas_destroy(atlas);
        return mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "out of memory for an atlas of %llu x %llu pixels",
                          (unsigned long long)width, (unsigned long long)height);
    }
    MANYLODS_ASSERT(atlas->bytes == L.bytes);
    for (v = 0; v < view_count; v++) atlas->tiles[4 * (size_t)v + 2] = 0; /* no cell yet (tiles are never empty) */
    for (v = 0; v < view_count; v++) { /* cell v holds view w */
        uint32_t w = desc->order ? desc->order[v] : v, *t = atlas->tiles + 4 * (size_t)w;
        if (w >= view_count || t[2] != 0) {
            mlod_atlas_destroy(atlas);
            return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT,
                              "desc->order is not a permutation of the %u views: order[%u] = %u %s", view_count, v,
                              w, w >= view_count ? "is out of range" : "was given before");
        }
        t[0] = (v % columns) * cell_w;
        t[1] = (v / columns) * cell_h;
        t[2] = views[w].width;
        t[3] = views[w].height;
    }
    atlas->bands[0] = 0;
    for (v = 0; v < view_count; v++)
        atlas->bands[v + 1] =
            atlas->bands[v] + (uint32_t)(((uint64_t)atlas->tiles[4 * (size_t)v + 3] + MLOD__BAND_ROWS - 1) / MLOD__BAND_ROWS);
    {
        size_t i;
        for (i = 0; i < (size_t)pixels; i++) atlas->depth[i] = INFINITY;
    }
    if (atlas->normal) memset(atlas->normal, 0, (size_t)pixels * 3 * sizeof(float));
    if (atlas->color) memset(atlas->color, 0, (size_t)pixels * 3 * sizeof(float));
    mlod_atlas_invalidate(atlas);
    *out_atlas = atlas;
    return mlod__succeed(error);
}

static mlod_result mlod__atlas_layout_of(const mlod_view *views, uint32_t view_count, const mlod_atlas_desc *desc,
                                         mlod__atlas_layout *L, mlod_error *error)
{
    uint32_t v, rows;
    uint64_t bands = 0;
    size_t per_pixel, tables;
    memset(L, 0, sizeof *L);
    if (!views || !desc) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "views and desc must not be NULL");
    if (view_count == 0) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "view_count is 0");
    if (desc->channels & ~(uint32_t)(MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR))
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "unknown atlas channel bits 0x%x", desc->channels);
    if (!(desc->disc_scale >= 0.0f && desc->disc_scale <= 1.0f))
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "disc_scale %g is not in (0, 1] (or 0 for 1)",
                          (double)desc->disc_scale);
    if (desc->splat > MLOD_SPLAT_TANGENT)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "splat %u is not an MLOD_SPLAT_*", desc->splat);
    if (desc->fill_holes > 1)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "fill_holes %u is not 0 or 1", desc->fill_holes);
    L->cell_w = L->cell_h = 1;
    for (v = 0; v < view_count; v++) {
        if (views[v].width == 0 || views[v].height == 0)
            return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "view %u has an empty tile", v);
        if (views[v].width > L->cell_w) L->cell_w = views[v].width;
        if (views[v].height > L->cell_h) L->cell_h = views[v].height;
        bands += ((uint64_t)views[v].height + MLOD__BAND_ROWS - 1) / MLOD__BAND_ROWS;
        if (bands >= 0x7fffffffu) return mlod__fail(error, MLOD_ERROR_OVERFLOW, "too many tile rows");
    }
    L->columns = desc->columns;
    if (L->columns == 0) {
        L->columns = (uint32_t)ceil(sqrt((double)view_count));
        if (L->columns == 0) L->columns = 1;
    }
    if (L->columns > view_count) L->columns = view_count;
    rows = (uint32_t)(((uint64_t)view_count + L->columns - 1) / L->columns);
    L->width = (uint64_t)L->columns * L->cell_w;
    L->height = (uint64_t)rows * L->cell_h;
    L->pixels = L->width * L->height;
    if (L->width > 0xffffffffu || L->height > 0xffffffffu || L->pixels > (size_t)-1 / (3 * sizeof(float)))
        return mlod__fail(error, MLOD_ERROR_OVERFLOW, "an atlas of %llu x %llu pixels is too large",
                          (unsigned long long)L->width, (unsigned long long)L->height);
    /* depth and the channels per pixel, the tile and band tables per view */
    per_pixel = sizeof(float) + ((desc->channels & MLOD_ATLAS_NORMAL) ? 3 * sizeof(float) : 0) +
                ((desc->channels & MLOD_ATLAS_COLOR) ? 3 * sizeof(float) : 0);
    L->bands = (uint32_t)bands;
    tables = sizeof(mlod_atlas) + (size_t)view_count * (4 * sizeof(uint32_t) + MLOD__SHOWN * sizeof(uint64_t)) +
             ((size_t)view_count + 1 + bands) * sizeof(uint32_t);
    L->bytes = L->pixels > ((size_t)-1 - tables) / per_pixel ? (size_t)-1 : tables + (size_t)L->pixels * per_pixel;
    return MLOD_OK;
}

MLOD__PUBLIC size_t mlod_atlas_bound(const mlod_view *views, uint32_t view_count, const mlod_atlas_desc *desc)
{
    mlod__atlas_layout L;
    return mlod__atlas_layout_of(views, view_count, desc, &L, NULL) == MLOD_OK ? L.bytes : 0;
}

/* ------------------------------------------------------------- splat -- */

typedef struct mlod__splat_job {
    mlod_atlas *atlas;
    const mlod_tree *tree;
    const mlod_cut *cut;
    const mlod_view *views;
    uint32_t points_per_view; /* ISM */
    uint64_t seed;
    const uint32_t *tasks;    /* NULL: task i draws band i; else band tasks[i] */
    int patch;                /* the bands are patched (mlod__patch_task), not cleared */
} mlod__splat_job;

/* One band of rows of one tile while it is drawn: the tile's pixel
   (col, row) is depth[row * stride + col] (normal and colour 3 floats per
   pixel likewise, or NULL), holding the nearest drawn node's depth and
   channels, and its index in ids[row * id_stride + col] (a MegaViews map,
   mlod_megaviews_render's, has no channels; a band that draws nothing,
   only cleared or begun from a parent's map, may have no ids).  Of nodes
   at equal depths the lower index wins (mlod__wins), so a pixel does not
   depend on the order of the draws. */
typedef struct mlod__band {
    const mlod_tree *tree;
    float *depth, *normal, *color;
    uint32_t *ids;
    size_t stride;               /* pixels from one row to the next */
    size_t id_stride;            /* ids from one row to the next */
    float disc_scale;
    int tangent;                 /* MLOD_SPLAT_TANGENT (mlod__splat_tangent), else MLOD_SPLAT_SPHERES */
    uint32_t row_begin, row_end; /* tile rows */
    const mlod__fdiscs *fast;    /* the view's float filter (mlod__disc_prepare), or NULL: the double path */
    const uint8_t *mask;         /* NULL, or per pixel (id_stride apart): only the pixels whose byte is
                                    set are drawn (a patch, mlod__patch_task) */
} mlod__band;

/* Whether an atlas's splat setting (MLOD_SPLAT_*) draws this tree's nodes
   as tangent discs. */
static int mlod__splat_tangent(uint32_t splat, const mlod_tree *tree)
{
    return splat == MLOD_SPLAT_TANGENT || (splat == MLOD_SPLAT_AUTO && tree->cones != NULL);
}

/* Set a tile pixel to the node: its depth, index and channels. */
static void mlod__band_set(const mlod__band *band, uint32_t row, uint32_t col, float depth, uint32_t node)
{
    size_t at = (size_t)row * band->stride + col;
    int k;
    band->depth[at] = depth;
    if (band->ids) band->ids[(size_t)row * band->id_stride + col] = node;
    for (k = 0; k < 3 && band->normal; k++) band->normal[3 * at + k] = band->tree->cones[4 * (size_t)node + k];
    for (k = 0; k < 3 && band->color; k++) band->color[3 * at + k] = band->tree->colors[3 * (size_t)node + k];
}

/* Whether a node drawn at depth takes a pixel that holds node `held` at
   depth `old`: it is nearer, or as near with a lower index (0 or 1,
   without a branch).  The pixel's value is then the least (depth, node)
   of its draws in that order, whatever order they come in.  An empty
   pixel holds +inf and node 0: no depth is less, and a node at +inf,
   were there one, takes no pixel.  The shaders keep the same minimum with
   atomics (shaders/splat_draw.comp and mv_draw.comp, plot). */
MLOD__FORCE_INLINE uint32_t mlod__wins(float depth, uint32_t node, float old, uint32_t held)
{
    return (uint32_t)(depth < old) | ((uint32_t)(depth == old) & (uint32_t)(node < held));
}

/* Keep the node's depth, index and channels at a tile pixel if it wins there. */
static void mlod__plot(const mlod__band *band, uint32_t row, uint32_t col, float depth, uint32_t node)
{
    size_t at = (size_t)row * band->stride + col;
    if (band->mask && !band->mask[(size_t)row * band->id_stride + col]) return;
    if (mlod__wins(depth, node, band->depth[at], band->ids[(size_t)row * band->id_stride + col]))
        mlod__band_set(band, row, col, depth, node);
}

/* mlod__plot where cond (0 or 1) holds.  A band of depth and ids alone
   takes it as a select, not a branch: whether a pixel centre lies in a
   small disc, and whether it wins, are hard to predict. */
MLOD__FORCE_INLINE void mlod__plot_if(const mlod__band *band, uint32_t row, uint32_t col, float depth, uint32_t node,
                          uint32_t cond)
{
    size_t at = (size_t)row * band->stride + col, id_at = (size_t)row * band->id_stride + col;
    float old;
    uint32_t mask, depth_bits, old_bits;
    if (band->mask) cond &= (uint32_t)(band->mask[id_at] != 0);
    if (band->normal || band->color) {
        if (cond) mlod__plot(band, row, col, depth, node);
        return;
    }
    old = band->depth[at];
    mask = 0u - (cond & mlod__wins(depth, node, old, band->ids[id_at]));
    memcpy(&depth_bits, &depth, sizeof depth_bits);
    memcpy(&old_bits, &old, sizeof old_bits);
    old_bits = (depth_bits & mask) | (old_bits & ~mask);
    memcpy(&band->depth[at], &old_bits, sizeof old_bits);
    band->ids[id_at] = (node & mask) | (band->ids[id_at] & ~mask);
}


/* ---------------------------------------------------- tangent discs -- */

/* The ray through tile position (x, y) (a pixel's centre: col + 0.5,
   row + 0.5) in sub-projection sub of this kind, in double, relative to
   the eye: origin eye + o (orthographic: on the plane through the eye;
   else o = 0), direction dir (not unit; mlod_view_pixel_ray normalises
   it), and the factor that turns the ray's parameter into depth: 1 + q
   for paraboloids (|dir| in exact arithmetic), else 1 (dir.w).  The
   position's offsets are multiplied by the reciprocal of the scale.  0
   when the position lies outside a paraboloid's disc. */
/* The direction of the paraboloid sub-projection's position (x, y) in tile
   pixels, at any distance off the axis: the inverse stereographic
   projection, times 1 + q (returned; q <= 1 within the paraboloid's disc). */
static double mlod__paraboloid_dir(const mlod_view_sub *sub, double x, double y, double *dir)
{
    double px = (x - sub->x) * (2.0 / sub->width) - 1.0, py = 1.0 - (y - sub->y) * (2.0 / sub->height);
    double q = px * px + py * py;
    int k;
    for (k = 0; k < 3; k++) dir[k] = 2.0 * px * sub->right[k] + 2.0 * py * sub->up[k] + (1.0 - q) * sub->forward[k];
    return q;
}

/* GLSL twin: centre_ray */
static int mlod__centre_ray(const mlod_view_sub *sub, int kind, double x, double y, double *o, double *dir,
                            double *depth_per_t)
{
    double px, py, q;
    int k;
    for (k = 0; k < 3; k++) o[k] = 0.0;
    *depth_per_t = 1.0;
    if (kind == MLOD_VIEW_PERSPECTIVE) {
        double inv = 1.0 / sub->scale;
        px = (x - (sub->x + 0.5 * sub->width)) * inv;
        py = ((sub->y + 0.5 * sub->height) - y) * inv;
        for (k = 0; k < 3; k++) dir[k] = sub->forward[k] + px * sub->right[k] + py * sub->up[k];
    } else if (kind == MLOD_VIEW_ORTHOGRAPHIC) {
        px = (x - (sub->x + 0.5 * sub->width)) * (1.0 / sub->scale_x);
        py = ((sub->y + 0.5 * sub->height) - y) * (1.0 / sub->scale_y);
        for (k = 0; k < 3; k++) {
            o[k] = px * sub->right[k] + py * sub->up[k];
            dir[k] = sub->forward[k];
        }
    } else {
        q = mlod__paraboloid_dir(sub, x, y, dir);
        if (!(q <= 1.0)) return 0;
        *depth_per_t = 1.0 + q;
    }
    return 1;
}

/* Whether the node draws as a tangent disc: its cone's half-angle is
   below pi (it has an axis). */
static int mlod__has_plane(const float *cone)
{
    return (double)cone[3] < MLOD__PI;
}

/* Where the ray eye + o + t dir (mlod__centre_ray) meets the plane through
   the sphere's centre (x = centre - eye) whose normal is the cone's axis:
   *t = n.(x - o) / n.dir; returns whether that point, o + t dir, lies
   within rr of the centre (|o + t dir - x|^2 <= rr^2) in front of the eye
   (t > 0; orthographic views: anywhere on the line). */
/* GLSL twin: plane_hit */
static int mlod__plane_hit(const double *x, const float *cone, const double *o, const double *dir, double rr,
                           int ortho, double *t)
{
    double n[3], w[3], e[3];
    int k;
    for (k = 0; k < 3; k++) {
        n[k] = cone[k];
        w[k] = x[k] - o[k];
    }
    *t = mlod__dot3(n, w) / mlod__dot3(n, dir);
    for (k = 0; k < 3; k++) e[k] = (o[k] + *t * dir[k]) - x[k];
    return (ortho || *t > 0.0) && mlod__dot3(e, e) <= rr * rr;
}

/* A point's depth (relative to the eye) as sub-projection kind measures
   it: z along forward (perspective, orthographic), else its distance. */
static double mlod__view_depth(int kind, const mlod_view_sub *sub, const double *x)
{
    return kind == MLOD_VIEW_PARABOLOID ? mlod__length3(x) : mlod__dot3(x, sub->forward);
}

/* MLOD_SPLAT_TANGENT at tile pixel (col, row) of sub-projection s: whether
   the ray through its centre meets the node's tangent disc (the plane
   through the sphere's centre normal to the cone's axis, within the
   sphere's radius times ds of the centre, in front of the eye but for an
   orthographic view) and, if so, the depth there in *depth: t times the
   depth per unit of t (mlod__centre_ray), z along the axis for
   perspective and orthographic views, the distance for paraboloids. */
/* GLSL twin: tangent_hit */
static int mlod__tangent_hit(const mlod__pview *pv, int s, const float *sphere, const float *cone, float ds,
                             uint32_t col, uint32_t row, float *depth)
{
    double o[3], dir[3], x[3], t, per_t;
    int k;
    if (!mlod__centre_ray(&pv->f.subs[s], pv->kind[s], col + 0.5, row + 0.5, o, dir, &per_t)) return 0;
    for (k = 0; k < 3; k++) x[k] = (double)sphere[k] - pv->f.eye[k];
    if (!mlod__plane_hit(x, cone, o, dir, (double)sphere[3] * (double)ds, pv->kind[s] == MLOD_VIEW_ORTHOGRAPHIC, &t))
        return 0;
    *depth = (float)(t * per_t);
    return 1;
}

/* Nodes a filtered draw takes at once (mlod__draw_filtered): enough
   independent lanes for the processor to overlap their long chains of
   divisions and square roots. */
#define MLOD__DRAW_CHUNK 64u

#ifdef MLOD__VD
/* Two rows of four floats (a, b) as four pairs of doubles: out[k] holds
   a[k] in lane 0 and b[k] in lane 1 (conversions: exact). */
MLOD__FORCE_INLINE void mlod__vd_pairs(const float *a, const float *b, mlod__vd *out)
{
#if MLOD__SIMD_X86
    __m128 la = _mm_loadu_ps(a), lb = _mm_loadu_ps(b), lo = _mm_unpacklo_ps(la, lb), hi = _mm_unpackhi_ps(la, lb);
    out[0] = _mm_cvtps_pd(lo);
    out[1] = _mm_cvtps_pd(_mm_movehl_ps(lo, lo));
    out[2] = _mm_cvtps_pd(hi);
    out[3] = _mm_cvtps_pd(_mm_movehl_ps(hi, hi));
#else
    int k;
    for (k = 0; k < 4; k++) out[k] = MLOD__DPAIR(a[k], b[k]);
#endif
}
#endif

/* mlod__tangent_hit for nodes[i] at tile pixel (cols[i], rows[i]) (whole
   numbers, as floats), i < n <= MLOD__DRAW_CHUNK, in a perspective or
   paraboloid sub-projection s: bit 0 of hit[i] and depth[i]; bit 1 of
   hit[i]: mlod__has_plane (below, with the vector lanes: VECTOR LANES at
   the end). */
static void mlod__tangent_hits(const mlod__pview *pv, int s, const mlod_tree *tree, const uint32_t *nodes,
                               const float *cols, const float *rows, uint32_t n, float ds, uint8_t *hit, float *depth);

/* The depth of the sphere's centre in sub-projection s (as
   mlod__image_discs measures it). */
static float mlod__centre_depth(const mlod__pview *pv, int s, const float *sphere)
{
    double x[3];
    int k;
    for (k = 0; k < 3; k++) x[k] = (double)sphere[k] - pv->f.eye[k];
    return (float)mlod__view_depth(pv->kind[s], &pv->f.subs[s], x);
}

/* Draw the disc into the band, clipped to tile columns [columns[0],
   columns[1]) and rows [rows[0], rows[1]) (a sub-tile, see mlod_view_sub):
   the pixels whose centre lies in it, at its depth, or with a band of
   tangent discs, those of them whose centre's ray meets the node's tangent
   disc, at that point's depth (a node without a cone axis: its disc). */
static void mlod__raster_disc(const mlod__band *band, const mlod__pview *pv, int s, const mlod__disc *disc,
                              uint32_t node, const uint32_t *columns, const uint32_t *rows)
{
    double radius = disc->radius * (double)band->disc_scale, r2 = radius * radius;
    double y0 = floor(disc->y - radius), y1 = ceil(disc->y + radius);
    double x0 = floor(disc->x - radius), x1 = ceil(disc->x + radius);
    uint32_t row, col, rb, re, cb, ce, col_begin = columns[0], col_end = columns[1];
    uint32_t row_begin = rows[0] < band->row_begin ? band->row_begin : rows[0];
    uint32_t row_end = rows[1] > band->row_end ? band->row_end : rows[1];
    float depth = (float)disc->depth;
    const float *sphere = NULL, *cone = NULL;
    int hit = 0, plane = 0;
    if (!(disc->radius < 1e9) || !isfinite(disc->x) || !isfinite(disc->y)) return;
    if (row_begin >= row_end) return;
    if (!band->tangent && band->disc_scale >= 1.0f && radius < MLOD__SMALL_DISC) {
        /* A small disc (most of them, at epsilon 1): every pixel centre but the one of the pixel holding the
           disc's centre is 0.5 or more away along a row or a column, so its squared distance rounds to at
           least 0.25 (1 - 2^-50) > r2 (radius below 0.5 - 2^-30): only that pixel can be in, and when it is
           not, the rule below plots it all the same (the same pixel, within the same rows and columns).  The
           loops' result. */
        if (disc->x >= col_begin && disc->x < col_end && disc->y >= row_begin && disc->y < row_end)
            mlod__plot(band, (uint32_t)floor(disc->y), (uint32_t)floor(disc->x), depth, node);
        return;
    }
    if (band->tangent) { /* the pixel centres in the disc whose ray meets the tangent disc; no rule for none */
        sphere = band->tree->spheres + 4 * (size_t)node;
        cone = band->tree->cones + 4 * (size_t)node;
        plane = mlod__has_plane(cone);
    }
    rb = y0 < row_begin ? row_begin : (y0 >= row_end ? row_end : (uint32_t)y0);
    re = y1 > row_end ? row_end : (y1 <= row_begin ? row_begin : (uint32_t)y1);
    cb = x0 < col_begin ? col_begin : (x0 >= col_end ? col_end : (uint32_t)x0);
    ce = x1 > col_end ? col_end : (x1 <= col_begin ? col_begin : (uint32_t)x1);
    if (plane && pv->kind[s] != MLOD_VIEW_ORTHOGRAPHIC) { /* the pixels in the disc, their rays in lanes */
        float fc[MLOD__DRAW_CHUNK], fr[MLOD__DRAW_CHUNK], at[MLOD__DRAW_CHUNK];
        uint32_t ids[MLOD__DRAW_CHUNK], m = 0, j;
        uint8_t in[MLOD__DRAW_CHUNK];
        for (row = rb; row < re; row++) {
            double dy = row + 0.5 - disc->y;
            for (col = cb; col < ce; col++) {
                double dx = col + 0.5 - disc->x;
                fc[m] = (float)col; /* below 2^24: the sub-tiles' bounds */
                fr[m] = (float)row;
                ids[m] = node;
                m += dx * dx + dy * dy <= r2 && (!band->mask || band->mask[(size_t)row * band->id_stride + col]);
                if (m == MLOD__DRAW_CHUNK || (m > 0 && row + 1 == re && col + 1 == ce)) {
                    mlod__tangent_hits(pv, s, band->tree, ids, fc, fr, m, band->disc_scale, in, at);
                    for (j = 0; j < m; j++) mlod__plot_if(band, (uint32_t)fr[j], (uint32_t)fc[j], at[j], node, in[j] & 1u);
                    m = 0;
                }
            }
        }
        return;
    }
    for (row = rb; row < re; row++) {
        double dy = row + 0.5 - disc->y;
        for (col = cb; col < ce; col++) {
            double dx = col + 0.5 - disc->x;
            float at = depth;
            uint32_t in = dx * dx + dy * dy <= r2;
            if (in && plane) in = (uint32_t)mlod__tangent_hit(pv, s, sphere, cone, band->disc_scale, col, row, &at);
            mlod__plot_if(band, row, col, at, node, in);
            hit |= (int)in;
        }
    }
    /* sphere discs, no pixel centre in the disc: at disc_scale 1, the pixel holding its centre */
    if (!hit && !band->tangent && band->disc_scale >= 1.0f && disc->x >= col_begin && disc->x < col_end && disc->y >= row_begin &&
        disc->y < row_end)
        mlod__plot(band, (uint32_t)floor(disc->y), (uint32_t)floor(disc->x), depth, node);
}

/* Draw nodes[0 .. count - 1], each of which reaches sub-projection s, in
   order, by the double path: MLOD__LANES images at a time. */
static void mlod__draw_exact(const mlod__band *band, const mlod__pview *pv, int s, const uint32_t *nodes,
                             uint32_t count)
{
    double c[MLOD__LANES][3], r[MLOD__LANES];
    mlod__disc disc[MLOD__LANES];
    int bounded[MLOD__LANES], k;
    uint32_t i, l;
    for (i = 0; i < count; i += MLOD__LANES) {
        uint32_t lanes = count - i < MLOD__LANES ? count - i : MLOD__LANES;
        for (l = 0; l < lanes; l++) {
            const float *sphere = band->tree->spheres + 4 * (size_t)nodes[i + l];
            for (k = 0; k < 3; k++) c[l][k] = sphere[k];
            r[l] = sphere[3];
        }
        mlod__image_discs(pv, s, (const double (*)[3])c, r, disc, bounded, lanes);
        for (l = 0; l < lanes; l++)
            if (bounded[l]) mlod__raster_disc(band, pv, s, &disc[l], nodes[i + l], pv->columns[s], pv->rows[s]);
    }
}

/* mlod__node_distance of a list of nodes (defined with MegaViews, below,
   where its GLSL twin's order puts it). */
static void mlod__node_distances(const mlod_tree *scene, const uint32_t *nodes, uint32_t n, const double *centre,
                                 float *out);

/* Draw n <= MLOD__DRAW_CHUNK nodes into the band, in order, in each
   sub-projection their spheres reach (with the vector lanes: VECTOR LANES
   at the end). */
static void mlod__draw_nodes(const mlod__band *band, const mlod__pview *pv, const uint32_t *nodes, uint32_t n);


/* A band over the whole tile of one view of the atlas. */
static void mlod__tile_band(mlod_atlas *atlas, const mlod_tree *tree, uint32_t view, mlod__band *band)
{
    const uint32_t *tile = atlas->tiles + 4 * (size_t)view;
    size_t origin = (size_t)tile[1] * atlas->width + tile[0];
    band->tree = tree;
    band->depth = atlas->depth + origin;
    band->normal = atlas->normal ? atlas->normal + 3 * origin : NULL;
    band->color = atlas->color ? atlas->color + 3 * origin : NULL;
    band->ids = atlas->ids ? atlas->ids + origin : NULL; /* (mlod__atlas_ids) */
    band->id_stride = atlas->width;
    band->fast = NULL;
    band->mask = NULL;
    band->stride = atlas->width;
    band->disc_scale = atlas->disc_scale;
    band->tangent = mlod__splat_tangent(atlas->splat, tree);
    band->row_begin = 0;
    band->row_end = tile[3];
}

/* Empty the band's rows: depth +inf, node 0, channels 0. */
static void mlod__band_clear(const mlod__band *band, uint32_t width)
{
    uint32_t row, col;
    for (row = band->row_begin; row < band->row_end; row++) {
        size_t at = (size_t)row * band->stride;
        for (col = 0; col < width; col++) band->depth[at + col] = INFINITY;
        if (band->ids) memset(band->ids + (size_t)row * band->id_stride, 0, sizeof(uint32_t) * width);
        if (band->normal) memset(band->normal + 3 * at, 0, 3 * sizeof(float) * width);
        if (band->color) memset(band->color + 3 * at, 0, 3 * sizeof(float) * width);
    }
}

/* Which view and rows a band task covers; clears those rows (not for a
   patch). */
static uint32_t mlod__band_begin(const mlod__splat_job *job, uint32_t index, mlod__band *band)
{
    mlod_atlas *atlas = job->atlas;
    uint32_t lo = 0, hi = atlas->view_count, view, height;
    if (job->tasks) index = job->tasks[index];
    while (hi - lo > 1) { /* the view whose bands hold index */
        uint32_t mid = lo + (hi - lo) / 2;
        if (atlas->bands[mid] <= index)
            lo = mid;
        else
            hi = mid;
    }
    view = lo;
    mlod__tile_band(atlas, job->tree, view, band);
    height = band->row_end;
    band->row_begin = (index - atlas->bands[view]) * MLOD__BAND_ROWS;
    band->row_end = (uint64_t)band->row_begin + MLOD__BAND_ROWS > height ? height : band->row_begin + MLOD__BAND_ROWS;
    if (!job->patch) mlod__band_clear(band, atlas->tiles[4 * (size_t)view + 2]);
    return view;
}

/* A draw task's band (mlod__band_begin), its view prepared and the
   splat's float filter set up for it in *fast; returns the view. */
static uint32_t mlod__draw_begin(const mlod__splat_job *job, uint32_t index, mlod__band *band, mlod__pview *pv,
                                 mlod__fdiscs *fast)
{
    uint32_t view = mlod__band_begin(job, index, band);
    mlod__view_prepare(&job->views[view], pv, NULL);
    mlod__fast_prepare(pv, 1.0); /* the planes' float filter (mlod__draw_nodes; epsilon plays no part there) */
    if (mlod__disc_prepare(pv, fast)) band->fast = fast;
    return view;
}

/* Draw a view's cut (its entries not culled) into the band,
   MLOD__DRAW_CHUNK nodes at a time, in order. */
static void mlod__draw_cut(const mlod__band *band, const mlod__pview *pv, const mlod_cut_view *cv)
{
    uint32_t i, batch[MLOD__DRAW_CHUNK], n = 0;
    for (i = 0; i < cv->count; i++) {
        if (cv->status[i] == MLOD_STATUS_CULLED) continue;
        batch[n++] = cv->nodes[i];
        if (n == MLOD__DRAW_CHUNK) {
            mlod__draw_nodes(band, pv, batch, n);
            n = 0;
        }
    }
    mlod__draw_nodes(band, pv, batch, n);
}

static void mlod__splat_task(void *context, uint32_t index)
{
    const mlod__splat_job *job = (const mlod__splat_job *)context;
    mlod__band band;
    mlod__pview pv;
    mlod__fdiscs fast;
    uint32_t view = mlod__draw_begin(job, index, &band, &pv, &fast);
    mlod_cut_view cv = mlod_cut_get(job->cut, view);
    mlod__draw_cut(&band, &pv, &cv);
}

/* The marked pixels of a patch, by blocks (at most MLOD__CONES), each as
   a cone of directions: axis (unit) and the cosine and sine of its
   half-angle g, widened by 3 / width (mlod__patch_outside). */
#define MLOD__CONES 16
typedef struct mlod__cones {
    uint32_t count;                             /* the blocks with a marked pixel */
    double axis[MLOD__CONES + 1][3], cs[MLOD__CONES + 1][2]; /* theirs, then the whole band's */
} mlod__cones;

/* The cones of the marked pixels' centres (the band's mask, its rows, the
   tile's `width` columns) in blocks of a quarter of the band's width and
   rows, for a view of one square paraboloid sub-projection.  0 where they
   cannot serve: another view, a disc_scale above 1, a half-angle of pi / 2
   or more. */
static int mlod__marked_cones(const mlod__pview *pv, const mlod__band *band, uint32_t width, mlod__cones *out)
{
    const mlod_view_sub *sub = &pv->f.subs[0];
    uint32_t rows = band->row_end - band->row_begin, bw = (width + 3) / 4, bh = (rows + 3) / 4, b;
    out->count = 0;
    if (pv->sub_count != 1 || pv->kind[0] != MLOD_VIEW_PARABOLOID || sub->width != sub->height ||
        sub->scale != 0.5 * sub->width || !(band->disc_scale <= 1.0f))
        return 0;
    for (b = 0; b <= MLOD__CONES; b++) { /* the band's blocks, then the whole band (held after them) */
        uint32_t r0 = b < MLOD__CONES ? band->row_begin + (b / 4) * bh : band->row_begin;
        uint32_t c0 = b < MLOD__CONES ? (b % 4) * bw : 0, h = b < MLOD__CONES ? bh : rows, w = b < MLOD__CONES ? bw : width;
        uint32_t row, col, pass, marked = 0;
        double sum[3] = {0.0, 0.0, 0.0}, len, lowest = 1.0, gamma, *axis = out->axis[out->count];
        int k;
        for (pass = 0; pass < 2; pass++) { /* the axis, then the widest angle from it */
            for (row = r0; row < r0 + h && row < band->row_end; row++)
                for (col = c0; col < c0 + w && col < width; col++) {
                    double d[3], n;
                    if (!band->mask[(size_t)row * band->id_stride + col]) continue;
                    mlod__paraboloid_dir(sub, col + 0.5, row + 0.5, d);
                    n = mlod__length3(d);
                    for (k = 0; k < 3; k++) d[k] /= n;
                    if (pass == 0) {
                        for (k = 0; k < 3; k++) sum[k] += d[k];
                        marked++;
                    } else {
                        double c = mlod__dot3(d, axis);
                        if (c < lowest) lowest = c;
                    }
                }
            if (marked == 0) break;
            if (pass == 0) {
                len = mlod__length3(sum);
                if (!(len > 0.0)) return 0;
                for (k = 0; k < 3; k++) axis[k] = sum[k] / len;
            }
        }
        if (marked == 0) continue;
        gamma = acos(lowest < -1.0 ? -1.0 : lowest > 1.0 ? 1.0 : lowest) + 3.0 / sub->width + 1e-6;
        if (!(gamma < 0.5 * MLOD__PI)) return 0;
        out->cs[out->count][0] = cos(gamma);
        out->cs[out->count][1] = sin(gamma);
        if (b < MLOD__CONES) out->count++;
    }
    return out->count > 0;
}

/* Whether a node draws no pixel whose centre's direction lies in a cone of
   mlod__marked_cones.  In such a view the disc of a sphere (centre x from
   the eye, radius r < |x|) is the stereographic image of the directions
   within b = asin(r / |x|) of x, exactly: its radial extent from
   tan((t - b) / 2) to tan((t + b) / 2) at angle t off the axis
   (mlod__image_discs), and the projection maps circles of directions to
   circles.  A drawn pixel's centre lies in the disc (scaled by at most 1),
   or, a sphere disc of no pixel centre, within 0.75 pixel of its centre,
   an angle of at most 0.75 * 2 / (width / 2) (the projection stretches
   angles least on its axis, where a pixel spans 2 / (width / 2) radians);
   the cones were widened by that.  So a node whose directions all lie
   more than a cone's half-angle g off its axis draws none of its pixels:
   x.axis < |x| cos(g + b) = t cos g - r sin g, t = |x| cos b, with a
   margin of 2^-30 (t + 2 r) for rounding. */
static int mlod__patch_outside(const mlod__pview *pv, const float *sphere, const mlod__cones *cones)
{
    double x[3], r = sphere[3], d2, t, margin;
    uint32_t i;
    int k;
    for (k = 0; k < 3; k++) x[k] = (double)sphere[k] - pv->f.eye[k];
    d2 = mlod__dot3(x, x);
    if (!(r * r < d2)) return 0;
    t = sqrt(d2 - r * r);
    margin = (t + 2.0 * r) * (1.0 / 1073741824.0);
    for (i = cones->count + 1; i-- > 0;) { /* the band's first (it holds the blocks'): most nodes lie outside it */
        int outside = mlod__dot3(x, cones->axis[i]) < cones->cs[i][0] * t - cones->cs[i][1] * r - margin;
        if (i == cones->count ? outside : !outside) return outside;
    }
    return 1;
}

/* A patch's drawing (mlod__patch_task): its bands, view, cut list, the
   batches waiting, the cones of its marked pixels. */
typedef struct mlod__patch {
    const mlod__band *band, *masked;
    const mlod__pview *pv;
    mlod_cut_view cv;
    uint32_t batch[2][MLOD__DRAW_CHUNK], waiting[2]; /* the suspect entries, the others */
    const mlod__cones *cones;                      /* NULL: no pruning */
} mlod__patch;

/* Add entry j to batch b (0 drawn over the band, 1 over the marked pixels),
   drawing the batch when full. */
static void mlod__patch_add(mlod__patch *p, int b, uint32_t j)
{
    if (p->cv.status[j] == MLOD_STATUS_CULLED) return;
    p->batch[b][p->waiting[b]++] = p->cv.nodes[j];
    if (p->waiting[b] < MLOD__DRAW_CHUNK) return;
    mlod__draw_nodes(b ? p->masked : p->band, p->pv, p->batch[b], p->waiting[b]);
    p->waiting[b] = 0;
}

/* A patch of a band of a tile (mlod_splat, mlod__tile_patchable): the tile
   shows the basic cut of its view at an earlier revision of the tree, and
   the cut holds the basic cut of the same view and epsilon now.  A drawn
   entry that is not suspect (mlod__suspect) was drawn then with the same
   bits, and a pixel whose node is not suspect holds the least of the
   discs of entries that are still drawn, with the same bits.  So the
   pixels whose node is suspect are emptied and marked, the suspect
   entries drawn over the whole band and the others over the marked
   pixels only (those that cannot reach one left out: mlod__patch_outside):
   each pixel gets the least of all the drawn entries' discs (nearest
   depth, then lowest node, whatever the order), what a full redraw gives,
   bit for bit. */
static void mlod__patch_task(void *context, uint32_t index)
{
    const mlod__splat_job *job = (const mlod__splat_job *)context;
    const mlod_tree *tree = job->tree;
    mlod__band band, masked;
    mlod__pview pv;
    mlod__fdiscs fast;
    mlod__patch p;
    mlod__cones cones;
    uint32_t view = mlod__draw_begin(job, index, &band, &pv, &fast), i, end, row, col, marked = 0;
    const uint32_t *tile = job->atlas->tiles + 4 * (size_t)view;
    uint32_t age = mlod__record_age(tree, job->atlas->shown[MLOD__SHOWN * (size_t)view + 1]);
    uint8_t *mask = job->atlas->dirty + (size_t)tile[1] * job->atlas->width + tile[0];
    for (row = band.row_begin; row < band.row_end; row++)
        for (col = 0; col < tile[2]; col++) {
            size_t at = (size_t)row * band.stride + col, id_at = (size_t)row * band.id_stride + col;
            int k, empty = band.depth[at] < INFINITY && mlod__suspect(tree, age, band.ids[id_at]);
            mask[id_at] = (uint8_t)empty;
            if (!empty) continue;
            band.depth[at] = INFINITY;
            band.ids[id_at] = 0;
            for (k = 0; k < 3 && band.normal; k++) band.normal[3 * at + k] = 0.0f;
            for (k = 0; k < 3 && band.color; k++) band.color[3 * at + k] = 0.0f;
            marked++;
        }
    p.cv = mlod_cut_get(job->cut, view);
    if (2 * (size_t)marked > (size_t)(band.row_end - band.row_begin) * tile[2]) {
        /* most pixels marked: the band drawn whole is the same, for less */
        mlod__band_clear(&band, tile[2]);
        mlod__draw_cut(&band, &pv, &p.cv);
        return;
    }
    masked = band;
    masked.mask = mask;
    p.band = &band;
    p.masked = &masked;
    p.pv = &pv;
    p.waiting[0] = p.waiting[1] = 0;
    p.cones = marked && mlod__marked_cones(&pv, &masked, tile[2], &cones) ? &cones : NULL;
    /* the entries whose parent did not change come in runs
       (mlod__unchanged_run: the same test, a climb per run) */
    for (i = 0; i < p.cv.count; i = end) {
        uint32_t j;
        end = mlod__unchanged_run(tree, age, p.cv.nodes, i, p.cv.count);
        if (end == i) { /* suspect */
            mlod__patch_add(&p, 0, i);
            end = i + 1;
            continue;
        }
        for (j = i; marked && j < end; j++) /* (no pixel marked: none to draw them over) */
            if (p.cv.status[j] != MLOD_STATUS_CULLED &&
                (!p.cones || !mlod__patch_outside(&pv, tree->spheres + 4 * (size_t)p.cv.nodes[j], p.cones)))
                mlod__patch_add(&p, 1, j);
    }
    mlod__draw_nodes(&band, &pv, p.batch[0], p.waiting[0]);
    mlod__draw_nodes(&masked, &pv, p.batch[1], p.waiting[1]);
}

/* ISM's point k of view `view` (mlod_splat_ism): the node of the leaf
   that (seed, view, k) picks, uniformly. */
static uint32_t mlod__ism_node(const mlod_tree *tree, uint64_t seed, uint32_t view, uint32_t k)
{
    uint32_t leaf = (uint32_t)(mlod__hash01(seed, 2 + (uint64_t)view, k) * tree->leaf_count);
    return tree->leaf_count - 1 + (leaf < tree->leaf_count ? leaf : tree->leaf_count - 1);
}

/* ISM's points for a view, MLOD__DRAW_CHUNK at a time: each classified
   (the float filter decides most, the exact path the rest; epsilon plays
   no part in whether a leaf is culled), those not culled drawn in order,
   as a cut's drawn entries are. */
static void mlod__ism_task(void *context, uint32_t index)
{
    const mlod__splat_job *job = (const mlod__splat_job *)context;
    const mlod_tree *tree = job->tree;
    mlod__band band;
    mlod__pview pv;
    mlod__fdiscs fast;
    uint32_t view = mlod__draw_begin(job, index, &band, &pv, &fast), k, l, n, m, points[MLOD__DRAW_CHUNK];
    uint8_t status[MLOD__DRAW_CHUNK];
    band.tangent = 0; /* ISM's points are discs, a point covering no pixel centre its pixel (MLOD_SPLAT_SPHERES) */
    for (k = 0; k < job->points_per_view; k += n) {
        n = job->points_per_view - k < MLOD__DRAW_CHUNK ? job->points_per_view - k : MLOD__DRAW_CHUNK;
        for (l = 0; l < n; l++) points[l] = mlod__ism_node(tree, job->seed, view, k + l);
        mlod__classify_list(&pv, tree, points, n, 1.0, status);
        for (l = m = 0; l < n; l++)
            if (status[l] != MLOD_STATUS_CULLED) points[m++] = points[l];
        mlod__draw_nodes(&band, &pv, points, m);
    }
}

static mlod_result mlod__check_splat(const mlod_atlas *atlas, const mlod_tree *tree, const mlod_view *views,
                                     mlod_error *error)
{
    uint32_t v;
    if (!atlas || !tree || !views)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "atlas, tree and views must not be NULL");
    if (atlas->normal && !tree->cones)
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "the atlas has normals and the tree no cones");
    if (atlas->color && !tree->colors)
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "the atlas has colours and the tree none");
    if (atlas->splat == MLOD_SPLAT_TANGENT && !tree->cones)
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "MLOD_SPLAT_TANGENT needs a tree with cones");
    for (v = 0; v < atlas->view_count; v++) {
        mlod__pview pv;
        mlod_error detail;
        mlod_result res = mlod__view_prepare(&views[v], &pv, &detail);
        const uint32_t *t = atlas->tiles + 4 * (size_t)v;
        if (res != MLOD_OK) return mlod__fail(error, res, "view %u: %.160s", v, detail.message);
        if (views[v].width != t[2] || views[v].height != t[3])
            return mlod__fail(error, MLOD_ERROR_MISMATCH, "view %u has a %ux%u tile, the atlas was made for %ux%u", v,
                              views[v].width, views[v].height, t[2], t[3]);
    }
    return MLOD_OK;
}

MLOD__PUBLIC void mlod_atlas_invalidate(mlod_atlas *atlas)
{
    if (!atlas) return;
    memset(atlas->shown, 0, atlas->view_count * MLOD__SHOWN * sizeof(uint64_t));
}

/* Whether the tile of `view` shows what mlod_splat would draw now: it was
   drawn from this version of the view's cut (mlod_cut_view.version: the
   same view, and the same drawn entries in the same order) and no refit
   since changed a node it draws (mlod_tree.changes: sphere, cone, colour).
   A tree of another build is 2^32 or more revisions away, or, in its
   first 2^32, every node of it counts as changed (its record holds its own
   revisions, fewer than the refits it seems to be ahead), unless the tile
   draws nothing, which no tree changes (whatever the record says). */
static int mlod__tile_current(const mlod_atlas *atlas, const mlod_tree *tree, const mlod_cut *cut, uint32_t view)
{
    const uint64_t *shown = atlas->shown + MLOD__SHOWN * (size_t)view;
    uint32_t i, now = (uint32_t)tree->revision, age = mlod__record_age(tree, shown[1]);
    mlod_cut_view cv;
    if (shown[0] != cut->version[view]) return 0; /* versions are never 0: a tile not known */
    if (tree->revision == shown[1]) return 1;
    cv = mlod_cut_get(cut, view);
    for (i = 0; i < cv.count; i++) /* without the record, every node counts as changed */
        if (cv.status[i] != MLOD_STATUS_CULLED && (!age || now - tree->changes[cv.nodes[i]] < age)) return 0;
    return 1;
}

/* The basis a tile drawn now from the cut's list of `view` records: the
   cut's (mlod_cut.basis) where the list is the basic cut of the tree as it
   is, else 0. */
static uint64_t mlod__tile_basis(const mlod_tree *tree, const mlod_cut *cut, uint32_t view)
{
    int basic = (cut->known[view] & MLOD__EXACT) && cut->seen_tree == tree && cut->seen_revision == tree->revision &&
                cut->seen_spheres == tree->spheres && cut->seen_cones == tree->cones;
    return basic ? cut->basis[view] : 0;
}

/* Whether mlod_splat may patch the tile of `view` (mlod__patch_task) rather
   than draw it whole: it shows the basic cut of its view at an earlier
   revision of this tree, refitted fewer than 2^32 times since with its
   record of changes kept, the cut holds the basic cut of the same view and
   epsilon now (the same basis), and the atlas does not fill holes.  Not
   where the last refit changed most of the tree (as mlod__skip_views):
   nearly every pixel would be marked, and a patch costs more than a
   redraw. */
static int mlod__tile_patchable(const mlod_atlas *atlas, const mlod_tree *tree, const mlod_cut *cut, uint32_t view)
{
    const uint64_t *shown = atlas->shown + MLOD__SHOWN * (size_t)view;
    return shown[0] != 0 && shown[2] != 0 && shown[2] == mlod__tile_basis(tree, cut, view) && !atlas->fill_holes &&
           mlod__record_age(tree, shown[1]) > 0 && tree->changes_share <= MLOD__STAMPED_SHARE;
}

static int mlod__fill_tiles(mlod_atlas *atlas, const uint32_t *list, uint32_t count, const mlod_parallel *parallel,
                            size_t *floats);

#define MLOD__ATLAS_CHUNK 16u
static uint32_t mlod__atlas_chunks(const mlod_atlas *atlas) { return (atlas->view_count - 1) / MLOD__ATLAS_CHUNK + 1; }

/* mlod_splat's decision for MLOD__ATLAS_CHUNK views: a current tile
   (mlod__tile_current) is now known to show this revision and basis; the others
   are marked unknown (version 0), to draw: those to patch
   (mlod__tile_patchable) keep their basis, the others, drawn whole, get
   basis 0. */
static void mlod__shown_task(void *context, uint32_t index)
{
    const mlod__splat_job *job = (const mlod__splat_job *)context;
    mlod_atlas *atlas = job->atlas;
    uint32_t v = index * MLOD__ATLAS_CHUNK,
             end = atlas->view_count - v < MLOD__ATLAS_CHUNK ? atlas->view_count : v + MLOD__ATLAS_CHUNK;
    for (; v < end; v++) {
        uint64_t *shown = atlas->shown + MLOD__SHOWN * (size_t)v;
        if (mlod__tile_current(atlas, job->tree, job->cut, v)) { /* as if drawn now */
            shown[1] = job->tree->revision;
            shown[2] = mlod__tile_basis(job->tree, job->cut, v);
            continue;
        }
        if (!mlod__tile_patchable(atlas, job->tree, job->cut, v)) shown[2] = 0;
        shown[0] = 0;
    }
}

/* The atlas's record of the node drawn at each pixel (atlas->ids), which
   mlod_splat and mlod_splat_ism draw with, allocated at their first call
   (4 bytes per pixel, counted in atlas->bytes).  MLOD_OK, or
   MLOD_ERROR_OUT_OF_MEMORY with the atlas as it was. */
static mlod_result mlod__atlas_ids(mlod_atlas *atlas, mlod_error *error)
{
    size_t pixels = (size_t)atlas->width * atlas->height;
    if (atlas->ids) return MLOD_OK;
    atlas->ids = (uint32_t *)mlod__alloc_array(&atlas->allocator, pixels, sizeof(uint32_t), &atlas->bytes);
    if (!atlas->ids)
        return mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "out of memory for the atlas's record of the nodes drawn");
    memset(atlas->ids, 0, pixels * sizeof(uint32_t));
    return MLOD_OK;
}

MLOD__PUBLIC mlod_result mlod_splat(mlod_atlas *atlas, const mlod_tree *tree, const mlod_cut *cut,
                                    const mlod_view *views, const mlod_parallel *parallel, mlod_error *error)
{
    mlod__splat_job job;
    mlod_result res = mlod__check_splat(atlas, tree, views, error);
    if (res != MLOD_OK) return res;
    if (!cut) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "cut is NULL");
    if (cut->view_count != atlas->view_count)
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "the cut has %u views, the atlas %u", cut->view_count,
                          atlas->view_count);
    if (cut->tree_nodes != 0 && cut->tree_nodes != tree->node_count)
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "the cut was computed for another tree");
    if (cut->tree_nodes != 0) { /* lists to draw: for these views, byte for byte */
        uint32_t v;
        for (v = 0; v < cut->view_count; v++)
            if (!(cut->known[v] & MLOD__SEEN) || memcmp(&views[v], &cut->seen[v], sizeof(mlod_view)) != 0)
                return mlod__fail(error, MLOD_ERROR_MISMATCH,
                                  "view %u differs from the view of the cut's last update: update the cut first", v);
    }
    if ((res = mlod__atlas_ids(atlas, error)) != MLOD_OK) return res;
    memset(&job, 0, sizeof job);
    job.atlas = atlas;
    job.tree = tree;
    job.cut = cut;
    job.views = views;
    if (atlas->shown_scale != atlas->disc_scale || atlas->shown_splat != atlas->splat ||
        atlas->shown_fill != atlas->fill_holes)
        mlod_atlas_invalidate(atlas);
    mlod__run(parallel, mlod__atlas_chunks(atlas), mlod__shown_task, &job);
    {
        uint32_t v, b, tasks = 0, patches;
        /* patches need the mask (1 byte per pixel), allocated at the first;
           without it, their tiles are drawn whole */
        for (v = 0; v < atlas->view_count && !atlas->dirty; v++)
            if (atlas->shown[MLOD__SHOWN * (size_t)v] == 0 && atlas->shown[MLOD__SHOWN * (size_t)v + 2] != 0) {
                atlas->dirty = (uint8_t *)mlod__alloc_array(&atlas->allocator, (size_t)atlas->width * atlas->height,
                                                            1, &atlas->bytes);
                if (!atlas->dirty)
                    for (; v < atlas->view_count; v++)
                        if (atlas->shown[MLOD__SHOWN * (size_t)v] == 0) atlas->shown[MLOD__SHOWN * (size_t)v + 2] = 0;
                break;
            }
        atlas->redrawn = atlas->patched = 0;
        for (v = 0; v < atlas->view_count; v++)
            if (atlas->shown[MLOD__SHOWN * (size_t)v] == 0 && atlas->shown[MLOD__SHOWN * (size_t)v + 2] == 0) {
                for (b = atlas->bands[v]; b < atlas->bands[v + 1]; b++) atlas->redraw[tasks++] = b;
                atlas->redrawn++;
            }
        for (v = 0, patches = tasks; v < atlas->view_count; v++)
            if (atlas->shown[MLOD__SHOWN * (size_t)v] == 0 && atlas->shown[MLOD__SHOWN * (size_t)v + 2] != 0) {
                for (b = atlas->bands[v]; b < atlas->bands[v + 1]; b++) atlas->redraw[patches++] = b;
                atlas->patched++;
            }
        job.tasks = atlas->redraw;
        job.patch = 0;
        mlod__run(parallel, tasks, mlod__splat_task, &job);
        job.tasks = atlas->redraw + tasks;
        job.patch = 1;
        mlod__run(parallel, patches - tasks, mlod__patch_task, &job);
        if (atlas->fill_holes && atlas->redrawn) { /* the drawn tiles' holes, the list in place of the bands */
            uint32_t n = 0;
            size_t floats;
            for (v = 0; v < atlas->view_count; v++)
                if (atlas->shown[MLOD__SHOWN * (size_t)v] == 0) atlas->redraw[n++] = v;
            if (!mlod__fill_tiles(atlas, atlas->redraw, n, parallel, &floats))
                return mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY,
                                  "out of memory filling the holes of %u tiles (%zu floats); they stay unfilled, "
                                  "and the next mlod_splat draws them again", n, floats);
        }
        for (v = 0; v < atlas->view_count; v++) {
            uint64_t *shown = atlas->shown + MLOD__SHOWN * (size_t)v;
            if (shown[0] != 0) continue;
            shown[0] = cut->version[v];
            shown[1] = tree->revision;
            shown[2] = mlod__tile_basis(tree, cut, v);
        }
    }
    atlas->shown_scale = atlas->disc_scale;
    atlas->shown_splat = atlas->splat;
    atlas->shown_fill = atlas->fill_holes;
    return mlod__succeed(error);
}

MLOD__PUBLIC mlod_result mlod_splat_ism(mlod_atlas *atlas, const mlod_tree *tree, const mlod_view *views,
                                        uint32_t points_per_view, uint64_t seed, const mlod_parallel *parallel,
                                        mlod_error *error)
{
    mlod__splat_job job;
    mlod_result res = mlod__check_splat(atlas, tree, views, error);
    if (res != MLOD_OK) return res;
    if ((res = mlod__atlas_ids(atlas, error)) != MLOD_OK) return res;
    memset(&job, 0, sizeof job);
    mlod_atlas_invalidate(atlas);
    job.atlas = atlas;
    job.tree = tree;
    job.views = views;
    job.points_per_view = points_per_view;
    job.seed = seed;
    mlod__run(parallel, atlas->bands[atlas->view_count], mlod__ism_task, &job);
    return mlod__succeed(error);
}

/* ---------------------------------------------------------- pull-push -- */

typedef struct mlod__fill_job {
    mlod_atlas *atlas;
    float *scratch;
    size_t *tile_scratch; /* per tile filled: first float of its pyramid */
    uint32_t values;      /* floats per pixel: depth + channels */
    const uint32_t *list; /* the views to fill, NULL: all */
} mlod__fill_job;

/* Floats of a w x h tile's coarser pyramid levels, values per pixel. */
static size_t mlod__pyramid_floats(uint32_t w, uint32_t h, uint32_t values)
{
    size_t total = 0;
    while (w > 1 || h > 1) {
        w = (uint32_t)(((uint64_t)w + 1) / 2);
        h = (uint32_t)(((uint64_t)h + 1) / 2);
        total += (size_t)w * h * (values + 1);
    }
    return total;
}

/* Pointer to value v of pixel (x, y) of the tile itself. */
static float *mlod__tile_value(mlod_atlas *atlas, const uint32_t *tile, uint32_t x, uint32_t y, uint32_t v)
{
    size_t at = (size_t)(tile[1] + y) * atlas->width + tile[0] + x;
    if (v == 0) return atlas->depth + at;
    if (v <= 3 && atlas->normal) return atlas->normal + 3 * at + (v - 1);
    return atlas->color + 3 * at + (v - (atlas->normal ? 4 : 1));
}

static void mlod__fill_task(void *context, uint32_t index)
{
    const mlod__fill_job *job = (const mlod__fill_job *)context;
    mlod_atlas *atlas = job->atlas;
    uint32_t view = job->list ? job->list[index] : index;
    const uint32_t *tile = atlas->tiles + 4 * (size_t)view;
    uint32_t values = job->values, stride = values + 1, w = tile[2], h = tile[3], levels = 0, level;
    float *pyramid = job->scratch + job->tile_scratch[index], *level_at[40];
    uint32_t lw[40], lh[40];
    /* pull: each coarser pixel is the mean of its non-empty children;
       a pixel is (weight, values...), weight 0 when empty */
    lw[0] = w;
    lh[0] = h;
    level_at[0] = NULL;
    while (lw[levels] > 1 || lh[levels] > 1) {
        uint32_t x, y, cw = (uint32_t)(((uint64_t)lw[levels] + 1) / 2),
                 ch = (uint32_t)(((uint64_t)lh[levels] + 1) / 2);
        float *dst = levels == 0 ? pyramid : level_at[levels] + (size_t)lw[levels] * lh[levels] * stride;
        for (y = 0; y < ch; y++)
            for (x = 0; x < cw; x++) {
                float *p = dst + ((size_t)y * cw + x) * stride;
                uint32_t dx, dy, v;
                memset(p, 0, stride * sizeof(float));
                for (dy = 0; dy < 2; dy++)
                    for (dx = 0; dx < 2; dx++) {
                        uint32_t sx = 2 * x + dx, sy = 2 * y + dy;
                        if (sx >= lw[levels] || sy >= lh[levels]) continue;
                        if (levels == 0) {
                            if (!isfinite(*mlod__tile_value(atlas, tile, sx, sy, 0))) continue;
                            p[0] += 1.0f;
                            for (v = 0; v < values; v++) p[1 + v] += *mlod__tile_value(atlas, tile, sx, sy, v);
                        } else {
                            const float *q = level_at[levels] + ((size_t)sy * lw[levels] + sx) * stride;
                            if (q[0] == 0.0f) continue;
                            p[0] += 1.0f;
                            for (v = 0; v < values; v++) p[1 + v] += q[1 + v];
                        }
                    }
                if (p[0] > 0.0f) {
                    for (v = 0; v < values; v++) p[1 + v] /= p[0];
                    p[0] = 1.0f;
                }
            }
        levels++;
        level_at[levels] = dst;
        lw[levels] = cw;
        lh[levels] = ch;
    }
    /* push: empty pixels take their parent's value, coarse to fine */
    for (level = levels; level-- > 0;) {
        uint32_t x, y, v;
        for (y = 0; y < lh[level]; y++)
            for (x = 0; x < lw[level]; x++) {
                const float *parent = level_at[level + 1] + ((size_t)(y / 2) * lw[level + 1] + x / 2) * stride;
                if (parent[0] == 0.0f) continue;
                if (level == 0) {
                    if (isfinite(*mlod__tile_value(atlas, tile, x, y, 0))) continue;
                    for (v = 0; v < values; v++) *mlod__tile_value(atlas, tile, x, y, v) = parent[1 + v];
                } else {
                    float *p = level_at[level] + ((size_t)y * lw[level] + x) * stride;
                    if (p[0] != 0.0f) continue;
                    memcpy(p, parent, stride * sizeof(float));
                }
            }
    }
}

/* Pull-push on the tiles of views list[0 .. count - 1] (list NULL: every
   view, count = view_count); 0 when out of memory (nothing filled). */
static int mlod__fill_tiles(mlod_atlas *atlas, const uint32_t *list, uint32_t count, const mlod_parallel *parallel,
                            size_t *floats)
{
    mlod__fill_job job;
    size_t total = 0;
    uint32_t i;
    job.atlas = atlas;
    job.list = list;
    job.values = 1 + (atlas->normal ? 3u : 0u) + (atlas->color ? 3u : 0u);
    *floats = 0;
    if (count == 0) return 1;
    job.tile_scratch = (size_t *)mlod__alloc_array(&atlas->allocator, count, sizeof(size_t), NULL);
    if (!job.tile_scratch) return 0;
    for (i = 0; i < count; i++) {
        const uint32_t *tile = atlas->tiles + 4 * (size_t)(list ? list[i] : i);
        job.tile_scratch[i] = total;
        total += mlod__pyramid_floats(tile[2], tile[3], job.values);
    }
    *floats = total;
    job.scratch = (float *)mlod__alloc_array(&atlas->allocator, total, sizeof(float), NULL);
    if (!job.scratch) {
        mlod__free(&atlas->allocator, job.tile_scratch);
        return 0;
    }
    mlod__run(parallel, count, mlod__fill_task, &job);
    mlod__free(&atlas->allocator, job.scratch);
    mlod__free(&atlas->allocator, job.tile_scratch);
    return 1;
}

MLOD__PUBLIC mlod_result mlod_atlas_fill_holes(mlod_atlas *atlas, const mlod_parallel *parallel, mlod_error *error)
{
    uint32_t *list = NULL, count = 0, v;
    size_t floats;
    int ok;
    if (!atlas) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "atlas is NULL");
    if (atlas->fill_holes) { /* the tiles mlod_splat drew or kept are filled already */
        list = (uint32_t *)mlod__alloc_array(&atlas->allocator, atlas->view_count, sizeof(uint32_t), NULL);
        if (!list) return mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "out of memory filling holes");
        for (v = 0; v < atlas->view_count; v++)
            if (atlas->shown[MLOD__SHOWN * (size_t)v] == 0) list[count++] = v;
    }
    ok = mlod__fill_tiles(atlas, list, list ? count : atlas->view_count, parallel, &floats);
    mlod__free(&atlas->allocator, list);
    if (!ok) return mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "out of memory filling holes (%zu floats)", floats);
    if (!atlas->fill_holes) mlod_atlas_invalidate(atlas); /* the filled tiles are not what mlod_splat draws */
    return mlod__succeed(error);
}

/* ------------------------------------------------------- shadow lookups -- */

/* The tile of `view` when it is the frame's size, else NULL. */
/* GLSL twin: lookup_tile */
static const uint32_t *mlod__lookup_tile(const mlod_atlas *atlas, uint32_t view, const mlod_view_frame *frame)
{
    const uint32_t *tile;
    if (!atlas || !frame || view >= atlas->view_count) return NULL;
    tile = atlas->tiles + 4 * (size_t)view;
    return (double)tile[2] == frame->width && (double)tile[3] == frame->height ? tile : NULL;
}

/* The depth the tile holds at its pixel (i, j), clamped into the
   sub-tile's columns [c0, c1) and rows [r0, r1). */
/* GLSL twin: lookup_depth */
static double mlod__lookup_depth(const mlod_atlas *atlas, const uint32_t *tile, double i, double j, const double *c)
{
    if (i < c[0]) i = c[0];
    if (i > c[1] - 1.0) i = c[1] - 1.0;
    if (j < c[2]) j = c[2];
    if (j > c[3] - 1.0) j = c[3] - 1.0;
    return atlas->depth[((size_t)tile[1] + (size_t)j) * atlas->width + tile[0] + (size_t)i];
}

/* Sub-projection s's pixels: columns c[0] .. c[1] - 1, rows c[2] .. c[3] - 1,
   as mlod__view_prepare rounds them. */
/* GLSL twin: lookup_sub_pixels */
static void mlod__lookup_sub_pixels(const mlod_view_sub *sub, double *c)
{
    c[0] = (double)(uint32_t)sub->x;
    c[1] = (double)(uint32_t)(sub->x + sub->width);
    c[2] = (double)(uint32_t)sub->y;
    c[3] = (double)(uint32_t)(sub->y + sub->height);
}

/* GLSL twin: mlod_atlas_lookup */
MLOD__PUBLIC int mlod_atlas_lookup(const mlod_atlas *atlas, uint32_t view, const mlod_view_frame *frame,
                                   const float point[3], float pixel[2], float *depth, float *map_depth)
{
    const uint32_t *tile = mlod__lookup_tile(atlas, view, frame);
    double x, y, z, c[4];
    int s;
    if (!tile || !point || mlod__frame_project(frame, point, &s, &x, &y, &z) != 1) return 0;
    x = floor(x);
    y = floor(y);
    mlod__lookup_sub_pixels(&frame->subs[s], c);
    if (!(x >= 0.0 && x < (double)tile[2] && y >= 0.0 && y < (double)tile[3])) return 0;
    if (pixel) {
        pixel[0] = (float)x;
        pixel[1] = (float)y;
    }
    if (depth) *depth = (float)z;
    if (map_depth) *map_depth = (float)mlod__lookup_depth(atlas, tile, x, y, c);
    return 1;
}

/* The footprint of mlod_shadow_params at point p (e: p - eye) in
   sub-projection sub (pixels c) at tile position (x, y): the rays of the
   centre of the pixel holding it and of its right neighbour (the left one
   past the sub-tile or the disc), unit directions, |o1 - o0| + |e - o0|
   |d1 - d0|; 0 when neither neighbour has a ray. */
/* GLSL twin: lookup_footprint */
static double mlod__footprint(const mlod_view_sub *sub, const double *c, const double *e, double x, double y)
{
    double o0[3], d0[3], o1[3], d1[3], per_t, l0, l1, oo = 0.0, ee = 0.0, dd = 0.0;
    double cx = floor(x) + 0.5, cy = floor(y) + 0.5;
    int kind = (int)sub->kind, k;
    if (!mlod__centre_ray(sub, kind, cx, cy, o0, d0, &per_t)) return 0.0;
    if (!(cx + 1.0 < c[1] && mlod__centre_ray(sub, kind, cx + 1.0, cy, o1, d1, &per_t)) &&
        !(cx - 1.0 > c[0] && mlod__centre_ray(sub, kind, cx - 1.0, cy, o1, d1, &per_t)))
        return 0.0;
    l0 = mlod__length3(d0);
    l1 = mlod__length3(d1);
    for (k = 0; k < 3; k++) {
        double od = o1[k] - o0[k], ed = e[k] - o0[k], dv = d1[k] / l1 - d0[k] / l0;
        oo += od * od;
        ee += ed * ed;
        dd += dv * dv;
    }
    return sqrt(oo) + sqrt(ee) * sqrt(dd);
}

/* GLSL twin: mlod_atlas_shadow */
MLOD__PUBLIC float mlod_atlas_shadow(const mlod_atlas *atlas, uint32_t view, const mlod_view_frame *frame,
                                     const float point[3], const float normal[3], const mlod_shadow_params *params)
{
    const uint32_t *tile = mlod__lookup_tile(atlas, view, frame);
    const mlod_view_sub *sub;
    double x, y, z, c[4], e[3], bias, slope = 1.0, lit = 0.0, half, x0, x1, y0, y1, i, j, k2;
    int s, k, inside;
    if (!tile || !point || !params || params->filter > MLOD_SHADOW_MAX_FILTER || !(params->bias >= 0.0f) ||
        !(params->bias <= FLT_MAX) || !(params->slope_bias >= 0.0f) || !(params->slope_bias <= FLT_MAX))
        return NAN;
    inside = mlod__frame_project(frame, point, &s, &x, &y, &z);
    if (inside != 1 || !(x >= 0.0 && x < (double)tile[2] && y >= 0.0 && y < (double)tile[3])) return 1.0f;
    sub = &frame->subs[s];
    mlod__lookup_sub_pixels(sub, c);
    for (k = 0; k < 3; k++) e[k] = (double)point[k] - frame->eye[k];
    bias = params->bias;
    if (params->slope_bias > 0.0f) {
        if (normal) {
            double n[3], l[3], nl, nn, ll, cos2, t2;
            for (k = 0; k < 3; k++) {
                n[k] = normal[k];
                l[k] = (int)sub->kind == MLOD_VIEW_ORTHOGRAPHIC ? -sub->forward[k] : -e[k];
            }
            nl = mlod__dot3(n, l);
            nn = mlod__dot3(n, n);
            ll = mlod__dot3(l, l);
            cos2 = nl * nl / (nn * ll);
            t2 = 1.0 / cos2 - 1.0; /* tan^2 = 1 / cos^2 - 1: rounding may take it below 0 for a normal facing the eye */
            slope = t2 <= 0.0 ? 0.0 : sqrt(t2);
            if (!(slope <= MLOD_SHADOW_MAX_SLOPE)) slope = MLOD_SHADOW_MAX_SLOPE; /* NaN (a zero normal): the steepest */
        }
        bias += (double)params->slope_bias * mlod__footprint(sub, c, e, x, y) * slope;
    }
    if (params->filter == 0)
        return z > mlod__lookup_depth(atlas, tile, floor(x), floor(y), c) + bias ? 0.0f : 1.0f;
    /* the k x k square [x - k/2, x + k/2] x [y - k/2, y + k/2]: pixel (i, j)
       covers [i, i + 1) x [j, j + 1) */
    half = 0.5 * params->filter;
    x0 = x - half;
    x1 = x + half;
    y0 = y - half;
    y1 = y + half;
    for (j = floor(y0); j < y1; j += 1.0) {
        double wy = (j + 1.0 < y1 ? j + 1.0 : y1) - (j > y0 ? j : y0);
        for (i = floor(x0); i < x1; i += 1.0) {
            double wx = (i + 1.0 < x1 ? i + 1.0 : x1) - (i > x0 ? i : x0);
            if (!(z > mlod__lookup_depth(atlas, tile, i, j, c) + bias)) lit += wx * wy;
        }
    }
    k2 = (double)params->filter * params->filter;
    lit /= k2;
    return (float)(lit < 1.0 ? lit : 1.0);
}

/* ----------------------------------------------------------- choosing N -- */

MLOD__PUBLIC double mlod_mesh_area(const mlod_mesh *mesh)
{
    double total = 0.0;
    uint32_t i;
    if (mlod__check_mesh(mesh, NULL) != MLOD_OK) return 0.0;
    for (i = 0; i < mesh->index_count / 3; i++) total += mlod__triangle_area(mesh, i);
    return total;
}

/* The largest leaf radius whose image in sub-projection s of the view is
   at most epsilon pixels across at distance `closest` (from the eye to the
   leaf's centre), where it magnifies most: a leaf just touching the
   sub-tile's border from outside, beyond the corner of a perspective
   sub-tile or behind the rim of a paraboloid (its centre at angle
   theta0 + asin(r / closest) off the axis), measured in that
   sub-projection alone with no culling (at the border it would be culled,
   or measured in a neighbour whose image is smaller). */
static double mlod__largest_leaf_radius(const mlod__pview *pv, int s, double epsilon, double closest)
{
    const mlod_view_sub *sub = &pv->f.subs[s];
    mlod__pview one;
    double side[3], lo = 0.0, hi = closest, theta0, len;
    int k, step;
    if (pv->kind[s] == MLOD_VIEW_ORTHOGRAPHIC) return epsilon / (2.0 * sub->scale);
    memset(&one, 0, sizeof one);
    for (k = 0; k < 3; k++) one.f.eye[k] = pv->f.eye[k];
    one.f.subs[0] = *sub;
    one.kind[0] = pv->kind[s];
    one.sub_count = 1;
    if (pv->kind[s] == MLOD_VIEW_PERSPECTIVE) {
        double tx = 0.5 * sub->width / sub->scale, ty = 0.5 * sub->height / sub->scale;
        for (k = 0; k < 3; k++) side[k] = tx * sub->right[k] + ty * sub->up[k];
        theta0 = atan(sqrt(tx * tx + ty * ty));
    } else {
        for (k = 0; k < 3; k++) side[k] = sub->right[k];
        theta0 = 0.5 * MLOD__PI;
    }
    len = mlod__length3(side);
    for (step = 0; step < 60; step++) { /* bisection on the radius */
        double r = 0.5 * (lo + hi), theta = theta0 + asin(r / closest), c;
        float sphere[4];
        int culled;
        for (k = 0; k < 3; k++)
            sphere[k] = (float)(pv->f.eye[k] + closest * (cos(theta) * sub->forward[k] + sin(theta) * side[k] / len));
        sphere[3] = (float)r;
        c = mlod__evaluate(&one, sphere, NULL, &culled);
        if (c <= epsilon)
            lo = r;
        else
            hi = r;
    }
    return lo;
}

MLOD__PUBLIC uint32_t mlod_suggest_sample_count(double surface_area, const mlod_view *views, uint32_t view_count,
                                                float epsilon, float radius_scale, double closest)
{
    double radius = INFINITY, n;
    uint32_t v;
    if (!(surface_area > 0.0) || !isfinite(surface_area) || !(epsilon > 0.0f) || !(closest > 0.0) ||
        !isfinite(closest) || !views || view_count == 0)
        return 0;
    if (!(radius_scale > 0.0f)) radius_scale = 1.0f;
    for (v = 0; v < view_count; v++) {
        mlod__pview pv;
        double r;
        int s;
        if (mlod__view_prepare(&views[v], &pv, NULL) != MLOD_OK) return 0;
        for (s = 0; s < pv.sub_count; s++) {
            r = mlod__largest_leaf_radius(&pv, s, epsilon, closest);
            if (r < radius) radius = r;
        }
    }
    if (!(radius > 0.0)) return MANYLODS_MAX_LEAVES;
    n = ceil(surface_area * (radius_scale / radius) * (radius_scale / radius));
    return n >= MANYLODS_MAX_LEAVES ? MANYLODS_MAX_LEAVES : (n < 1.0 ? 1u : (uint32_t)n);
}

/* --------------------------------------------------- choosing the views -- */

/* The radical inverse of n in base 2 (the Halton sequence's first
   coordinate), rotated by `shift` modulo 1: in [0, 1). */
static double mlod__halton2(uint32_t n, double shift)
{
    double scale = 0.5, x = 0.0;
    for (; n > 0; n >>= 1, scale *= 0.5) x += (double)(n & 1u) * scale;
    x += shift;
    return x >= 1.0 ? x - 1.0 : x;
}

/* Position x of a keyed pseudo-random permutation of [0, size): a
   four-round Feistel network on the smallest even number of bits that
   holds size, walked round its cycle until it lands below size (at most
   four steps expected: the bits hold less than 4 size). */
static uint64_t mlod__permute(uint64_t x, uint64_t size, uint64_t key)
{
    uint32_t half = 1, round;
    uint64_t mask;
    while (((uint64_t)1 << (2 * half)) < size) half++;
    mask = ((uint64_t)1 << half) - 1;
    do {
        uint64_t left = x >> half, right = x & mask;
        for (round = 0; round < 4; round++) {
            uint64_t next = left ^ (mlod__mix64(key + 0x9e3779b97f4a7c15ull * (round + 1) + right) & mask);
            left = right;
            right = next;
        }
        x = left << half | right;
    } while (x >= size);
    return x;
}

typedef struct mlod__sample_job {
    const float *importance;
    uint32_t domain_size, sample_count, chain_length;
    uint64_t seed;
    double shift;       /* inverse transform: the seed's rotation */
    const double *cdf;  /* inverse transform: cdf[i] = sum of importance[0 .. i) */
    uint32_t *samples;
    float *weights;
} mlod__sample_job;

#define MLOD__SAMPLE_TASK 1024u

static void mlod__inverse_task(void *context, uint32_t index)
{
    const mlod__sample_job *job = (const mlod__sample_job *)context;
    uint32_t j, end = index * MLOD__SAMPLE_TASK + MLOD__SAMPLE_TASK;
    double total = job->cdf[job->domain_size];
    if (end > job->sample_count || end < index * MLOD__SAMPLE_TASK) end = job->sample_count;
    for (j = index * MLOD__SAMPLE_TASK; j < end; j++) {
        double u = mlod__halton2(j, job->shift), target = u * total;
        uint32_t lo = 0, hi = job->domain_size - 1;
        if (!(total > 0.0)) { /* nothing to follow: uniform, weight 0 */
            double x = floor(u * job->domain_size);
            job->samples[j] = x >= job->domain_size ? job->domain_size - 1 : (uint32_t)x;
            job->weights[j] = 0.0f;
            continue;
        }
        while (lo < hi) { /* the first i with cdf[i + 1] > target: its importance is > 0 */
            uint32_t mid = lo + (hi - lo) / 2;
            if (job->cdf[mid + 1] > target)
                hi = mid;
            else
                lo = mid + 1;
        }
        job->samples[j] = lo;
        job->weights[j] = (float)(total / job->importance[lo]);
    }
}

static void mlod__metropolis_task(void *context, uint32_t index)
{
    const mlod__sample_job *job = (const mlod__sample_job *)context;
    uint32_t j, k, end = index * MLOD__SAMPLE_TASK + MLOD__SAMPLE_TASK;
    if (end > job->sample_count || end < index * MLOD__SAMPLE_TASK) end = job->sample_count;
    for (j = index * MLOD__SAMPLE_TASK; j < end; j++) {
        uint32_t current = 0;
        double f_current = 0.0, sum = 0.0;
        for (k = 0; k < job->chain_length; k++) {
            /* proposal n = j + N k (no two chains share one) is position
               n mod D of the (n / D)-th random permutation of the
               domain: uniform, and distinct while n < D */
            uint64_t n = j + (uint64_t)job->sample_count * k;
            uint32_t proposal = (uint32_t)mlod__permute(n % job->domain_size, job->domain_size,
                                                        mlod__mix64(job->seed + n / job->domain_size));
            double f = job->importance[proposal];
            sum += f;
            /* the first proposal starts the chain; later ones are taken
               with probability min(1, f / f_current) (always from a
               state of importance 0, never into one from a state above) */
            if (k == 0 || f_current == 0.0 || (f > 0.0 && f >= mlod__hash01(job->seed, 1, n) * f_current)) {
                current = proposal;
                f_current = f;
            }
        }
        job->samples[j] = current;
        /* f_current = 0 only where every proposal had importance 0 */
        job->weights[j] = f_current > 0.0 ? (float)((double)job->domain_size * (sum / job->chain_length) / f_current)
                                          : 0.0f;
    }
}

MLOD__PUBLIC size_t mlod_sample_bound(uint32_t domain_size, mlod_sampler method)
{
    size_t entries = (size_t)domain_size + 1;
    if (method == MLOD_SAMPLER_METROPOLIS) return 0;
    if (method != MLOD_SAMPLER_INVERSE_TRANSFORM) return (size_t)-1;
    return entries == 0 || entries > (size_t)-1 / sizeof(double) ? (size_t)-1 : entries * sizeof(double);
}

MLOD__PUBLIC mlod_result mlod_sample(const float *importance, uint32_t domain_size, uint32_t sample_count,
                                      const mlod_sample_params *params, uint32_t *samples, float *weights,
                                      mlod_error *error)
{
    mlod__sample_job job;
    mlod_allocator a;
    double total = 0.0, largest = 0.0, smallest = INFINITY, *cdf = NULL;
    uint32_t i, tasks;
    if (!importance || !params || !samples || !weights)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "importance, params, samples and weights must not be NULL");
    if (params->method != MLOD_SAMPLER_INVERSE_TRANSFORM && params->method != MLOD_SAMPLER_METROPOLIS)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "unknown sampling method %d", (int)params->method);
    if (domain_size == 0 || sample_count == 0)
        return mlod__fail(error, MLOD_ERROR_EMPTY, "%s is 0", domain_size == 0 ? "domain_size" : "sample_count");
    for (i = 0; i < domain_size; i++) {
        double f = importance[i];
        if (!isfinite(f)) return mlod__fail(error, MLOD_ERROR_NON_FINITE, "importance[%u] is not finite", i);
        if (f < 0.0) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "importance[%u] = %g is negative", i, f);
        total += f;
        if (f > largest) largest = f;
        if (f > 0.0 && f < smallest) smallest = f;
    }
    /* the weights are at most this ratio (and its rounding); half of
       FLT_MAX leaves them room */
    if (total > 0.0 && (params->method == MLOD_SAMPLER_INVERSE_TRANSFORM ? total : (double)domain_size * largest) /
                               smallest > 1.7014117331926443e38)
        return mlod__fail(error, MLOD_ERROR_RANGE,
                          "importances from %g to %g (total %g) would give weights beyond float range", smallest,
                          largest, total);
    memset(&job, 0, sizeof job);
    job.importance = importance;
    job.domain_size = domain_size;
    job.sample_count = sample_count;
    job.chain_length = params->chain_length ? params->chain_length : 8;
    job.samples = samples;
    job.weights = weights;
    job.seed = mlod__mix64(params->seed ^ 0x5851f42d4c957f2dull);
    job.shift = mlod__hash01(params->seed, 0, 0);
    tasks = (uint32_t)(((uint64_t)sample_count + MLOD__SAMPLE_TASK - 1) / MLOD__SAMPLE_TASK);
    if (params->method == MLOD_SAMPLER_METROPOLIS) {
        mlod__run(params->parallel, tasks, mlod__metropolis_task, &job);
        return mlod__succeed(error);
    }
    if (mlod_sample_bound(domain_size, MLOD_SAMPLER_INVERSE_TRANSFORM) == (size_t)-1)
        return mlod__fail(error, MLOD_ERROR_OVERFLOW, "a table of %u + 1 doubles does not fit in size_t", domain_size);
    a = mlod__allocator(params->allocator);
    cdf = (double *)mlod__alloc_array(&a, (size_t)domain_size + 1, sizeof(double), NULL);
    if (!cdf) return mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "%zu bytes for the cumulative importance",
                                mlod_sample_bound(domain_size, MLOD_SAMPLER_INVERSE_TRANSFORM));
    cdf[0] = 0.0;
    for (i = 0; i < domain_size; i++) cdf[i + 1] = cdf[i] + importance[i];
    job.cdf = cdf;
    mlod__run(params->parallel, tasks, mlod__inverse_task, &job);
    mlod__free(&a, cdf);
    return mlod__succeed(error);
}

/* ------------------------------------------------------------ MegaViews -- */

/* -------------------------------------------- MegaViews: the view tree -- */

static float mlod__view_half_fov(const mlod_view_set *views, uint32_t i)
{
    if (!views->half_fovs) return views->half_fov > 0.0f ? views->half_fov : (float)(0.5 * MLOD__PI);
    return mlod__scalar_at(views->half_fovs, views->half_fov_stride, i);
}

static mlod_result mlod__check_view_set(const mlod_view_set *views, mlod_error *error)
{
    mlod_result res;
    uint32_t i;
    if (!views) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "views is NULL");
    if (views->count == 0) return mlod__fail(error, MLOD_ERROR_EMPTY, "the view set has no views");
    if (views->count > MANYLODS_MAX_LEAVES)
        return mlod__fail(error, MLOD_ERROR_OVERFLOW, "%u views exceed MANYLODS_MAX_LEAVES", views->count);
    if (!views->eyes) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "the views' eyes are NULL");
    res = mlod__check_floats(views->eyes, views->eye_stride, views->count, 1, "eye", error);
    if (res != MLOD_OK || !views->directions) return res;
    res = mlod__check_floats(views->directions, views->direction_stride, views->count, 0, "direction", error);
    if (res != MLOD_OK) return res;
    for (i = 0; i < views->count; i++) {
        const float *p = mlod__at(views->directions, views->direction_stride, i);
        double n[3] = {p[0], p[1], p[2]};
        if (!(mlod__length3(n) > 0.0))
            return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "direction %u has zero length", i);
    }
    if (views->half_fovs && views->half_fov_stride % sizeof(float))
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "half_fov stride %lu is not a multiple of 4",
                          (unsigned long)views->half_fov_stride);
    if (!views->half_fovs && isnan(views->half_fov))
        return mlod__fail(error, MLOD_ERROR_NON_FINITE, "half_fov is NaN");
    if (!views->half_fovs && views->half_fov != 0.0f && !(views->half_fov > 0.0f && views->half_fov <= (float)MLOD__PI))
        return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "half_fov %g is not 0 or in (0, pi]", views->half_fov);
    for (i = 0; views->half_fovs && i < views->count; i++) {
        float h = mlod__view_half_fov(views, i);
        if (isnan(h)) return mlod__fail(error, MLOD_ERROR_NON_FINITE, "half_fovs[%u] is NaN", i);
        if (!(h > 0.0f && h <= (float)MLOD__PI))
            return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "half_fovs[%u] = %g is not in (0, pi]", i, h);
    }
    return MLOD_OK;
}

/* Each node's smallest and largest half field of view below it, leaves
   from the views. */
static void mlod__view_tree_fovs(mlod_view_tree *tree, const mlod_view_set *views)
{
    const mlod_tree *t = tree->eyes;
    float *f = tree->half_fovs;
    uint32_t n = t->leaf_count, i;
    for (i = 0; i < n; i++) f[2 * (n - 1 + i)] = f[2 * (n - 1 + i) + 1] = mlod__view_half_fov(views, t->leaf_sources[i]);
    for (i = n - 1; i-- > 0;) {
        const float *a = f + 2 * (2 * i + 1), *b = f + 2 * (2 * i + 2);
        f[2 * i] = a[0] < b[0] ? a[0] : b[0];
        f[2 * i + 1] = a[1] > b[1] ? a[1] : b[1];
    }
}

/* The largest float <= x (x finite). */
static float mlod__float_down(double x)
{
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}

/* Each node's floor and spread (mlod_view_tree.floors), children first.
   With a the node's unit axis and c its centre, every eye e below has
   (e - c).a >= floor: a leaf's eye lies within its ball (-rho); an inner
   node's eyes lie, for each child (centre c', unit axis a', radius rho',
   floor h'), at (c' - c).a + (e - c').a' + (e - c').(a - a') >= (c' -
   c).a + h' - rho' |a - a'|, each computed in double with 2^-40 of its
   terms to spare, rounded down.  -inf where the node's cone or largest
   half field of view phi reaches pi, or an axis has no length (no
   floor).  The spread: 2 sin(alpha / 2) bounds |a - n| over the unit
   directions n within the cone, and a view of half field phi > pi/2 sees
   p only where (p - e).n >= -|p - e| sin(phi - pi/2); both rounded up.
   O(nodes); deterministic (no libm trigonometry). */
static void mlod__view_tree_floors(mlod_view_tree *tree)
{
    const mlod_tree *t = tree->eyes;
    float *f = tree->floors;
    uint32_t n = t->leaf_count, i;
    for (i = 2 * n - 1; i-- > 0;) {
        const float *sphere = t->spheres + 4 * (size_t)i, *cone = t->cones + 4 * (size_t)i;
        double axis[3], len, h = INFINITY, sin_half, cos_half, fov = tree->half_fovs[2 * (size_t)i + 1], spread = 2.0;
        int j, k;
        for (k = 0; k < 3; k++) axis[k] = cone[k];
        len = mlod__length3(axis);
        if (cone[3] < MLOD__PI) {
            mlod__sin_cos(0.5 * (double)cone[3], &sin_half, &cos_half);
            spread = 2.0 * sin_half;
        }
        if (fov > 0.5 * MLOD__PI && fov < MLOD__PI) {
            mlod__sin_cos(fov - 0.5 * MLOD__PI, &sin_half, &cos_half);
            spread += sin_half;
        }
        f[2 * i + 1] = mlod__float_up(spread + 1e-15);
        if (!(len > 0.0) || !(cone[3] < MLOD__PI) || !(fov < MLOD__PI)) {
            f[2 * i] = -INFINITY;
            continue;
        }
        if (i >= n - 1) { /* a leaf: its eye within its ball */
            f[2 * i] = -sphere[3];
            continue;
        }
        for (j = 1; j <= 2 && h > -INFINITY; j++) {
            uint32_t c = 2 * i + (uint32_t)j;
            const float *cs = t->spheres + 4 * (size_t)c, *cc = t->cones + 4 * (size_t)c;
            double off[3], caxis[3], clen, turn = 0.0, up, v;
            if (!(f[2 * c] > -INFINITY)) {
                h = -INFINITY;
                break;
            }
            for (k = 0; k < 3; k++) {
                off[k] = (double)cs[k] - sphere[k];
                caxis[k] = cc[k];
            }
            clen = mlod__length3(caxis);
            up = mlod__dot3(off, axis) / len;
            if (cs[3] > 0.0f) {
                double diff[3];
                for (k = 0; k < 3; k++) diff[k] = axis[k] / len - caxis[k] / clen;
                turn = (double)cs[3] * mlod__length3(diff);
            }
            v = up + (double)f[2 * c] - turn;
            v -= (fabs(up) + fabs((double)f[2 * c]) + turn + mlod__length3(off) + cs[3]) / 1099511627776.0;
            if (v < h) h = v;
        }
        f[2 * i] = h > -INFINITY ? mlod__float_down(h) : -INFINITY;
    }
}

/* The view set as radius-0 points with the directions as normals. */
static mlod_points mlod__view_points(const mlod_view_set *views, const float *zeros)
{
    mlod_points p;
    memset(&p, 0, sizeof p);
    p.positions = views->eyes;
    p.position_stride = views->eye_stride;
    p.count = views->count;
    p.normals = views->directions;
    p.normal_stride = views->direction_stride;
    p.radii = zeros;
    return p;
}

/* The view tree's leaf order, for views with directions: top-down median
   splits over six coordinates per view, its eye's three and the three of
   its unit direction.  Node i's views are split so that the left child
   gets as many as it has leaves (the scene tree's layout), along the
   coordinate whose two halves have the smaller sum of (p + t q)^3, p the
   diagonal of a half's box of eyes, q that of its box of directions and t
   = MLOD__VIEW_TURN times the diagonal of every eye's box: a view node
   culls by its cone of directions as by its ball, and views of one place
   looking different ways (a room's corner) share less than they cull.
   Ties go to the first coordinate (x, y, z, then the directions'), equal
   coordinates to the lower view index.  On the bench's room (lights along
   the surface normals) 0.02 gave the fewest MegaViews pairs of the values
   tried (0.003 to 1); 0.3 and more give more pairs than the eyes' order
   alone, as does moving each eye along its direction before ordering by
   eyes. */
#define MLOD__VIEW_TURN 0.02
#ifndef MLOD__VIEW_NARROW
#define MLOD__VIEW_NARROW 1e-3
#endif
#ifndef MLOD__VIEW_SAMPLE
#define MLOD__VIEW_SAMPLE 512u
#endif

typedef struct mlod__vkey {
    float k[6]; /* the eye, the unit direction */
    uint32_t item; /* the view */
} mlod__vkey;

/* Whether key a is less than key b along dim: by (k[dim], item), a
   strict order. */
static int mlod__vkey_less(const mlod__vkey *a, const mlod__vkey *b, int dim)
{
    return a->k[dim] < b->k[dim] || (a->k[dim] == b->k[dim] && a->item < b->item);
}

/* keys[0 .. count) reordered so that the first nth (0 < nth < count) are
   the least along dim: quickselect with Hoare's partition, its pivot the
   median of three keys picked by a hash of the range (expected linear
   time for any input, the same result every time). */
static void mlod__vkey_select(mlod__vkey *keys, uint32_t count, uint32_t nth, int dim)
{
    uint32_t lo = 0, hi = count, a; /* the first nth of keys hold those of [0, lo) and the least of [lo, hi) */
    while (hi - lo > 16) {
        uint64_t h = mlod__mix64(((uint64_t)lo << 32) ^ hi);
        uint32_t span = hi - lo, b = lo + (uint32_t)((h >> 21) % span);
        uint32_t c = lo + (uint32_t)((h >> 42) % span), i = lo, j = hi - 1;
        const mlod__vkey *x, *y = &keys[b], *z = &keys[c];
        mlod__vkey pivot, t;
        a = lo + (uint32_t)(h % span);
        x = &keys[a];
        if (a == b || b == c || a == c) { /* the middle key alone */
            pivot = keys[lo + span / 2];
        } else { /* the median of three distinct keys: never the largest */
            const mlod__vkey *m = mlod__vkey_less(x, y, dim) ? (mlod__vkey_less(y, z, dim) ? y : mlod__vkey_less(x, z, dim) ? z : x)
                                                            : (mlod__vkey_less(x, z, dim) ? x : mlod__vkey_less(y, z, dim) ? z : y);
            pivot = *m;
        }
        for (;;) { /* [lo, i) not above the pivot, (j, hi) not below it */
            while (mlod__vkey_less(&keys[i], &pivot, dim)) i++;
            while (mlod__vkey_less(&pivot, &keys[j], dim)) j--;
            if (i >= j) break;
            t = keys[i];
            keys[i++] = keys[j];
            keys[j--] = t;
        }
        /* keys [lo, j] are at most the pivot, (j, hi) at least it, both non-empty */
        if (nth <= j)
            hi = j + 1;
        else
            lo = j + 1;
    }
    for (a = lo + 1; a < hi; a++) { /* a few left: sorted in place */
        mlod__vkey t = keys[a];
        uint32_t i = a;
        for (; i > lo && mlod__vkey_less(&t, &keys[i - 1], dim); i--) keys[i] = keys[i - 1];
        keys[i] = t;
    }
}

/* The box of count >= 1 keys in their six coordinates. */
static void mlod__vkey_box(const mlod__vkey *keys, uint32_t count, float lo[6], float hi[6])
{
    uint32_t i;
    int k;
    for (k = 0; k < 6; k++) lo[k] = hi[k] = keys[0].k[k];
    for (i = 1; i < count; i++)
        for (k = 0; k < 6; k++) {
            lo[k] = keys[i].k[k] < lo[k] ? keys[i].k[k] : lo[k];
            hi[k] = keys[i].k[k] > hi[k] ? keys[i].k[k] : hi[k];
        }
}

/* (p + turn q)^3 of count keys (see MLOD__VIEW_TURN). */
static double mlod__vkey_cost(const mlod__vkey *keys, uint32_t count, double turn)
{
    float lo[6], hi[6];
    double p = 0.0, q = 0.0, d;
    int k;
    mlod__vkey_box(keys, count, lo, hi);
    for (k = 0; k < 3; k++) {
        p += ((double)hi[k] - lo[k]) * ((double)hi[k] - lo[k]);
        q += ((double)hi[k + 3] - lo[k + 3]) * ((double)hi[k + 3] - lo[k + 3]);
    }
    d = sqrt(p) + turn * sqrt(q);
    return d * d * d;
}

typedef struct mlod__view_order_job {
    mlod__vkey *keys;
    uint32_t *order; /* per leaf: its view */
    uint32_t n;
    double turn;
    uint32_t depth;   /* the tasks' nodes: every node of this depth */
    uint32_t stop;    /* their splits stop above this depth */
} mlod__view_order_job;

/* Split node's count keys, nl to the left, along the coordinate whose
   halves have the least summed cost (mlod__vkey_cost), of those along
   which the views spread (above MLOD__VIEW_NARROW of the widest,
   directions weighed by turn), the first on a tie; for a node of more
   than MLOD__VIEW_SAMPLE views, the coordinate chosen on that many of
   them, evenly spaced in their order. */
static void mlod__view_partition(const mlod__view_order_job *job, mlod__vkey *keys, uint32_t count, uint32_t nl)
{
    mlod__vkey sample[MLOD__VIEW_SAMPLE], *set = keys;
    uint32_t i, m = count, ml = nl;
    double best = 0.0, widest = 0.0, extent[6];
    float lo[6], hi[6];
    int dim, axis = 0, last = -1;
    if (count > MLOD__VIEW_SAMPLE) {
        for (i = 0; i < MLOD__VIEW_SAMPLE; i++) sample[i] = keys[(uint64_t)i * count / MLOD__VIEW_SAMPLE];
        m = MLOD__VIEW_SAMPLE;
        ml = (uint32_t)(((uint64_t)nl * m + count / 2) / count);
        ml = ml < 1 ? 1 : ml > m - 1 ? m - 1 : ml;
        set = sample;
    }
    mlod__vkey_box(set, m, lo, hi);
    for (dim = 0; dim < 6; dim++) {
        extent[dim] = ((double)hi[dim] - lo[dim]) * (dim < 3 ? 1.0 : job->turn);
        widest = extent[dim] > widest ? extent[dim] : widest;
    }
    for (dim = 0; dim < 6; dim++) {
        double cost;
        if (!(extent[dim] > MLOD__VIEW_NARROW * widest)) continue;
        mlod__vkey_select(set, m, ml, dim);
        cost = mlod__vkey_cost(set, ml, job->turn) + mlod__vkey_cost(set + ml, m - ml, job->turn);
        if (last < 0 || cost < best) {
            best = cost;
            axis = dim;
        }
        last = dim;
    }
    /* the keys themselves, unless the last coordinate tried split them so */
    if (set != keys || axis != last) mlod__vkey_select(keys, count, nl, axis);
}

/* Split node `node` (its views keys[0 .. its leaves)) and, above depth
   `stop`, its subtree; a leaf writes its view. */
static void mlod__view_split(const mlod__view_order_job *job, mlod__vkey *keys, uint32_t node, uint32_t stop)
{
    uint32_t count = mlod__leaves_below(node, job->n), nl;
    if (count == 1) {
        job->order[node - (job->n - 1)] = keys[0].item;
        return;
    }
    if (mlod__depth_of(node) >= stop) return;
    nl = mlod__leaves_below(2 * node + 1, job->n);
    mlod__view_partition(job, keys, count, nl);
    mlod__view_split(job, keys, 2 * node + 1, stop);
    mlod__view_split(job, keys + nl, 2 * node + 2, stop);
}

/* The first key of node `node`: the leaves left of its subtree. */
static uint32_t mlod__view_begin(uint32_t node, uint32_t n)
{
    uint32_t begin = 0;
    while (node > 0) {
        uint32_t parent = (node - 1) / 2;
        if (node == 2 * parent + 2) begin += mlod__leaves_below(2 * parent + 1, n);
        node = parent;
    }
    return begin;
}

/* Task `index`: node 2^depth - 1 + index, if there is one, split (job->
   stop: its subtree too). */
static void mlod__view_order_task(void *context, uint32_t index)
{
    const mlod__view_order_job *job = (const mlod__view_order_job *)context;
    uint32_t node = ((uint32_t)1 << job->depth) - 1 + index;
    if (node > 2 * job->n - 2) return;
    mlod__view_split(job, job->keys + mlod__view_begin(node, job->n), node, job->stop);
}

/* The view tree's leaf order (see MLOD__VIEW_TURN) into order[0 .. count):
   the top levels' nodes a task each, depth after depth, then the subtrees
   below them a task each; the same order for any hook.  0 when out of
   memory. */
#define MLOD__VIEW_ORDER_DEPTH 6u
static int mlod__view_order(const mlod_view_set *views, const mlod_allocator *a, const mlod_parallel *parallel,
                            uint32_t *order)
{
    mlod__view_order_job job;
    uint32_t i, n = views->count, depth;
    double lo[3], hi[3], diagonal = 0.0;
    int k;
    job.keys = (mlod__vkey *)mlod__alloc_array(a, n, sizeof(mlod__vkey), NULL);
    if (!job.keys) return 0;
    for (i = 0; i < n; i++) {
        const float *e = (const float *)mlod__at(views->eyes, views->eye_stride, i);
        const float *d = (const float *)mlod__at(views->directions, views->direction_stride, i);
        double length = sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
        for (k = 0; k < 3; k++) {
            job.keys[i].k[k] = e[k];
            job.keys[i].k[k + 3] = (float)(d[k] / length);
        }
        job.keys[i].item = i;
    }
    mlod__box_of(views->eyes, views->eye_stride, n, lo, hi);
    for (k = 0; k < 3; k++) diagonal += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    job.order = order;
    job.n = n;
    job.turn = MLOD__VIEW_TURN * sqrt(diagonal);
    depth = mlod__depth_of(2 * (uint64_t)n - 2) < MLOD__VIEW_ORDER_DEPTH ? 0u : MLOD__VIEW_ORDER_DEPTH;
    for (job.depth = 0; job.depth <= depth; job.depth++) {
        job.stop = job.depth < depth ? job.depth + 1 : 64u;
        mlod__run(parallel, (uint32_t)1 << job.depth, mlod__view_order_task, &job);
    }
    mlod__free(a, job.keys);
    return 1;
}

MLOD__PUBLIC mlod_result mlod_view_tree_build(const mlod_view_set *views, const mlod_allocator *allocator,
                                              const mlod_parallel *parallel, mlod_view_tree **out,
                                              mlod_error *error)
{
    mlod_allocator a;
    mlod_view_tree *tree;
    mlod_build_desc desc;
    mlod_points points;
    mlod_result res;
    size_t bytes = 0;
    if (!out) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "out is NULL");
    *out = NULL;
    if ((res = mlod__check_view_set(views, error)) != MLOD_OK) return res;
    a = mlod__allocator(allocator);
    tree = (mlod_view_tree *)mlod__alloc_array(&a, 1, sizeof *tree, &bytes);
    if (!tree) return mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "no memory for the view tree");
    memset(tree, 0, sizeof *tree);
    tree->allocator = a;
    tree->radii = (float *)mlod__alloc_array(&a, views->count, sizeof(float), &bytes);
    if (!tree->radii) {
        mlod_view_tree_destroy(tree);
        return mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "no memory for the view tree");
    }
    memset(tree->radii, 0, views->count * sizeof(float));
    memset(&desc, 0, sizeof desc);
    desc.attributes = MLOD_ATTR_REFIT | (views->directions ? (uint32_t)MLOD_ATTR_CONE : 0u);
    desc.allocator = &a;
    desc.parallel = parallel;
    points = mlod__view_points(views, tree->radii);
    if (views->directions) { /* the order by eyes and directions (MLOD__VIEW_TURN) */
        uint32_t *order = (uint32_t *)mlod__alloc_array(&a, views->count, sizeof(uint32_t), NULL);
        res = order && mlod__view_order(views, &a, parallel, order)
                  ? mlod__build_points_in(&points, &desc, order, &tree->eyes, error)
                  : mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "no memory for the view tree");
        mlod__free(&a, order);
    } else {
        res = mlod_build_points(&points, &desc, &tree->eyes, error);
    }
    if (res == MLOD_OK && views->directions) {
        tree->half_fovs = (float *)mlod__alloc_array(&a, tree->eyes->node_count, 2 * sizeof(float), &bytes);
        tree->floors = (float *)mlod__alloc_array(&a, tree->eyes->node_count, 2 * sizeof(float), &bytes);
        if (!tree->half_fovs || !tree->floors)
            res = mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "no memory for the view tree");
    }
    if (res != MLOD_OK) {
        mlod_view_tree_destroy(tree);
        return res;
    }
    if (tree->half_fovs) {
        mlod__view_tree_fovs(tree, views);
        mlod__view_tree_floors(tree);
    }
    tree->view_count = views->count;
    tree->bytes = bytes + tree->eyes->bytes;
    *out = tree;
    return mlod__succeed(error);
}

MLOD__PUBLIC mlod_result mlod_view_tree_refit(mlod_view_tree *tree, const mlod_view_set *views,
                                              const mlod_parallel *parallel, mlod_error *error)
{
    mlod_points points;
    mlod_result res;
    if (!tree) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "tree is NULL");
    if ((res = mlod__check_view_set(views, error)) != MLOD_OK) return res;
    if (views->count != tree->view_count)
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "%u views for a view tree of %u", views->count,
                          tree->view_count);
    if (!views->directions != !tree->half_fovs)
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "the view tree was built %s directions",
                          tree->half_fovs ? "with" : "without");
    points = mlod__view_points(views, tree->radii);
    res = mlod_refit_points(tree->eyes, &points, parallel, error);
    if (res == MLOD_OK && tree->half_fovs) {
        mlod__view_tree_fovs(tree, views);
        mlod__view_tree_floors(tree);
    }
    return res;
}

MLOD__PUBLIC void mlod_view_tree_destroy(mlod_view_tree *tree)
{
    mlod_allocator a;
    if (!tree) return;
    a = tree->allocator;
    mlod_tree_destroy(tree->eyes);
    mlod__free(&a, tree->half_fovs);
    mlod__free(&a, tree->floors);
    mlod__free(&a, tree->radii);
    a.free(a.user, tree);
}

/* Is the orientation (forward, up) the default one: both NULL or 0? */
static int mlod__megaviews_default_axes(const float *forward, const float *up)
{
    int k;
    for (k = 0; k < 3; k++)
        if ((forward && forward[k] != 0.0f) || (up && up[k] != 0.0f)) return 0;
    return 1;
}

MLOD__PUBLIC mlod_view mlod_megaviews_view_oriented(const float eye[3], uint32_t resolution, uint32_t flags,
                                                    const float forward[3], const float up[3])
{
    mlod_view v;
    int k;
    memset(&v, 0, sizeof v);
    v.kind = MLOD_VIEW_DUAL_PARABOLOID;
    for (k = 0; k < 3; k++) v.position[k] = eye ? eye[k] : 0.0f;
    if (mlod__megaviews_default_axes(forward, up)) {
        v.forward[2] = 1.0f;
        v.up[1] = 1.0f;
    } else {
        for (k = 0; k < 3; k++) {
            v.forward[k] = forward ? forward[k] : 0.0f;
            v.up[k] = up ? up[k] : 0.0f;
        }
    }
    v.width = resolution > 0x7fffffffu ? 0u : 2u * resolution;
    v.height = resolution;
    v.flags = flags;
    return v;
}

MLOD__PUBLIC mlod_view mlod_megaviews_view(const float eye[3], uint32_t resolution, uint32_t flags)
{
    return mlod_megaviews_view_oriented(eye, resolution, flags, NULL, NULL);
}

/* ---------------------------------------------- MegaViews: pair bounds -- */

/* Pairs (scene node s, view node v) and what the traversal does with them. */
enum { MLOD__PAIR_CULL, MLOD__PAIR_DRAW, MLOD__PAIR_DRAW_LEAF, MLOD__PAIR_SPLIT_SCENE, MLOD__PAIR_SPLIT_VIEW };

/* Does no direction from a point of the ball (0, g) around x (d = |x|) to
   ... lie within `margin` of the cone (axis, alpha) widened by theta?
   I.e. angle(x, axis) > alpha + theta + asin(g / d) + margin (< pi).  For
   view nodes x = scene centre - view centre and g = r + rho (Minkowski:
   every eye of the ball sees every point of the sphere within that
   angular radius of x): no view below looks at the sphere.  With the
   scene's normal cone, -x and theta = pi/2: every normal faces away from
   every eye (the back-face test).  The inner nodes' margin of 2^-30 rad
   keeps their answers implying their views' (margin 0), the
   angles being within 1e-11 rad (mlod__atan2). */
/* GLSL twin: outside_cone */
static int mlod__outside_cone(const double *x, double d, double g, const float *cone, double theta, double margin)
{
    double axis[3], reach;
    if (!(d > g) || !(cone[3] < MLOD__PI)) return 0;
    reach = cone[3] + theta + mlod__atan2(g, sqrt((d - g) * (d + g))) + margin;
    if (!(reach < MLOD__PI)) return 0;
    axis[0] = cone[0];
    axis[1] = cone[1];
    axis[2] = cone[2];
    return mlod__angle(x, axis) > reach;
}

/* Is the sphere (x, d = |x|, r) within the cone (axis, widened by limit)
   from every eye of the ball (0, rho), however the direction it is seen
   in turns within `spread` of the axis?  angle(x, axis) + spread +
   asin(rho / d) + 2^-30 <= limit + asin(r / (d + rho)): from an eye e,
   x - e is within asin(rho / d) of x, and the sphere's angular radius is
   at least asin(r / (d + rho)).  With the views' cone (spread alpha) and
   smallest half field of view: no view below culls the sphere; with the
   scene's normal cone, -x and limit pi/2 + its half-angle: no eye below
   finds it facing away.  What may be shared must be drawn by every view
   below. */
/* GLSL twin: within_cone */
static int mlod__within_cone(const double *x, double d, double r, double rho, const float *cone, double spread,
                             double limit)
{
    double axis[3] = {cone[0], cone[1], cone[2]}, turn, seen;
    if (!(d > rho)) return 0;
    turn = mlod__atan2(rho, sqrt((d - rho) * (d + rho)));
    seen = r > 0.0 ? mlod__atan2(r, sqrt((d + rho - r) * (d + rho + r))) : 0.0;
    return mlod__angle(x, axis) + spread + turn + 1.0 / 1073741824.0 <= limit + seen;
}

/* x in the frame of the maps (axes: their u, v, w, 9 doubles, as
   mlod__mv_job.axes), for the bounds below, which read x.w (x[2]) and the
   length across it (of x[0], x[1]); x itself in the default frame (not
   oriented), where those are x's own (the coordinates -x[0], x[1],
   x[2]). */
/* GLSL twin: map_coords */
static const double *mlod__map_coords(const double *x, const double *axes, int oriented, double *out)
{
    int k;
    if (!oriented) return x;
    for (k = 0; k < 3; k++) out[k] = mlod__dot3(x, axes + 3 * k);
    return out;
}

/* Bounds on c, in pixels, over every eye of the ball (c + y, |y| <= rho)
   for the sphere (x = centre - c in the maps' frame, mlod__map_coords, d
   = |x|, r) in the global dual paraboloid of scale S: from the eye, d
   moves within [d - rho, d + rho] and x.w within [x.w - rho, x.w +
   rho], so each half's denominator x.w + sqrt(d^2 - r^2) is at least (x.w - rho) + sqrt((d - rho)^2 - r^2) and at
   most (x.w + rho) + sqrt((d + rho)^2 - r^2).  cmax: the largest over the
   halves some eye reaches (x.w + rho + r >= 0); cmin: over the halves every
   eye reaches (x.w - rho + r >= 0), 0 if none.  2^-40 relative to spare,
   far above the rounding of either side. */
/* GLSL twin: ball_diameters */
static void mlod__ball_diameters(double S, const double *x, double d, double r, double rho, double *cmax,
                                 double *cmin)
{
    /* the largest quotient over the halves is S 2 r over the least denominator (division being monotone):
       one division each, the same bits as a division per half */
    double closest = d - rho, farthest = d + rho, t_closest, t_farthest, least_near = INFINITY, least_far = INFINITY;
    int h, some = 0, every = 0;
    *cmax = 0.0;
    *cmin = 0.0;
    if (!(farthest > r)) { /* every eye inside the sphere */
        *cmax = *cmin = INFINITY;
        return;
    }
    t_closest = closest > r ? sqrt((closest - r) * (closest + r)) : 0.0;
    t_farthest = sqrt((farthest - r) * (farthest + r));
    for (h = 0; h < 2; h++) {
        double xw = h ? -x[2] : x[2], den;
        if (xw + rho + r >= 0.0) { /* some eye reaches this half */
            den = xw - rho + t_closest;
            some = 1;
            if (!(closest > r) || !(den > 0.0)) den = 0.0;
            if (den < least_near) least_near = den;
        }
        if (xw - rho + r >= 0.0) { /* every eye */
            den = xw + rho + t_farthest;
            every = 1;
            if (!(den > 0.0)) den = 0.0;
            if (den < least_far) least_far = den;
        }
    }
    if (some) *cmax = least_near > 0.0 ? S * 2.0 * r / least_near : INFINITY;
    if (every) *cmin = least_far > 0.0 ? S * 2.0 * r / least_far : INFINITY;
    *cmax *= 1.0 + 1.0 / 1099511627776.0;
    *cmin *= 1.0 - 1.0 / 1099511627776.0;
}

/* How farthest, in pixels, any point of the sphere's image in the global dual
   paraboloid of scale S moves between the ball's centre and any eye of
   the ball: the direction to a point p of the sphere turns by at most
   asin(rho / |p - c|) <= asin(rho / (d - r)) <= its tangent, and a
   direction phi off a half's axis maps to radius tan(phi / 2), whose rate
   1 / (1 + cos phi) (radially and across, the map being conformal) grows
   with phi up to the largest angle off the axis of any direction from an
   eye to the sphere, phi + b, with phi = angle(x, w) (x in the maps'
   frame: mlod__map_coords) and b = asin((r + rho) / d).  Halves no eye
   sees the sphere in (phi - b > pi / 2) are left out; +inf where the
   bound does not hold (phi + b >= pi).  Sines and cosines of phi +- b
   from their sums: no trigonometry. */
/* GLSL twin: ball_motion */
static double mlod__ball_motion(double S, const double *x, double d, double r, double rho)
{
    /* the largest quotient over the halves is S turn over the least 1 + cos(phi + b) (division being
       monotone), and the halves' cos phi are +-x.w / d: the same bits as dividing per half */
    double closest = d - r, g = r + rho, turn, sin_b, cos_b, sin_phi, cos_w, least = INFINITY;
    int h;
    if (rho == 0.0) return 0.0;
    if (!(closest > rho) || !(d > g)) return INFINITY;
    turn = rho / sqrt((closest - rho) * (closest + rho));
    sin_b = g / d;
    cos_b = sqrt((d - g) * (d + g)) / d;
    sin_phi = sqrt(x[0] * x[0] + x[1] * x[1]) / d;
    cos_w = x[2] / d;
    for (h = 0; h < 2; h++) {
        double cos_phi = h ? -cos_w : cos_w, sin_sum, cos_sum;
        if (cos_phi * cos_b + sin_phi * sin_b < -1e-12) continue; /* cos(phi - b) < 0 */
        sin_sum = sin_phi * cos_b + cos_phi * sin_b;
        cos_sum = cos_phi * cos_b - sin_phi * sin_b;
        /* phi + b at pi, or rounded past it (1 + cos below 0): no bound */
        if (!(sin_sum > 1e-12 || cos_sum > 0.0) || !(1.0 + cos_sum > 0.0)) return INFINITY;
        if (1.0 + cos_sum < least) least = 1.0 + cos_sum;
    }
    return least < INFINITY ? S * turn / least * (1.0 + 1.0 / 1048576.0) : 0.0;
}

/* ------------------------------------ MegaViews: the traversal's state -- */

/* A view node as the pair test sees it. */
typedef struct mlod__vnode {
    uint32_t node;
    int leaf, group; /* group: an inner node within params->group_radius, one view at its centre */
    double centre[3], radius, least_fov, most_fov; /* half fields of view below */
    const float *cone;   /* the views' directions, NULL: every direction */
    /* the fast paths' constants (mlod__pair_action): |axis|, A = alpha + most_fov + the culling margin
       (cos, sin; cos -2 when A reaches pi), and L = least_fov - alpha - 2^-30 (cos, sin; L < 0: none) */
    double axis_length, cos_reach, sin_reach, cos_least, sin_least;
    /* inner nodes with a floor: the eyes' least height along the unit axis and the spread of their
       directions and fields of view (mlod_view_tree.floors), slab 0: none (mlod__below_floor) */
    int slab;
    double floor, spread;
    mlod__pview pv;      /* leaves: the view's map, its float filter for epsilon */
    /* inner nodes: the pair filter's constants (mlod__vpair), fast = 0: none.  cull: 0 no cone, 1 the
       cone test, 2 never culled (A reaches pi); axis the cone's unit axis, cos_reach and sin_reach A's,
       kc = 2 S / epsilon, km = S / delta, all rounded to float */
    int fast, fast_cull;
    float fc[3], frho, faxis[3], fcos_reach, fsin_reach, fkc, fkm;
    const float (*fframe)[3]; /* the maps' frame in float (mlod__mv_job.faxes), NULL: the default */
    int fslab;        /* the floor's test, floor and spread (floats: exact) */
    float ffloor, fspread;
} mlod__vnode;

/* One task's output: pairs (inner view node, scene node) to draw and to
   hand to the view node's children, in the order met (view leaves draw
   into their tiles at once); a subtree walk (mlod__mv_walk) lists only the
   scene nodes it hands down (with_view 0). */
typedef struct mlod__mv_out {
    uint32_t *draw, *split;
    size_t draw_count, split_count, capacity; /* pairs each */
    uint64_t pairs, culled, drawn;            /* drawn: at once, into a band */
    uint64_t leaves;                          /* drawn or listed: scene leaves above epsilon, shared */
    int with_view;
    int overflow;
    int owned; /* draw and split were grown: the task's own allocation */
    /* pairs per view node: a chunk's first and last view nodes may go on
       in the chunks beside it (their pairs summed in order), those between
       are whole (the most of them) */
    uint32_t first_node, last_node;
    uint64_t first_pairs, last_pairs, most_pairs;
} mlod__mv_out;

/* Drawing at once into a band (a leaf's tile, or an inner map of a subtree
   walk): the nodes wait in batches of MLOD__DRAW_CHUNK, as mlod_splat draws a
   cut.  The view is prepared at the first draw. */
typedef struct mlod__mv_drawer {
    mlod__band band;
    mlod__pview *pv;
    int ready;
    uint32_t node; /* the view node */
    uint32_t batch[MLOD__DRAW_CHUNK], n;
    /* a walk's inner map, begun (from the parent's map) at the first draw;
       NULL once begun, or when the band was begun before the first draw */
    float *lazy_depth;
    uint32_t *lazy_ids;
    const float *lazy_parent_depth;
    const uint32_t *lazy_parent_ids;
    int filter_ready;    /* band.fast set for the view (at the first flush) */
    mlod__fdiscs filter; /* the splat's float filter for the view */
} mlod__mv_drawer;

typedef struct mlod__mv_job {
    const mlod_tree *scene;
    const mlod_view_tree *views;
    mlod_atlas *atlas;
    double epsilon, delta, S, group_radius;
    uint32_t resolution, flags;
    /* the maps' orientation (params.forward, up; 0: the default) and frame: axes u, v, w (the front
       half's right, up and forward, as mlod_view_frame_of gives them), in float too; oriented 0 where
       that frame is the default's, (-1, 0, 0), (0, 1, 0), (0, 0, 1) (mlod__mv_orient) */
    float forward[3], up[3];
    double axes[3][3];
    float faxes[3][3];
    int oriented;
    float disc_scale;
    int tangent;               /* tangent discs (mlod__splat_tangent) */
    mlod_megaviews_maps *keep; /* unfused: every node's own map, leaves too; NULL: fuse into the atlas */
    /* the level: view nodes first .. first + count - 1 */
    uint32_t first, count, prev_first;
    const uint32_t *in;     /* scene nodes handed down, by parent */
    const size_t *in_off;   /* per parent (the previous level's nodes), count + 1; NULL at the root */
    size_t units;
    const size_t *chunk_begin; /* the chunks' first units, chunk count + 1 */
    mlod__mv_out *outs;
    const uint32_t *redo;   /* chunks to run again (task i runs redo[i]), or NULL */
    /* drawing the level */
    const uint32_t *draws;  /* scene nodes to draw, by node of the level */
    const size_t *draw_off;
    float *depth;           /* this level's maps: pixels per map, depth and node */
    uint32_t *ids;
    uint32_t *leaf_ids;     /* a level's classification that draws view leaves: pixels per chunk, the node
                               drawn at each pixel of the leaf the chunk draws (mlod__mv_leaf_begin) */
    const uint32_t *map_of; /* per node of the level: its map, or UINT32_MAX */
    const float *parent_depth; /* the previous level's maps */
    const uint32_t *parent_ids, *parent_map_of;
    size_t pixels;          /* 2 R^2, a map's pixels (mlod__megaviews_run: bytes of any count of maps fit size_t) */
    /* below the walk level: one walk per view subtree (mlod__mv_walk_task) */
    struct mlod__mv_walk *walks;
    uint32_t walk_level, levels;
    size_t walk_room; /* a walk's first list stack: 4 entries per scene node handed to it, and this */
    uint32_t descend_room; /* the most pairs a descent's group of roots takes (mlod__mv_descend) */
    int exact;        /* no float filter (mlod__vpair): every pair by the exact path (the tests compare) */
} mlod__mv_job;

#define MLOD__MV_CHUNK 1024u
#define MLOD__MV_DRAW_NODES 16u
/* The level from which the fused render walks each view subtree depth
   first (its 2^6 subtrees are the tasks): its memory below then grows with
   the tree's depth, not with a level's pairs.  Any level gives the same
   result (the tests walk from each). */
#define MLOD__MV_WALK_LEVEL 6u
#define MLOD__MV_WALK_ROOM 4096u
#define MLOD__NO_MAP 0xffffffffu

static mlod_view mlod__node_map_view(const mlod__mv_job *job, uint32_t node)
{
    return mlod_megaviews_view_oriented(job->views->eyes->spheres + 4 * (size_t)node, job->resolution, job->flags,
                                        job->forward, job->up);
}

/* Set the job's orientation (mlod_megaviews_check took it) and its maps'
   frame.  Returns 0 for an orientation the maps' view refuses. */
static int mlod__mv_orient(mlod__mv_job *job, const float *forward, const float *up)
{
    static const double standard[3][3] = {{-1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
    mlod_view view = mlod_megaviews_view_oriented(NULL, 1, 0, forward, up);
    mlod__pview pv;
    int j, k;
    for (k = 0; k < 3; k++) {
        job->forward[k] = forward ? forward[k] : 0.0f;
        job->up[k] = up ? up[k] : 0.0f;
    }
    if (mlod__view_prepare(&view, &pv, NULL) != MLOD_OK) return 0;
    job->oriented = 0;
    for (k = 0; k < 3; k++) {
        job->axes[0][k] = pv.f.subs[0].right[k];
        job->axes[1][k] = pv.f.subs[0].up[k];
        job->axes[2][k] = pv.f.subs[0].forward[k];
    }
    for (j = 0; j < 3; j++)
        for (k = 0; k < 3; k++) {
            job->faxes[j][k] = (float)job->axes[j][k];
            job->oriented |= job->axes[j][k] != standard[j][k];
        }
    return 1;
}

/* ----------------------------------- MegaViews: classifying node pairs -- */

/* The fast paths' constants of a view node from its cone, fields of view
   and leafness (mlod__vnode). */
static void mlod__vnode_cone_set(mlod__vnode *vn)
{
    double axis[3], reach, least;
    if (!vn->cone) return;
    axis[0] = vn->cone[0];
    axis[1] = vn->cone[1];
    axis[2] = vn->cone[2];
    reach = vn->cone[3] + vn->most_fov + (vn->leaf ? 0.0 : 1.0 / 1073741824.0);
    least = vn->least_fov - vn->cone[3] - 1.0 / 1073741824.0;
    vn->axis_length = mlod__length3(axis);
    vn->cos_reach = -2.0;
    vn->sin_reach = 0.0;
    if (reach < MLOD__PI) mlod__sin_cos(reach, &vn->sin_reach, &vn->cos_reach);
    vn->cos_least = -2.0;
    vn->sin_least = 0.0;
    if (least >= 0.0) mlod__sin_cos(least, &vn->sin_least, &vn->cos_least);
}

/* The pair filter's constants of a view node (mlod__vpair): only where
   delta > 0 and back faces are not culled (those pairs take the exact
   path), and every constant lies within its guarded range; fast = 2 for a
   group or a leaf, whose view (at its centre, its eye) has a float filter
   (vn->pv, set before). */
static void mlod__vnode_fast_set(const mlod__mv_job *job, mlod__vnode *vn)
{
    const double lo = 1.0 / 1073741824.0, hi = 1073741824.0; /* 2^-30, 2^30 */
    double kc = 2.0 * job->S / job->epsilon, km = job->delta > 0.0 ? job->S / job->delta : 0.0;
    int k;
    vn->fast = 0;
    if (job->exact || !(job->delta > 0.0) || ((vn->group || vn->leaf) && !vn->pv.fast.ok)) return;
    if (job->flags & MLOD_VIEW_CULL_BACKFACES && job->scene->cones) return;
    if (!(kc >= lo && kc <= hi && km >= lo && km <= hi && vn->radius <= hi)) return;
    if (vn->radius != 0.0 && !(vn->radius >= lo)) return;
    for (k = 0; k < 3; k++) vn->fc[k] = (float)vn->centre[k]; /* view tree spheres are floats: exact */
    vn->frho = (float)vn->radius;
    vn->fkc = (float)kc;
    vn->fkm = (float)km;
    vn->fframe = job->oriented ? (const float(*)[3])job->faxes : NULL;
    vn->fast_cull = 0;
    if (vn->cone) {
        if (!(vn->axis_length >= lo && vn->axis_length <= hi)) return;
        vn->fast_cull = vn->cos_reach < -1.0 ? 2 : 1;
        for (k = 0; k < 3; k++) vn->faxis[k] = (float)(vn->cone[k] / vn->axis_length);
        vn->fcos_reach = (float)vn->cos_reach;
        vn->fsin_reach = (float)vn->sin_reach;
    }
    vn->fslab = vn->slab && fabs(vn->floor) <= hi;
    vn->ffloor = (float)vn->floor;
    vn->fspread = (float)vn->spread;
    vn->fast = vn->group || vn->leaf ? 2 : 1;
}

static void mlod__vnode_set(const mlod__mv_job *job, uint32_t node, mlod__vnode *vn)
{
    const mlod_tree *t = job->views->eyes;
    const float *sphere = t->spheres + 4 * (size_t)node;
    int k;
    vn->node = node;
    vn->leaf = node >= t->leaf_count - 1;
    for (k = 0; k < 3; k++) vn->centre[k] = sphere[k];
    vn->radius = sphere[3];
    vn->group = !vn->leaf && job->group_radius > 0.0 && vn->radius <= job->group_radius;
    vn->cone = mlod__cone_of(t, node);
    vn->least_fov = job->views->half_fovs ? job->views->half_fovs[2 * (size_t)node] : MLOD__PI;
    vn->most_fov = job->views->half_fovs ? job->views->half_fovs[2 * (size_t)node + 1] : MLOD__PI;
    mlod__vnode_cone_set(vn);
    vn->slab = 0;
    vn->floor = vn->spread = 0.0;
    if (!vn->leaf && vn->cone && job->views->floors && vn->axis_length > 0.0 &&
        job->views->floors[2 * (size_t)node] >= -FLT_MAX) {
        vn->slab = 1;
        vn->floor = job->views->floors[2 * (size_t)node];
        vn->spread = job->views->floors[2 * (size_t)node + 1];
    }
    if (vn->leaf || vn->group) {
        mlod_view view = mlod__node_map_view(job, node);
        mlod_result ok;
        if (vn->group) view.flags &= ~(uint32_t)MLOD_VIEW_CULL_BACKFACES; /* culled for all eyes, above */
        ok = mlod__view_prepare(&view, &vn->pv, NULL); /* the flags and resolution were checked, the eyes are finite */
        MANYLODS_ASSERT(ok == MLOD_OK);
        (void)ok;
        mlod__fast_prepare(&vn->pv, job->epsilon);
    }
    mlod__vnode_fast_set(job, vn);
}

/* Sine and cosine of asin(a / b), 0 <= a < b: a / b, and the cosine from
   both sides, sqrt((b - a)(b + a)) / b (not sqrt(1 - sin^2), which keeps
   only half the digits of a cosine near 0: an eye nearly touching a
   sphere); one division. */
static void mlod__asin_sin_cos(double a, double b, double *sin_a, double *cos_a)
{
    double inv = 1.0 / b;
    *sin_a = a * inv;
    *cos_a = sqrt((b - a) * (b + a)) * inv;
}

/* mlod__within_cone's answer for the views' cone where cosines settle it,
   without its arc tangents: within when phi <= psi = L - turn + seen, with
   L from the node (least_fov - alpha - 2^-30), turn = asin(rho / d) and
   seen = asin(r / (d + rho)), i.e. cos phi >= cos psi while psi is in [0,
   pi]; psi's sine and cosine come from their sums.  With L >= 0, psi lies
   in (-pi / 2, 3 pi / 2): below 0 (only when L < turn) nothing is within,
   above pi everything; with L < 0 it is below 0 where seen < turn (sines
   1e-9 apart).  1 within, 0 not, -1 when cos phi lies within 1e-9 of cos
   psi or psi within 1e-9 of 0 or pi (by its sine), far above both sides'
   errors (the arc tangents' 1e-11 rad): the exact test decides those.
   Sines and cosines of turn and seen from mlod__asin_sin_cos. */
static int mlod__surely_within(double cos_phi, double d, double r, const mlod__vnode *vn)
{
    double rho = vn->radius, e = d + rho, sin_t, cos_t, sin_1, cos_1, sin_s, cos_s, sin_psi, cos_psi;
    if (!(d > rho) || !(e > r)) return -1; /* an eye in reach: the exact test */
    mlod__asin_sin_cos(rho, d, &sin_t, &cos_t);
    mlod__asin_sin_cos(r, e, &sin_s, &cos_s);
    if (vn->cos_least < -1.0) return sin_s < sin_t - 1e-9 ? 0 : -1; /* L < 0: psi < 0 where seen < turn */
    sin_1 = vn->sin_least * cos_t - vn->cos_least * sin_t; /* L - turn, in (-pi / 2, pi] */
    cos_1 = vn->cos_least * cos_t + vn->sin_least * sin_t;
    sin_psi = sin_1 * cos_s + cos_1 * sin_s;
    cos_psi = cos_1 * cos_s - sin_1 * sin_s;
    if (sin_psi > -1e-9 && sin_psi < 1e-9) return -1; /* psi near 0 or pi */
    if (sin_psi < 0.0) return sin_1 < 0.0 ? 0 : 1;    /* psi below 0, or above pi */
    if (cos_phi > cos_psi + 1e-9) return 1;
    if (cos_phi < cos_psi - 1e-9) return 0;
    return -1;
}

/* mlod__outside_cone's answer where cosines settle it, without its arc
   tangents: the sphere (d, grown to g) is outside when phi > psi = A + b,
   b = asin(g / d), i.e. cos phi < cos psi = cos A cos b - sin A sin b with
   psi < pi (sin psi > 0), b's sine and cosine from mlod__asin_sin_cos.
   1 outside, 0 not, -1 when cos phi lies within
   1e-9 of cos psi (or psi near pi), far above both sides' errors (the
   arc tangents' 1e-11 rad): the exact test decides those. */
static int mlod__surely_outside(double cos_phi, double d, double g, const mlod__vnode *vn)
{
    double sin_b, cos_b, cos_psi, sin_psi;
    if (vn->cos_reach < -1.0 || !(d > g)) return 0; /* A >= pi, or an eye in the sphere: never culled */
    mlod__asin_sin_cos(g, d, &sin_b, &cos_b);
    cos_psi = vn->cos_reach * cos_b - vn->sin_reach * sin_b;
    sin_psi = vn->sin_reach * cos_b + vn->cos_reach * sin_b;
    if (!(sin_psi > 1e-9)) return -1;
    if (cos_phi > cos_psi + 1e-9) return 0;
    if (cos_phi < cos_psi - 1e-9) return 1;
    return -1;
}

/* Bounds on sin a and cos a for a in [0, pi/2): exact at 0 (a leaf's
   cone), else mlod__sin_cos (within 1e-16) with 1e-15 to spare. */
static void mlod__sin_cos_bounds(double a, double *sin_lo, double *sin_hi, double *cos_lo, double *cos_hi)
{
    double sa = 0.0, ca = 1.0, spare = 0.0;
    if (a != 0.0) {
        mlod__sin_cos(a, &sa, &ca);
        spare = 1e-15;
    }
    *sin_lo = sa - spare;
    *sin_hi = sa + spare;
    *cos_lo = ca - spare;
    *cos_hi = ca + spare;
}

/* The back-face tests of an inner view node without their arc tangents,
   where cosines settle them; the scene node's normal cone (axis n, half-
   angle theta < pi/2) and gamma = angle(-x, n), cos gamma = -x.n / (d |n|).
   Culled (mlod__outside_cone(-x, d, g, cone, pi/2, 2^-30)) when gamma >
   pi/2 + theta + b + 2^-30, b = asin(g / d), i.e. cos gamma < -sin(theta + b)
   while theta + b < pi/2.  Shared (mlod__within_cone(-x, d, r, rho, cone,
   0, pi/2 + theta)) when gamma + turn + 2^-30 <= pi/2 + theta + seen, turn =
   asin(rho / d), seen = asin(r / (d + rho)): gamma <= pi/2 + delta - 2^-30,
   delta = theta + sigma, sigma = seen - turn in (-pi/2, pi/2); for delta
   >= pi/2 always.  Sines and cosines from mlod__asin_sin_cos and their sums
   (theta's from mlod__sin_cos_bounds); each answer is given only 1e-8 (in cosines:
   as much in angle) clear of its threshold, far above the 2^-30 of the
   definitions and the arc tangents' 1e-11 rad; -1 otherwise (the exact
   tests decide). */
/* cos gamma = -x.n / (d |n|) for the scene node's normal cone n; 0 when
   its axis has no length (the exact tests decide). */
static int mlod__cos_gamma(const double *x, double d, const float *cone, double *cos_gamma)
{
    double len = sqrt((double)cone[0] * cone[0] + (double)cone[1] * cone[1] + (double)cone[2] * cone[2]);
    if (!(len > 0.0)) return 0;
    *cos_gamma = -(x[0] * cone[0] + x[1] * cone[1] + x[2] * cone[2]) / (d * len);
    return 1;
}

static int mlod__surely_backfacing(const double *x, double d, double g, const float *cone)
{
    double theta = cone[3], cos_gamma, sin_b, cos_b, s_lo, s_hi, c_lo, c_hi, sum_hi, sum_lo, cos_sum_lo;
    if (!(theta >= 0.0)) return -1;
    if (!(theta < 0.5 * MLOD__PI)) return 0; /* pi/2 + theta >= pi: never culled */
    if (!(d > g)) return 0;
    if (!mlod__cos_gamma(x, d, cone, &cos_gamma)) return -1;
    mlod__asin_sin_cos(g, d, &sin_b, &cos_b);
    mlod__sin_cos_bounds(theta, &s_lo, &s_hi, &c_lo, &c_hi);
    sum_hi = s_hi * cos_b + c_hi * sin_b;      /* sin(theta + b) at most */
    sum_lo = s_lo * cos_b + c_lo * sin_b;      /* at least */
    cos_sum_lo = c_lo * cos_b - s_hi * sin_b;  /* cos(theta + b) at least */
    if (cos_gamma > -sum_lo + 1e-8) return 0;
    if (cos_sum_lo > 1e-8 && cos_gamma < -sum_hi - 1e-8) return 1;
    return -1;
}

static int mlod__surely_facing(const double *x, double d, double r, double rho, const float *cone)
{
    double theta = cone[3], e, cos_gamma, sin_t, cos_t, sin_s, cos_s, sin_sg, cos_sg, s_lo, s_hi, c_lo, c_hi;
    double sin_d_lo, sin_d_hi, cos_d_lo, cos_d_hi;
    if (!(theta >= 0.0 && theta < 0.5 * MLOD__PI) || !(d > rho)) return -1;
    if (!mlod__cos_gamma(x, d, cone, &cos_gamma)) return -1;
    e = d + rho;
    if (!(e > r)) return -1;
    mlod__asin_sin_cos(rho, d, &sin_t, &cos_t);
    mlod__asin_sin_cos(r, e, &sin_s, &cos_s);
    sin_sg = sin_s * cos_t - cos_s * sin_t; /* sigma = seen - turn */
    cos_sg = cos_s * cos_t + sin_s * sin_t;
    mlod__sin_cos_bounds(theta, &s_lo, &s_hi, &c_lo, &c_hi);
    /* delta = theta + sigma: sin delta = sin theta cos sigma + cos theta sin sigma, cos sigma > 0 */
    sin_d_lo = s_lo * cos_sg + (sin_sg >= 0.0 ? c_lo : c_hi) * sin_sg;
    sin_d_hi = s_hi * cos_sg + (sin_sg >= 0.0 ? c_hi : c_lo) * sin_sg;
    cos_d_lo = c_lo * cos_sg - (sin_sg >= 0.0 ? s_hi : s_lo) * sin_sg;
    cos_d_hi = c_hi * cos_sg - (sin_sg >= 0.0 ? s_lo : s_hi) * sin_sg;
    if (cos_d_hi < -1e-8) return 1;     /* delta > pi/2: pi/2 + delta > pi >= gamma */
    if (!(cos_d_lo > 1e-8)) return -1;  /* delta near pi/2 */
    if (cos_gamma > -sin_d_lo + 1e-8) return 1;
    if (cos_gamma < -sin_d_hi - 1e-8) return 0;
    return -1;
}

/* Whether scene sphere (x = its centre - the view node's, d = |x|, radius
   r) lies outside the field of view of every view below inner view node
   vn (vn->slab): for an eye e and a point p of the sphere, (p - e).n <=
   (p - e).a + |p - e| |n - a| <= x.a + r - floor + (d + r + rho) 2
   sin(alpha / 2), n the eye's unit direction and a the cone's unit axis,
   and the view sees p only where (p - e).n >= -|p - e| sin(phi - pi/2)
   (phi > pi/2; else 0): culled when x.a + r - floor + (d + r + rho)
   spread (mlod_view_tree.floors) is below 0 by 2^-30 of d + r + rho +
   |floor|, far beyond the double's rounding.  A bound the views' cone
   test (mlod__outside_cone) does not give: that one lets any point of the
   ball be an eye. */
/* GLSL twin: below_floor */
static int mlod__below_floor(const double *x, double d, double r, const mlod__vnode *vn)
{
    double g = r + vn->radius;
    double up = (x[0] * vn->cone[0] + x[1] * vn->cone[1] + x[2] * vn->cone[2]) / vn->axis_length;
    double high = ((up + r) - vn->floor) + (d + g) * vn->spread;
    return high + ((d + g) + fabs(vn->floor)) / 1073741824.0 < 0.0;
}

/* With delta > 0, an inner scene node s that some eyes of a view ball of
   radius rho find within epsilon and others not: the larger splits
   (MegaViews 3.2.3), s when both its children are at least as large as
   the ball, else the view node. */
static int mlod__larger_splits(const mlod_tree *scene, uint32_t s, double rho)
{
    const float *left = scene->spheres + 4 * (size_t)(2 * s + 1), *right = left + 4;
    return (left[3] < right[3] ? left[3] : right[3]) >= rho ? MLOD__PAIR_SPLIT_SCENE : MLOD__PAIR_SPLIT_VIEW;
}

/* What the traversal does with (s, v).  A leaf decides as the cut does for
   its view (after its own field of view); an inner node culls what every
   view below culls, draws what is within epsilon for every eye of its
   ball, moves by at most delta and faces every eye (back faces culled),
   and with delta = 0 lies within every field of view below; it splits
   the scene node where every eye finds it above epsilon, and otherwise
   itself; a group (an inner node within the group radius) culls as an
   inner node and decides the rest as the cut does for one view at its
   centre. */
/* GLSL twin: pair_action */
static int mlod__pair_action(const mlod__mv_job *job, const mlod__vnode *vn, uint32_t s)
{
    const mlod_tree *scene = job->scene;
    const float *sphere = scene->spheres + 4 * (size_t)s;
    const float *cone = NULL; /* the scene node's normals, when back faces are culled */
    const double *xm;         /* x in the maps' frame */
    double x[3], away[3], in_map[3], d, r = sphere[3], cmax, cmin, cos_phi = 0.0;
    int k;
    for (k = 0; k < 3; k++) x[k] = (double)sphere[k] - vn->centre[k], away[k] = -x[k];
    d = mlod__length3(x);
    if (vn->cone) {
        cos_phi = (x[0] * vn->cone[0] + x[1] * vn->cone[1] + x[2] * vn->cone[2]) / (d * vn->axis_length);
        k = mlod__surely_outside(cos_phi, d, r + vn->radius, vn);
        if (k > 0 || (k < 0 && mlod__outside_cone(x, d, r + vn->radius, vn->cone, vn->most_fov,
                                                  vn->leaf ? 0.0 : 1.0 / 1073741824.0)))
            return MLOD__PAIR_CULL;
    }
    if (vn->slab && mlod__below_floor(x, d, r, vn)) return MLOD__PAIR_CULL;
    if (vn->leaf) {
        uint8_t st = mlod__classify(&vn->pv, scene, s, job->epsilon);
        return st == MLOD_STATUS_CULLED ? MLOD__PAIR_CULL
                                        : st == MLOD_STATUS_COARSE ? MLOD__PAIR_SPLIT_SCENE : MLOD__PAIR_DRAW;
    }
    if (job->flags & MLOD_VIEW_CULL_BACKFACES && scene->cones) {
        cone = scene->cones + 4 * (size_t)s;
        k = mlod__surely_backfacing(x, d, r + vn->radius, cone);
        if (k > 0 || (k < 0 && mlod__outside_cone(away, d, r + vn->radius, cone, 0.5 * MLOD__PI, 1.0 / 1073741824.0)))
            return MLOD__PAIR_CULL;
    }
    if (vn->group) {
        uint8_t st = mlod__classify(&vn->pv, scene, s, job->epsilon);
        return st == MLOD_STATUS_COARSE ? MLOD__PAIR_SPLIT_SCENE : MLOD__PAIR_DRAW;
    }
    xm = mlod__map_coords(x, job->axes[0], job->oriented, in_map);
    mlod__ball_diameters(job->S, xm, d, r, vn->radius, &cmax, &cmin);
    /* within epsilon for every eye, or a scene leaf (no finer node to split into: every view below draws it
       whole, an oversize leaf where above epsilon; MegaViews 3.2.4): shared if it moves by at most delta
       (delta 0: and every view below draws it) */
    if (cmax <= job->epsilon || s >= scene->leaf_count - 1) {
        if (!(mlod__ball_motion(job->S, xm, d, r, vn->radius) <= job->delta)) return MLOD__PAIR_SPLIT_VIEW;
        if (vn->cone && job->delta == 0.0) { /* delta 0: only what every view below would draw itself */
            k = mlod__surely_within(cos_phi, d, r, vn);
            if (!(k >= 0 ? k : mlod__within_cone(x, d, r, vn->radius, vn->cone, vn->cone[3], vn->least_fov)))
                return MLOD__PAIR_SPLIT_VIEW;
        }
        if (cone && cone[3] < 0.5 * MLOD__PI) {
            k = mlod__surely_facing(x, d, r, vn->radius, cone);
            if (!(k >= 0 ? k : mlod__within_cone(away, d, r, vn->radius, cone, 0.0, 0.5 * MLOD__PI + cone[3])))
                return MLOD__PAIR_SPLIT_VIEW;
        }
        return cmax <= job->epsilon ? MLOD__PAIR_DRAW : MLOD__PAIR_DRAW_LEAF;
    }
    if (cmin > job->epsilon) return MLOD__PAIR_SPLIT_SCENE;
    /* some eyes find s within epsilon, some not: split the larger (MegaViews 3.2.3) */
    return job->delta > 0.0 ? mlod__larger_splits(scene, s, vn->radius) : MLOD__PAIR_SPLIT_VIEW;
}

/* ------------------------------------ MegaViews: the float pair filter -- */

/* The pair test of inner view nodes in float, several pairs at once
   (MegaViews' hot path: nearly every pair has an inner view node).  Each
   lane gives mlod__pair_action's answer where it can prove it, or says it
   is unsure; only then does the exact path run, so every build, with or
   without lanes, gives the same actions bit for bit (tests/test_megaviews.c
   compares them).  It takes view nodes with delta > 0 and back faces not
   culled (mlod__vnode_fast_set); it decides every step of
   mlod__pair_action but the last, the children's radii against the view
   node's (MLOD__VPAIR_MIDDLE, done by the caller).  The pairs of a group
   or a leaf, once not culled by the views' cone, take the cut's vector
   filter (mlod__vstatus) for the view at its centre (a leaf's: its eye).

   The proof, with u = 2^-24 (float rounding) and each quantity's exact
   counterpart the real number that the double path approximates (within
   about 2^-45 relative, and within its own margins: 2^-40 on diameters,
   2^-20 on motion, 2^-30 rad and 1e-9 in cosines on cones):
   - The view node's centre is a float (view tree spheres are), so x =
     centre - c errs by u |x_k|; d^2 = |x|^2 by 5.01 u d^2 and d by 3.6 u d.
     Guards: 2^-40 <= d^2 <= 2^60, r and rho 0 or in [2^-30, 2^30], 2 S /
     epsilon and S / delta in [2^-30, 2^30]: no value overflows, and no
     value other than an exact 0 falls below 2^-100, where a denormal's
     absolute error 2^-149 would matter.
   - With U = d + r + rho, every length below (sums of x_k, d, r, rho, and
     the square roots) errs by at most 150 u U, every area (d^2(1 +- cos)
     and the like) by 160 u U^2: a difference of lengths adds at most 6 u
     U, and a square root sqrt(Y) of an area Y = (a - b)(a + b) (a, b
     lengths <= U) with |dY| <= 13 u U^2 errs by |dY| / (sqrt(Y) +
     sqrt(Y')) + u U <= 106 u U, given the guard 64 Y' >= U^2 on the
     computed Y'; the motion's t_m (an area over U^2 / 64, so 800 u
     relative) errs by 400 u relative.  A lane that fails a guard it needs
     is unsure.
   - Every comparison of lengths is decided only M = 2^-14 U (1024 u U)
     clear, of areas M U clear, and the motion's comparison of volumes
     2^-13 (2048 u) of its right side clear: five times the errors above
     or more, so the decided side is the real numbers' side with a gap of
     at least 860 u U (2^-14 relative for the motion), far beyond the
     double path's errors and margins; the cone's cosines are lengths over
     d, with U <= 2 d where they are compared, and an angle is at least as
     far from its threshold as its cosine.
   - Maps of another orientation (mlod_megaviews_params.forward, up) take
     x.w and P = d sin phi, the length across w, from dot products with
     their axes rounded to float (u relative off the double path's): x.w
     errs by at most 6 u d, P by 10 u d, x's own rounding included (the
     default frame's x2 and sqrt(x0^2 + x1^2): u d and 3 u d), which the
     budgets above absorb (each enters a length, or an area as a factor
     of one <= U, once: a length errs by 115 u U at most, an area by 131
     u U^2).
   - The floor's test (mlod__below_floor: x.a + r - floor + U spread, a
     the float unit axis, floor and spread floats, |floor| <= 2^30) errs
     by at most 20 u (U + |floor|), and is decided 2^-14 (U + |floor|)
     clear.
   Codes: 0 unsure, else 1 + the action (MLOD__VPAIR_MIDDLE: cmax above
   epsilon and cmin not, so the children's radii decide). */
#define MLOD__VPAIR_MIDDLE 6

/* A descent's room (mlod__mv_descend): the most pairs one group of roots
   takes, all its levels (11 bytes of stack each), and the most roots in a
   group. */
#define MLOD__MV_ROOM 2048u
#define MLOD__MV_GROUP 256u
#define MLOD__MV_LEVELS 40u /* the scene tree's depth (< 33) and more */

/* The actions of n <= MLOD__MV_ROOM pairs (scene nodes nodes[0 .. n) with
   view node vn), as mlod__pair_action gives them (with the vector lanes:
   VECTOR LANES at the end). */
static void mlod__pair_actions(const mlod__mv_job *job, const mlod__vnode *vn, const uint32_t *nodes, uint32_t n,
                               uint8_t *actions);


/* ------------------------------------------ MegaViews: a level's units -- */

/* The level's units in order: unit u is scene node in[in_off[j] + i] of
   parent j (a node of the previous level) handed to its left child (u =
   2 in_off[j] + i) or its right (u = 2 in_off[j] + len_j + i).  A cursor
   walks them from any unit on. */
typedef struct mlod__mv_cursor {
    size_t u;
    uint32_t parent;
} mlod__mv_cursor;

static void mlod__mv_seek(const mlod__mv_job *job, size_t u, mlod__mv_cursor *at)
{
    uint32_t lo = 0, hi = job->first - job->prev_first; /* parents: the previous level's nodes */
    size_t half = u / 2;
    at->u = u;
    at->parent = 0;
    if (!job->in_off) return;
    while (hi - lo > 1) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (job->in_off[mid] <= half)
            lo = mid;
        else
            hi = mid;
    }
    while (job->in_off[lo + 1] == job->in_off[lo]) lo++; /* parents that handed nothing down */
    at->parent = lo;
}

/* The view node and scene node of the cursor's unit; moves it on. */
static void mlod__mv_next(const mlod__mv_job *job, mlod__mv_cursor *at, uint32_t *view, uint32_t *scene)
{
    size_t begin, length, local;
    if (!job->in_off) { /* the root level: one unit, (root, root) */
        *view = *scene = 0;
        at->u++;
        return;
    }
    begin = job->in_off[at->parent];
    length = job->in_off[at->parent + 1] - begin;
    local = at->u - 2 * begin;
    *view = 2 * (job->prev_first + at->parent) + 1 + (local >= length);
    *scene = job->in[begin + (local >= length ? local - length : local)];
    if (++at->u == 2 * job->in_off[at->parent + 1] && at->u < job->units) {
        do at->parent++;
        while (job->in_off[at->parent + 1] == job->in_off[at->parent]);
    }
}

/* --------------------------------------- MegaViews: drawing and fusion -- */

/* A scene node's depth in the paraboloid maps of a view node with this
   centre: the distance from it to the node's centre (as mlod__image_discs
   measures it). */
/* GLSL twin: node_distance */
static float mlod__node_distance(const mlod_tree *scene, uint32_t node, const double *centre)
{
    const float *sphere = scene->spheres + 4 * (size_t)node;
    double x[3];
    int k;
    for (k = 0; k < 3; k++) x[k] = (double)sphere[k] - centre[k];
    return (float)mlod__length3(x);
}


/* A scene node's depth at pixel (col, row) of a map whose view is pv (a
   dual paraboloid from a view node's centre), as the fusion measures
   again a node drawn into an ancestor's map: sphere discs (and a node
   without a cone axis, or a pixel outside the paraboloids' discs), d, the
   distance from the eye to the node's centre; tangent discs, the depth
   where the pixel centre's ray meets the node's tangent disc of the
   sphere's radius (mlod__tangent_hit at disc scale 1: so a pixel the
   map's own eye drew keeps the depth it drew), and where it misses it,
   that depth on the disc's plane clamped to the sphere's [d - r, d + r]
   (d + r when the plane lies behind the eye). */
/* GLSL twin: remeasure */
static float mlod__remeasure(const mlod__pview *pv, const mlod_tree *scene, uint32_t node, uint32_t col, uint32_t row,
                             int tangent)
{
    const float *sphere = scene->spheres + 4 * (size_t)node, *cone;
    double x[3], o[3], dir[3], d, t, per_t, v, lo, hi;
    int k, s = col < pv->columns[0][1] ? 0 : 1;
    for (k = 0; k < 3; k++) x[k] = (double)sphere[k] - pv->f.eye[k];
    cone = tangent ? scene->cones + 4 * (size_t)node : NULL;
    if (cone && mlod__has_plane(cone) && mlod__centre_ray(&pv->f.subs[s], pv->kind[s], col + 0.5, row + 0.5, o, dir, &per_t)) {
        if (mlod__plane_hit(x, cone, o, dir, (double)sphere[3], 0, &t)) return (float)(t * per_t);
    } else {
        return (float)mlod__length3(x);
    }
    d = mlod__length3(x);
    lo = d - (double)sphere[3];
    hi = d + (double)sphere[3];
    v = t > 0.0 ? t * per_t : hi;
    if (!(v >= lo)) v = lo;
    if (v > hi) v = hi;
    return (float)v;
}

static void mlod__mv_centre(const mlod__mv_job *job, uint32_t node, double *centre)
{
    int k;
    for (k = 0; k < 3; k++) centre[k] = job->views->eyes->spheres[4 * (size_t)node + k];
}

/* Begin a map (or a leaf's tile) from its parent's map (NULL: empty),
   depths measured again from this node's centre (the eye, for a leaf):
   the parent's node keeps a pixel until a nearer one is drawn; the other
   pixels are cleared.  The parent's drawn pixels are gathered without a
   branch; without channels each pixel is written once. */
static void mlod__mv_inherit(const mlod__mv_job *job, const mlod__band *band, const float *parent_depth,
                             const uint32_t *parent_ids, uint32_t node)
{
    uint32_t width = 2 * job->resolution, row, col, n, l, cols[MLOD__DRAW_CHUNK], ids[MLOD__DRAW_CHUNK];
    float depth[MLOD__DRAW_CHUNK];
    double centre[3];
    mlod__pview pv;
    if (band->normal || band->color || !parent_depth) {
        mlod__band_clear(band, width);
        if (!parent_depth) return;
    }
    mlod__mv_centre(job, node, centre);
    if (job->tangent) { /* the map's view: its pixels' rays */
        mlod_view view = mlod__node_map_view(job, node);
        mlod_result ok = mlod__view_prepare(&view, &pv, NULL);
        MANYLODS_ASSERT(ok == MLOD_OK && pv.sub_count == 2 && pv.columns[0][1] == job->resolution);
        (void)ok;
    }
    for (row = 0; row < job->resolution; row++) {
        float *out = band->depth + (size_t)row * band->stride;
        uint32_t *out_ids = band->ids ? band->ids + (size_t)row * band->id_stride : NULL;
        for (col = 0; col < width;) { /* the row's drawn pixels, up to a chunk at a time */
            const size_t at = (size_t)row * width;
            const uint32_t end = col < job->resolution ? job->resolution : width; /* a chunk within one half */
            for (n = 0; col < end && n < MLOD__DRAW_CHUNK; col++) {
                out[col] = INFINITY;
                if (out_ids) out_ids[col] = 0;
                cols[n] = col;
                ids[n] = parent_ids[at + col];
                n += parent_depth[at + col] < INFINITY;
            }
            if (job->tangent && n > 0) { /* the rays that meet their node's disc in lanes (mlod__remeasure's first case) */
                float fc[MLOD__DRAW_CHUNK], fr[MLOD__DRAW_CHUNK];
                uint8_t hit[MLOD__DRAW_CHUNK];
                for (l = 0; l < n; l++) {
                    fc[l] = (float)cols[l]; /* below 2^31 and whole; and 2 R below 2^24 for the lanes' pixels */
                    fr[l] = (float)row;
                }
                if (width <= 16777216u)
                    mlod__tangent_hits(&pv, cols[0] < job->resolution ? 0 : 1, job->scene, ids, fc, fr, n, 1.0f, hit, depth);
                else
                    memset(hit, 0, n);
                for (l = 0; l < n; l++)
                    if ((hit[l] & 3u) != 3u) depth[l] = mlod__remeasure(&pv, job->scene, ids[l], cols[l], row, 1);
            } else
                mlod__node_distances(job->scene, ids, n, centre, depth);
            if (band->normal || band->color) { /* the node's channels too */
                for (l = 0; l < n; l++) mlod__band_set(band, row, cols[l], depth[l], ids[l]);
                continue;
            }
            for (l = 0; l < n; l++) out[cols[l]] = depth[l];
            for (l = 0; out_ids && l < n; l++) out_ids[cols[l]] = ids[l];
        }
    }
}

/* A view node's parent's map in the level-synchronous traversal (NULL:
   none). */
static void mlod__mv_parent_map(const mlod__mv_job *job, uint32_t node, const float **depth, const uint32_t **ids)
{
    uint32_t map = node > 0 ? job->parent_map_of[(node - 1) / 2 - job->prev_first] : MLOD__NO_MAP;
    *depth = map == MLOD__NO_MAP ? NULL : job->parent_depth + (size_t)map * job->pixels;
    *ids = map == MLOD__NO_MAP ? NULL : job->parent_ids + (size_t)map * job->pixels;
}

/* A view leaf's tile, cleared and initialised from its parent's map (NULL:
   none); ids: pixels for the node drawn at each of its pixels while it
   draws (NULL: it draws nothing). */
static void mlod__mv_leaf_begin(const mlod__mv_job *job, uint32_t node, mlod__band *band, const float *parent_depth,
                                const uint32_t *parent_ids, uint32_t *ids)
{
    const mlod_tree *eyes = job->views->eyes;
    uint32_t leaf = node - (eyes->leaf_count - 1), row;
    mlod__tile_band(job->atlas, job->scene, eyes->leaf_sources[leaf], band);
    band->ids = ids;
    band->id_stride = 2 * (size_t)job->resolution; /* the tile's width */
    /* the walks go on in leaf order: the place of the leaf 8 on (the tiles' table is in view order), and
       the next leaf's tile rows out in the atlas, unless that tile follows this one in its row of cells
       (mlod_atlas_desc.order), where the processor's own prefetch has them */
    if (leaf + 8 < eyes->leaf_count) MLOD__PREFETCH(job->atlas->tiles + 4 * (size_t)eyes->leaf_sources[leaf + 8]);
    if (leaf + 1 < eyes->leaf_count) {
        const uint32_t *here = job->atlas->tiles + 4 * (size_t)eyes->leaf_sources[leaf];
        const uint32_t *tile = job->atlas->tiles + 4 * (size_t)eyes->leaf_sources[leaf + 1];
        float *next = job->atlas->depth + (size_t)tile[1] * job->atlas->width + tile[0];
        if (tile[1] != here[1] || tile[0] != here[0] + job->atlas->cell_width)
            for (row = 0; row < tile[3]; row++) {
                MLOD__PREFETCH_WRITE(next + (size_t)row * job->atlas->width);
                MLOD__PREFETCH_WRITE(next + (size_t)row * job->atlas->width + tile[2] - 1);
            }
    }
    mlod__mv_inherit(job, band, parent_depth, parent_ids, node);
}

/* An inner view node's map (depth and ids, pixels each) as a band, begun
   from its parent's map (NULL: none; mlod__mv_inherit). */
static void mlod__mv_map_begin(const mlod__mv_job *job, uint32_t node, float *depth, uint32_t *ids,
                               const float *parent_depth, const uint32_t *parent_ids, mlod__band *band)
{
    memset(band, 0, sizeof *band);
    band->tree = job->scene;
    band->depth = depth;
    band->ids = ids;
    band->stride = band->id_stride = 2 * job->resolution;
    band->disc_scale = job->disc_scale;
    band->tangent = job->tangent;
    band->row_end = job->resolution;
    mlod__mv_inherit(job, band, parent_depth, parent_ids, node);
}

/* Draw the drawer's waiting nodes; at the first, begin the map and
   prepare the view. */
static void mlod__mv_flush(const mlod__mv_job *job, mlod__mv_drawer *dr)
{
    if (!dr->n) return;
    if (dr->lazy_depth) {
        mlod__mv_map_begin(job, dr->node, dr->lazy_depth, dr->lazy_ids, dr->lazy_parent_depth, dr->lazy_parent_ids,
                           &dr->band);
        dr->lazy_depth = NULL;
    }
    if (!dr->ready) {
        mlod_view view = mlod__node_map_view(job, dr->node);
        mlod_result ok = mlod__view_prepare(&view, dr->pv, NULL); /* as in mlod__vnode_set */
        MANYLODS_ASSERT(ok == MLOD_OK);
        (void)ok;
        mlod__fast_prepare(dr->pv, job->epsilon); /* its planes' float filter (mlod__draw_nodes) */
        dr->ready = 1;
    }
    if (!dr->filter_ready) { /* the band and the view are set by now */
        dr->band.fast = mlod__disc_prepare(dr->pv, &dr->filter) ? &dr->filter : NULL;
        dr->filter_ready = 1;
    }
    mlod__draw_nodes(&dr->band, dr->pv, dr->batch, dr->n);
    dr->n = 0;
}

/* Draw scene nodes[0 .. n) into the drawer's band, in turn with the
   others. */
static void mlod__mv_draw(const mlod__mv_job *job, mlod__mv_drawer *dr, const uint32_t *nodes, size_t n)
{
    while (n) {
        uint32_t k = MLOD__DRAW_CHUNK - dr->n < n ? MLOD__DRAW_CHUNK - dr->n : (uint32_t)n;
        memcpy(dr->batch + dr->n, nodes, k * sizeof *nodes);
        dr->n += k;
        nodes += k;
        n -= k;
        if (dr->n == MLOD__DRAW_CHUNK) mlod__mv_flush(job, dr);
    }
}

/* ------------------------------------------- MegaViews: level by level -- */

/* Scene nodes given to a view node at once in the level-synchronous
   traversal (mlod__mv_classify_task). */
#define MLOD__MV_ROOTS 64u

/* Classify the pairs (roots[i], the view node), i < n, and, depth first,
   the scene nodes below them that split: culled pairs are counted, drawn
   ones drawn at once (dr) or listed, view splits listed, each in depth-
   first order.  Level by level: a group of roots, then the children of
   those that split the scene node, and so on, each level classified at
   once (mlod__pair_actions: full batches of lanes, independent of each
   other); then the pairs are met again in depth-first order, where each
   draw and view split is written: depth first meets a level's pairs in
   their order, so one cursor per level finds the next, and a scene
   split's children are the next two of the level below.  A group whose levels
   outgrow the room (job->descend_room pairs) is taken again with half
   the roots; a root alone that outgrows it is classified by itself and
   its children wait first in line (pending, the next on top).  Each pair
   is counted once, whatever the room.  0 when a list is full. */
static int mlod__mv_descend(const mlod__mv_job *job, const mlod__vnode *vn, const uint32_t *roots, size_t n,
                            mlod__mv_out *out, mlod__mv_drawer *dr)
{
    /* node[i], act[i]: the pairs, level after level (level k: lb[k] .. lb[k + 1] - 1, the children of a level's
       scene splits in their order); cur[k]: level k's next pair in depth-first order; left[k]: how many of the
       current pair's siblings at level k (the roots, at level 0) are still to be met, itself included; list:
       the draws in depth-first order */
    uint32_t node[MLOD__MV_ROOM + 2], lb[MLOD__MV_LEVELS + 1], pend[2 * MLOD__MV_LEVELS], list[MLOD__MV_ROOM + 1];
    uint32_t cur[MLOD__MV_LEVELS], left[MLOD__MV_LEVELS];
    uint8_t act[MLOD__MV_ROOM + 8]; /* (mlod__pair_actions writes whole batches of lanes) */
    const uint32_t room = job->descend_room;
    uint32_t most = room / 2 < MLOD__MV_GROUP ? room / 2 : MLOD__MV_GROUP; /* roots in a group */
    uint32_t npend = 0, group = most, step = out->with_view ? 2u : 1u, unused[2];
    size_t next = 0;
    uint64_t culled = 0, leaves = 0, pairs = 0;
    MANYLODS_ASSERT(room >= 4 && room <= MLOD__MV_ROOM);
    while (npend || next < n) {
        uint32_t g = 0, levels = 0, k, i, w, ns = 0, nd = 0, nv = 0, nc = 0, nl = 0; /* splits, draws, ... */
        int from_pend = npend > 0;
        if (from_pend) /* the group: pending nodes first, in order */
            while (g < group && npend) node[g++] = pend[--npend];
        else {
            g = n - next < group ? (uint32_t)(n - next) : group;
            memcpy(node, roots + next, g * sizeof *node);
        }
        lb[0] = 0;
        lb[1] = g;
        for (k = 0;; k++) { /* classify level k, then list the children of its scene splits as level k + 1 */
            uint32_t b = lb[k], e = lb[k + 1];
            mlod__pair_actions(job, vn, node + b, e - b, act + b);
            for (i = b, ns = 0; i < e; i++) { /* the level's scene splits; the group's draws, view splits, culls */
                uint32_t a = act[i];
                ns += a == MLOD__PAIR_SPLIT_SCENE;
                nd += a == MLOD__PAIR_DRAW || a == MLOD__PAIR_DRAW_LEAF;
                nv += a == MLOD__PAIR_SPLIT_VIEW;
                nc += a == MLOD__PAIR_CULL;
                nl += a == MLOD__PAIR_DRAW_LEAF;
            }
            if (ns == 0 || e + 2 * ns > room || k + 2 > MLOD__MV_LEVELS) {
                levels = k + 1;
                break;
            }
            for (i = b, w = e; i < e; i++) {
                uint32_t s = node[i];
                node[w] = 2 * s + 1;
                node[w + 1] = 2 * s + 2;
                w += act[i] == MLOD__PAIR_SPLIT_SCENE ? 2u : 0u;
            }
            lb[k + 2] = w;
        }
        if (ns) { /* out of room: fewer roots, or this root one level down */
            if (g > 1) {
                if (from_pend)
                    for (i = g; i-- > 0;) pend[npend++] = node[i];
                group = g / 2;
                continue;
            }
            MANYLODS_ASSERT(npend + 2 <= 2 * MLOD__MV_LEVELS);
            pairs++;
            next += !from_pend;
            pend[npend++] = 2 * node[0] + 2;
            pend[npend++] = 2 * node[0] + 1;
            continue;
        }
        if ((dr ? 0 : out->capacity - out->draw_count < nd) || out->capacity - out->split_count < nv) return 0;
        for (k = 0; k < levels; k++) cur[k] = lb[k];
        k = 0;
        left[0] = g;
        for (nd = nv = 0;;) { /* depth first: each pair met, its draw or view split written in turn */
            uint32_t a, s, *to;
            i = cur[k]++;
            a = act[i];
            s = node[i];
            to = a == MLOD__PAIR_SPLIT_VIEW ? out->split + step * (out->split_count + nv) : unused;
            list[nd] = s; /* (kept only for a draw) */
            nd += a == MLOD__PAIR_DRAW || a == MLOD__PAIR_DRAW_LEAF;
            nv += a == MLOD__PAIR_SPLIT_VIEW;
            to[0] = vn->node; /* (written, without a branch, into unused for any other pair) */
            to[step - 1] = s;
            left[k]--;
            if (a == MLOD__PAIR_SPLIT_SCENE) { /* its children next */
                left[++k] = 2;
                continue;
            }
            while (left[k] == 0 && k > 0) k--; /* up to the nearest level with a sibling still to meet */
            if (left[k] == 0) break;
        }
        culled += nc;
        leaves += nl;
        pairs += lb[levels];
        out->split_count += nv;
        if (dr) {
            out->drawn += nd;
            mlod__mv_draw(job, dr, list, nd);
        } else {
            for (i = 0; i < nd; i++) {
                out->draw[2 * (out->draw_count + i)] = vn->node;
                out->draw[2 * (out->draw_count + i) + 1] = list[i];
            }
            out->draw_count += nd;
        }
        next += from_pend ? 0 : g;
        if (2 * group <= most && 2 * lb[levels] <= room) group *= 2;
    }
    out->pairs += pairs;
    out->culled += culled;
    out->leaves += leaves;
    return 1;
}

/* A view leaf's drawer: its tile, begun from its parent's map. */
static void mlod__mv_leaf_drawer(const mlod__mv_job *job, mlod__vnode *vn, const float *parent_depth,
                                 const uint32_t *parent_ids, uint32_t *ids, mlod__mv_drawer *dr)
{
    mlod__mv_leaf_begin(job, vn->node, &dr->band, parent_depth, parent_ids, ids);
    dr->pv = &vn->pv; /* the leaf's own view (mlod__vnode_set) */
    dr->ready = 1;
    dr->filter_ready = 0;
    dr->node = vn->node;
    dr->n = 0;
    dr->lazy_depth = NULL;
}

/* The pairs of view node `node` (all of them, or the part in this chunk)
   into the chunk's output, once its last unit there is classified. */
static void mlod__mv_node_pairs(mlod__mv_out *out, uint32_t node, uint64_t pairs)
{
    if (out->first_node == MLOD__NO_MAP) {
        out->first_node = node;
        out->first_pairs = pairs;
        return;
    }
    if (out->last_node != MLOD__NO_MAP && out->last_pairs > out->most_pairs) out->most_pairs = out->last_pairs;
    out->last_node = node;
    out->last_pairs = pairs;
}

/* The most pairs of one view node over a level's chunks, in order. */
static uint64_t mlod__mv_level_node_pairs(const mlod__mv_out *outs, uint32_t chunks)
{
    uint32_t c, node = MLOD__NO_MAP;
    uint64_t most = 0, sum = 0;
    for (c = 0; c < chunks; c++) {
        const mlod__mv_out *o = &outs[c];
        if (o->first_node == MLOD__NO_MAP) continue;
        if (o->first_node != node) {
            if (sum > most) most = sum;
            node = o->first_node;
            sum = 0;
        }
        sum += o->first_pairs;
        if (o->most_pairs > most) most = o->most_pairs;
        if (o->last_node != MLOD__NO_MAP) {
            if (sum > most) most = sum;
            node = o->last_node;
            sum = o->last_pairs;
        }
    }
    return sum > most ? sum : most;
}

/* Classify a chunk of the level's units: each scene node handed to a view
   node, and depth first below it while the scene node splits.  A chunk
   holds whole view leaves (mlod__mv_chunks), which it draws at once, in
   the order met. */
static void mlod__mv_classify_task(void *context, uint32_t index)
{
    const mlod__mv_job *job = (const mlod__mv_job *)context;
    uint32_t chunk = job->redo ? job->redo[index] : index, view = MLOD__NO_MAP, s0 = 0;
    mlod__mv_out *out = &job->outs[chunk];
    size_t u = job->chunk_begin[chunk], end = job->chunk_begin[chunk + 1];
    mlod__vnode vn;
    mlod__mv_cursor at = {0, 0};
    mlod__mv_drawer dr, *drawing = NULL;
    uint64_t node_start = 0; /* out->pairs at the view node's first unit */
    uint32_t roots[MLOD__MV_ROOTS], count = 0; /* the view node's scene nodes not classified yet */
    vn.node = MLOD__NO_MAP;
    out->draw_count = out->split_count = 0;
    out->pairs = out->culled = out->drawn = out->leaves = 0;
    out->with_view = 1;
    out->overflow = 0;
    out->first_node = out->last_node = MLOD__NO_MAP;
    out->first_pairs = out->last_pairs = out->most_pairs = 0;
    if (u < end) mlod__mv_seek(job, u, &at);
    for (; u <= end; u++) { /* u == end: the last scene nodes classified */
        if (u < end) mlod__mv_next(job, &at, &view, &s0);
        if (count && (u == end || view != vn.node || count == MLOD__MV_ROOTS)) {
            if (!mlod__mv_descend(job, &vn, roots, count, out, drawing)) {
                out->overflow = 1;
                return;
            }
            count = 0;
        }
        if (u == end) break;
        if (view != vn.node) {
            if (vn.node != MLOD__NO_MAP) mlod__mv_node_pairs(out, vn.node, out->pairs - node_start);
            node_start = out->pairs;
            if (drawing) mlod__mv_flush(job, drawing);
            mlod__vnode_set(job, view, &vn);
            drawing = NULL;
            if (vn.leaf && !job->keep) {
                const float *parent_depth;
                const uint32_t *parent_ids;
                mlod__mv_parent_map(job, view, &parent_depth, &parent_ids);
                mlod__mv_leaf_drawer(job, &vn, parent_depth, parent_ids, job->leaf_ids + (size_t)chunk * job->pixels,
                                     &dr);
                drawing = &dr;
            }
        }
        roots[count++] = s0;
    }
    if (vn.node != MLOD__NO_MAP) mlod__mv_node_pairs(out, vn.node, out->pairs - node_start);
    if (drawing) mlod__mv_flush(job, drawing);
}

/* Draw a chunk of the level's nodes: each map (or leaf tile) starts from
   its parent's and takes its own drawn nodes, nearest first. */
static void mlod__mv_draw_task(void *context, uint32_t index)
{
    const mlod__mv_job *job = (const mlod__mv_job *)context;
    const mlod_tree *eyes = job->views->eyes;
    uint32_t i = index * MLOD__MV_DRAW_NODES, end = i + MLOD__MV_DRAW_NODES > job->count ? job->count : i + MLOD__MV_DRAW_NODES;
    for (; i < end; i++) {
        uint32_t node = job->first + i;
        size_t n = job->draw_off[i + 1] - job->draw_off[i];
        const float *parent_depth = NULL;
        const uint32_t *parent_ids = NULL;
        mlod__pview pv;
        mlod__mv_drawer dr;
        if (!job->keep) mlod__mv_parent_map(job, node, &parent_depth, &parent_ids);
        if (node >= eyes->leaf_count - 1 && !job->keep) { /* leaves given no pair: the parent's map alone */
            uint32_t p = (node - 1) / 2 - job->prev_first;
            if (node > 0 && job->in_off[p + 1] == job->in_off[p])
                mlod__mv_leaf_begin(job, node, &dr.band, parent_depth, parent_ids, NULL);
            continue;
        }
        if (job->map_of[i] == MLOD__NO_MAP) continue;
        mlod__mv_map_begin(job, node, job->depth + (size_t)job->map_of[i] * job->pixels,
                           job->ids + (size_t)job->map_of[i] * job->pixels, parent_depth, parent_ids, &dr.band);
        dr.pv = &pv;
        dr.ready = 0;
        dr.filter_ready = 0;
        dr.node = node;
        dr.n = 0;
        dr.lazy_depth = NULL;
        mlod__mv_draw(job, &dr, job->draws + job->draw_off[i], n);
        mlod__mv_flush(job, &dr);
    }
}

/* The call's memory, with its peak. */
typedef struct mlod__mv_memory {
    mlod_allocator a;
    size_t live, peak;
    int failed;
} mlod__mv_memory;

/* The bytes an array of count x size takes from the allocator: a
   zero-size array takes one (mlod__alloc_array). */
static size_t mlod__mv_bytes(size_t count, size_t size)
{
    return count && size ? count * size : 1;
}

static void *mlod__mv_alloc(mlod__mv_memory *m, size_t count, size_t size)
{
    void *p = m->failed ? NULL : mlod__alloc_array(&m->a, count, size, NULL);
    if (!p) {
        m->failed = 1;
        return NULL;
    }
    m->live += mlod__mv_bytes(count, size);
    if (m->live > m->peak) m->peak = m->live;
    return p;
}

static void mlod__mv_free(mlod__mv_memory *m, void *p, size_t count, size_t size)
{
    if (!p) return;
    m->live -= mlod__mv_bytes(count, size);
    mlod__free(&m->a, p);
}

MLOD__PUBLIC mlod_result mlod_megaviews_check(const mlod_megaviews_params *params, mlod_error *error)
{
    uint32_t v;
    if (!params) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "params must not be NULL");
    if (!(params->epsilon > 0.0f))
        return mlod__fail(error, MLOD_ERROR_BAD_EPSILON, "epsilon %g is not > 0", params->epsilon);
    for (v = 0; v < 2; v++) { /* delta, group_radius: finite and >= 0 */
        float x = v ? params->group_radius : params->delta;
        if (!(x >= 0.0f && x < INFINITY))
            return mlod__fail(error, isnan(x) ? MLOD_ERROR_NON_FINITE : MLOD_ERROR_INVALID_ARGUMENT,
                              "%s %g is not finite and >= 0", v ? "group_radius" : "delta", x);
    }
    if (params->resolution == 0 || params->resolution > 0x7fffffffu)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "resolution %u is not in 1 .. 2^31 - 1",
                          params->resolution);
    if (params->flags & ~(uint32_t)MLOD_VIEW_CULL_BACKFACES)
        return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "unknown flags 0x%x (only MLOD_VIEW_CULL_BACKFACES, 0x%x)",
                          params->flags, (unsigned)MLOD_VIEW_CULL_BACKFACES);
    if (!mlod__megaviews_default_axes(params->forward, params->up)) { /* the maps' frame, as mlod_view_check takes it */
        const float *f = params->forward, *u = params->up;
        mlod_view view = mlod_megaviews_view_oriented(NULL, 1, 0, f, u);
        mlod__pview pv;
        mlod_error why;
        if (!mlod__finite3(f) || !mlod__finite3(u))
            return mlod__fail(error, MLOD_ERROR_NON_FINITE, "forward (%g, %g, %g) and up (%g, %g, %g) must be finite",
                              f[0], f[1], f[2], u[0], u[1], u[2]);
        if (mlod__view_prepare(&view, &pv, &why) != MLOD_OK)
            return mlod__fail(error, why.code, "forward (%g, %g, %g), up (%g, %g, %g): %s (both 0: the default)", f[0],
                              f[1], f[2], u[0], u[1], u[2], why.message);
    }
    return mlod__succeed(error);
}

/* The checks of mlod_megaviews_render (atlas NULL: of
   mlod_megaviews_render_maps, which has none). */
static mlod_result mlod__check_megaviews(const mlod_atlas *atlas, const mlod_tree *scene,
                                         const mlod_view_tree *views, const mlod_megaviews_params *params,
                                         mlod_error *error)
{
    uint32_t v;
    mlod_result res;
    if (!scene || !views || !params || !views->eyes)
        return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "scene, views (with its eyes) and params must not be NULL");
    res = mlod_megaviews_check(params, error);
    if (res != MLOD_OK || !atlas) return res;
    if (atlas->view_count != views->view_count)
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "the atlas has %u views, the view tree %u", atlas->view_count,
                          views->view_count);
    for (v = 0; v < atlas->view_count; v++) {
        const uint32_t *t = atlas->tiles + 4 * (size_t)v;
        if (t[2] != 2 * params->resolution || t[3] != params->resolution)
            return mlod__fail(error, MLOD_ERROR_MISMATCH, "view %u has a %ux%u tile, the maps are %ux%u", v, t[2], t[3],
                              2 * params->resolution, params->resolution);
    }
    if (atlas->normal && !scene->cones)
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "the atlas has normals and the scene no cones");
    if (atlas->color && !scene->colors)
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "the atlas has colours and the scene none");
    if (atlas->splat == MLOD_SPLAT_TANGENT && !scene->cones)
        return mlod__fail(error, MLOD_ERROR_MISMATCH, "MLOD_SPLAT_TANGENT needs a scene tree with cones");
    return MLOD_OK;
}

/* Classify one level's units into its job's outputs, growing the outputs
   of chunks that ran out and running those again (a chunk's result does
   not depend on its capacity).  0 when memory failed. */
static int mlod__mv_classify_level(mlod__mv_job *job, mlod__mv_memory *m, const mlod_parallel *parallel,
                                   uint32_t chunks)
{
    uint32_t *redo = (uint32_t *)mlod__mv_alloc(m, chunks, sizeof(uint32_t)), count = chunks, i;
    if (!redo) return 0;
    job->redo = NULL;
    for (;;) {
        uint32_t again = 0;
        mlod__run(parallel, count, mlod__mv_classify_task, job);
        for (i = 0; i < count; i++) {
            uint32_t c = job->redo ? job->redo[i] : i;
            mlod__mv_out *out = &job->outs[c];
            size_t grown;
            uint32_t *pairs;
            if (!out->overflow) continue;
            grown = 4 * out->capacity;
            pairs = (uint32_t *)mlod__mv_alloc(m, grown, 4 * sizeof(uint32_t));
            if (!pairs) break;
            if (out->owned) mlod__mv_free(m, out->draw, out->capacity, 4 * sizeof(uint32_t));
            out->draw = pairs;
            out->split = pairs + 2 * grown;
            out->capacity = grown;
            out->owned = 1;
            redo[again++] = c;
        }
        if (m->failed) break;
        if (!again) break;
        job->redo = redo;
        count = again;
    }
    job->redo = NULL;
    mlod__mv_free(m, redo, chunks, sizeof(uint32_t));
    return !m->failed;
}

/* ---------------------------------------- MegaViews: the subtree walks -- */

/* A walk of one view subtree, depth first: each view node classifies the
   scene nodes its parent handed down, draws into its map (or its tile) at
   once and hands its view splits to both children.  The lists along the
   path share one stack; the inner levels' maps and view nodes one slot
   per level below the subtree's root. */
typedef struct mlod__mv_walk {
    uint32_t root;                      /* its view node, at the walk level */
    const uint32_t *in;                 /* the scene nodes handed to it */
    size_t in_count;
    const float *parent_depth;          /* its parent's map, NULL: none */
    const uint32_t *parent_ids;
    uint32_t *list;                     /* the lists along the path */
    size_t capacity;
    float *depth;                       /* one map per inner level */
    uint32_t *ids;                      /* the maps' nodes, then a leaf's while it draws */
    uint32_t *leaf_ids;                 /* (in ids: after the maps') */
    mlod__vnode *vn;                    /* one per level */
    mlod__pview *pv;                    /* one per level: the inner maps' views */
    int overflow;
    /* where a walk that ran out of room stopped (MLOD__NO_MAP: none): the
       subtrees before it, depth first, are done (their tiles drawn, their
       statistics counted), so the walk runs again only along the path to
       it and from there on */
    uint32_t resume;
    uint64_t pairs, culled, leaf_draws, shared_draws, shared_views, shared_leaves;
    uint64_t node_pairs; /* the most pairs of one view node */
} mlod__mv_walk;

/* Whether view node `node` is `below` or one of its ancestors. */
static int mlod__mv_on_path(uint32_t node, uint32_t below)
{
    while (below > node) below = (below - 1) / 2;
    return below == node;
}

/* One view node of a walk (level: below the subtree's root) and its
   subtree; the scene nodes in[0 .. n) handed to it, the list stack free
   from `top` on. */
static void mlod__mv_walk_node(const mlod__mv_job *job, mlod__mv_walk *w, uint32_t node, uint32_t level,
                               const uint32_t *in, size_t n, size_t top, const float *parent_depth,
                               const uint32_t *parent_ids)
{
    const mlod_tree *eyes = job->views->eyes;
    mlod__vnode *vn = &w->vn[level];
    mlod__mv_drawer dr;
    mlod__mv_out out;
    uint64_t leaf_draws = 0, shared_draws = 0, shared_leaves = 0;
    memset(&out, 0, sizeof out);
    out.split = w->list + top;
    out.capacity = w->capacity - top;
    vn->node = node;
    if (node == w->resume) w->resume = MLOD__NO_MAP; /* from here on, all again */
    if (n) mlod__vnode_set(job, node, vn);
    if (node >= eyes->leaf_count - 1) {
        mlod__mv_leaf_drawer(job, vn, parent_depth, parent_ids, w->leaf_ids, &dr);
        mlod__mv_descend(job, vn, in, n, &out, &dr); /* a leaf splits no view */
        mlod__mv_flush(job, &dr);
        leaf_draws = out.drawn;
    } else {
        float *map_depth = w->depth + (size_t)level * job->pixels; /* this node's map, begun at the first draw */
        uint32_t *map_ids = w->ids + (size_t)level * job->pixels;
        const float *child_depth;
        const uint32_t *child_ids;
        uint32_t c;
        dr.lazy_depth = map_depth;
        dr.lazy_ids = map_ids;
        dr.lazy_parent_depth = parent_depth;
        dr.lazy_parent_ids = parent_ids;
        dr.pv = &w->pv[level];
        dr.ready = 0;
        dr.filter_ready = 0;
        dr.node = node;
        dr.n = 0;
        if (!mlod__mv_descend(job, vn, in, n, &out, &dr)) {
            w->overflow = 1;
            w->resume = node;
            return;
        }
        mlod__mv_flush(job, &dr);
        shared_draws = out.drawn;
        shared_leaves = out.leaves;
        /* a map that drew nothing would be the parent's, each pixel measured again from this node's
           centre: the children measure again from theirs anyway, so they begin from the parent's */
        child_depth = out.drawn ? map_depth : parent_depth;
        child_ids = out.drawn ? map_ids : parent_ids;
        for (c = 2 * node + 1; c <= 2 * node + 2; c++) {
            if (w->resume != MLOD__NO_MAP && !mlod__mv_on_path(c, w->resume)) continue; /* done before */
            mlod__mv_walk_node(job, w, c, level + 1, out.split, out.split_count, top + out.split_count, child_depth,
                               child_ids);
            if (w->overflow) return; /* counted when run again */
        }
    }
    w->pairs += out.pairs;
    w->culled += out.culled;
    w->leaf_draws += leaf_draws;
    w->shared_draws += shared_draws;
    w->shared_views += shared_draws * mlod__leaves_below(node, eyes->leaf_count);
    w->shared_leaves += shared_leaves;
    if (out.pairs > w->node_pairs) w->node_pairs = out.pairs;
}

static void mlod__mv_walk_task(void *context, uint32_t index)
{
    const mlod__mv_job *job = (const mlod__mv_job *)context;
    mlod__mv_walk *w = &job->walks[job->redo ? job->redo[index] : index];
    w->overflow = 0;
    if (w->resume == MLOD__NO_MAP) /* the first run (a run again keeps what the done subtrees counted) */
        w->pairs = w->culled = w->leaf_draws = w->shared_draws = w->shared_views = w->shared_leaves = w->node_pairs = 0;
    mlod__mv_walk_node(job, w, w->root, 0, w->in, w->in_count, 0, w->parent_depth, w->parent_ids);
}

/* The levels from the walk level down: one walk per view node of that
   level, from the scene nodes and maps the level above handed down (the
   job's in, in_off and parent maps), in parallel; walks whose list stack
   ran out get one twice as large and go on from where they stopped, the
   path to it classified again (a walk's result does not depend on its
   room).  0 when memory failed. */
static int mlod__mv_walks(mlod__mv_job *job, mlod__mv_memory *m, const mlod_parallel *parallel,
                          mlod_megaviews_stats *st)
{
    uint32_t count = job->count, i, depth = job->levels - job->walk_level, *redo, todo = count;
    size_t inner = depth > 1 ? depth - 1 : 1; /* maps: one per inner level (room for one at least) */
    mlod__mv_walk *walks = (mlod__mv_walk *)mlod__mv_alloc(m, count, sizeof(mlod__mv_walk));
    redo = (uint32_t *)mlod__mv_alloc(m, count, sizeof(uint32_t));
    if (walks) memset(walks, 0, count * sizeof(mlod__mv_walk));
    for (i = 0; walks && i < count && !m->failed; i++) {
        mlod__mv_walk *w = &walks[i];
        static const uint32_t scene_root = 0;
        w->root = job->first + i;
        w->resume = MLOD__NO_MAP;
        if (job->in_off) {
            uint32_t p = (w->root - 1) / 2 - job->prev_first;
            w->in = job->in + job->in_off[p];
            w->in_count = job->in_off[p + 1] - job->in_off[p];
        } else { /* walking from the root */
            w->in = &scene_root;
            w->in_count = 1;
        }
        mlod__mv_parent_map(job, w->root, &w->parent_depth, &w->parent_ids);
        w->capacity = 4 * w->in_count + job->walk_room;
        w->list = (uint32_t *)mlod__mv_alloc(m, w->capacity, sizeof(uint32_t));
        w->depth = (float *)mlod__mv_alloc(m, inner * job->pixels, sizeof(float));
        w->ids = (uint32_t *)mlod__mv_alloc(m, (inner + 1) * job->pixels, sizeof(uint32_t));
        w->leaf_ids = w->ids ? w->ids + inner * job->pixels : NULL;
        w->vn = (mlod__vnode *)mlod__mv_alloc(m, depth, sizeof(mlod__vnode));
        w->pv = (mlod__pview *)mlod__mv_alloc(m, depth, sizeof(mlod__pview));
    }
    job->walks = walks;
    job->redo = NULL;
    while (!m->failed && todo) {
        uint32_t again = 0;
        mlod__run(parallel, todo, mlod__mv_walk_task, job);
        for (i = 0; i < todo; i++) {
            mlod__mv_walk *w = &walks[job->redo ? job->redo[i] : i];
            if (!w->overflow) continue;
            mlod__mv_free(m, w->list, w->capacity, sizeof(uint32_t));
            w->capacity *= 2;
            w->list = (uint32_t *)mlod__mv_alloc(m, w->capacity, sizeof(uint32_t));
            if (!w->list) w->capacity = 0;
            redo[again++] = (uint32_t)(w - walks);
        }
        job->redo = redo;
        todo = again;
    }
    job->redo = NULL;
    for (i = 0; walks && i < count; i++) {
        mlod__mv_walk *w = &walks[i];
        st->pairs += w->pairs;
        st->culled += w->culled;
        st->leaf_draws += w->leaf_draws;
        st->shared_draws += w->shared_draws;
        st->shared_views += w->shared_views;
        st->shared_leaves += w->shared_leaves;
        if (w->node_pairs > st->node_pairs) st->node_pairs = w->node_pairs;
        mlod__mv_free(m, w->list, w->capacity, sizeof(uint32_t));
        mlod__mv_free(m, w->depth, inner * job->pixels, sizeof(float));
        mlod__mv_free(m, w->ids, (inner + 1) * job->pixels, sizeof(uint32_t));
        mlod__mv_free(m, w->vn, depth, sizeof(mlod__vnode));
        mlod__mv_free(m, w->pv, depth, sizeof(mlod__pview));
    }
    mlod__mv_free(m, walks, count, sizeof(mlod__mv_walk));
    mlod__mv_free(m, redo, count, sizeof(uint32_t));
    job->walks = NULL;
    return !m->failed;
}

/* ----------------------------------------------- MegaViews: the render -- */

struct mlod_megaviews_maps {
    uint32_t resolution, levels;
    uint32_t view_count, scene_nodes; /* of the render's view tree and scene (mlod_megaviews_query refuses others) */
    int tangent;          /* drawn as tangent discs (mlod__splat_tangent) */
    float forward[3], up[3]; /* the maps' orientation (params.forward, up; 0: the default) */
    uint32_t *map_of;     /* per view node: its map among its level's, or MLOD__NO_MAP */
    uint32_t *leaf_of;    /* per view: its leaf node */
    float **depth;        /* per level: the maps' depths from their node's centre, 2 R^2 per map */
    uint32_t **ids;       /* per level: the maps' scene nodes */
    uint32_t *level_maps; /* per level: how many maps */
    size_t bytes;
    mlod_allocator allocator;
};

MLOD__PUBLIC size_t mlod_megaviews_maps_bytes(const mlod_megaviews_maps *maps) { return maps ? maps->bytes : 0; }

MLOD__PUBLIC void mlod_megaviews_maps_destroy(mlod_megaviews_maps *maps)
{
    uint32_t d;
    if (!maps) return;
    for (d = 0; d < maps->levels && maps->depth && maps->ids; d++) {
        mlod__free(&maps->allocator, maps->depth[d]);
        mlod__free(&maps->allocator, maps->ids[d]);
    }
    mlod__free(&maps->allocator, maps->map_of);
    mlod__free(&maps->allocator, maps->leaf_of);
    mlod__free(&maps->allocator, maps->depth);
    mlod__free(&maps->allocator, maps->ids);
    mlod__free(&maps->allocator, maps->level_maps);
    mlod__free(&maps->allocator, maps);
}

/* An empty maps object for the views and levels; NULL without memory. */
static mlod_megaviews_maps *mlod__maps_create(const mlod_allocator *a, const mlod_view_tree *views,
                                              const mlod_tree *scene, uint32_t levels, uint32_t resolution)
{
    const mlod_tree *eyes = views->eyes;
    size_t bytes = 0;
    mlod_megaviews_maps *maps = (mlod_megaviews_maps *)mlod__alloc_array(a, 1, sizeof *maps, &bytes);
    uint32_t i;
    if (!maps) return NULL;
    memset(maps, 0, sizeof *maps);
    maps->allocator = *a;
    maps->resolution = resolution;
    maps->levels = levels;
    maps->view_count = views->view_count;
    maps->scene_nodes = scene->node_count;
    maps->tangent = mlod__splat_tangent(MLOD_SPLAT_AUTO, scene);
    maps->map_of = (uint32_t *)mlod__alloc_array(a, eyes->node_count, sizeof(uint32_t), &bytes);
    maps->leaf_of = (uint32_t *)mlod__alloc_array(a, eyes->leaf_count, sizeof(uint32_t), &bytes);
    maps->depth = (float **)mlod__alloc_array(a, levels, sizeof(float *), &bytes);
    maps->ids = (uint32_t **)mlod__alloc_array(a, levels, sizeof(uint32_t *), &bytes);
    maps->level_maps = (uint32_t *)mlod__alloc_array(a, levels, sizeof(uint32_t), &bytes);
    maps->bytes = bytes;
    if (maps->depth) memset(maps->depth, 0, levels * sizeof(float *));
    if (maps->ids) memset(maps->ids, 0, levels * sizeof(uint32_t *));
    if (!maps->map_of || !maps->leaf_of || !maps->depth || !maps->ids || !maps->level_maps) {
        mlod_megaviews_maps_destroy(maps);
        return NULL;
    }
    memset(maps->level_maps, 0, levels * sizeof(uint32_t));
    for (i = 0; i < eyes->node_count; i++) maps->map_of[i] = MLOD__NO_MAP;
    for (i = 0; i < eyes->leaf_count; i++) maps->leaf_of[eyes->leaf_sources[i]] = eyes->leaf_count - 1 + i;
    return maps;
}

/* The level's chunks of units, their first units into begin (chunk count
   + 1 entries; NULL: count only).  A level with view leaves cuts only
   between parents, so that a chunk draws whole leaves. */
static uint32_t mlod__mv_chunks(const mlod__mv_job *job, int whole_parents, size_t *begin)
{
    uint32_t n = 0, j, parents = job->first - job->prev_first;
    size_t start = 0;
    if (begin) begin[0] = 0;
    if (!job->in_off) {
        if (begin) begin[1] = 1;
        return 1;
    }
    if (!whole_parents) {
        for (start = 0; start < job->units; start += MLOD__MV_CHUNK) {
            n++;
            if (begin) begin[n] = start + MLOD__MV_CHUNK < job->units ? start + MLOD__MV_CHUNK : job->units;
        }
        return n;
    }
    for (j = 0; j < parents; j++) {
        size_t end = 2 * job->in_off[j + 1];
        if (end - start >= MLOD__MV_CHUNK || (j + 1 == parents && end > start)) {
            n++;
            if (begin) begin[n] = end;
            start = end;
        }
    }
    return n;
}

/* The render: fused into the atlas, or (keep) every node's own map kept. */
static mlod_result mlod__megaviews_run(mlod_atlas *atlas, mlod_megaviews_maps **keep, const mlod_tree *scene,
                                       const mlod_view_tree *views, const mlod_megaviews_params *params,
                                       uint32_t walk_level, size_t walk_room, uint32_t descend_room, int exact,
                                       mlod_megaviews_stats *stats, mlod_error *error)
{
    mlod_result res = mlod__check_megaviews(atlas, scene, views, params, error);
    const mlod_tree *eyes;
    mlod__mv_memory m;
    mlod__mv_job job;
    mlod_megaviews_stats st;
    uint32_t levels, d, i, maps = 0, parent_maps = 0, parent_count = 0;
    size_t *in_off = NULL, in_total = 0, u;
    uint32_t *in = NULL, *parent_map_of = NULL, *parent_ids = NULL;
    float *parent_depth = NULL;
    if (res != MLOD_OK) return res;
    eyes = views->eyes;
    memset(&m, 0, sizeof m);
    m.a = params->allocator ? mlod__allocator(params->allocator) : atlas ? atlas->allocator : mlod__allocator(NULL);
    memset(&st, 0, sizeof st);
    memset(&job, 0, sizeof job);
    job.scene = scene;
    job.views = views;
    job.atlas = atlas;
    job.disc_scale = atlas ? atlas->disc_scale : 1.0f;
    job.tangent = mlod__splat_tangent(atlas ? atlas->splat : (uint32_t)MLOD_SPLAT_AUTO, scene);
    job.epsilon = params->epsilon;
    job.delta = params->delta;
    job.group_radius = params->group_radius;
    job.resolution = params->resolution;
    job.flags = params->flags;
    job.S = 0.5 * params->resolution;
    if (!mlod__mv_orient(&job, params->forward, params->up)) /* (mlod_megaviews_check took it) */
        return mlod__fail(error, MLOD_ERROR_BAD_VIEW, "the maps' forward and up make no frame");
    /* every array of maps holds at most one map per view node, 8 bytes a pixel: those sizes must fit size_t */
    if (2.0 * params->resolution * params->resolution * 8.0 * eyes->node_count >= (double)(size_t)-1)
        return mlod__fail(error, MLOD_ERROR_OVERFLOW, "resolution %u: the maps of %u view nodes (%.3g bytes) do not fit size_t",
                          params->resolution, eyes->node_count, 16.0 * params->resolution * params->resolution * eyes->node_count);
    job.pixels = 2 * (size_t)params->resolution * params->resolution;
    levels = mlod__depth_of(eyes->node_count - 1) + 1;
    st.levels = levels;
    if (keep && !(job.keep = mlod__maps_create(&m.a, views, scene, levels, params->resolution)))
        return mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "no memory for the maps");
    if (job.keep) {
        m.live = m.peak = job.keep->bytes;
        memcpy(job.keep->forward, job.forward, sizeof job.forward);
        memcpy(job.keep->up, job.up, sizeof job.up);
    }
    job.levels = levels;
    job.walk_level = keep || levels <= walk_level ? levels : walk_level;
    job.walk_room = walk_room;
    job.descend_room = descend_room ? descend_room : MLOD__MV_ROOM;
    job.exact = exact;
    for (d = 0; d < levels && !m.failed; d++) {
        uint32_t first = (uint32_t)((1ull << d) - 1), count, chunks, c, leaf_slots;
        size_t draws = 0, splits = 0, room, *draw_off, *split_off, *chunk_begin;
        uint32_t *draw, *split, *map_of;
        mlod__mv_out *outs;
        uint32_t *block;
        count = (uint32_t)((uint64_t)eyes->node_count - first < (1ull << d) ? eyes->node_count - first : (1u << d));
        job.first = first;
        job.count = count;
        job.in = in;
        job.in_off = in_off;
        job.units = d == 0 ? 1 : 2 * in_total;
        job.parent_depth = parent_depth;
        job.parent_ids = parent_ids;
        job.parent_map_of = parent_map_of;
        job.depth = NULL; /* this level's maps, once allocated */
        job.ids = NULL;
        maps = 0;
        if (d == job.walk_level) { /* the rest depth first, a walk per view subtree */
            mlod__mv_walks(&job, &m, params->parallel, &st);
            break;
        }
        chunks = mlod__mv_chunks(&job, first + count > eyes->leaf_count - 1, NULL);
        chunk_begin = (size_t *)mlod__mv_alloc(&m, (size_t)chunks + 1, sizeof(size_t));
        /* first pass: each chunk room for its units and a half of either kind, plus 64 */
        room = job.units + job.units / 2 + 64 * (size_t)chunks + 1;
        outs = (mlod__mv_out *)mlod__mv_alloc(&m, chunks ? chunks : 1, sizeof(mlod__mv_out));
        block = (uint32_t *)mlod__mv_alloc(&m, room, 4 * sizeof(uint32_t));
        if (m.failed) {
            mlod__mv_free(&m, chunk_begin, (size_t)chunks + 1, sizeof(size_t));
            mlod__mv_free(&m, outs, chunks ? chunks : 1, sizeof(mlod__mv_out));
            mlod__mv_free(&m, block, room, 4 * sizeof(uint32_t));
            break;
        }
        mlod__mv_chunks(&job, first + count > eyes->leaf_count - 1, chunk_begin);
        job.chunk_begin = chunk_begin;
        for (c = 0, u = 0; c < chunks; c++) {
            size_t n = chunk_begin[c + 1] - chunk_begin[c];
            memset(&outs[c], 0, sizeof outs[c]);
            outs[c].capacity = n + n / 2 + 64;
            outs[c].draw = block + 4 * u;
            outs[c].split = outs[c].draw + 2 * outs[c].capacity;
            u += outs[c].capacity;
        }
        job.outs = outs;
        /* a level of view leaves: each chunk draws its leaves one after the other */
        leaf_slots = !job.keep && first + count > eyes->leaf_count - 1 ? chunks : 0;
        job.leaf_ids = leaf_slots ? (uint32_t *)mlod__mv_alloc(&m, (size_t)leaf_slots * job.pixels, sizeof(uint32_t)) : NULL;
        if (chunks && !m.failed) mlod__mv_classify_level(&job, &m, params->parallel, chunks);
        mlod__mv_free(&m, job.leaf_ids, (size_t)leaf_slots * job.pixels, sizeof(uint32_t));
        job.leaf_ids = NULL;
        draw_off = (size_t *)mlod__mv_alloc(&m, (size_t)count + 1, sizeof(size_t));
        split_off = (size_t *)mlod__mv_alloc(&m, (size_t)count + 1, sizeof(size_t));
        if (!m.failed) {
            uint64_t most = mlod__mv_level_node_pairs(outs, chunks);
            if (most > st.node_pairs) st.node_pairs = most;
        }
        for (c = 0; c < chunks; c++) {
            draws += outs[c].draw_count;
            splits += outs[c].split_count;
            st.pairs += outs[c].pairs;
            st.culled += outs[c].culled;
            st.shared_leaves += outs[c].leaves;
            st.leaf_draws += outs[c].drawn;
            for (u = 0; job.keep && u < outs[c].draw_count; u++) st.leaf_draws += outs[c].draw[2 * u] >= eyes->leaf_count - 1;
        }
        draw = (uint32_t *)mlod__mv_alloc(&m, draws, sizeof(uint32_t));
        split = (uint32_t *)mlod__mv_alloc(&m, splits, sizeof(uint32_t));
        map_of = (uint32_t *)mlod__mv_alloc(&m, count, sizeof(uint32_t));
        if (!m.failed) {
            /* gather by view node, in the order met (chunks in order) */
            memset(draw_off, 0, ((size_t)count + 1) * sizeof(size_t));
            memset(split_off, 0, ((size_t)count + 1) * sizeof(size_t));
            for (c = 0; c < chunks; c++) {
                for (u = 0; u < outs[c].draw_count; u++) draw_off[outs[c].draw[2 * u] - first + 1]++;
                for (u = 0; u < outs[c].split_count; u++) split_off[outs[c].split[2 * u] - first + 1]++;
            }
            for (i = 0; i < count; i++) {
                draw_off[i + 1] += draw_off[i];
                split_off[i + 1] += split_off[i];
            }
            for (c = 0; c < chunks; c++) {
                for (u = 0; u < outs[c].draw_count; u++) {
                    uint32_t v = outs[c].draw[2 * u] - first;
                    draw[draw_off[v]++] = outs[c].draw[2 * u + 1];
                    if (v + first >= eyes->leaf_count - 1) continue; /* kept maps: leaves draw here too */
                    st.shared_draws++;
                    st.shared_views += mlod__leaves_below(v + first, eyes->leaf_count);
                }
                for (u = 0; u < outs[c].split_count; u++) split[split_off[outs[c].split[2 * u] - first]++] = outs[c].split[2 * u + 1];
            }
            for (i = count; i > 0; i--) {
                draw_off[i] = draw_off[i - 1];
                split_off[i] = split_off[i - 1];
            }
            draw_off[0] = split_off[0] = 0;
        }
        for (c = 0; c < chunks; c++)
            if (outs[c].owned) mlod__mv_free(&m, outs[c].draw, outs[c].capacity, 4 * sizeof(uint32_t));
        mlod__mv_free(&m, block, room, 4 * sizeof(uint32_t));
        mlod__mv_free(&m, outs, chunks ? chunks : 1, sizeof(mlod__mv_out));
        mlod__mv_free(&m, chunk_begin, (size_t)chunks + 1, sizeof(size_t));
        if (!m.failed) {
            /* the level's maps: inner nodes with a parent's map or a draw (kept: nodes with a draw) */
            for (i = maps = 0; i < count; i++) {
                uint32_t node = first + i;
                int inherits = !job.keep && node > 0 && parent_map_of[(node - 1) / 2 - job.prev_first] != MLOD__NO_MAP;
                int holds = job.keep || node < eyes->leaf_count - 1;
                map_of[i] = holds && (inherits || draw_off[i + 1] > draw_off[i]) ? maps++ : MLOD__NO_MAP;
            }
            job.depth = (float *)mlod__mv_alloc(&m, (size_t)maps * job.pixels, sizeof(float));
            job.ids = (uint32_t *)mlod__mv_alloc(&m, (size_t)maps * job.pixels, sizeof(uint32_t));
        }
        if (!m.failed) {
            job.draws = draw;
            job.draw_off = draw_off;
            job.map_of = map_of;
            mlod__run(params->parallel, (count + MLOD__MV_DRAW_NODES - 1) / MLOD__MV_DRAW_NODES, mlod__mv_draw_task,
                      &job);
        } else {
            mlod__mv_free(&m, job.depth, (size_t)maps * job.pixels, sizeof(float));
            mlod__mv_free(&m, job.ids, (size_t)maps * job.pixels, sizeof(uint32_t));
            job.depth = NULL;
            job.ids = NULL;
            maps = 0;
        }
        if (job.keep && !m.failed) { /* the level's maps move to the maps object */
            job.keep->depth[d] = job.depth;
            job.keep->ids[d] = job.ids;
            job.keep->level_maps[d] = maps;
            /* still held by the call (m.live): the maps it returns */
            job.keep->bytes += mlod__mv_bytes((size_t)maps * job.pixels, sizeof(float)) +
                               mlod__mv_bytes((size_t)maps * job.pixels, sizeof(uint32_t));
            for (i = 0; i < count; i++) job.keep->map_of[first + i] = map_of[i];
            job.depth = NULL;
            job.ids = NULL;
            maps = 0;
        }
        mlod__mv_free(&m, draw, draws, sizeof(uint32_t));
        mlod__mv_free(&m, draw_off, (size_t)count + 1, sizeof(size_t));
        mlod__mv_free(&m, in, in_total, sizeof(uint32_t));
        mlod__mv_free(&m, in_off, (size_t)parent_count + 1, sizeof(size_t));
        mlod__mv_free(&m, parent_depth, (size_t)parent_maps * job.pixels, sizeof(float));
        mlod__mv_free(&m, parent_ids, (size_t)parent_maps * job.pixels, sizeof(uint32_t));
        mlod__mv_free(&m, parent_map_of, parent_count, sizeof(uint32_t));
        in = split;
        in_off = split_off;
        in_total = splits;
        parent_depth = job.depth;
        parent_ids = job.ids;
        parent_map_of = map_of;
        parent_maps = maps;
        parent_count = count;
        job.prev_first = first;
    }
    mlod__mv_free(&m, in, in_total, sizeof(uint32_t));
    mlod__mv_free(&m, in_off, (size_t)parent_count + 1, sizeof(size_t));
    mlod__mv_free(&m, parent_depth, (size_t)parent_maps * job.pixels, sizeof(float));
    mlod__mv_free(&m, parent_ids, (size_t)parent_maps * job.pixels, sizeof(uint32_t));
    mlod__mv_free(&m, parent_map_of, parent_count, sizeof(uint32_t));
    if (m.failed) {
        for (i = 0; atlas && i < atlas->view_count; i++) {
            mlod__band band;
            mlod__tile_band(atlas, scene, i, &band);
            mlod__band_clear(&band, atlas->tiles[4 * (size_t)i + 2]);
        }
        mlod_megaviews_maps_destroy(job.keep);
        return mlod__fail(error, MLOD_ERROR_OUT_OF_MEMORY, "no memory for the render (%zu bytes held at most)", m.peak);
    }
    st.peak_bytes = m.peak;
    if (stats) *stats = st;
    if (keep) *keep = job.keep;
    return mlod__succeed(error);
}

/* The most bytes mlod__megaviews_run holds at once, fused (walks from
   walk_level, first list room `room`), when no view node classifies more
   than P pairs.  Level by level it holds the level above's hand-down (its
   splits, their offsets, its maps and map table) and its own arrays, each
   at its largest:
   - of a level of C nodes, I of them inner: the pairs handed down U <= C P
     and <= 2 T' (T' the level above's splits), draws and splits D + T
     <= C P (distinct pairs), splits T <= I P;
   - chunks K <= U / MLOD__MV_CHUNK + 1;
   - a chunk's grown lists: a capacity below four times its need (its
     draws or its splits, the more), the one before it (a quarter) held
     while it is allocated: 16 (4 + 1) bytes per need, the needs summing to
     at most D + T;
   - one map per inner node;
   - a walk's list: its first room (4 entries per scene node handed to its
     root, <= P, and `room`), or grown, below twice what its path needs
     (each inner level's list <= P, one level less than the walk's depth);
   and every array one byte more (a zero-size allocation takes one).  The
   phases of a level are summed, not overlapped. */
static double mlod__mv_bound(const mlod_tree *eyes, uint32_t resolution, uint64_t P, uint32_t walk_level, size_t room)
{
    const double px = 2.0 * (double)resolution * (double)resolution, p = P > 0 ? (double)P : 1.0;
    const double per_level = (double)(sizeof(mlod__vnode) + sizeof(mlod__pview));
    uint32_t levels = mlod__depth_of(eyes->node_count - 1) + 1, d;
    double most = 0.0, prev = 0.0, splits_above = 0.0;
    for (d = 0; d < levels; d++) {
        uint64_t first = (1ull << d) - 1, count = eyes->node_count - first < (1ull << d) ? eyes->node_count - first : (1ull << d);
        uint64_t inner = eyes->leaf_count - 1 > first ? eyes->leaf_count - 1 - first : 0;
        double C = (double)count, I = (double)(inner < count ? inner : count), Q = C * p, T = I * p, U, K;
        double classify, gather, maps, level;
        if (d == walk_level) {
            uint32_t depth = levels - d;
            double inner_maps = depth > 1 ? depth - 1.0 : 1.0, list = 4.0 * p + (double)room;
            double grown = 2.0 * (depth - 1.0) * p; /* twice a path's lists */
            if (grown > list) list = grown;
            level = prev + C * ((double)sizeof(mlod__mv_walk) + 4.0) + 2.0 +
                    C * (4.0 * list + (8.0 * inner_maps + 4.0) * px + depth * per_level + 5.0); /* + a leaf's ids */
            return level > most ? level : most;
        }
        U = d == 0 ? 1.0 : (Q < 2.0 * splits_above ? Q : 2.0 * splits_above);
        K = floor(U / MLOD__MV_CHUNK) + 1.0;
        classify = 8.0 * (K + 1.0) + (double)sizeof(mlod__mv_out) * K + 16.0 * (U + floor(U / 2.0) + 64.0 * K + 1.0) +
                   4.0 * K + 80.0 * Q + 2.0 * K + 4.0 + (C > I ? 4.0 * K * px + 1.0 : 0.0); /* + the leaves' ids */
        gather = 16.0 * (C + 1.0) + 4.0 * Q + 4.0 * C + 5.0; /* offsets, draw and split lists, map table */
        maps = 8.0 * I * px + 2.0;
        level = prev + classify + gather + maps;
        if (level > most) most = level;
        /* handed to the next level: the splits, their offsets, the maps and the map table */
        prev = 4.0 * T + 8.0 * (C + 1.0) + 4.0 * C + 3.0 + maps;
        splits_above = T;
    }
    return most;
}

MLOD__PUBLIC size_t mlod_megaviews_bound(const mlod_view_tree *views, uint32_t resolution, uint64_t node_pairs)
{
    double bytes;
    if (!views || !views->eyes || resolution == 0 || resolution > 0x7fffffffu) return 0;
    bytes = mlod__mv_bound(views->eyes, resolution, node_pairs, MLOD__MV_WALK_LEVEL, MLOD__MV_WALK_ROOM);
    return bytes >= (double)(size_t)-1 ? (size_t)-1 : (size_t)bytes;
}

MLOD__PUBLIC mlod_result mlod_megaviews_render(mlod_atlas *atlas, const mlod_tree *scene, const mlod_view_tree *views,
                                               const mlod_megaviews_params *params, mlod_megaviews_stats *stats,
                                               mlod_error *error)
{
    if (!atlas) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "atlas is NULL");
    mlod_atlas_invalidate(atlas); /* its tiles become the maps (mlod_splat redraws them all next) */
    return mlod__megaviews_run(atlas, NULL, scene, views, params, MLOD__MV_WALK_LEVEL, MLOD__MV_WALK_ROOM, 0, 0, stats,
                               error);
}

MLOD__PUBLIC mlod_result mlod_megaviews_render_maps(const mlod_tree *scene, const mlod_view_tree *views,
                                                    const mlod_megaviews_params *params, mlod_megaviews_maps **out,
                                                    mlod_megaviews_stats *stats, mlod_error *error)
{
    if (!out) return mlod__fail(error, MLOD_ERROR_INVALID_ARGUMENT, "out is NULL");
    *out = NULL;
    return mlod__megaviews_run(NULL, out, scene, views, params, 0, 0, 0, 0, stats, error);
}

MLOD__PUBLIC int mlod_megaviews_query(const mlod_megaviews_maps *maps, const mlod_tree *scene,
                                      const mlod_view_tree *views, uint32_t view, uint32_t x, uint32_t y, float *depth,
                                      uint32_t *node)
{
    const mlod_tree *eyes;
    uint32_t path[64], count = 0, leaf, k, have = 0, at_node = 0;
    float at_depth = INFINITY;
    size_t pixel;
    if (!maps || !scene || !views || !views->eyes || view >= views->view_count || x >= 2 * maps->resolution ||
        y >= maps->resolution || views->view_count != maps->view_count || scene->node_count != maps->scene_nodes)
        return 0;
    eyes = views->eyes;
    pixel = (size_t)y * 2 * maps->resolution + x;
    leaf = maps->leaf_of[view];
    for (path[count++] = leaf; leaf > 0;) path[count++] = leaf = (leaf - 1) / 2;
    while (count--) { /* root first */
        uint32_t n = path[count], m = maps->map_of[n], level = mlod__depth_of(n), own;
        double centre[3];
        size_t at;
        for (k = 0; k < 3; k++) centre[k] = eyes->spheres[4 * (size_t)n + k];
        if (have && maps->tangent && scene->cones) { /* measured again from this node's centre, as the fusion does */
            mlod_view mv = mlod_megaviews_view_oriented(eyes->spheres + 4 * (size_t)n, maps->resolution, 0,
                                                        maps->forward, maps->up);
            mlod__pview pv;
            if (mlod__view_prepare(&mv, &pv, NULL) != MLOD_OK) return 0;
            at_depth = mlod__remeasure(&pv, scene, at_node, x, y, 1);
        } else if (have)
            at_depth = mlod__node_distance(scene, at_node, centre); /* measured again from this node's centre */
        if (m == MLOD__NO_MAP) continue;
        at = (size_t)m * 2 * maps->resolution * maps->resolution + pixel;
        if (!mlod__wins(maps->depth[level][at], maps->ids[level][at], at_depth, at_node)) continue;
        own = maps->ids[level][at];
        at_depth = maps->depth[level][at];
        at_node = own;
        have = 1;
    }
    if (!have) return 0;
    if (depth) *depth = at_depth;
    if (node) *node = at_node;
    return 1;
}

/* ------------------------------------------------- pthreads thread pool -- */
#ifdef MANYLODS_PTHREADS

struct mlod_pool {
    pthread_t *threads;
    uint32_t thread_count; /* started threads: workers - 1 */
    pthread_mutex_t lock;
    pthread_cond_t wake, done;
    uint64_t generation;
    mlod_task_fn *task;
    void *context;
    uint32_t count, next, busy;
    int quit;
};

/* Run tasks of the current job until none is left; called with the lock. */
static void mlod__pool_drain(mlod_pool *pool)
{
    while (pool->next < pool->count) {
        uint32_t i = pool->next++;
        mlod_task_fn *task = pool->task;
        void *context = pool->context;
        pool->busy++;
        pthread_mutex_unlock(&pool->lock);
        task(context, i);
        pthread_mutex_lock(&pool->lock);
        pool->busy--;
    }
    if (pool->busy == 0) pthread_cond_broadcast(&pool->done);
}

static void *mlod__pool_worker(void *argument)
{
    mlod_pool *pool = (mlod_pool *)argument;
    uint64_t seen = 0;
    pthread_mutex_lock(&pool->lock);
    for (;;) {
        while (!pool->quit && pool->generation == seen) pthread_cond_wait(&pool->wake, &pool->lock);
        if (pool->quit) break;
        seen = pool->generation;
        mlod__pool_drain(pool);
    }
    pthread_mutex_unlock(&pool->lock);
    return NULL;
}

static void mlod__pool_run(void *user, uint32_t count, mlod_task_fn *task, void *context)
{
    mlod_pool *pool = (mlod_pool *)user;
    pthread_mutex_lock(&pool->lock);
    pool->task = task;
    pool->context = context;
    pool->count = count;
    pool->next = 0;
    pool->generation++;
    pthread_cond_broadcast(&pool->wake);
    mlod__pool_drain(pool);
    while (pool->next < pool->count || pool->busy > 0) pthread_cond_wait(&pool->done, &pool->lock);
    pthread_mutex_unlock(&pool->lock);
}

MLOD__PUBLIC mlod_pool *mlod_pool_create(uint32_t threads)
{
    mlod_pool *pool;
    uint32_t i;
    if (threads == 0 || threads > 1024) return NULL;
    pool = (mlod_pool *)malloc(sizeof *pool);
    if (!pool) return NULL;
    memset(pool, 0, sizeof *pool);
    pool->threads = (pthread_t *)malloc(sizeof(pthread_t) * (threads > 1 ? threads - 1 : 1));
    if (!pool->threads) {
        free(pool);
        return NULL;
    }
    pthread_mutex_init(&pool->lock, NULL);
    pthread_cond_init(&pool->wake, NULL);
    pthread_cond_init(&pool->done, NULL);
    for (i = 0; i + 1 < threads; i++) {
        if (pthread_create(&pool->threads[i], NULL, mlod__pool_worker, pool) != 0) break;
        pool->thread_count++;
    }
    if (pool->thread_count + 1 != threads) {
        mlod_pool_destroy(pool);
        return NULL;
    }
    return pool;
}

MLOD__PUBLIC void mlod_pool_destroy(mlod_pool *pool)
{
    uint32_t i;
    if (!pool) return;
    pthread_mutex_lock(&pool->lock);
    pool->quit = 1;
    pthread_cond_broadcast(&pool->wake);
    pthread_mutex_unlock(&pool->lock);
    for (i = 0; i < pool->thread_count; i++) pthread_join(pool->threads[i], NULL);
    pthread_mutex_destroy(&pool->lock);
    pthread_cond_destroy(&pool->wake);
    pthread_cond_destroy(&pool->done);
    free(pool->threads);
    free(pool);
}

MLOD__PUBLIC mlod_parallel mlod_pool_parallel(mlod_pool *pool)
{
    mlod_parallel p;
    p.run = pool ? mlod__pool_run : NULL; /* NULL: the calling thread alone */
    p.user = pool;
    return p;
}
#endif /* MANYLODS_PTHREADS */

/* ---------------------------------------- vector lanes: one pass a level */
/* VECTOR LANES (the end of this file) once per level: AVX2 and AVX-512
   (where the build dispatches to them), none (where the build has lanes),
   and last the build's own, with the plain names. */
#define MLOD__LV3(name, suffix) name##suffix
#define MLOD__LV2(name, suffix) MLOD__LV3(name, suffix)
#define MLOD__LV(name) MLOD__LV2(name, MLOD__LANES_SUFFIX)
#if defined(__has_include)
#if !__has_include(MANYLODS_SELF)
#error "manylods: the implementation includes its own file again as MANYLODS_SELF (default \"manylods.h\", looked up beside it first): define MANYLODS_SELF as this file's name"
#endif
#endif
#if MLOD__DISPATCH_AVX2
#define MLOD__PASS_LEVEL 3
#define MLOD__LANES_SUFFIX _avx2
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2")
#endif
#include MANYLODS_SELF
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif
#undef MLOD__PASS_LEVEL
#undef MLOD__LANES_SUFFIX
#endif
#if MLOD__DISPATCH_AVX512 /* (gcc only) */
#define MLOD__PASS_LEVEL 4
#define MLOD__LANES_SUFFIX _avx512
#pragma GCC push_options
#pragma GCC target("avx2,avx512f,avx512vl,avx512dq,avx512bw")
#include MANYLODS_SELF
#pragma GCC pop_options
#undef MLOD__PASS_LEVEL
#undef MLOD__LANES_SUFFIX
#endif
#if MLOD__BASE_LEVEL != 0
#define MLOD__PASS_LEVEL 0
#define MLOD__LANES_SUFFIX _none
#include MANYLODS_SELF
#undef MLOD__PASS_LEVEL
#undef MLOD__LANES_SUFFIX
#endif
#define MLOD__PASS_LEVEL MLOD__BASE_LEVEL
#define MLOD__PASS_BASE 1
#define MLOD__LANES_SUFFIX
#include MANYLODS_SELF
#undef MLOD__PASS_LEVEL
#undef MLOD__PASS_BASE
#undef MLOD__LANES_SUFFIX
#undef MLOD__LV
#undef MLOD__LV2
#undef MLOD__LV3
#undef mlod__all_set
#undef mlod__classify_children
#undef mlod__classify_known
#undef mlod__classify_lanes
#undef mlod__classify_list
#undef mlod__classify_pairs
#undef mlod__classify_pairs_vector
#undef mlod__classify_vector
#undef mlod__disc_insides
#undef mlod__disc_pixels
#undef mlod__draw_filtered
#undef mlod__draw_nodes
#undef mlod__fast_disc
#undef mlod__fast_disc_lanes
#undef mlod__fast_discs
#undef mlod__fast_fixed
#undef mlod__filtered
#undef mlod__lowest_bit
#undef mlod__node_distances
#undef mlod__pad_last
#undef mlod__pair_actions
#undef mlod__reached_lanes
#undef mlod__settle_lanes
#undef mlod__tangent_hits
#undef mlod__vat_least
#undef mlod__vbackfacing
#undef mlod__vbits
#undef mlod__vbytes
#undef mlod__vbytes_pairs
#undef mlod__vclear
#undef mlod__vdot
#undef mlod__vleaf
#undef mlod__vleaf_pairs
#undef mlod__vload
#undef mlod__vload_pairs
#undef mlod__vmin
#undef mlod__vpack
#undef mlod__vpair
#undef mlod__vpair_action
#undef mlod__vpair_bytes
#undef mlod__vplanes
#undef mlod__vrelative
#undef mlod__vrows
#undef mlod__vselect
#undef mlod__vsetup
#undef mlod__vstatus
#undef mlod__vstatus_known
#undef mlod__vundecided
#undef mlod__wd_rows
#undef mlod__vf
#undef mlod__wd

#if defined(__clang__)
#ifdef MLOD__NO_FMA_TARGET
#pragma clang attribute pop
#undef MLOD__NO_FMA_TARGET
#endif
#pragma STDC FP_CONTRACT DEFAULT
#if __clang_major__ >= 11
#pragma float_control(pop)
#endif
#elif defined(__GNUC__)
#pragma GCC pop_options
#endif
#undef MLOD__PUBLIC
#endif /* MANYLODS_IMPLEMENTATION_DONE */
#endif /* MANYLODS_IMPLEMENTATION */

/* ======================================================================== */
/*               VECTOR LANES: compiled once per level in use                */
/* ======================================================================== */
/* The code that runs in float vector lanes (the cut's float filter, the
   splat's small discs and plane tests, MegaViews' pair filter) and the
   functions that call it, compiled once per level of mlod_simd that the
   build has (MLOD__PASS_LEVEL): the implementation includes this file
   again for each (MANYLODS_SELF), its functions renamed for every level
   but the build's own (MLOD__LANES_SUFFIX), the AVX2 pass for that target
   (gcc, clang).  The build's own level comes last, with the plain names:
   its entries (mlod__classify_list, mlod__classify_children,
   mlod__draw_nodes, mlod__pair_actions, mlod__node_distances) hand each
   call to the level in use (mlod_simd_level).  Every level computes the
   same bits. */
#ifdef MLOD__PASS_LEVEL
/* a pass of its own: the previous pass's lane macros gone */
#undef MLOD__BOX_STRIDE
#undef MLOD__BY_SHAPE
#undef MLOD__FIX
#undef MLOD__LIST_AHEAD
#undef MLOD__LOAD4
#undef MLOD__VABS
#undef MLOD__VADD
#undef MLOD__VAND
#undef MLOD__VANDNOT
#undef MLOD__VBITS
#undef MLOD__VBITWISE
#undef MLOD__VDIV
#undef MLOD__VDOT
#undef MLOD__VEQ
#undef MLOD__VGE
#undef MLOD__VGT
#undef MLOD__VKEEP
#undef MLOD__VLANES
#undef MLOD__VLE
#undef MLOD__VLOADU
#undef MLOD__VLT
#undef MLOD__VMUL
#undef MLOD__VOR
#undef MLOD__VPAIRS
#undef MLOD__VSET
#undef MLOD__VSQRT
#undef MLOD__VSTORE
#undef MLOD__VSUB
#undef MLOD__VTRUNC
#undef MLOD__X86_LANES
#undef MLOD__WADD
#undef MLOD__WDIV
#undef MLOD__WFLOATS
#undef MLOD__WLANES
#undef MLOD__WMUL
#undef MLOD__WSPLAT
#undef MLOD__WSQRT
#undef MLOD__WSTORE
#undef MLOD__WSUB
/* this pass's names: name##MLOD__LANES_SUFFIX (the build's own level: the
   plain names); the implementation undefines them after its last pass */
#define mlod__all_set MLOD__LV(mlod__all_set)
#define mlod__classify_children MLOD__LV(mlod__classify_children)
#define mlod__classify_known MLOD__LV(mlod__classify_known)
#define mlod__classify_lanes MLOD__LV(mlod__classify_lanes)
#define mlod__classify_list MLOD__LV(mlod__classify_list)
#define mlod__classify_pairs MLOD__LV(mlod__classify_pairs)
#define mlod__classify_pairs_vector MLOD__LV(mlod__classify_pairs_vector)
#define mlod__classify_vector MLOD__LV(mlod__classify_vector)
#define mlod__disc_insides MLOD__LV(mlod__disc_insides)
#define mlod__disc_pixels MLOD__LV(mlod__disc_pixels)
#define mlod__draw_filtered MLOD__LV(mlod__draw_filtered)
#define mlod__draw_nodes MLOD__LV(mlod__draw_nodes)
#define mlod__fast_disc MLOD__LV(mlod__fast_disc)
#define mlod__fast_disc_lanes MLOD__LV(mlod__fast_disc_lanes)
#define mlod__fast_discs MLOD__LV(mlod__fast_discs)
#define mlod__fast_fixed MLOD__LV(mlod__fast_fixed)
#define mlod__filtered MLOD__LV(mlod__filtered)
#define mlod__lowest_bit MLOD__LV(mlod__lowest_bit)
#define mlod__node_distances MLOD__LV(mlod__node_distances)
#define mlod__pad_last MLOD__LV(mlod__pad_last)
#define mlod__pair_actions MLOD__LV(mlod__pair_actions)
#define mlod__reached_lanes MLOD__LV(mlod__reached_lanes)
#define mlod__settle_lanes MLOD__LV(mlod__settle_lanes)
#define mlod__tangent_hits MLOD__LV(mlod__tangent_hits)
#define mlod__vat_least MLOD__LV(mlod__vat_least)
#define mlod__vbackfacing MLOD__LV(mlod__vbackfacing)
#define mlod__vbits MLOD__LV(mlod__vbits)
#define mlod__vbytes MLOD__LV(mlod__vbytes)
#define mlod__vbytes_pairs MLOD__LV(mlod__vbytes_pairs)
#define mlod__vclear MLOD__LV(mlod__vclear)
#define mlod__vdot MLOD__LV(mlod__vdot)
#define mlod__vleaf MLOD__LV(mlod__vleaf)
#define mlod__vleaf_pairs MLOD__LV(mlod__vleaf_pairs)
#define mlod__vload MLOD__LV(mlod__vload)
#define mlod__vload_pairs MLOD__LV(mlod__vload_pairs)
#define mlod__vmin MLOD__LV(mlod__vmin)
#define mlod__vpack MLOD__LV(mlod__vpack)
#define mlod__vpair MLOD__LV(mlod__vpair)
#define mlod__vpair_action MLOD__LV(mlod__vpair_action)
#define mlod__vpair_bytes MLOD__LV(mlod__vpair_bytes)
#define mlod__vplanes MLOD__LV(mlod__vplanes)
#define mlod__vrelative MLOD__LV(mlod__vrelative)
#define mlod__vrows MLOD__LV(mlod__vrows)
#define mlod__vselect MLOD__LV(mlod__vselect)
#define mlod__vsetup MLOD__LV(mlod__vsetup)
#define mlod__vstatus MLOD__LV(mlod__vstatus)
#define mlod__vstatus_known MLOD__LV(mlod__vstatus_known)
#define mlod__vundecided MLOD__LV(mlod__vundecided)
#define mlod__wd_rows MLOD__LV(mlod__wd_rows)
#define mlod__vf MLOD__LV(mlod__vf)
#define mlod__wd MLOD__LV(mlod__wd)
/* The build's own level hands a call to the level in use where it is
   another: `name args` as name_avx2 or name_none. */
#if defined(MLOD__PASS_BASE) && MLOD__BASE_LEVEL != 0
#if MLOD__DISPATCH_AVX2
#define MLOD__IF_AVX2(x) x
#else
#define MLOD__IF_AVX2(x)
#endif
#if MLOD__DISPATCH_AVX512
#define MLOD__IF_AVX512(x) x
#else
#define MLOD__IF_AVX512(x)
#endif
#define MLOD__LANES_REDIRECT(name, args)                                                                               \
    switch (mlod__simd_pass()) {                                                                                       \
        MLOD__IF_AVX2(case 3: name##_avx2 args; return;)                                                               \
        MLOD__IF_AVX512(case 4: name##_avx512 args; return;)                                                           \
    case 0:                                                                                                            \
        name##_none args;                                                                                              \
        return;                                                                                                        \
    default:                                                                                                           \
        break;                                                                                                         \
    }
#else
#define MLOD__LANES_REDIRECT(name, args) (void)0
#endif

/* mlod__fast_status on several node-views at once: lanes of 8 floats in
   the AVX2 pass, 4 in the SSE2 and NEON passes, none in the scalar one
   (MLOD__PASS_LEVEL).  Each lane
   proves its status with the same bounds as mlod__fast_status, so a
   decided lane agrees with the exact path; a lane that cannot prove it
   takes the exact path, so every build gives the same cuts bit for bit
   (tests/test_cut.c compares them). */
#ifdef MLOD__NO_FMA_TARGET
/* clang cannot inline an intrinsic into a function built for a target
   without FMA: the vector filter keeps the caller's target, and may be
   fused (its bounds hold for fused multiply-adds: each rounds less), its
   decisions being exact either way */
#pragma clang attribute pop
#endif
#if MLOD__PASS_LEVEL >= 3
#include <immintrin.h>
#define MLOD__VLANES 8
#define MLOD__X86_LANES 1
typedef __m256 mlod__vf;
#define MLOD__VADD _mm256_add_ps
#define MLOD__VSUB _mm256_sub_ps
#define MLOD__VMUL _mm256_mul_ps
#define MLOD__VDIV _mm256_div_ps
#define MLOD__VSTORE _mm256_storeu_ps
#define MLOD__VLOADU _mm256_loadu_ps
#define MLOD__VAND _mm256_and_ps
#define MLOD__VOR _mm256_or_ps
#define MLOD__VANDNOT _mm256_andnot_ps /* (not a) and b */
#define MLOD__VSET _mm256_set1_ps
#define MLOD__VSQRT _mm256_sqrt_ps
#define MLOD__VLT(a, b) _mm256_cmp_ps(a, b, _CMP_LT_OQ)
#define MLOD__VLE(a, b) _mm256_cmp_ps(a, b, _CMP_LE_OQ)
#define MLOD__VGT(a, b) _mm256_cmp_ps(a, b, _CMP_GT_OQ)
#define MLOD__VGE(a, b) _mm256_cmp_ps(a, b, _CMP_GE_OQ)
#define MLOD__VEQ(a, b) _mm256_cmp_ps(a, b, _CMP_EQ_OQ)
#define MLOD__VBITS _mm256_movemask_ps
/* a rounded toward zero (lanes below 2^31 in magnitude: those that read it) */
#define MLOD__VTRUNC(a) _mm256_round_ps(a, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC)

/* Rows of four floats, one per lane: lane l gets x, y, z, w of row
   nodes[l] of rows. */
MLOD__FORCE_INLINE __m256 mlod__vrows(const float *rows, uint32_t low, uint32_t high)
{
    return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(rows + 4 * (size_t)low)),
                                _mm_loadu_ps(rows + 4 * (size_t)high), 1);
}

MLOD__FORCE_INLINE void mlod__vload(const float *rows, const uint32_t *nodes, mlod__vf *x, mlod__vf *y, mlod__vf *z, mlod__vf *w)
{
    __m256 a = mlod__vrows(rows, nodes[0], nodes[4]), b = mlod__vrows(rows, nodes[1], nodes[5]);
    __m256 c = mlod__vrows(rows, nodes[2], nodes[6]), d = mlod__vrows(rows, nodes[3], nodes[7]);
    __m256 ab0 = _mm256_unpacklo_ps(a, b), ab1 = _mm256_unpackhi_ps(a, b);
    __m256 cd0 = _mm256_unpacklo_ps(c, d), cd1 = _mm256_unpackhi_ps(c, d);
    *x = _mm256_shuffle_ps(ab0, cd0, 0x44);
    *y = _mm256_shuffle_ps(ab0, cd0, 0xEE);
    *z = _mm256_shuffle_ps(ab1, cd1, 0x44);
    *w = _mm256_shuffle_ps(ab1, cd1, 0xEE);
}

/* v - e in double, rounded to float. */
static mlod__vf mlod__vrelative(mlod__vf v, double e)
{
    __m256d de = _mm256_set1_pd(e);
    __m128 lo = _mm256_cvtpd_ps(_mm256_sub_pd(_mm256_cvtps_pd(_mm256_castps256_ps128(v)), de));
    __m128 hi = _mm256_cvtpd_ps(_mm256_sub_pd(_mm256_cvtps_pd(_mm256_extractf128_ps(v, 1)), de));
    return _mm256_insertf128_ps(_mm256_castps128_ps256(lo), hi, 1);
}

/* Status codes (small whole numbers in float lanes) as bytes, lane l in
   byte l. */
MLOD__FORCE_INLINE __m128i mlod__vpack(__m256 codes)
{
    __m256i i = _mm256_cvttps_epi32(codes);
    __m128i p = _mm_packs_epi32(_mm256_castsi256_si128(i), _mm256_extractf128_si256(i, 1));
    return _mm_packus_epi16(p, p);
}

/* Status codes to bytes at out. */
MLOD__FORCE_INLINE void mlod__vbytes(__m256 codes, uint8_t *out) { _mm_storel_epi64((__m128i *)(void *)out, mlod__vpack(codes)); }

/* The children of four parents in one load per pair (a pair's rows are
   adjacent): lanes 0 - 3 the left children 2p + 1, lanes 4 - 7 the right
   ones 2p + 2. */
#define MLOD__VPAIRS 4
MLOD__FORCE_INLINE void mlod__vload_pairs(const float *rows, const uint32_t *parents, __m256 *x, __m256 *y, __m256 *z, __m256 *w)
{
    __m256 a = _mm256_loadu_ps(rows + 8 * (size_t)parents[0] + 4), b = _mm256_loadu_ps(rows + 8 * (size_t)parents[1] + 4);
    __m256 c = _mm256_loadu_ps(rows + 8 * (size_t)parents[2] + 4), d = _mm256_loadu_ps(rows + 8 * (size_t)parents[3] + 4);
    __m256 ab0 = _mm256_unpacklo_ps(a, b), ab1 = _mm256_unpackhi_ps(a, b);
    __m256 cd0 = _mm256_unpacklo_ps(c, d), cd1 = _mm256_unpackhi_ps(c, d);
    *x = _mm256_shuffle_ps(ab0, cd0, 0x44);
    *y = _mm256_shuffle_ps(ab0, cd0, 0xEE);
    *z = _mm256_shuffle_ps(ab1, cd1, 0x44);
    *w = _mm256_shuffle_ps(ab1, cd1, 0xEE);
}
/* mlod__vbytes with the pairs' order undone: out[2i] the left child of
   parent i, out[2i + 1] its right one. */
MLOD__FORCE_INLINE void mlod__vbytes_pairs(__m256 codes, uint8_t *out)
{
    __m128i p = mlod__vpack(codes);
    _mm_storel_epi64((__m128i *)(void *)out, _mm_unpacklo_epi8(p, _mm_srli_si128(p, 4)));
}
#elif MLOD__PASS_LEVEL == 1
#include <emmintrin.h>
#define MLOD__VLANES 4
#define MLOD__X86_LANES 1
typedef __m128 mlod__vf;
#define MLOD__VADD _mm_add_ps
#define MLOD__VSUB _mm_sub_ps
#define MLOD__VMUL _mm_mul_ps
#define MLOD__VDIV _mm_div_ps
#define MLOD__VSTORE _mm_storeu_ps
#define MLOD__VLOADU _mm_loadu_ps
#define MLOD__VAND _mm_and_ps
#define MLOD__VOR _mm_or_ps
#define MLOD__VANDNOT _mm_andnot_ps
#define MLOD__VSET _mm_set1_ps
#define MLOD__VSQRT _mm_sqrt_ps
#define MLOD__VLT _mm_cmplt_ps
#define MLOD__VLE _mm_cmple_ps
#define MLOD__VGT _mm_cmpgt_ps
#define MLOD__VGE _mm_cmpge_ps
#define MLOD__VEQ _mm_cmpeq_ps
#define MLOD__VBITS _mm_movemask_ps
#define MLOD__VTRUNC(a) _mm_cvtepi32_ps(_mm_cvttps_epi32(a))

MLOD__FORCE_INLINE void mlod__vload(const float *rows, const uint32_t *nodes, mlod__vf *x, mlod__vf *y, mlod__vf *z, mlod__vf *w)
{
    __m128 a = _mm_loadu_ps(rows + 4 * (size_t)nodes[0]), b = _mm_loadu_ps(rows + 4 * (size_t)nodes[1]);
    __m128 c = _mm_loadu_ps(rows + 4 * (size_t)nodes[2]), d = _mm_loadu_ps(rows + 4 * (size_t)nodes[3]);
    __m128 ab0 = _mm_unpacklo_ps(a, b), ab1 = _mm_unpackhi_ps(a, b);
    __m128 cd0 = _mm_unpacklo_ps(c, d), cd1 = _mm_unpackhi_ps(c, d);
    *x = _mm_movelh_ps(ab0, cd0);
    *y = _mm_movehl_ps(cd0, ab0);
    *z = _mm_movelh_ps(ab1, cd1);
    *w = _mm_movehl_ps(cd1, ab1);
}

static mlod__vf mlod__vrelative(mlod__vf v, double e)
{
    __m128d de = _mm_set1_pd(e);
    __m128 lo = _mm_cvtpd_ps(_mm_sub_pd(_mm_cvtps_pd(v), de));
    __m128 hi = _mm_cvtpd_ps(_mm_sub_pd(_mm_cvtps_pd(_mm_movehl_ps(v, v)), de));
    return _mm_movelh_ps(lo, hi);
}

/* Status codes (small whole numbers in float lanes) to bytes at out. */
MLOD__FORCE_INLINE void mlod__vbytes(__m128 codes, uint8_t *out)
{
    __m128i p = _mm_cvttps_epi32(codes);
    int word;
    p = _mm_packs_epi32(p, p);
    word = _mm_cvtsi128_si32(_mm_packus_epi16(p, p));
    memcpy(out, &word, 4);
}
#elif MLOD__PASS_LEVEL == 2
#include <arm_neon.h>
#define MLOD__VLANES 4
typedef float32x4_t mlod__vf;
#define MLOD__VADD vaddq_f32
#define MLOD__VSUB vsubq_f32
#define MLOD__VMUL vmulq_f32
#define MLOD__VDIV vdivq_f32
#define MLOD__VSTORE vst1q_f32
#define MLOD__VLOADU vld1q_f32
#define MLOD__VBITWISE(op, a, b) vreinterpretq_f32_u32(op(vreinterpretq_u32_f32(a), vreinterpretq_u32_f32(b)))
#define MLOD__VAND(a, b) MLOD__VBITWISE(vandq_u32, a, b)
#define MLOD__VOR(a, b) MLOD__VBITWISE(vorrq_u32, a, b)
#define MLOD__VANDNOT(a, b) MLOD__VBITWISE(vbicq_u32, b, a) /* (not a) and b */
#define MLOD__VSET vdupq_n_f32
#define MLOD__VSQRT vsqrtq_f32
#define MLOD__VLT(a, b) vreinterpretq_f32_u32(vcltq_f32(a, b))
#define MLOD__VLE(a, b) vreinterpretq_f32_u32(vcleq_f32(a, b))
#define MLOD__VGT(a, b) vreinterpretq_f32_u32(vcgtq_f32(a, b))
#define MLOD__VGE(a, b) vreinterpretq_f32_u32(vcgeq_f32(a, b))
#define MLOD__VEQ(a, b) vreinterpretq_f32_u32(vceqq_f32(a, b))
#define MLOD__VTRUNC vrndq_f32

/* Lane l's bit l where its mask is set. */
#define MLOD__VBITS mlod__vbits
static int mlod__vbits(mlod__vf mask)
{
    static const uint32_t bit[4] = {1u, 2u, 4u, 8u};
    return (int)vaddvq_u32(vandq_u32(vreinterpretq_u32_f32(mask), vld1q_u32(bit)));
}

MLOD__FORCE_INLINE void mlod__vload(const float *rows, const uint32_t *nodes, mlod__vf *x, mlod__vf *y, mlod__vf *z, mlod__vf *w)
{
    float32x4x2_t ab = vtrnq_f32(vld1q_f32(rows + 4 * (size_t)nodes[0]), vld1q_f32(rows + 4 * (size_t)nodes[1]));
    float32x4x2_t cd = vtrnq_f32(vld1q_f32(rows + 4 * (size_t)nodes[2]), vld1q_f32(rows + 4 * (size_t)nodes[3]));
    *x = vcombine_f32(vget_low_f32(ab.val[0]), vget_low_f32(cd.val[0]));
    *y = vcombine_f32(vget_low_f32(ab.val[1]), vget_low_f32(cd.val[1]));
    *z = vcombine_f32(vget_high_f32(ab.val[0]), vget_high_f32(cd.val[0]));
    *w = vcombine_f32(vget_high_f32(ab.val[1]), vget_high_f32(cd.val[1]));
}

static mlod__vf mlod__vrelative(mlod__vf v, double e)
{
    float64x2_t de = vdupq_n_f64(e);
    float32x2_t lo = vcvt_f32_f64(vsubq_f64(vcvt_f64_f32(vget_low_f32(v)), de));
    float32x2_t hi = vcvt_f32_f64(vsubq_f64(vcvt_f64_f32(vget_high_f32(v)), de));
    return vcombine_f32(lo, hi);
}

/* Lanes whose node is at least `first`, as a mask. */
static float32x4_t mlod__vleaf(const uint32_t *nodes, uint32_t first)
{
    return vreinterpretq_f32_u32(vcgeq_u32(vld1q_u32(nodes), vdupq_n_u32(first)));
}

/* Status codes (small whole numbers in float lanes) to bytes at out. */
MLOD__FORCE_INLINE void mlod__vbytes(float32x4_t codes, uint8_t *out)
{
    uint16x4_t h = vmovn_u32(vcvtq_u32_f32(codes));
    uint8_t bytes[8];
    vst1_u8(bytes, vmovn_u16(vcombine_u16(h, h)));
    memcpy(out, bytes, 4);
}
#endif

/* Doubles in lanes, for the steps that the exact path takes in double
   (mlod__tangent_hits, mlod__node_distances): four a vector in the AVX2
   and AVX-512 passes, two (MLOD__VD) in the others, but none where the
   build has no double lanes.  Each lane computes the same operations in
   the same order as the scalar steps: the same bits. */
#if defined(MLOD__VD) && MLOD__PASS_LEVEL >= 3
#define MLOD__WLANES 4
typedef __m256d mlod__wd;
#define MLOD__WSPLAT _mm256_set1_pd
#define MLOD__WADD _mm256_add_pd
#define MLOD__WSUB _mm256_sub_pd
#define MLOD__WMUL _mm256_mul_pd
#define MLOD__WDIV _mm256_div_pd
#define MLOD__WSQRT _mm256_sqrt_pd
#define MLOD__WSTORE _mm256_storeu_pd
#define MLOD__WFLOATS(p) _mm256_cvtps_pd(_mm_loadu_ps(p)) /* four floats (exact) */
/* rows[0 .. 3], four floats each, as four vectors: out[k] lane l holds rows[l][k] */
MLOD__FORCE_INLINE void mlod__wd_rows(const float *const *rows, mlod__wd *out)
{
    __m128 a = _mm_loadu_ps(rows[0]), b = _mm_loadu_ps(rows[1]), c = _mm_loadu_ps(rows[2]), d = _mm_loadu_ps(rows[3]);
    __m128 ab0 = _mm_unpacklo_ps(a, b), ab1 = _mm_unpackhi_ps(a, b), cd0 = _mm_unpacklo_ps(c, d);
    __m128 cd1 = _mm_unpackhi_ps(c, d);
    out[0] = _mm256_cvtps_pd(_mm_movelh_ps(ab0, cd0));
    out[1] = _mm256_cvtps_pd(_mm_movehl_ps(cd0, ab0));
    out[2] = _mm256_cvtps_pd(_mm_movelh_ps(ab1, cd1));
    out[3] = _mm256_cvtps_pd(_mm_movehl_ps(cd1, ab1));
}
#elif defined(MLOD__VD)
#define MLOD__WLANES 2
typedef mlod__vd mlod__wd;
#define MLOD__WSPLAT MLOD__DSPLAT
#define MLOD__WADD MLOD__DADD
#define MLOD__WSUB MLOD__DSUB
#define MLOD__WMUL MLOD__DMUL
#define MLOD__WDIV MLOD__DDIV
#define MLOD__WSQRT MLOD__DSQRT
#define MLOD__WSTORE MLOD__DSTORE
#define MLOD__WFLOATS(p) MLOD__DPAIR((p)[0], (p)[1])
MLOD__FORCE_INLINE void mlod__wd_rows(const float *const *rows, mlod__wd *out) { mlod__vd_pairs(rows[0], rows[1], out); }
#endif

#ifdef MLOD__X86_LANES
/* Four node indices' lanes that are at least `first` (unsigned), as a mask. */
static __m128 mlod__vat_least(__m128i n, uint32_t first)
{
    const __m128i flip = _mm_set1_epi32((int)0x80000000u);
    __m128i below = _mm_cmpgt_epi32(_mm_xor_si128(_mm_set1_epi32((int)first), flip), _mm_xor_si128(n, flip));
    return _mm_castsi128_ps(_mm_xor_si128(below, _mm_set1_epi32(-1)));
}
#define MLOD__LOAD4(nodes) _mm_loadu_si128((const __m128i *)(const void *)(nodes))
#if MLOD__VLANES == 8
/* Lanes whose node (nodes[l]) is a leaf, `first` the first leaf; and for
   the pairs of mlod__vload_pairs, of the children of four parents. */
static __m256 mlod__vleaf(const uint32_t *nodes, uint32_t first)
{
    return _mm256_insertf128_ps(_mm256_castps128_ps256(mlod__vat_least(MLOD__LOAD4(nodes), first)),
                                mlod__vat_least(MLOD__LOAD4(nodes + 4), first), 1);
}
static __m256 mlod__vleaf_pairs(const uint32_t *parents, uint32_t first)
{
    __m128i twice = _mm_slli_epi32(MLOD__LOAD4(parents), 1);
    return _mm256_insertf128_ps(
        _mm256_castps128_ps256(mlod__vat_least(_mm_add_epi32(twice, _mm_set1_epi32(1)), first)),
        mlod__vat_least(_mm_add_epi32(twice, _mm_set1_epi32(2)), first), 1);
}
#else
static __m128 mlod__vleaf(const uint32_t *nodes, uint32_t first) { return mlod__vat_least(MLOD__LOAD4(nodes), first); }
#endif
#undef MLOD__LOAD4
#endif

#ifdef MLOD__VLANES

/* The back-face test of mlod__fast_backfacing on lanes: *culled and
   *unsure as masks, given x (unused orthographic), t and r. */
MLOD__FORCE_INLINE void mlod__vbackfacing(const mlod__fview *fv, const mlod__vf *x, mlod__vf t, mlod__vf r, const mlod__vf *cone,
                              mlod__vf *culled, mlod__vf *unsure)
{
    mlod__vf a = cone[3], away, len, a2, sa, ca, e, m1, lm, z1, z2, live, settled, cull, one = MLOD__VSET(1.0f);
    live = MLOD__VLT(a, MLOD__VSET((float)(0.5 * MLOD__PI)));
    if (fv->ortho) {
        const float *w = fv->subs[0].w;
        away = MLOD__VADD(MLOD__VADD(MLOD__VMUL(cone[0], MLOD__VSET(w[0])), MLOD__VMUL(cone[1], MLOD__VSET(w[1]))),
                          MLOD__VMUL(cone[2], MLOD__VSET(w[2])));
    } else {
        away = MLOD__VADD(MLOD__VADD(MLOD__VMUL(cone[0], x[0]), MLOD__VMUL(cone[1], x[1])), MLOD__VMUL(cone[2], x[2]));
    }
    away = MLOD__VSUB(MLOD__VSET(0.0f), away);
    len = MLOD__VSQRT(MLOD__VADD(MLOD__VADD(MLOD__VMUL(cone[0], cone[0]), MLOD__VMUL(cone[1], cone[1])),
                                 MLOD__VMUL(cone[2], cone[2])));
    a2 = MLOD__VMUL(a, a);
    sa = MLOD__VMUL(a, MLOD__VSUB(one, MLOD__VMUL(a2, MLOD__VSUB(MLOD__VSET(1.0f / 6.0f),
                                                                   MLOD__VMUL(a2, MLOD__VSET(1.0f / 120.0f))))));
    ca = MLOD__VSUB(one, MLOD__VMUL(a2, MLOD__VSUB(MLOD__VSET(0.5f),
                                                   MLOD__VMUL(a2, MLOD__VSUB(MLOD__VSET(1.0f / 24.0f),
                                                                             MLOD__VMUL(a2, MLOD__VSET(1.0f / 720.0f)))))));
    e = MLOD__VADD(MLOD__VMUL(MLOD__VMUL(MLOD__VMUL(MLOD__VMUL(a2, a2), a2), a), MLOD__VSET(1.0f / 5040.0f)),
                   MLOD__VSET(40.0f * MLOD__FAST_U));
    m1 = MLOD__VMUL(MLOD__VADD(t, r), e);
    lm = MLOD__VMUL(len, m1);
    z2 = MLOD__VADD(away, MLOD__VMUL(len, MLOD__VADD(MLOD__VMUL(sa, t), MLOD__VMUL(ca, r))));
    z1 = MLOD__VSUB(MLOD__VMUL(ca, t), MLOD__VMUL(sa, r));
    settled = MLOD__VOR(MLOD__VGT(z2, lm), MLOD__VLT(z1, MLOD__VSUB(MLOD__VSET(0.0f), m1)));
    cull = MLOD__VANDNOT(settled, MLOD__VAND(MLOD__VGT(z1, m1), MLOD__VLT(z2, MLOD__VSUB(MLOD__VSET(0.0f), lm))));
    live = MLOD__VAND(live, MLOD__VGE(a, MLOD__VSET(0.0f)));
    /* a >= pi/2 (or NaN): not culled; 0 <= a < pi/2: as decided; a < 0: unsure */
    *culled = MLOD__VAND(live, cull);
    *unsure = MLOD__VOR(MLOD__VLT(a, MLOD__VSET(0.0f)), MLOD__VANDNOT(MLOD__VOR(settled, cull), live));
}

/* mlod__classify_list's vector path: the statuses of the lanes' node-views
   (rows x, y, z, r of their spheres; cone their cones' rows, NULL for
   none; leaf the lanes whose node is a leaf) as status codes in float
   lanes: MLOD_STATUS_CULLED, _DRAWN, _COARSE or _OVERSIZE (invalid
   internal node or leaf), 0 (MLOD__UNSURE) where the lane cannot prove
   its status. */
/* mlod__vstatus below, with what is known of the planes of a view of one
   sub-projection.  track 1: *inside gets the lanes whose sphere surely
   lies wholly inside every plane of it (else none); known 1 (and track
   1): every lane's sphere is known to, and the plane tests are left out.
   A plane's test reached (mlod__fast_status) is n.x + l r - k' > m: the
   sphere reaches into the half-space, m bounding the float rounding of
   the sum (by the magnitudes of its terms, l >= |n|).  The same sum with
   - l r, over m, proves n.x - l r - k' > 0 in exact arithmetic: the whole
   sphere lies inside, and a child's sphere lies inside its parent's
   exactly (the build and the refit round radii up, DESIGN.md), so every
   node below lies wholly inside too and reaches into every half-space:
   its plane tests pass, known without them.  Its status, by the other
   tests (size, back faces), is what the full filter or the exact path
   gives: the same bits on every path (tests/test_cut.c checks the
   children of nodes proved inside against the exact path).  Only lanes
   the filter decided (their guards passed) are proved inside. */
/* The lanes' setup of the float filter (mlod__fast_status's): x =
   centre - eye, d2 = |x|^2, t the tangent length (1 orthographic) and
   reach >= |x| + r, which the planes' margins take; *unsure gets the
   lanes that fail a guard. */
MLOD__FORCE_INLINE void mlod__vsetup(const mlod__fview *fv, const mlod__vf *sphere, mlod__vf *x, mlod__vf *d2, mlod__vf *t,
                                     mlod__vf *reach, mlod__vf *unsure)
{
    mlod__vf r = sphere[3], zero = MLOD__VSET(0.0f), all = MLOD__VEQ(zero, zero), u;
    int j;
    for (j = 0; j < 3; j++)
        x[j] = fv->float_eye ? MLOD__VSUB(sphere[j], MLOD__VSET(fv->eye_f[j])) : mlod__vrelative(sphere[j], fv->eye[j]);
    *d2 = MLOD__VADD(MLOD__VADD(MLOD__VMUL(x[0], x[0]), MLOD__VMUL(x[1], x[1])), MLOD__VMUL(x[2], x[2]));
    u = MLOD__VANDNOT(MLOD__VAND(MLOD__VGE(*d2, MLOD__VSET(9.09494702e-13f)), MLOD__VLE(*d2, MLOD__VSET(1.20892582e24f))),
                      all);
    u = MLOD__VOR(u, MLOD__VANDNOT(MLOD__VOR(MLOD__VEQ(r, zero), MLOD__VAND(MLOD__VGE(r, MLOD__VSET(9.09494702e-13f)),
                                                                          MLOD__VLE(r, MLOD__VSET(1.09951163e12f)))),
                                   all));
    if (fv->ortho) {
        *t = MLOD__VSET(1.0f);
        *reach = MLOD__VADD(MLOD__VSQRT(*d2), r);
    } else {
        mlod__vf t2 = MLOD__VSUB(*d2, MLOD__VMUL(r, r));
        u = MLOD__VOR(u, MLOD__VANDNOT(MLOD__VGE(MLOD__VMUL(MLOD__VSET(4.0f), t2), *d2), all));
        *t = MLOD__VSQRT(MLOD__VAND(t2, MLOD__VGT(t2, zero)));
        *reach = MLOD__VADD(*t, MLOD__VADD(r, r));
    }
    *unsure = u;
}

/* The plane tests of sub-projection fs in lanes (x, r and reach from
   mlod__vsetup): *out gets the lanes surely outside some plane (the
   sphere misses the sub-projection), *in those surely reaching into every
   half-space; with track, *inside keeps only the lanes whose sphere lies
   surely wholly inside every plane (mlod__vstatus_known; else inside is
   not read). */
MLOD__FORCE_INLINE void mlod__vplanes(const mlod__fsub *fs, const mlod__vf *x, mlod__vf r, mlod__vf reach, int track,
                                      mlod__vf *out, mlod__vf *in, mlod__vf *inside)
{
    mlod__vf zero = MLOD__VSET(0.0f);
    int j;
    *out = zero;
    *in = MLOD__VEQ(zero, zero);
    for (j = 0; j < fs->plane_count; j++) {
        const float *p = fs->planes[j];
        mlod__vf a0 = MLOD__VMUL(MLOD__VSET(p[0]), x[0]), a1 = MLOD__VMUL(MLOD__VSET(p[1]), x[1]);
        mlod__vf a2 = MLOD__VMUL(MLOD__VSET(p[2]), x[2]), a3 = MLOD__VMUL(MLOD__VSET(p[3]), r);
        mlod__vf centre = MLOD__VADD(MLOD__VADD(a0, a1), a2);
        mlod__vf v = MLOD__VSUB(MLOD__VADD(centre, a3), MLOD__VSET(p[4]));
        mlod__vf m = MLOD__VADD(MLOD__VMUL(MLOD__VSET(fs->slope[j]), reach), MLOD__VSET(fs->err[j]));
        *out = MLOD__VOR(*out, MLOD__VLT(v, MLOD__VSUB(zero, m)));
        *in = MLOD__VAND(*in, MLOD__VGT(v, m));
        if (track) *inside = MLOD__VAND(*inside, MLOD__VGT(MLOD__VSUB(MLOD__VSUB(centre, a3), MLOD__VSET(p[4])), m));
    }
}

MLOD__FORCE_INLINE mlod__vf mlod__vstatus_known(const mlod__fview *fv, const mlod__vf *sphere, const mlod__vf *cone,
                                              mlod__vf leaf, int known, int track, mlod__vf *inside)
{
    mlod__vf x[3], r = sphere[3], d2, t, twice = MLOD__VADD(r, r), reach, unsure, none, culled, coarse, small;
    mlod__vf zero = MLOD__VSET(0.0f), all = MLOD__VEQ(zero, zero);
    int s;
    mlod__vsetup(fv, sphere, x, &d2, &t, &reach, &unsure);
    none = all;
    coarse = zero;
    small = all;
    *inside = track ? all : zero;
    for (s = 0; s < fv->sub_count; s++) {
        const mlod__fsub *fs = &fv->subs[s];
        mlod__vf out = zero, in = all, xw, lhs, rhs, ok;
        if (!known) mlod__vplanes(fs, x, r, reach, track && s == 0, &out, &in, inside);
        /* a sub-projection neither surely reached nor surely missed */
        unsure = MLOD__VOR(unsure, MLOD__VANDNOT(MLOD__VOR(out, in), all));
        none = MLOD__VAND(none, out);
        xw = MLOD__VADD(MLOD__VADD(MLOD__VMUL(x[0], MLOD__VSET(fs->w[0])), MLOD__VMUL(x[1], MLOD__VSET(fs->w[1]))),
                        MLOD__VMUL(x[2], MLOD__VSET(fs->w[2])));
        if (fs->kind == MLOD_VIEW_PERSPECTIVE) {
            mlod__vf near_side = MLOD__VSUB(xw, r);
            ok = MLOD__VAND(MLOD__VGT(near_side, zero),
                            MLOD__VGE(MLOD__VMUL(MLOD__VMUL(MLOD__VSET(256.0f), near_side), near_side), d2));
            lhs = MLOD__VMUL(twice, t);
            rhs = MLOD__VMUL(near_side, MLOD__VADD(xw, r));
        } else if (fs->kind == MLOD_VIEW_PARABOLOID) {
            rhs = MLOD__VADD(xw, t);
            ok = MLOD__VAND(MLOD__VGT(rhs, zero), MLOD__VGE(MLOD__VMUL(MLOD__VMUL(MLOD__VSET(256.0f), rhs), rhs), d2));
            lhs = twice;
        } else {
            ok = all;
            lhs = twice;
            rhs = MLOD__VSET(1.0f);
        }
        /* over reached sub-projections: one surely too large makes the
           node coarse, all surely small enough make it drawn */
        coarse = MLOD__VOR(coarse, MLOD__VAND(MLOD__VAND(in, ok), MLOD__VGT(MLOD__VMUL(lhs, MLOD__VSET(fs->invalid)), rhs)));
        small = MLOD__VAND(small, MLOD__VOR(out, MLOD__VAND(ok, MLOD__VLE(MLOD__VMUL(lhs, MLOD__VSET(fs->valid)), rhs))));
    }
    culled = none;
    if (cone) {
        mlod__vf back, back_unsure;
        mlod__vbackfacing(fv, x, t, fv->ortho ? zero : r, cone, &back, &back_unsure);
        culled = MLOD__VOR(culled, back);
        unsure = MLOD__VOR(unsure, MLOD__VANDNOT(none, back_unsure));
    }
    /* every lane sure of its setup and planes: culled, else coarse (an
       oversize leaf), else drawn; anything else is unsure (0); the masks
       exclusive, so or selects */
    coarse = MLOD__VANDNOT(culled, coarse);
    small = MLOD__VANDNOT(MLOD__VOR(culled, coarse), small);
    if (track && !known) *inside = MLOD__VANDNOT(unsure, *inside);
    return MLOD__VANDNOT(unsure,
                         MLOD__VOR(MLOD__VOR(MLOD__VAND(culled, MLOD__VSET((float)MLOD_STATUS_CULLED)),
                                             MLOD__VAND(small, MLOD__VSET((float)MLOD_STATUS_DRAWN))),
                                   MLOD__VAND(coarse, MLOD__VOR(MLOD__VAND(leaf, MLOD__VSET((float)MLOD_STATUS_OVERSIZE)),
                                                                MLOD__VANDNOT(leaf, MLOD__VSET((float)MLOD_STATUS_COARSE))))));
}

MLOD__FORCE_INLINE mlod__vf mlod__vstatus(const mlod__fview *fv, const mlod__vf *sphere, const mlod__vf *cone, mlod__vf leaf)
{
    mlod__vf inside;
    return mlod__vstatus_known(fv, sphere, cone, leaf, 0, 0, &inside);
}

/* The lanes of status codes that the filter left undecided (0), as bits. */
static uint32_t mlod__vundecided(mlod__vf codes) { return (uint32_t)MLOD__VBITS(MLOD__VEQ(codes, MLOD__VSET(0.0f))); }
#endif
#if defined(MLOD__NO_FMA_TARGET) && defined(MLOD__VLANES) /* (a region with no function: refused) */
#pragma clang attribute push(__attribute__((target("no-fma"))), apply_to = function)
#endif


#ifdef MLOD__VLANES
/* The index of the lowest set bit of x (x != 0). */
static uint32_t mlod__lowest_bit(uint32_t x)
{
#if defined(__GNUC__) || defined(__clang__)
    return (uint32_t)__builtin_ctz(x);
#else
    uint32_t i = 0;
    while (!(x >> i & 1u)) i++;
    return i;
#endif
}
#endif


/* How many nodes ahead mlod__classify_lanes asks for rows, for the loads to overlap. */
#define MLOD__LIST_AHEAD 16u
#ifdef MLOD__VLANES
/* The exact path for the lanes the vector filter left undecided (status
   0): lane l is nodes[l], its status out[l]; lanes `valid` and above are
   padding. */
static void mlod__settle_lanes(const mlod__pview *pv, const mlod_tree *tree, mlod__vf codes, const uint32_t *nodes,
                               uint32_t valid, double epsilon, uint8_t *out)
{
    uint32_t undecided = mlod__vundecided(codes), l;
    if (valid < MLOD__VLANES) undecided &= (1u << valid) - 1u;
    for (; undecided; undecided &= undecided - 1u) {
        l = mlod__lowest_bit(undecided);
        out[l] = mlod__classify_exact(pv, tree, nodes[l], epsilon);
    }
}
#endif

#if defined(MLOD__NO_FMA_TARGET) && defined(MLOD__VLANES)
#pragma clang attribute pop
#endif

#ifdef MLOD__VLANES
/* Whether flags[0 .. n - 1] are all set. */
static int mlod__all_set(const uint8_t *flags, uint32_t n)
{
    uint32_t i, all = 1;
    for (i = 0; i < n; i++) all &= flags[i];
    return (int)all;
}

/* mlod__classify_list's vector path with the float filter fv: pv's own,
   or a copy whose counts are constants (mlod__fast_fixed), for which the
   compiler unrolls the plane loops and keeps the view's constants in
   registers across groups. */
MLOD__FORCE_INLINE void mlod__classify_lanes(const mlod__fview *fv, const mlod__pview *pv, const mlod_tree *tree,
                                             const uint32_t *nodes, uint32_t count, double epsilon, uint8_t *status,
                                             const uint8_t *known, uint8_t *inside)
{
    const int cones = fv->backfaces && tree->cones, planes = mlod__known_planes(fv);
    uint32_t i;
    for (i = 0; i < count; i += MLOD__VLANES) {
        uint32_t pad[MLOD__VLANES], l, valid = count - i < MLOD__VLANES ? count - i : MLOD__VLANES;
        const uint32_t *lanes = nodes + i;
        uint8_t part[MLOD__VLANES], *out = valid == MLOD__VLANES ? status + i : part;
        mlod__vf sphere[4], cone[4], codes, in, leaf;
        int all_known = planes && known != NULL && mlod__all_set(known + i, valid);
        if (valid < MLOD__VLANES) { /* the last group: padded with its last node */
            for (l = 0; l < MLOD__VLANES; l++) pad[l] = nodes[i + (l < valid ? l : valid - 1)];
            lanes = pad;
        } else if (i + MLOD__VLANES + MLOD__LIST_AHEAD <= count) { /* rows a few groups on, for the loads to overlap */
            for (l = 0; l < MLOD__VLANES; l++) {
                MLOD__PREFETCH(tree->spheres + 4 * (size_t)nodes[i + l + MLOD__LIST_AHEAD]);
                if (cones) MLOD__PREFETCH(tree->cones + 4 * (size_t)nodes[i + l + MLOD__LIST_AHEAD]);
            }
        }
        mlod__vload(tree->spheres, lanes, &sphere[0], &sphere[1], &sphere[2], &sphere[3]);
        if (cones) mlod__vload(tree->cones, lanes, &cone[0], &cone[1], &cone[2], &cone[3]);
        leaf = mlod__vleaf(lanes, tree->leaf_count - 1);
        /* two calls, each with its own constant: the plane loop compiled out of one */
        codes = all_known ? mlod__vstatus_known(fv, sphere, cones ? cone : NULL, leaf, 1, 1, &in)
                          : mlod__vstatus_known(fv, sphere, cones ? cone : NULL, leaf, 0, planes, &in);
        if (inside) {
            uint8_t flags[MLOD__VLANES];
            mlod__vbytes(MLOD__VAND(in, MLOD__VSET(1.0f)), valid == MLOD__VLANES ? inside + i : flags);
            if (valid < MLOD__VLANES) memcpy(inside + i, flags, valid);
        }
        /* statuses stored as bytes at once (they are hard to predict:
           no branch per lane); an undecided lane (rare) takes the
           exact path */
        mlod__vbytes(codes, out);
        if (mlod__vundecided(codes)) mlod__settle_lanes(pv, tree, codes, lanes, valid, epsilon, out);
        if (out == part) memcpy(status + i, part, valid);
    }
}


/* The view's shape; for one of the fixed shapes, *fixed gets a copy of its
   float filter (its one sub-projection; the caller writes the counts as
   constants, see MLOD__FIX), a local of the caller, out of reach of the
   statuses it stores. */
MLOD__FORCE_INLINE int mlod__fast_fixed(const mlod__pview *pv, mlod__fview *fixed)
{
    const mlod__fview *f = &pv->fast;
    int shape = MLOD__SHAPE_OTHER;
    if (f->sub_count == 1 && !f->ortho && f->float_eye) {
        if (f->subs[0].kind == MLOD_VIEW_PARABOLOID && f->subs[0].plane_count == 1) shape = MLOD__SHAPE_PARABOLOID;
        if (f->subs[0].kind == MLOD_VIEW_PERSPECTIVE && f->subs[0].plane_count == 6) shape = MLOD__SHAPE_PERSPECTIVE;
    }
    if (shape != MLOD__SHAPE_OTHER) memcpy(fixed, f, offsetof(mlod__fview, subs) + sizeof(mlod__fsub));
    return shape;
}

/* Write the fixed shape's counts and flags into the copy as constants,
   just before the call that inlines the filter. */
#define MLOD__FIX(fixed, kind_, planes)                                                                                \
    ((fixed).sub_count = 1, (fixed).ortho = 0, (fixed).float_eye = 1, (fixed).subs[0].kind = (kind_),                  \
     (fixed).subs[0].plane_count = (planes))

/* The vector paths of mlod__classify_list and mlod__classify_children,
   for the view's shape (MLOD__BY_SHAPE: fn, mlod__classify_lanes or
   mlod__classify_pairs, with the view's filter fixed for its shape, else
   its own).  Not inlined into the cut's code: where that is
   built for a target without FMA (MLOD__NO_FMA_TARGET), these keep the
   caller's target, as the vector filter they inline does. */
#define MLOD__BY_SHAPE(fn, pv, ...)                                                                                    \
    do {                                                                                                               \
        mlod__fview fixed_;                                                                                            \
        switch (mlod__fast_fixed(pv, &fixed_)) {                                                                       \
        case MLOD__SHAPE_PARABOLOID:                                                                                   \
            MLOD__FIX(fixed_, MLOD_VIEW_PARABOLOID, 1);                                                                \
            fn(&fixed_, pv, __VA_ARGS__);                                                                              \
            break;                                                                                                     \
        case MLOD__SHAPE_PERSPECTIVE:                                                                                  \
            MLOD__FIX(fixed_, MLOD_VIEW_PERSPECTIVE, 6);                                                               \
            fn(&fixed_, pv, __VA_ARGS__);                                                                              \
            break;                                                                                                     \
        default:                                                                                                       \
            fn(&(pv)->fast, pv, __VA_ARGS__);                                                                          \
        }                                                                                                              \
    } while (0)

static void mlod__classify_vector(const mlod__pview *pv, const mlod_tree *tree, const uint32_t *nodes, uint32_t count,
                                  double epsilon, uint8_t *status, const uint8_t *known, uint8_t *inside)
{
    MLOD__BY_SHAPE(mlod__classify_lanes, pv, tree, nodes, count, epsilon, status, known, inside);
}

#ifdef MLOD__VPAIRS
/* mlod__classify_children's vector path with the float filter fv (as
   mlod__classify_lanes): a pair's rows are adjacent, one load each,
   MLOD__VPAIRS pairs a vector. */
MLOD__FORCE_INLINE void mlod__classify_pairs(const mlod__fview *fv, const mlod__pview *pv, const mlod_tree *tree,
                                             const uint32_t *parents, uint32_t count, double epsilon, uint8_t *status,
                                             const uint8_t *known, uint8_t *inside)
{
    const int cones = fv->backfaces && tree->cones, planes = mlod__known_planes(fv);
    uint32_t i;
    for (i = 0; i < count; i += MLOD__VPAIRS) {
        uint32_t pad[MLOD__VPAIRS], lanes[2 * MLOD__VPAIRS], l, valid = count - i < MLOD__VPAIRS ? count - i : MLOD__VPAIRS;
        const uint32_t *group = parents + i;
        uint8_t part[2 * MLOD__VPAIRS], lane_status[2 * MLOD__VPAIRS];
        mlod__vf sphere[4], cone[4], codes, in, leaf;
        int all_known = planes && known != NULL && mlod__all_set(known + i, valid);
        if (valid < MLOD__VPAIRS) {
            for (l = 0; l < MLOD__VPAIRS; l++) pad[l] = parents[i + (l < valid ? l : valid - 1)];
            group = pad;
        }
        mlod__vload_pairs(tree->spheres, group, &sphere[0], &sphere[1], &sphere[2], &sphere[3]);
        if (cones) mlod__vload_pairs(tree->cones, group, &cone[0], &cone[1], &cone[2], &cone[3]);
        leaf = mlod__vleaf_pairs(group, tree->leaf_count - 1);
        codes = all_known ? mlod__vstatus_known(fv, sphere, cones ? cone : NULL, leaf, 1, 1, &in)
                          : mlod__vstatus_known(fv, sphere, cones ? cone : NULL, leaf, 0, planes, &in);
        if (inside) { /* in the order of the statuses: each parent's left child, then its right one */
            uint8_t flags[2 * MLOD__VPAIRS];
            mlod__vbytes_pairs(MLOD__VAND(in, MLOD__VSET(1.0f)), valid == MLOD__VPAIRS ? inside + 2 * i : flags);
            if (valid < MLOD__VPAIRS) memcpy(inside + 2 * i, flags, 2 * valid);
        }
        mlod__vbytes_pairs(codes, valid == MLOD__VPAIRS ? status + 2 * i : part);
        if (mlod__vundecided(codes)) { /* rare: lanes the filter left undecided */
            for (l = 0; l < MLOD__VPAIRS; l++) {
                lanes[l] = 2 * group[l] + 1;
                lanes[MLOD__VPAIRS + l] = 2 * group[l] + 2;
            }
            mlod__vbytes(codes, lane_status);
            mlod__settle_lanes(pv, tree, codes, lanes, 2 * MLOD__VPAIRS, epsilon, lane_status);
            for (l = 0; l < valid; l++) {
                uint8_t *to = valid == MLOD__VPAIRS ? status + 2 * (i + l) : part + 2 * l;
                to[0] = lane_status[l];
                to[1] = lane_status[MLOD__VPAIRS + l];
            }
        }
        if (valid < MLOD__VPAIRS) memcpy(status + 2 * i, part, 2 * valid);
    }
}

static void mlod__classify_pairs_vector(const mlod__pview *pv, const mlod_tree *tree, const uint32_t *parents,
                                        uint32_t count, double epsilon, uint8_t *status, const uint8_t *known,
                                        uint8_t *inside)
{
    MLOD__BY_SHAPE(mlod__classify_pairs, pv, tree, parents, count, epsilon, status, known, inside);
}
#endif
#endif
#ifdef MLOD__NO_FMA_TARGET
#pragma clang attribute push(__attribute__((target("no-fma"))), apply_to = function)
#endif

/* mlod__classify_list with, per node, whether it is known to lie inside
   every plane of the view's one sub-projection (known, NULL: none), and
   into inside[] (NULL: not wanted) whether it surely does (known, or
   proved by the vector filter; 0 where unsure, or without lanes). */
MLOD__FORCE_INLINE void mlod__classify_known(const mlod__pview *pv, const mlod_tree *tree, const uint32_t *nodes,
                                             uint32_t count, double epsilon, uint8_t *status, const uint8_t *known,
                                             uint8_t *inside)
{
    uint32_t i;
#ifdef MLOD__VLANES
    if (pv->fast.ok) {
        mlod__classify_vector(pv, tree, nodes, count, epsilon, status, known, inside);
        return;
    }
#endif
    for (i = 0; i < count; i++) status[i] = mlod__classify(pv, tree, nodes[i], epsilon);
    if (inside) memset(inside, 0, count);
    (void)known;
}

static void mlod__classify_list(const mlod__pview *pv, const mlod_tree *tree, const uint32_t *nodes, uint32_t count,
                                double epsilon, uint8_t *status)
{
    MLOD__LANES_REDIRECT(mlod__classify_list, (pv, tree, nodes, count, epsilon, status));
    mlod__classify_known(pv, tree, nodes, count, epsilon, status, NULL, NULL);
}

#if (defined(MLOD__VLANES) && MLOD__VLANES > MLOD__BATCH_PAD) || (defined(MLOD__VPAIRS) && MLOD__VPAIRS > MLOD__BATCH_PAD)
#error "manylods.h: MLOD__BATCH_PAD must hold a vector's lanes"
#endif

#ifdef MLOD__VLANES
/* Pad items[0 .. count) (count > 0) up to a multiple of `multiple` by
   repeating its last item, and flags[] (NULL: none) alike; the caller's
   arrays have the room.  Returns the padded count: whole vectors for the
   lanes, whose extra statuses nobody reads. */
static uint32_t mlod__pad_last(uint32_t *items, uint8_t *flags, uint32_t count, uint32_t multiple)
{
    uint32_t padded = count;
    for (; padded % multiple; padded++) {
        items[padded] = items[count - 1];
        if (flags) flags[padded] = flags[count - 1];
    }
    return padded;
}
#endif

/* The statuses of the children 2p + 1 and 2p + 2 of each of the count
   (<= MLOD__BATCH) parents p, into status[2i] and status[2i + 1]; known[i]:
   parent i surely lies inside every plane (mlod__classify_known), and so
   its children; their own such flags into inside[2i], inside[2i + 1].
   The vector paths take whole vectors: parents[] and known[] have room
   for MLOD__BATCH_PAD more entries, status[] and inside[] for 2
   MLOD__BATCH_PAD more, which the lanes past the batch fill (padding
   with the last parent, whose statuses the caller does not read: no
   partial vector, whose extra copies cost a small batch more than a
   whole one). */
static void mlod__classify_children(const mlod__pview *pv, const mlod_tree *tree, uint32_t *parents,
                                                uint32_t count, double epsilon, uint8_t *status, uint8_t *known,
                                                uint8_t *inside)
{
    uint32_t children[2 * (MLOD__BATCH + MLOD__BATCH_PAD)], i, padded = 2 * count;
    uint8_t child_known[2 * (MLOD__BATCH + MLOD__BATCH_PAD)];
    MLOD__LANES_REDIRECT(mlod__classify_children, (pv, tree, parents, count, epsilon, status, known, inside));
    for (i = 0; i < count; i++) { /* ask for every pair's rows first: their loads overlap */
        MLOD__PREFETCH(tree->spheres + 8 * (size_t)parents[i] + 4);
        if (tree->cones) MLOD__PREFETCH(tree->cones + 8 * (size_t)parents[i] + 4);
    }
#ifdef MLOD__VPAIRS
    if (pv->fast.ok) {
        padded = mlod__pad_last(parents, known, count, MLOD__VPAIRS);
        mlod__classify_pairs_vector(pv, tree, parents, padded, epsilon, status, known, inside);
        return;
    }
#endif
    for (i = 0; i < count; i++) {
        children[2 * i] = 2 * parents[i] + 1;
        children[2 * i + 1] = 2 * parents[i] + 2;
    }
    if (known)
        for (i = 0; i < count; i++) child_known[2 * i] = child_known[2 * i + 1] = known[i];
#ifdef MLOD__VLANES
    if (pv->fast.ok) padded = mlod__pad_last(children, known ? child_known : NULL, padded, MLOD__VLANES);
#endif
    mlod__classify_known(pv, tree, children, padded, epsilon, status, known ? child_known : NULL, inside);
}

#ifndef MLOD__VLANES
/* The filter for one sphere in sub-projection f at disc scale ds > 0
   (mlod_atlas.disc_scale): where the disc is small for sure, box[k *
   stride], k = 0 .. 5 = the bounds xl, xh, yl, yh of its centre and rl, rh
   of its radius times ds (the box the caller hands to mlod__disc_decide),
   else NAN. */
static void mlod__fast_disc(const mlod__fdiscs *fd, const mlod__fdisc *f, const float *sphere, float ds, float *box,
                            size_t stride)
{
    int k;
    const float u = MLOD__DISC_U, widen = 1.0f + 1.0f / 256.0f;
    float x0 = sphere[0] - fd->eye[0], x1 = sphere[1] - fd->eye[1], x2 = sphere[2] - fd->eye[2], r = sphere[3];
    float d2 = x0 * x0 + x1 * x1 + x2 * x2, d = sqrtf(d2);
    float a = (x0 * f->right[0] + x1 * f->right[1] + x2 * f->right[2]) / d;
    float b = (x0 * f->up[0] + x1 * f->up[1] + x2 * f->up[2]) / d;
    float c = (x0 * f->forward[0] + x1 * f->forward[1] + x2 * f->forward[2]) / d;
    float rho = r / d, st, cb, s_hi, c_hi, s_lo, c_lo, dx, dy, e_dir, hi, lo, e_hi, e_lo, g, e_g, R, e_R;
    float X, Y, e_X, e_Y, q_hi, q_lo, e_q;
    const float e_s = 42.0f * u;
    /* |x|^2 in [2^-100, 2^100]: no product that counts rounds below the
       normal floats (whose error is absolute) or overflows */
    if (!(d2 >= 7.88860905e-31f && d2 <= 1.26765060e30f)) goto unsure;
    if (!(rho + 7.0f * u * rho <= 0.5f)) goto unsure; /* also d = 0 or not finite */
    st = sqrtf(a * a + b * b);
    if (!(st > 40.0f * u)) goto unsure;
    cb = sqrtf(1.0f - rho * rho);
    s_hi = st * cb + c * rho;
    c_hi = c * cb - st * rho;
    s_lo = st * cb - c * rho;
    c_lo = c * cb + st * rho;
    dx = a / st;
    dy = b / st;
    e_dir = 33.0f * u / (st - 20.0f * u) + u;
    /* the denominators: 1 + cos (paraboloid, tan of half the angle) or
       cos (perspective), each at least 1/8 */
    q_hi = f->kind == MLOD_VIEW_PARABOLOID ? 1.0f + c_hi : c_hi;
    q_lo = f->kind == MLOD_VIEW_PARABOLOID ? 1.0f + c_lo : c_lo;
    e_q = f->kind == MLOD_VIEW_PARABOLOID ? 44.0f * u : e_s;
    if (!(q_hi >= 0.125f && q_lo >= 0.125f)) goto unsure;
    if (f->kind == MLOD_VIEW_PARABOLOID && !(s_hi > e_s || c_hi > e_s)) goto unsure;
    hi = s_hi / q_hi;
    lo = s_lo / q_lo;
    e_hi = (e_s + fabsf(hi) * e_q) / (q_hi - e_q) + u * fabsf(hi);
    e_lo = (e_s + fabsf(lo) * e_q) / (q_lo - e_q) + u * fabsf(lo);
    if (f->kind == MLOD_VIEW_PARABOLOID) {
        float k, e_k, mx, my, e_mx, e_my, nx, ny;
        k = 0.5f * (hi + lo);
        e_k = 0.5f * (e_hi + e_lo) + u * fabsf(k);
        mx = k * dx;
        my = k * dy;
        e_mx = fabsf(k) * e_dir + fabsf(dx) * e_k + e_k * e_dir + u * fabsf(mx);
        e_my = fabsf(k) * e_dir + fabsf(dy) * e_k + e_k * e_dir + u * fabsf(my);
        nx = 1.0f + mx;
        ny = 1.0f - my;
        X = f->x0 + f->half_w * nx;
        Y = f->y0 + f->half_h * ny;
        e_X = f->half_w * (e_mx + u * fabsf(nx)) + u * fabsf(f->half_w * nx) + u * fabsf(X);
        e_Y = f->half_h * (e_my + u * fabsf(ny)) + u * fabsf(f->half_h * ny) + u * fabsf(Y);
    } else {
        float kk, e_kk;
        kk = f->half_scale * (hi + lo);
        e_kk = f->half_scale * (e_hi + e_lo + u * fabsf(hi + lo)) + 2.0f * u * fabsf(kk);
        X = f->x0 + kk * dx;
        Y = f->y0 + kk * -dy;
        e_X = fabsf(kk) * e_dir + fabsf(dx) * e_kk + e_kk * e_dir + u * fabsf(kk * dx) + u * fabsf(X);
        e_Y = fabsf(kk) * e_dir + fabsf(dy) * e_kk + e_kk * e_dir + u * fabsf(kk * dy) + u * fabsf(Y);
    }
    g = hi - lo;
    e_g = e_hi + e_lo + u * fabsf(g);
    R = f->half_scale * g;
    e_R = f->half_scale * e_g + 2.0f * u * fabsf(R);
    /* small: R ds < 0.5 - 2^-30 for the double path too */
    if (!((R + e_R * widen) * ds <= (float)(MLOD__SMALL_DISC * (1.0 - 1.0 / 1048576.0)))) goto unsure;
    e_X = e_X * widen + 2.0f * u * fabsf(X); /* and the rounding of X +- e_X below */
    e_Y = e_Y * widen + 2.0f * u * fabsf(Y);
    box[0] = X - e_X;
    box[stride] = X + e_X;
    box[2 * stride] = Y - e_Y;
    box[3 * stride] = Y + e_Y;
    box[4 * stride] = (R - e_R * widen) * ds;
    box[5 * stride] = (R + e_R * widen) * ds;
    return;
unsure:
    for (k = 0; k < 6; k++) box[k * stride] = NAN;
}

static void mlod__fast_discs(const mlod__fdiscs *fd, const mlod__fdisc *f, const float *spheres, const uint32_t *nodes,
                             uint32_t count, float ds, float *box, size_t stride)
{
    uint32_t i;
    for (i = 0; i < count; i++) mlod__fast_disc(fd, f, spheres + 4 * (size_t)nodes[i], ds, box + i, stride);
}
#endif

#ifdef MLOD__VLANES
#ifdef MLOD__NO_FMA_TARGET
#pragma clang attribute pop
#endif
/* mlod__fast_disc for the spheres of nodes[0 .. MLOD__VLANES - 1], in
   vector lanes, step for step as it (the same bounds): for lane l,
   box[k * stride + l], k = 0 .. 5 = the bounds xl, xh, yl, yh of its
   disc's centre and rl, rh of its radius times ds, or NAN where the node
   must take the double path (the box the caller hands to
   mlod__disc_decide). */
static void mlod__fast_disc_lanes(const mlod__fdiscs *fd, const mlod__fdisc *f, const float *spheres,
                                  const uint32_t *nodes, float ds, float *box, size_t stride)
{
#define MLOD__VABS(v) MLOD__VANDNOT(MLOD__VSET(-0.0f), v)
#define MLOD__VDOT(v) MLOD__VADD(MLOD__VADD(MLOD__VMUL(x0, MLOD__VSET((v)[0])), MLOD__VMUL(x1, MLOD__VSET((v)[1]))), \
                             MLOD__VMUL(x2, MLOD__VSET((v)[2])))
    const float uf = MLOD__DISC_U;
    const mlod__vf u = MLOD__VSET(uf), one = MLOD__VSET(1.0f), widen = MLOD__VSET(1.0f + 1.0f / 256.0f);
    const mlod__vf e_s = MLOD__VSET(42.0f * uf), two_u = MLOD__VSET(2.0f * uf);
    mlod__vf x0, x1, x2, r, d, a, b, c, rho, st, cb, s_hi, c_hi, s_lo, c_lo, dx, dy, e_dir, hi, lo, e_hi, e_lo;
    mlod__vf q_hi, q_lo, e_q;
    mlod__vf g, e_g, R, e_R, X, Y, e_X, e_Y, ok, nan = MLOD__VSET(NAN);
    mlod__vload(spheres, nodes, &x0, &x1, &x2, &r);
    x0 = MLOD__VSUB(x0, MLOD__VSET(fd->eye[0]));
    x1 = MLOD__VSUB(x1, MLOD__VSET(fd->eye[1]));
    x2 = MLOD__VSUB(x2, MLOD__VSET(fd->eye[2]));
    d = MLOD__VADD(MLOD__VADD(MLOD__VMUL(x0, x0), MLOD__VMUL(x1, x1)), MLOD__VMUL(x2, x2)); /* |x|^2 first */
    ok = MLOD__VAND(MLOD__VGE(d, MLOD__VSET(7.88860905e-31f)), MLOD__VLE(d, MLOD__VSET(1.26765060e30f)));
    d = MLOD__VSQRT(d);
    a = MLOD__VDIV(MLOD__VDOT(f->right), d);
    b = MLOD__VDIV(MLOD__VDOT(f->up), d);
    c = MLOD__VDIV(MLOD__VDOT(f->forward), d);
    rho = MLOD__VDIV(r, d);
    ok = MLOD__VAND(ok, MLOD__VLE(MLOD__VADD(rho, MLOD__VMUL(MLOD__VSET(7.0f * uf), rho)), MLOD__VSET(0.5f)));
    st = MLOD__VSQRT(MLOD__VADD(MLOD__VMUL(a, a), MLOD__VMUL(b, b)));
    ok = MLOD__VAND(ok, MLOD__VGT(st, MLOD__VSET(40.0f * uf)));
    cb = MLOD__VSQRT(MLOD__VSUB(one, MLOD__VMUL(rho, rho)));
    s_hi = MLOD__VADD(MLOD__VMUL(st, cb), MLOD__VMUL(c, rho));
    c_hi = MLOD__VSUB(MLOD__VMUL(c, cb), MLOD__VMUL(st, rho));
    s_lo = MLOD__VSUB(MLOD__VMUL(st, cb), MLOD__VMUL(c, rho));
    c_lo = MLOD__VADD(MLOD__VMUL(c, cb), MLOD__VMUL(st, rho));
    dx = MLOD__VDIV(a, st);
    dy = MLOD__VDIV(b, st);
    e_dir = MLOD__VADD(MLOD__VDIV(MLOD__VSET(33.0f * uf), MLOD__VSUB(st, MLOD__VSET(20.0f * uf))), u);
    /* the denominators: 1 + cos (paraboloid, tan of half the angle) or
       cos (perspective), each at least 1/8 */
    if (f->kind == MLOD_VIEW_PARABOLOID) {
        q_hi = MLOD__VADD(one, c_hi);
        q_lo = MLOD__VADD(one, c_lo);
        e_q = MLOD__VSET(44.0f * uf);
        ok = MLOD__VAND(ok, MLOD__VOR(MLOD__VGT(s_hi, e_s), MLOD__VGT(c_hi, e_s)));
    } else {
        q_hi = c_hi;
        q_lo = c_lo;
        e_q = e_s;
    }
    ok = MLOD__VAND(ok, MLOD__VAND(MLOD__VGE(q_hi, MLOD__VSET(0.125f)), MLOD__VGE(q_lo, MLOD__VSET(0.125f))));
    hi = MLOD__VDIV(s_hi, q_hi);
    lo = MLOD__VDIV(s_lo, q_lo);
    e_hi = MLOD__VADD(MLOD__VDIV(MLOD__VADD(e_s, MLOD__VMUL(MLOD__VABS(hi), e_q)), MLOD__VSUB(q_hi, e_q)),
                      MLOD__VMUL(u, MLOD__VABS(hi)));
    e_lo = MLOD__VADD(MLOD__VDIV(MLOD__VADD(e_s, MLOD__VMUL(MLOD__VABS(lo), e_q)), MLOD__VSUB(q_lo, e_q)),
                      MLOD__VMUL(u, MLOD__VABS(lo)));
    if (f->kind == MLOD_VIEW_PARABOLOID) {
        mlod__vf k, e_k, mx, my, e_mx, e_my, nx, ny, hw = MLOD__VSET(f->half_w), hh = MLOD__VSET(f->half_h);
        k = MLOD__VMUL(MLOD__VSET(0.5f), MLOD__VADD(hi, lo));
        e_k = MLOD__VADD(MLOD__VMUL(MLOD__VSET(0.5f), MLOD__VADD(e_hi, e_lo)), MLOD__VMUL(u, MLOD__VABS(k)));
        mx = MLOD__VMUL(k, dx);
        my = MLOD__VMUL(k, dy);
        e_mx = MLOD__VADD(MLOD__VADD(MLOD__VMUL(MLOD__VABS(k), e_dir), MLOD__VMUL(MLOD__VABS(dx), e_k)),
                          MLOD__VADD(MLOD__VMUL(e_k, e_dir), MLOD__VMUL(u, MLOD__VABS(mx))));
        e_my = MLOD__VADD(MLOD__VADD(MLOD__VMUL(MLOD__VABS(k), e_dir), MLOD__VMUL(MLOD__VABS(dy), e_k)),
                          MLOD__VADD(MLOD__VMUL(e_k, e_dir), MLOD__VMUL(u, MLOD__VABS(my))));
        nx = MLOD__VADD(one, mx);
        ny = MLOD__VSUB(one, my);
        X = MLOD__VADD(MLOD__VSET(f->x0), MLOD__VMUL(hw, nx));
        Y = MLOD__VADD(MLOD__VSET(f->y0), MLOD__VMUL(hh, ny));
        e_X = MLOD__VADD(MLOD__VMUL(hw, MLOD__VADD(e_mx, MLOD__VMUL(u, MLOD__VABS(nx)))),
                         MLOD__VMUL(u, MLOD__VADD(MLOD__VABS(MLOD__VMUL(hw, nx)), MLOD__VABS(X))));
        e_Y = MLOD__VADD(MLOD__VMUL(hh, MLOD__VADD(e_my, MLOD__VMUL(u, MLOD__VABS(ny)))),
                         MLOD__VMUL(u, MLOD__VADD(MLOD__VABS(MLOD__VMUL(hh, ny)), MLOD__VABS(Y))));
    } else {
        mlod__vf hs = MLOD__VSET(f->half_scale), kk, e_kk, sum, px, py;
        sum = MLOD__VADD(hi, lo);
        kk = MLOD__VMUL(hs, sum);
        e_kk = MLOD__VADD(MLOD__VMUL(hs, MLOD__VADD(MLOD__VADD(e_hi, e_lo), MLOD__VMUL(u, MLOD__VABS(sum)))),
                          MLOD__VMUL(two_u, MLOD__VABS(kk)));
        px = MLOD__VMUL(kk, dx);
        py = MLOD__VMUL(kk, dy);
        X = MLOD__VADD(MLOD__VSET(f->x0), px);
        Y = MLOD__VSUB(MLOD__VSET(f->y0), py); /* y0 + kk * -dy: the same bits */
        e_X = MLOD__VADD(MLOD__VADD(MLOD__VMUL(MLOD__VABS(kk), e_dir), MLOD__VMUL(MLOD__VABS(dx), e_kk)),
                         MLOD__VADD(MLOD__VMUL(e_kk, e_dir), MLOD__VMUL(u, MLOD__VADD(MLOD__VABS(px), MLOD__VABS(X)))));
        e_Y = MLOD__VADD(MLOD__VADD(MLOD__VMUL(MLOD__VABS(kk), e_dir), MLOD__VMUL(MLOD__VABS(dy), e_kk)),
                         MLOD__VADD(MLOD__VMUL(e_kk, e_dir), MLOD__VMUL(u, MLOD__VADD(MLOD__VABS(py), MLOD__VABS(Y)))));
    }
    g = MLOD__VSUB(hi, lo);
    e_g = MLOD__VADD(MLOD__VADD(e_hi, e_lo), MLOD__VMUL(u, MLOD__VABS(g)));
    R = MLOD__VMUL(MLOD__VSET(f->half_scale), g);
    e_R = MLOD__VADD(MLOD__VMUL(MLOD__VSET(f->half_scale), e_g), MLOD__VMUL(two_u, MLOD__VABS(R)));
    ok = MLOD__VAND(ok, MLOD__VLE(MLOD__VMUL(MLOD__VADD(R, MLOD__VMUL(e_R, widen)), MLOD__VSET(ds)),
                                  MLOD__VSET((float)(MLOD__SMALL_DISC * (1.0 - 1.0 / 1048576.0)))));
    e_X = MLOD__VADD(MLOD__VMUL(e_X, widen), MLOD__VMUL(two_u, MLOD__VABS(X)));
    e_Y = MLOD__VADD(MLOD__VMUL(e_Y, widen), MLOD__VMUL(two_u, MLOD__VABS(Y)));
    /* unsure lanes: a NAN box, which mlod__disc_pixel finds unsure */
#define MLOD__VKEEP(v) MLOD__VOR(MLOD__VAND(ok, v), MLOD__VANDNOT(ok, nan))
    MLOD__VSTORE(box, MLOD__VKEEP(MLOD__VSUB(X, e_X)));
    MLOD__VSTORE(box + stride, MLOD__VKEEP(MLOD__VADD(X, e_X)));
    MLOD__VSTORE(box + 2 * stride, MLOD__VKEEP(MLOD__VSUB(Y, e_Y)));
    MLOD__VSTORE(box + 3 * stride, MLOD__VKEEP(MLOD__VADD(Y, e_Y)));
    MLOD__VSTORE(box + 4 * stride, MLOD__VKEEP(MLOD__VMUL(MLOD__VSUB(R, MLOD__VMUL(e_R, widen)), MLOD__VSET(ds))));
    MLOD__VSTORE(box + 5 * stride, MLOD__VKEEP(MLOD__VMUL(MLOD__VADD(R, MLOD__VMUL(e_R, widen)), MLOD__VSET(ds))));
#undef MLOD__VKEEP
#undef MLOD__VABS
#undef MLOD__VDOT
}

/* The lanes over nodes[0 .. count - 1], count a multiple of MLOD__VLANES. */
static void mlod__fast_discs(const mlod__fdiscs *fd, const mlod__fdisc *f, const float *spheres, const uint32_t *nodes,
                             uint32_t count, float ds, float *box, size_t stride)
{
    uint32_t i;
    for (i = 0; i < count; i += MLOD__VLANES) mlod__fast_disc_lanes(fd, f, spheres, nodes + i, ds, box + i, stride);
}

/* mlod__reached of the spheres of nodes[0 .. MLOD__VLANES - 1] through
   the view's float filter (pv->fast.ok; mlod__vplanes, the cut's plane
   tests and margins), as bit l of bits[s]: a sub-projection is reached
   where the lane is surely within every plane of it, missed where surely
   outside one.  Returns the lanes in doubt (one sub-projection neither,
   or a guard failed), whose bits are 0: the exact test's to decide. */
static unsigned mlod__reached_lanes(const mlod__pview *pv, const float *spheres, const uint32_t *nodes, unsigned *bits)
{
    const mlod__fview *fv = &pv->fast;
    mlod__vf sphere[4], x[3], d2, t, reach, unsure, out, in;
    unsigned doubt;
    int s;
    mlod__vload(spheres, nodes, &sphere[0], &sphere[1], &sphere[2], &sphere[3]);
    mlod__vsetup(fv, sphere, x, &d2, &t, &reach, &unsure);
    doubt = (unsigned)MLOD__VBITS(unsure);
    for (s = 0; s < fv->sub_count; s++) {
        mlod__vplanes(&fv->subs[s], x, sphere[3], reach, 0, &out, &in, NULL);
        bits[s] = (unsigned)MLOD__VBITS(in);
        doubt |= ~(unsigned)MLOD__VBITS(MLOD__VOR(out, in));
    }
    for (s = 0; s < fv->sub_count; s++) bits[s] &= ~doubt;
    return doubt & ((1u << MLOD__VLANES) - 1u);
}

/* mlod__disc_pixel for the boxes of MLOD__VLANES lanes (box[k * stride +
   l], k = 0 .. 3), the clip's bounds c[0 .. 3] below 2^24 as floats: bit l
   of *plot for MLOD__DISC_PLOT, its pixel in col[l] and row[l] (whole
   numbers), of *none for MLOD__DISC_NONE; in neither, unsure.  As there,
   the centre's box lies within the clip and xl and xh (yl and yh), xl <=
   xh, share a column (a row): xh < floor(xl) + 1, xl >= 0. */
static void mlod__disc_pixels(const float *box, size_t stride, const float *c, float *col, float *row, unsigned *plot,
                              unsigned *none)
{
    mlod__vf xl = MLOD__VLOADU(box), xh = MLOD__VLOADU(box + stride);
    mlod__vf yl = MLOD__VLOADU(box + 2 * stride), yh = MLOD__VLOADU(box + 3 * stride);
    mlod__vf c0 = MLOD__VSET(c[0]), c1 = MLOD__VSET(c[1]), c2 = MLOD__VSET(c[2]), c3 = MLOD__VSET(c[3]);
    mlod__vf one = MLOD__VSET(1.0f), fx, fy, in, out;
    out = MLOD__VOR(MLOD__VOR(MLOD__VLT(xh, c0), MLOD__VGE(xl, c1)), MLOD__VOR(MLOD__VLT(yh, c2), MLOD__VGE(yl, c3)));
    in = MLOD__VAND(MLOD__VAND(MLOD__VGE(xl, c0), MLOD__VLT(xh, c1)), MLOD__VAND(MLOD__VGE(yl, c2), MLOD__VLT(yh, c3)));
    fx = MLOD__VTRUNC(MLOD__VAND(in, xl)); /* (0 outside: within the conversion's range) */
    fy = MLOD__VTRUNC(MLOD__VAND(in, yl));
    in = MLOD__VAND(in, MLOD__VAND(MLOD__VLT(xh, MLOD__VADD(fx, one)), MLOD__VLT(yh, MLOD__VADD(fy, one))));
    MLOD__VSTORE(col, fx);
    MLOD__VSTORE(row, fy);
    *plot = (unsigned)MLOD__VBITS(in);
    *none = (unsigned)MLOD__VBITS(out);
}

/* mlod__disc_inside for MLOD__VLANES lanes, at the pixels (col[l], row[l])
   that mlod__disc_pixels found, step for step as it (the same bits): bit l
   of *in for MLOD__DISC_PLOT, of *out for MLOD__DISC_NONE; in neither,
   unsure. */
static void mlod__disc_insides(const float *box, size_t stride, const float *col, const float *row, unsigned *in,
                               unsigned *out)
{
    mlod__vf zero = MLOD__VSET(0.0f), half = MLOD__VSET(0.5f), sign = MLOD__VSET(-0.0f);
    mlod__vf cx = MLOD__VADD(MLOD__VLOADU(col), half), cy = MLOD__VADD(MLOD__VLOADU(row), half);
    mlod__vf dx0 = MLOD__VSUB(cx, MLOD__VLOADU(box + stride)), dx1 = MLOD__VSUB(cx, MLOD__VLOADU(box));
    mlod__vf dy0 = MLOD__VSUB(cy, MLOD__VLOADU(box + 3 * stride)), dy1 = MLOD__VSUB(cy, MLOD__VLOADU(box + 2 * stride));
    mlod__vf r_lo = MLOD__VLOADU(box + 4 * stride), r_hi = MLOD__VLOADU(box + 5 * stride);
    mlod__vf ax0 = MLOD__VANDNOT(sign, dx0), ax1 = MLOD__VANDNOT(sign, dx1);
    mlod__vf ay0 = MLOD__VANDNOT(sign, dy0), ay1 = MLOD__VANDNOT(sign, dy1), m;
    mlod__vf far_x, far_y, near_x, near_y, far2, near2;
    m = MLOD__VGT(ax0, ax1);
    far_x = MLOD__VOR(MLOD__VAND(m, ax0), MLOD__VANDNOT(m, ax1));
    m = MLOD__VGT(ay0, ay1);
    far_y = MLOD__VOR(MLOD__VAND(m, ay0), MLOD__VANDNOT(m, ay1));
    /* dx0 <= dx1: dx0 if it is positive, else -dx1 if that is, else 0 (a sum with a zero: exact) */
    near_x = MLOD__VADD(MLOD__VAND(MLOD__VGT(dx0, zero), dx0), MLOD__VAND(MLOD__VLT(dx1, zero), MLOD__VSUB(zero, dx1)));
    near_y = MLOD__VADD(MLOD__VAND(MLOD__VGT(dy0, zero), dy0), MLOD__VAND(MLOD__VLT(dy1, zero), MLOD__VSUB(zero, dy1)));
    far2 = MLOD__VMUL(MLOD__VADD(MLOD__VMUL(far_x, far_x), MLOD__VMUL(far_y, far_y)),
                      MLOD__VSET(1.0f + 1.0f / 1048576.0f));
    near2 = MLOD__VMUL(MLOD__VADD(MLOD__VMUL(near_x, near_x), MLOD__VMUL(near_y, near_y)),
                       MLOD__VSET(1.0f - 1.0f / 1048576.0f));
    *in = (unsigned)MLOD__VBITS(MLOD__VLE(far2, MLOD__VMUL(r_lo, r_lo)));
    *out = (unsigned)MLOD__VBITS(MLOD__VGT(near2, MLOD__VMUL(r_hi, r_hi)));
}
#ifdef MLOD__NO_FMA_TARGET
#pragma clang attribute push(__attribute__((target("no-fma"))), apply_to = function)
#endif
#endif


/* mlod__tangent_hit for nodes[i] at tile pixel (cols[i], rows[i]) (whole
   numbers, as floats), i < n <= MLOD__DRAW_CHUNK, in a perspective or
   paraboloid sub-projection s: bit 0 of hit[i] and depth[i], each node's
   operations those of mlod__tangent_hit in its order (the same bits),
   MLOD__WLANES nodes a vector where the pass has double lanes; bit 1 of
   hit[i]: mlod__has_plane. */
static void mlod__tangent_hits(const mlod__pview *pv, int s, const mlod_tree *tree, const uint32_t *nodes,
                               const float *cols, const float *rows, uint32_t n, float ds, uint8_t *hit, float *depth)
{
    uint32_t i = 0;
    MLOD__LANES_REDIRECT(mlod__tangent_hits, (pv, s, tree, nodes, cols, rows, n, ds, hit, depth));
    MANYLODS_ASSERT(n <= MLOD__DRAW_CHUNK &&
                    (pv->kind[s] == MLOD_VIEW_PARABOLOID || pv->kind[s] == MLOD_VIEW_PERSPECTIVE));
#ifdef MLOD__WLANES
    if (n >= MLOD__WLANES) { /* each lane mlod__tangent_hit's steps; the divisions in a pass of their own */
        const mlod_view_sub *sub = &pv->f.subs[s];
        const int parab = pv->kind[s] == MLOD_VIEW_PARABOLOID;
        const double mid_x = sub->x + 0.5 * sub->width, mid_y = sub->y + 0.5 * sub->height, inv = 1.0 / sub->scale;
        const double inv_w = 2.0 / sub->width, inv_h = 2.0 / sub->height;
        int k;
        mlod__wd vd[3][MLOD__DRAW_CHUNK / MLOD__WLANES], vx[3][MLOD__DRAW_CHUNK / MLOD__WLANES];
        mlod__wd vq[MLOD__DRAW_CHUNK / MLOD__WLANES], vt[MLOD__DRAW_CHUNK / MLOD__WLANES];
        mlod__wd vr[MLOD__DRAW_CHUNK / MLOD__WLANES];
        uint8_t vp[MLOD__DRAW_CHUNK];
        uint32_t j, l, groups = n / MLOD__WLANES;
        for (j = 0; j < groups; j++) {
            const float *sr[MLOD__WLANES], *cr[MLOD__WLANES];
            mlod__wd cx = MLOD__WADD(MLOD__WFLOATS(cols + MLOD__WLANES * j), MLOD__WSPLAT(0.5));
            mlod__wd cy = MLOD__WADD(MLOD__WFLOATS(rows + MLOD__WLANES * j), MLOD__WSPLAT(0.5));
            mlod__wd px, py, d[3], x[3], sp[4], cp[4];
            for (l = 0; l < MLOD__WLANES; l++) {
                sr[l] = tree->spheres + 4 * (size_t)nodes[MLOD__WLANES * j + l];
                cr[l] = tree->cones + 4 * (size_t)nodes[MLOD__WLANES * j + l];
                vp[MLOD__WLANES * j + l] = (uint8_t)((double)cr[l][3] < MLOD__PI);
            }
            if (parab) {
                mlod__wd x2, y2, w;
                px = MLOD__WSUB(MLOD__WMUL(MLOD__WSUB(cx, MLOD__WSPLAT(sub->x)), MLOD__WSPLAT(inv_w)), MLOD__WSPLAT(1.0));
                py = MLOD__WSUB(MLOD__WSPLAT(1.0), MLOD__WMUL(MLOD__WSUB(cy, MLOD__WSPLAT(sub->y)), MLOD__WSPLAT(inv_h)));
                vq[j] = MLOD__WADD(MLOD__WMUL(px, px), MLOD__WMUL(py, py));
                x2 = MLOD__WADD(px, px); /* 2 px, exact: (2 px) r as the scalar 2.0 * px * r */
                y2 = MLOD__WADD(py, py);
                w = MLOD__WSUB(MLOD__WSPLAT(1.0), vq[j]);
                for (k = 0; k < 3; k++)
                    d[k] = MLOD__WADD(MLOD__WADD(MLOD__WMUL(x2, MLOD__WSPLAT(sub->right[k])),
                                                 MLOD__WMUL(y2, MLOD__WSPLAT(sub->up[k]))),
                                      MLOD__WMUL(w, MLOD__WSPLAT(sub->forward[k])));
            } else {
                px = MLOD__WMUL(MLOD__WSUB(cx, MLOD__WSPLAT(mid_x)), MLOD__WSPLAT(inv));
                py = MLOD__WMUL(MLOD__WSUB(MLOD__WSPLAT(mid_y), cy), MLOD__WSPLAT(inv));
                vq[j] = MLOD__WSPLAT(0.0);
                for (k = 0; k < 3; k++)
                    d[k] = MLOD__WADD(MLOD__WADD(MLOD__WSPLAT(sub->forward[k]), MLOD__WMUL(px, MLOD__WSPLAT(sub->right[k]))),
                                      MLOD__WMUL(py, MLOD__WSPLAT(sub->up[k])));
            }
            mlod__wd_rows(sr, sp);
            mlod__wd_rows(cr, cp);
            for (k = 0; k < 3; k++) {
                x[k] = MLOD__WSUB(sp[k], MLOD__WSPLAT(pv->f.eye[k]));
                vd[k][j] = d[k];
                vx[k][j] = x[k];
            }
            vr[j] = MLOD__WMUL(sp[3], MLOD__WSPLAT((double)ds));
            /* t = n.(x - o) / n.dir with o = 0 (x - 0 is x, bit for bit) */
            vt[j] = MLOD__WDIV(MLOD__WADD(MLOD__WADD(MLOD__WMUL(cp[0], x[0]), MLOD__WMUL(cp[1], x[1])), MLOD__WMUL(cp[2], x[2])),
                               MLOD__WADD(MLOD__WADD(MLOD__WMUL(cp[0], d[0]), MLOD__WMUL(cp[1], d[1])), MLOD__WMUL(cp[2], d[2])));
        }
        for (j = 0; j < groups; j++) {
            mlod__wd e[3];
            double tq[MLOD__WLANES], tt[MLOD__WLANES], te[MLOD__WLANES], tr[MLOD__WLANES];
            /* (0 + t d) - x: without the 0, only a zero's sign may differ, which the square drops */
            for (k = 0; k < 3; k++) e[k] = MLOD__WSUB(MLOD__WMUL(vt[j], vd[k][j]), vx[k][j]);
            MLOD__WSTORE(te, MLOD__WADD(MLOD__WADD(MLOD__WMUL(e[0], e[0]), MLOD__WMUL(e[1], e[1])), MLOD__WMUL(e[2], e[2])));
            MLOD__WSTORE(tr, vr[j]);
            MLOD__WSTORE(tt, vt[j]);
            MLOD__WSTORE(tq, vq[j]);
            for (l = 0; l < MLOD__WLANES; l++) {
                const uint32_t at = MLOD__WLANES * j + l;
                hit[at] = (uint8_t)(((tq[l] <= 1.0) & (tt[l] > 0.0) & (te[l] <= tr[l] * tr[l])) | vp[at] << 1);
                depth[at] = (float)(tt[l] * (parab ? 1.0 + tq[l] : 1.0));
            }
        }
        i = MLOD__WLANES * groups;
    }
#endif
    for (; i < n; i++) { /* the rest one at a time, by the definition */
        const float *cone = tree->cones + 4 * (size_t)nodes[i];
        hit[i] = (uint8_t)(mlod__tangent_hit(pv, s, tree->spheres + 4 * (size_t)nodes[i], cone, ds, (uint32_t)cols[i],
                                             (uint32_t)rows[i], &depth[i]) |
                           mlod__has_plane(cone) << 1);
    }
}

/* mlod__node_distance of nodes[0 .. n) into out, MLOD__WLANES at a time
   where the pass has double lanes (each lane the same operations in the
   same order: the same bits). */
static void mlod__node_distances(const mlod_tree *scene, const uint32_t *nodes, uint32_t n, const double *centre,
                                 float *out)
{
    uint32_t l = 0;
    MLOD__LANES_REDIRECT(mlod__node_distances, (scene, nodes, n, centre, out));
#ifdef MLOD__WLANES
    for (; l + MLOD__WLANES <= n; l += MLOD__WLANES) {
        const float *rows[MLOD__WLANES];
        mlod__wd sp[4], x, y, z;
        double d[MLOD__WLANES];
        uint32_t k;
        for (k = 0; k < MLOD__WLANES; k++) rows[k] = scene->spheres + 4 * (size_t)nodes[l + k];
        mlod__wd_rows(rows, sp);
        x = MLOD__WSUB(sp[0], MLOD__WSPLAT(centre[0]));
        y = MLOD__WSUB(sp[1], MLOD__WSPLAT(centre[1]));
        z = MLOD__WSUB(sp[2], MLOD__WSPLAT(centre[2]));
        MLOD__WSTORE(d, MLOD__WSQRT(MLOD__WADD(MLOD__WADD(MLOD__WMUL(x, x), MLOD__WMUL(y, y)), MLOD__WMUL(z, z))));
        for (k = 0; k < MLOD__WLANES; k++) out[l + k] = (float)d[k];
    }
#endif
    for (; l < n; l++) out[l] = mlod__node_distance(scene, nodes[l], centre);
}

#define MLOD__BOX_STRIDE (MLOD__DRAW_CHUNK + 8u) /* room for the padding of the last lanes */

/* Draw nodes[0 .. count - 1] (count <= MLOD__DRAW_CHUNK), each of which
   reaches sub-projection s, in order, through the band's float filter: a
   small disc's pixel at once, with the double path's depth computed as it
   does; the others by the double path.  The same pixels as
   mlod__image_discs and mlod__raster_disc draw, bit for bit. */
static void mlod__draw_filtered(const mlod__band *band, const mlod__pview *pv, int s, const uint32_t *nodes,
                                uint32_t count)
{
    const mlod_view_sub *sub = &pv->f.subs[s];
    const float *spheres = band->tree->spheres;
    uint32_t clip[4], ids[MLOD__BOX_STRIDE], padded = count, l;
    float box[6 * MLOD__BOX_STRIDE], depth[MLOD__DRAW_CHUNK];
    clip[0] = pv->columns[s][0];
    clip[1] = pv->columns[s][1];
    clip[2] = pv->rows[s][0] < band->row_begin ? band->row_begin : pv->rows[s][0];
    clip[3] = pv->rows[s][1] > band->row_end ? band->row_end : pv->rows[s][1];
    MANYLODS_ASSERT(count > 0 && count <= MLOD__DRAW_CHUNK);
    memcpy(ids, nodes, count * sizeof *ids);
#ifdef MLOD__VLANES
    padded = mlod__pad_last(ids, NULL, count, MLOD__VLANES);
#endif
    if (clip[1] <= 16777216u && clip[3] <= 16777216u) /* (the clip's bounds are floats) */
        mlod__fast_discs(band->fast, &band->fast->subs[s], spheres, ids, padded, band->disc_scale, box, MLOD__BOX_STRIDE);
    else
        for (l = 0; l < 6 * MLOD__BOX_STRIDE; l++) box[l] = NAN;
    if (band->tangent) { /* each small disc's one pixel, if its centre lies in the disc and its ray meets the node */
        float cols[MLOD__BOX_STRIDE], rows[MLOD__BOX_STRIDE];
        uint8_t hit[MLOD__DRAW_CHUNK];
        uint64_t plot = 0, none = 0;
        l = 0;
#ifdef MLOD__VLANES
        if (clip[1] <= 16777216u && clip[3] <= 16777216u) { /* mlod__disc_decide in lanes, strictly */
            float c[4];
            unsigned p, q, in, out;
            for (l = 0; l < 4; l++) c[l] = (float)(int32_t)clip[l];
            for (l = 0; l < padded; l += MLOD__VLANES) {
                mlod__disc_pixels(box + l, MLOD__BOX_STRIDE, c, cols + l, rows + l, &p, &q);
                mlod__disc_insides(box + l, MLOD__BOX_STRIDE, cols + l, rows + l, &in, &out);
                plot |= (uint64_t)(p & in) << l;
                none |= (uint64_t)(q | (p & out & ~in)) << l;
            }
            l = count;
        }
#endif
        for (; l < count; l++) {
            uint32_t col = 0, row = 0;
            int code = mlod__disc_decide(box + l, MLOD__BOX_STRIDE, 1, clip, &col, &row);
            plot |= (uint64_t)(code == MLOD__DISC_PLOT) << l;
            none |= (uint64_t)(code == MLOD__DISC_NONE) << l;
            cols[l] = (float)col; /* below 2^24 */
            rows[l] = (float)row;
        }
        if (band->mask) /* a patch: a pixel it does not draw is left as it is */
            for (l = 0; l < count; l++)
                if ((plot >> l & 1u) && !band->mask[(size_t)rows[l] * band->id_stride + (size_t)cols[l]]) {
                    plot &= ~((uint64_t)1 << l);
                    none |= (uint64_t)1 << l;
                }
        if (plot) { /* the rays of the discs that plot, together */
            uint32_t at_lane[MLOD__DRAW_CHUNK], picked[MLOD__DRAW_CHUNK], m = 0;
            float pc[MLOD__DRAW_CHUNK], pr[MLOD__DRAW_CHUNK];
            for (l = 0; l < count; l++) {
                at_lane[m] = l;
                picked[m] = nodes[l];
                pc[m] = cols[l];
                pr[m] = rows[l];
                m += (uint32_t)(plot >> l) & 1u;
            }
            mlod__tangent_hits(pv, s, band->tree, picked, pc, pr, m, band->disc_scale, hit, depth);
            for (l = 0; l < m; l++) {
                uint32_t j = at_lane[l];
                int plane = hit[l] >> 1;
                float at = plane ? depth[l] : mlod__centre_depth(pv, s, spheres + 4 * (size_t)nodes[j]);
                mlod__plot_if(band, (uint32_t)rows[j], (uint32_t)cols[j], at, nodes[j], (uint32_t)(plane == 0) | (hit[l] & 1u));
            }
        }
        for (l = 0; l < count; l++)
            if (!((plot | none) >> l & 1u)) mlod__draw_exact(band, pv, s, nodes + l, 1);
        return;
    }
    /* the double path's depths, as it computes them */
    if (pv->kind[s] == MLOD_VIEW_PARABOLOID)
        mlod__node_distances(band->tree, nodes, count, pv->f.eye, depth);
    else
        for (l = 0; l < count; l++) {
            const float *sphere = spheres + 4 * (size_t)nodes[l];
            double x[3];
            int k;
            for (k = 0; k < 3; k++) x[k] = (double)sphere[k] - pv->f.eye[k];
            depth[l] = (float)(pv->kind[s] == MLOD_VIEW_PERSPECTIVE ? mlod__dot3(x, sub->forward) : mlod__length3(x));
        }
#ifdef MLOD__VLANES
    if (band->disc_scale >= 1.0f && clip[1] <= 16777216u && clip[3] <= 16777216u) {
        /* mlod__disc_decide in lanes (at disc scale 1 it is mlod__disc_pixel) */
        float c[4], cols[MLOD__BOX_STRIDE], rows[MLOD__BOX_STRIDE];
        uint64_t plot = 0, none = 0;
        unsigned p, q;
        for (l = 0; l < 4; l++) c[l] = (float)(int32_t)clip[l]; /* below 2^24 (a signed conversion: one instruction) */
        for (l = 0; l < padded; l += MLOD__VLANES) {
            mlod__disc_pixels(box + l, MLOD__BOX_STRIDE, c, cols + l, rows + l, &p, &q);
            plot |= (uint64_t)p << l;
            none |= (uint64_t)q << l;
        }
        for (l = 0; l < count; l++)
            if (plot >> l & 1u)
                mlod__plot_if(band, (uint32_t)rows[l], (uint32_t)cols[l], depth[l], nodes[l], 1u);
            else if (!(none >> l & 1u))
                mlod__draw_exact(band, pv, s, nodes + l, 1);
        return;
    }
#endif
    for (l = 0; l < count; l++) {
        uint32_t col = 0, row = 0;
        int code = mlod__disc_decide(box + l, MLOD__BOX_STRIDE, band->disc_scale < 1.0f, clip, &col, &row);
        if (code == MLOD__DISC_PLOT)
            mlod__plot_if(band, row, col, depth[l], nodes[l], 1u);
        else if (code == MLOD__DISC_UNSURE)
            mlod__draw_exact(band, pv, s, nodes + l, 1);
    }
}

/* Whether the band draws sub-projection s through its float filter. */
static int mlod__filtered(const mlod__band *band, int s)
{
    return band->fast && band->fast->subs[s].kind && band->disc_scale > 0.0f;
}

/* Draw n <= MLOD__DRAW_CHUNK nodes into the band, in order, in each
   sub-projection their spheres reach: through the band's float filter
   where it has one, else MLOD__LANES images at a time.  (Sub-projections
   draw into disjoint sub-tiles: each pixel sees its nodes in order.)  A
   view of one sub-projection draws them all: each drawn node of its cut
   reaches it (shaders/splat_draw.comp does the same). */
static void mlod__draw_nodes(const mlod__band *band, const mlod__pview *pv, const uint32_t *nodes, uint32_t n)
{
    int s;
    uint64_t reached[MLOD_VIEW_MAX_SUBS]; /* bit l of reached[s]: nodes[l] reaches sub-projection s */
    uint32_t l, m, reaching[MLOD__DRAW_CHUNK];
    const uint32_t *ids = nodes;
    MLOD__LANES_REDIRECT(mlod__draw_nodes, (band, pv, nodes, n));
    MANYLODS_ASSERT(n <= MLOD__DRAW_CHUNK && MLOD__DRAW_CHUNK <= 64);
    if (pv->sub_count > 1 && n > 0) {
        uint64_t exact = n == 64 ? ~(uint64_t)0 : ((uint64_t)1 << n) - 1u; /* the nodes the exact test takes */
        memset(reached, 0, sizeof reached);
#ifdef MLOD__VLANES
        if (pv->fast.ok) { /* the view's float filter, MLOD__VLANES nodes at a time */
            uint32_t padded[MLOD__DRAW_CHUNK + MLOD__VLANES];
            unsigned bits[MLOD_VIEW_MAX_SUBS], lanes = (1u << MLOD__VLANES) - 1u;
            memcpy(padded, nodes, n * sizeof *padded);
            mlod__pad_last(padded, NULL, n, MLOD__VLANES);
            for (l = 0; l < n; l += MLOD__VLANES) {
                uint64_t doubt = mlod__reached_lanes(pv, band->tree->spheres, padded + l, bits);
                exact = (exact & ~((uint64_t)lanes << l)) | (exact & doubt << l);
                for (s = 0; s < pv->sub_count; s++) reached[s] |= (uint64_t)bits[s] << l;
            }
        }
#endif
        for (l = 0; l < n; l++)
            if (exact >> l & 1u) {
                unsigned r = mlod__reached(pv, band->tree->spheres + 4 * (size_t)nodes[l]);
                for (s = 0; s < pv->sub_count; s++) reached[s] |= (uint64_t)(r >> s & 1u) << l;
            }
    }
    for (s = 0; s < pv->sub_count; s++) {
        m = n;
        if (pv->sub_count > 1) { /* the nodes reaching s, in order, without a branch */
            for (l = m = 0; l < n; l++) {
                reaching[m] = nodes[l];
                m += (uint32_t)(reached[s] >> l) & 1u;
            }
            ids = reaching;
        }
        if (m == 0) continue;
        if (mlod__filtered(band, s))
            mlod__draw_filtered(band, pv, s, ids, m);
        else
            mlod__draw_exact(band, pv, s, ids, m);
    }
}

#ifdef MLOD__NO_FMA_TARGET
#pragma clang attribute pop
#endif
#ifdef MLOD__VLANES
/* mask ? a : b, lane by lane */
MLOD__FORCE_INLINE mlod__vf mlod__vselect(mlod__vf mask, mlod__vf a, mlod__vf b)
{
    return MLOD__VOR(MLOD__VAND(mask, a), MLOD__VANDNOT(mask, b));
}

/* the lesser of a and b, lane by lane */
MLOD__FORCE_INLINE mlod__vf mlod__vmin(mlod__vf a, mlod__vf b) { return mlod__vselect(MLOD__VLT(a, b), a, b); }

/* the lanes where v's sign is sure: v > m or v < -m (neg_m = -m) */
MLOD__FORCE_INLINE mlod__vf mlod__vclear(mlod__vf v, mlod__vf m, mlod__vf neg_m)
{
    return MLOD__VOR(MLOD__VGT(v, m), MLOD__VLT(v, neg_m));
}

/* (x0, x1, x2).a, lane by lane */
MLOD__FORCE_INLINE mlod__vf mlod__vdot(mlod__vf x0, mlod__vf x1, mlod__vf x2, const float *a)
{
    return MLOD__VADD(MLOD__VADD(MLOD__VMUL(x0, MLOD__VSET(a[0])), MLOD__VMUL(x1, MLOD__VSET(a[1]))),
                      MLOD__VMUL(x2, MLOD__VSET(a[2])));
}

/* The lanes' codes (see above) for scene spheres (rows x, y, z, r) of
   inner view node vn (vn->fast set), leaf the lanes whose scene node is a
   leaf. */
MLOD__FORCE_INLINE mlod__vf mlod__vpair(const mlod__vnode *vn, const mlod__vf *sphere, mlod__vf leaf)
{
    const mlod__vf zero = MLOD__VSET(0.0f), all = MLOD__VEQ(zero, zero), big = MLOD__VSET(1.26765060e30f); /* 2^100 */
    const mlod__vf m_rel = MLOD__VSET(1.0f / 16384.0f), sixty4 = MLOD__VSET(64.0f);
    mlod__vf x0 = MLOD__VSUB(sphere[0], MLOD__VSET(vn->fc[0])), x1 = MLOD__VSUB(sphere[1], MLOD__VSET(vn->fc[1]));
    mlod__vf x2 = MLOD__VSUB(sphere[2], MLOD__VSET(vn->fc[2])), r = sphere[3], rho = MLOD__VSET(vn->frho);
    mlod__vf d2, d, U, M, nM, M2, UU, g, dg, Y, C, okY, unsure, cull, keep, kr, p;
    mlod__vf cl, cr, Yc, tc, near_ok, near_none, rp, rm, ln, small, large;
    mlod__vf fa, fr, Yf, tf, far_ok, far_none, ep, em, lf, some, none, cmin_large, cmin_small;
    mlod__vf cm, cmr, Ym, tm, P, m_ok, m_inf, least, lhs, move_ok, move_bad, go, code, live;
    int h;
    d2 = MLOD__VADD(MLOD__VADD(MLOD__VMUL(x0, x0), MLOD__VMUL(x1, x1)), MLOD__VMUL(x2, x2));
    d = MLOD__VSQRT(d2);
    g = MLOD__VADD(r, rho);
    U = MLOD__VADD(d, g);
    UU = MLOD__VMUL(U, U);
    M = MLOD__VMUL(U, m_rel);
    nM = MLOD__VSUB(zero, M);
    M2 = MLOD__VMUL(M, U);
    unsure =
        MLOD__VANDNOT(MLOD__VAND(MLOD__VGE(d2, MLOD__VSET(9.09494702e-13f)), MLOD__VLE(d2, MLOD__VSET(1.15292150e18f))),
                      all); /* 2^-40, 2^60 */
    unsure = MLOD__VOR(unsure,
                       MLOD__VANDNOT(MLOD__VOR(MLOD__VEQ(r, zero), MLOD__VAND(MLOD__VGE(r, MLOD__VSET(9.31322575e-10f)),
                                                                              MLOD__VLE(r, MLOD__VSET(1.07374182e9f)))),
                                     all)); /* 2^-30, 2^30 */
    /* Y = (d - g)(d + g) = d^2 cos^2 b, b = asin(g / d); C = d cos b */
    dg = MLOD__VSUB(d, g);
    Y = MLOD__VMUL(dg, MLOD__VADD(d, g));
    okY = MLOD__VAND(MLOD__VGT(dg, M), MLOD__VGE(MLOD__VMUL(sixty4, Y), UU));
    C = MLOD__VSQRT(MLOD__VAND(Y, MLOD__VGT(Y, zero)));
    /* the views' cone: culled when cos phi < cos(A + b) with sin(A + b) > 0;
       never where an eye is in the grown sphere (d < g) or A + b passes pi */
    cull = zero;
    keep = all;
    p = zero; /* x.a, a the views' unit axis: the cone's test and the floor's */
    if (vn->fast_cull == 1 || vn->fslab)
        p = MLOD__VADD(MLOD__VADD(MLOD__VMUL(x0, MLOD__VSET(vn->faxis[0])), MLOD__VMUL(x1, MLOD__VSET(vn->faxis[1]))),
                       MLOD__VMUL(x2, MLOD__VSET(vn->faxis[2])));
    if (vn->fast_cull == 1) {
        mlod__vf ca = MLOD__VSET(vn->fcos_reach), sa = MLOD__VSET(vn->fsin_reach);
        mlod__vf q = MLOD__VSUB(MLOD__VMUL(ca, C), MLOD__VMUL(sa, g)),
                 sp = MLOD__VADD(MLOD__VMUL(sa, C), MLOD__VMUL(ca, g));
        cull = MLOD__VAND(okY, MLOD__VAND(MLOD__VLT(p, MLOD__VSUB(q, M)), MLOD__VGT(sp, M)));
        keep =
            MLOD__VOR(MLOD__VLT(dg, nM), MLOD__VAND(okY, MLOD__VOR(MLOD__VGT(p, MLOD__VADD(q, M)), MLOD__VLT(sp, nM))));
    }
    if (vn->fslab) { /* outside every eye's field of view (mlod__below_floor), decided (U + |floor|) 2^-14 clear */
        mlod__vf fl = MLOD__VSET(vn->ffloor), high, clear;
        high = MLOD__VADD(MLOD__VSUB(MLOD__VADD(p, r), fl), MLOD__VMUL(U, MLOD__VSET(vn->fspread)));
        clear = MLOD__VMUL(MLOD__VADD(U, MLOD__VSET(fabsf(vn->ffloor))), m_rel);
        cull = MLOD__VOR(cull, MLOD__VLT(high, MLOD__VSUB(zero, clear)));
        keep = MLOD__VAND(keep, MLOD__VGT(high, clear));
    }
    if (vn->fast == 2) { /* a group or a leaf: as the cut for one view at its centre, coarse splits the
                            scene node, any other status draws (vn->pv's filter proves it), but culled
                            culls at a leaf (its map's view culls nothing here: back faces are not culled) */
        mlod__vf st = mlod__vstatus(&vn->pv.fast, sphere, NULL, leaf);
        code = MLOD__VAND(MLOD__VGT(st, zero), mlod__vselect(MLOD__VEQ(st, MLOD__VSET((float)MLOD_STATUS_COARSE)),
                                                             MLOD__VSET(4.0f), MLOD__VSET(2.0f)));
        if (vn->leaf) code = mlod__vselect(MLOD__VEQ(st, MLOD__VSET((float)MLOD_STATUS_CULLED)), MLOD__VSET(1.0f), code);
    } else {
        /* x.w: x2 in the default frame, else along the maps' float axis (mlod__map_coords) */
        mlod__vf xw = vn->fframe ? mlod__vdot(x0, x1, x2, vn->fframe[2]) : x2;
        /* cmax: the nearest eye, closest = d - rho; t_closest = sqrt((closest - r)(closest + r)); over the
           halves some eye reaches (x.w + rho + r >= 0), the least x.w - rho + t_closest (0 when not positive) */
        kr = MLOD__VMUL(MLOD__VSET(vn->fkc), r);
        cl = MLOD__VSUB(d, rho);
        cr = MLOD__VSUB(cl, r);
        Yc = MLOD__VMUL(cr, MLOD__VADD(cl, r));
        near_ok = MLOD__VAND(MLOD__VGT(cr, M), MLOD__VGE(MLOD__VMUL(sixty4, Yc), UU));
        near_none = MLOD__VLT(cr, nM); /* every eye within the sphere's reach: cmax infinite */
        tc = MLOD__VSQRT(MLOD__VAND(Yc, MLOD__VGT(Yc, zero)));
        rp = MLOD__VADD(xw, g);
        rm = MLOD__VSUB(g, xw);
        ln = mlod__vselect(MLOD__VGT(rp, M), MLOD__VADD(MLOD__VSUB(xw, rho), tc), big);
        ln = mlod__vmin(ln, mlod__vselect(MLOD__VGT(rm, M), MLOD__VSUB(MLOD__VSUB(tc, xw), rho), big));
        /* each half's reach decided, and the least denominator unless cmax is surely infinite */
        go = MLOD__VAND(mlod__vclear(rp, M, nM), mlod__vclear(rm, M, nM));
        small = MLOD__VAND(MLOD__VAND(go, near_ok), MLOD__VAND(MLOD__VGT(ln, M), MLOD__VLE(kr, MLOD__VSUB(ln, M))));
        large = MLOD__VOR(near_none, MLOD__VAND(MLOD__VAND(go, near_ok), MLOD__VGE(kr, MLOD__VADD(ln, M))));
        /* what the lanes that count (kept, not culled) need below: the far side for inner scene nodes
           surely too large for the nearest eye, the motion for leaves and for nodes surely small enough;
           what no such lane needs is left out (its masks 0: no lane reads them) */
        live = MLOD__VANDNOT(cull, keep);
        cmin_large = cmin_small = move_ok = move_bad = zero;
        if (MLOD__VBITS(MLOD__VANDNOT(leaf, MLOD__VAND(large, live)))) {
            /* cmin: the farthest eye, farthest = d + rho; over the halves every eye reaches (x.w - rho + r >= 0),
               the least x.w + rho + t_farthest; no such half: cmin = 0 */
            fa = MLOD__VADD(d, rho);
            fr = MLOD__VSUB(fa, r);
            Yf = MLOD__VMUL(fr, MLOD__VADD(fa, r));
            far_ok = MLOD__VAND(MLOD__VGT(fr, M), MLOD__VGE(MLOD__VMUL(sixty4, Yf), UU));
            far_none = MLOD__VLT(fr, nM);
            tf = MLOD__VSQRT(MLOD__VAND(Yf, MLOD__VGT(Yf, zero)));
            ep = MLOD__VADD(MLOD__VSUB(xw, rho), r);
            em = MLOD__VSUB(MLOD__VSUB(r, rho), xw);
            lf = mlod__vselect(MLOD__VGT(ep, M), MLOD__VADD(MLOD__VADD(xw, rho), tf), big);
            lf = mlod__vmin(lf, mlod__vselect(MLOD__VGT(em, M), MLOD__VSUB(MLOD__VADD(rho, tf), xw), big));
            some = MLOD__VOR(MLOD__VGT(ep, M), MLOD__VGT(em, M));
            none = MLOD__VAND(MLOD__VLT(ep, nM), MLOD__VLT(em, nM));
            go = MLOD__VAND(mlod__vclear(ep, M, nM), mlod__vclear(em, M, nM));
            cmin_large =
                MLOD__VOR(far_none, MLOD__VAND(MLOD__VAND(go, far_ok), MLOD__VAND(some, MLOD__VGE(kr, MLOD__VADD(lf, M)))));
            cmin_small = MLOD__VOR(
                none, MLOD__VAND(MLOD__VAND(go, far_ok), MLOD__VAND(MLOD__VGT(lf, M), MLOD__VLE(kr, MLOD__VSUB(lf, M)))));
        }
        if (vn->frho == 0.0f) { /* every eye at the centre: no motion */
            move_ok = all;
        } else if (MLOD__VBITS(MLOD__VAND(MLOD__VOR(leaf, small), live))) {
            /* motion (mlod__ball_motion): S turn / least (1 + cos(phi + b)) <= delta, turn = rho / t_m, t_m =
               sqrt((d - r - rho)(d - r + rho)), compared as S rho d^2 / delta <= (least d^2 (1 + cos)) t_m; with
               P = d sin phi (the length across w), per half (+-x.w): d^2 cos(phi - b) = x.w C + P g (the half
               counts unless below 0), d^2 cos(phi + b) = x.w C - P g, d^2 sin(phi + b) = P C + x.w g */
            cm = MLOD__VSUB(d, r);
            cmr = MLOD__VSUB(cm, rho);
            Ym = MLOD__VMUL(cmr, MLOD__VADD(cm, rho));
            m_ok = MLOD__VAND(okY, MLOD__VAND(MLOD__VGT(cmr, M), MLOD__VGE(MLOD__VMUL(sixty4, Ym), UU)));
            m_inf = MLOD__VOR(MLOD__VLT(cmr, nM), MLOD__VLT(dg, nM));
            tm = MLOD__VSQRT(MLOD__VAND(Ym, MLOD__VGT(Ym, zero)));
            if (vn->fframe) { /* across the maps' float axes */
                mlod__vf xa = mlod__vdot(x0, x1, x2, vn->fframe[0]), xb = mlod__vdot(x0, x1, x2, vn->fframe[1]);
                P = MLOD__VSQRT(MLOD__VADD(MLOD__VMUL(xa, xa), MLOD__VMUL(xb, xb)));
            } else {
                P = MLOD__VSQRT(MLOD__VADD(MLOD__VMUL(x0, x0), MLOD__VMUL(x1, x1)));
            }
            least = big;
            for (h = 0; h < 2; h++) {
                mlod__vf xh = h ? MLOD__VSUB(zero, xw) : xw, xc = MLOD__VMUL(xh, C), pg = MLOD__VMUL(P, g);
                mlod__vf e = MLOD__VADD(xc, pg), cs = MLOD__VSUB(xc, pg),
                         sn = MLOD__VADD(MLOD__VMUL(P, C), MLOD__VMUL(xh, g));
                mlod__vf one = MLOD__VADD(d2, cs), counts = MLOD__VGT(e, M2), mM2 = MLOD__VSUB(zero, M2);
                mlod__vf bounded = MLOD__VAND(MLOD__VGT(one, M2), MLOD__VOR(MLOD__VGT(cs, M2), MLOD__VGT(sn, M2)));
                mlod__vf endless = MLOD__VOR(MLOD__VLT(one, mM2), MLOD__VAND(MLOD__VLT(cs, mM2), MLOD__VLT(sn, mM2)));
                m_ok = MLOD__VAND(m_ok, MLOD__VOR(counts, MLOD__VLT(e, mM2)));
                m_ok = MLOD__VANDNOT(MLOD__VANDNOT(MLOD__VOR(bounded, endless), counts), m_ok);
                m_inf = MLOD__VOR(m_inf, MLOD__VAND(MLOD__VAND(m_ok, counts), endless));
                least = mlod__vmin(least, mlod__vselect(MLOD__VAND(counts, bounded), one, big));
            }
            lhs = MLOD__VMUL(MLOD__VMUL(MLOD__VSET(vn->fkm), rho), d2);
            move_ok = MLOD__VANDNOT(
                m_inf, MLOD__VAND(m_ok, MLOD__VOR(MLOD__VEQ(least, big),
                                                  MLOD__VLE(lhs, MLOD__VMUL(MLOD__VMUL(MLOD__VSUB(least, M2), tm),
                                                                            MLOD__VSET(1.0f - 1.0f / 8192.0f))))));
            move_ok = MLOD__VAND(move_ok, MLOD__VGT(least, M2));
            move_bad = MLOD__VOR(m_inf, MLOD__VAND(MLOD__VAND(m_ok, MLOD__VLT(least, big)),
                                                   MLOD__VGE(lhs, MLOD__VMUL(MLOD__VMUL(MLOD__VADD(least, M2), tm),
                                                                             MLOD__VSET(1.0f + 1.0f / 8192.0f)))));
        }
        /* scene leaves: drawn (2, 3) or split view (5) by the motion; others: small and moving little drawn,
           small and moving split view, large split scene (4) or middle (6), which splits the view (5) at once
           where r < rho: the children's spheres lie within the node's (the tree's containment), so their
           radii are r or less, and mlod__larger_splits would split the view without reading them */
        code = mlod__vselect(leaf,
                             mlod__vselect(move_bad, MLOD__VSET(5.0f),
                                           MLOD__VAND(move_ok, MLOD__VOR(MLOD__VAND(small, MLOD__VSET(2.0f)),
                                                                         MLOD__VAND(large, MLOD__VSET(3.0f))))),
                             MLOD__VOR(MLOD__VAND(small, mlod__vselect(move_bad, MLOD__VSET(5.0f),
                                                                       MLOD__VAND(move_ok, MLOD__VSET(2.0f)))),
                                       MLOD__VAND(large, MLOD__VOR(MLOD__VAND(cmin_large, MLOD__VSET(4.0f)),
                                                                   MLOD__VAND(cmin_small, mlod__vselect(MLOD__VLT(r, rho), MLOD__VSET(5.0f),
                                                                                                        MLOD__VSET(6.0f)))))));
    }
    /* culled first; not surely kept: unsure */
    code = mlod__vselect(keep, code, zero);
    code = mlod__vselect(cull, MLOD__VSET(1.0f), code);
    return MLOD__VANDNOT(unsure, code);
}

/* One batch of lanes of mlod__pair_actions: mlod__vpair's codes as
   actions, code - 1 (0 where unsure), in MLOD__VLANES bytes at out;
   returns the lanes whose code is unsure or middle, bit l for lane l. */
MLOD__FORCE_INLINE uint32_t mlod__vpair_bytes(const mlod__vnode *vn, const mlod__vf *sphere, mlod__vf leaf, uint8_t *out)
{
    const mlod__vf zero = MLOD__VSET(0.0f), code = mlod__vpair(vn, sphere, leaf);
    mlod__vbytes(MLOD__VAND(MLOD__VSUB(code, MLOD__VSET(1.0f)), MLOD__VGT(code, zero)), out);
    return (uint32_t)MLOD__VBITS(MLOD__VOR(MLOD__VEQ(code, zero), MLOD__VEQ(code, MLOD__VSET((float)MLOD__VPAIR_MIDDLE))));
}
#endif
#ifdef MLOD__NO_FMA_TARGET
#pragma clang attribute push(__attribute__((target("no-fma"))), apply_to = function)
#endif

#ifdef MLOD__VLANES
/* A lane's code as an action (mlod__pair_action's), the children's radii
   deciding MLOD__VPAIR_MIDDLE; -1 for 0 (unsure). */
static int mlod__vpair_action(const mlod_tree *scene, const mlod__vnode *vn, uint32_t s, uint8_t code)
{
    if (code == 0) return -1;
    if (code != MLOD__VPAIR_MIDDLE) return code - 1;
    return mlod__larger_splits(scene, s, vn->radius); /* an inner scene node: leaves are never middle */
}
#endif


/* The actions of n <= MLOD__MV_ROOM pairs (scene nodes nodes[0 .. n) with
   view node vn), as mlod__pair_action gives them: through the float
   filter where vn has one and the pass has lanes, the exact path for the
   lanes it leaves.  The lanes' codes as actions first, for all the pairs
   (whole batches: actions has room for n rounded up to MLOD__VLANES), the
   codes that need more listed; then those few (the children's radii, or
   the exact path): the batches of a level depend on no other
   pair's answer, and no loop over all the pairs branches on one pair's
   code.  (What that buys was measured: a tenth with 8 lanes, which the
   descent now fills; about nothing with 4, where the filter's arithmetic
   sets the pace, CHANGELOG.md, 0.1.0.) */
static void mlod__pair_actions(const mlod__mv_job *job, const mlod__vnode *vn, const uint32_t *nodes, uint32_t n,
                               uint8_t *actions)
{
    uint32_t i = 0;
    MLOD__LANES_REDIRECT(mlod__pair_actions, (job, vn, nodes, n, actions));
#ifdef MLOD__VLANES
    if (vn->fast && n > 1) {
        const mlod_tree *scene = job->scene;
        uint32_t lanes[MLOD__VLANES], l, m = 0;
        uint16_t odd[MLOD__MV_ROOM];
        MANYLODS_ASSERT(n <= MLOD__MV_ROOM);
        for (; i < n; i += MLOD__VLANES) { /* the actions (code - 1; 0 where unsure), the unsure and middle listed */
            mlod__vf sphere[4];
            uint32_t k = n - i < MLOD__VLANES ? n - i : MLOD__VLANES, bits;
            for (l = 0; l < MLOD__VLANES; l++) lanes[l] = nodes[i + (l < k ? l : 0)];
            mlod__vload(scene->spheres, lanes, &sphere[0], &sphere[1], &sphere[2], &sphere[3]);
            bits = mlod__vpair_bytes(vn, sphere, mlod__vleaf(lanes, scene->leaf_count - 1), actions + i);
            for (l = 0; l < k; l++) {
                odd[m] = (uint16_t)(i + l);
                m += bits >> l & 1u;
            }
        }
        for (l = 0; l < m; l++) {
            uint32_t k = odd[l];
            int a = mlod__vpair_action(scene, vn, nodes[k],
                                       actions[k] == MLOD__VPAIR_MIDDLE - 1 ? (uint8_t)MLOD__VPAIR_MIDDLE : 0);
            actions[k] = (uint8_t)(a >= 0 ? a : mlod__pair_action(job, vn, nodes[k]));
        }
        return;
    }
#endif
    for (; i < n; i++) actions[i] = (uint8_t)mlod__pair_action(job, vn, nodes[i]);
}

#undef MLOD__LANES_REDIRECT
#undef MLOD__IF_AVX2
#undef MLOD__IF_AVX512
#endif /* MLOD__PASS_LEVEL */

/*
------------------------------------------------------------------------------
This software is available under two licenses; choose whichever you prefer.
------------------------------------------------------------------------------
ALTERNATIVE A - MIT License
Copyright (c) 2026 manylods contributors
Permission is hereby granted, free of charge, to any person obtaining a copy of
this software and associated documentation files (the "Software"), to deal in
the Software without restriction, including without limitation the rights to
use, copy, modify, merge, publish, distribute, sublicense, and/or sell copies
of the Software, and to permit persons to whom the Software is furnished to do
so, subject to the following conditions:
The above copyright notice and this permission notice shall be included in all
copies or substantial portions of the Software.
THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE
SOFTWARE.
------------------------------------------------------------------------------
ALTERNATIVE B - Public Domain
The manylods contributors dedicate this file to the public domain. Anyone may
copy, modify, publish, use, compile, sell or distribute it, in source or
binary form, for any purpose, commercial or not, by any means, without
asking and without condition.
------------------------------------------------------------------------------
*/
