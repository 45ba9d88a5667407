/* shaders/interface.h - the binary interface between manylods_vk.h and its
   compute shaders, written once in the subset of C99 and GLSL that both
   read: the layout of a view in the views buffer, the kind and status
   codes, the binding of every buffer, the members of every push-constant
   block and of the cut's control block.  The shaders' layout files include
   it; shaders/embed.sh copies it into manylods_vk.h (between its INTERFACE
   markers), whose C side checks every size that crosses to the device
   (tests/check_shaders.sh fails when the copy differs).

   The member lists are X-macros: MEMBER(type, name) for one member,
   ARRAY(type, name, count) for an array, in std430 order.  The types are
   MLOD_IF_U32, MLOD_IF_UVEC4 (uint / uvec4 in GLSL, uint32_t / four of
   them in C), float, and MLOD_IF_F64 (a double: its bits as a uvec2 in
   GLSL, which real.glsl's r_load reads, so that no shader needs a 64-bit
   type; double in C).  64-bit counts are two 32-bit words, low first,
   which the shaders add to with 32-bit atomics and a carry
   (MLOD_IF_COUNT64 in the layout files).  Defined by the includer: in C,
   mlodvk__uvec4 (uint32_t[4]) before this file. */
#ifndef MLOD_IF_INTERFACE_H
#define MLOD_IF_INTERFACE_H

#if defined(VULKAN) || defined(GL_SPIRV) /* GLSL for SPIR-V (glslangValidator -V or -G) */
#define MLOD_IF_U32 uint
#define MLOD_IF_UVEC4 uvec4
#define MLOD_IF_F64 uvec2
#else
#define MLOD_IF_U32 uint32_t
#define MLOD_IF_UVEC4 mlodvk__uvec4
#define MLOD_IF_F64 double
#endif

/* One view in the views buffer: MLOD_IF_VIEW_STRIDE doubles, laid out as
   mlod_view_frame (manylods.h), which the host writes as it is: a head of
   MLOD_IF_V_SUBS doubles, then MLOD_IF_MAX_SUBS sub-projections of
   MLOD_IF_SUB_STRIDE doubles each (mlod_view_sub), the first sub_count of
   them used.  Fields are at these offsets, from the view's first double
   (V_) or from its sub-projection's (S_); manylods_vk.h checks them at
   compile time. */
#define MLOD_IF_MAX_SUBS 6
#define MLOD_IF_SUB_STRIDE 48
#define MLOD_IF_VIEW_STRIDE 296 /* MLOD_IF_V_SUBS + MLOD_IF_MAX_SUBS * MLOD_IF_SUB_STRIDE */
#define MLOD_IF_V_EYE 0         /* 3 */
#define MLOD_IF_V_WIDTH 3
#define MLOD_IF_V_HEIGHT 4
#define MLOD_IF_V_KIND 5
#define MLOD_IF_V_SUB_COUNT 6
#define MLOD_IF_V_BACKFACES 7
#define MLOD_IF_V_SUBS 8
#define MLOD_IF_S_RIGHT 0       /* 3 */
#define MLOD_IF_S_UP 3          /* 3 */
#define MLOD_IF_S_FORWARD 6     /* 3 */
#define MLOD_IF_S_KIND 9
#define MLOD_IF_S_SCALE 10
#define MLOD_IF_S_SCALE_X 11
#define MLOD_IF_S_SCALE_Y 12
#define MLOD_IF_S_X 13
#define MLOD_IF_S_Y 14
#define MLOD_IF_S_WIDTH 15
#define MLOD_IF_S_HEIGHT 16
#define MLOD_IF_S_PLANE_COUNT 17
#define MLOD_IF_S_PLANES 18     /* 6 planes of 5: n, k, l */

/* One view's float filter in the cut's filters buffer (vec4s):
   MLOD_IF_FILTER_STRIDE floats as mlod_view_filter_of (manylods.h) writes
   them, in groups of four that the shaders read as one vec4: a head of
   MLOD_IF_F_SUBS floats, then a sub-projection every MLOD_IF_F_SUB_STRIDE
   floats, its planes from MLOD_IF_FS_PLANES on, MLOD_IF_FP_STRIDE floats
   each; offsets from the view's first float (F_), its sub-projection's
   (FS_) or its plane's (FP_); manylods_vk.h checks them against
   manylods.h's MLOD_FILTER_* at compile time. */
#define MLOD_IF_FILTER_STRIDE 344
#define MLOD_IF_F_OK 0
#define MLOD_IF_F_BACKFACES 1
#define MLOD_IF_F_ORTHO 2
#define MLOD_IF_F_SUB_COUNT 3
#define MLOD_IF_F_EYE 4         /* 3 */
#define MLOD_IF_F_FLOAT_EYE 7
#define MLOD_IF_F_SUBS 8
#define MLOD_IF_F_SUB_STRIDE 56
#define MLOD_IF_FS_KIND 0
#define MLOD_IF_FS_PLANE_COUNT 1
#define MLOD_IF_FS_VALID 2
#define MLOD_IF_FS_INVALID 3
#define MLOD_IF_FS_W 4          /* 3 */
#define MLOD_IF_FS_PLANES 8     /* 6 planes */
#define MLOD_IF_FP_STRIDE 8
#define MLOD_IF_FP_N 0          /* 3, then l and k - n.eye */
#define MLOD_IF_FP_SLOPE 5
#define MLOD_IF_FP_ERR 6

/* mlod_view_kind and the statuses of a cut entry (MLOD_STATUS_*; 0: not
   yet classified). */
#define MLOD_IF_KIND_PERSPECTIVE 0
#define MLOD_IF_KIND_PARABOLOID 1
#define MLOD_IF_KIND_DUAL_PARABOLOID 2
#define MLOD_IF_KIND_ORTHOGRAPHIC 3
#define MLOD_IF_KIND_CUBE 4
#define MLOD_IF_STATUS_PENDING 0u
#define MLOD_IF_STATUS_DRAWN 1u
#define MLOD_IF_STATUS_CULLED 2u
#define MLOD_IF_STATUS_OVERSIZE 3u
#define MLOD_IF_STATUS_COARSE 4u

/* Threads per workgroup of every shader. */
#define MLOD_IF_GROUP 256u

/* The cut's descriptor set (shaders/cut_layout.glsl). */
#define MLOD_IF_CUT_SPHERES 0
#define MLOD_IF_CUT_CONES 1
#define MLOD_IF_CUT_VIEWS 2
#define MLOD_IF_CUT_LIST_IN 3
#define MLOD_IF_CUT_LIST_OUT 4
#define MLOD_IF_CUT_STATUS_IN 5
#define MLOD_IF_CUT_STATUS_OUT 6
#define MLOD_IF_CUT_ACTS 7
#define MLOD_IF_CUT_BLOCK_SUMS 8
#define MLOD_IF_CUT_CONTROL 9
#define MLOD_IF_CUT_VIEW_OFFSETS 10
#define MLOD_IF_CUT_FILTERS 11
#define MLOD_IF_CUT_BINDINGS 12

/* The splat's descriptor set (shaders/splat_layout.glsl). */
#define MLOD_IF_SPLAT_SPHERES 0
#define MLOD_IF_SPLAT_CONES 1
#define MLOD_IF_SPLAT_VIEWS 2
#define MLOD_IF_SPLAT_LIST 3
#define MLOD_IF_SPLAT_STATUS 4
#define MLOD_IF_SPLAT_COLORS 5
#define MLOD_IF_SPLAT_TILES 6
#define MLOD_IF_SPLAT_KEYS 7
#define MLOD_IF_SPLAT_DEPTH 8
#define MLOD_IF_SPLAT_NORMAL 9
#define MLOD_IF_SPLAT_COLOR 10
#define MLOD_IF_SPLAT_CONTROL 11
#define MLOD_IF_SPLAT_BINDINGS 12

/* The refit's descriptor set (shaders/refit_layout.glsl). */
#define MLOD_IF_REFIT_SPHERES 0
#define MLOD_IF_REFIT_CONES 1
#define MLOD_IF_REFIT_COLORS 2
#define MLOD_IF_REFIT_LEAF_SOURCES 3
#define MLOD_IF_REFIT_BARYCENTRICS 4
#define MLOD_IF_REFIT_TRIANGLE_AREAS 5
#define MLOD_IF_REFIT_INDICES 6
#define MLOD_IF_REFIT_POSITIONS 7
#define MLOD_IF_REFIT_NORMALS 8
#define MLOD_IF_REFIT_VERTEX_COLORS 9
#define MLOD_IF_REFIT_FINDINGS 10
#define MLOD_IF_REFIT_BINDINGS 11

/* The MegaViews render's descriptor set (shaders/mv_layout.glsl): the
   scene tree, the view tree (its eyes' spheres and cones), the map frames,
   the pair lists (a round's input and output; the next level's pairs and
   the level's draws, one buffer), the level block (tiles, the view
   leaves' sources, half fields of view, per-node counts and map slots),
   this level's maps and the previous level's, the control block and the
   atlas's depth, normal and colour. */
#define MLOD_IF_MV_SCENE_SPHERES 0
#define MLOD_IF_MV_SCENE_CONES 1
#define MLOD_IF_MV_SCENE_COLORS 2
#define MLOD_IF_MV_EYE_SPHERES 3
#define MLOD_IF_MV_EYE_CONES 4
#define MLOD_IF_MV_FRAMES 5
#define MLOD_IF_MV_PAIRS_IN 6
#define MLOD_IF_MV_PAIRS_OUT 7
#define MLOD_IF_MV_LISTS 8
#define MLOD_IF_MV_LEVEL 9
#define MLOD_IF_MV_MAPS 10
#define MLOD_IF_MV_PREV_MAPS 11
#define MLOD_IF_MV_CONTROL 12
#define MLOD_IF_MV_DEPTH 13
#define MLOD_IF_MV_NORMAL 14
#define MLOD_IF_MV_COLOR 15
#define MLOD_IF_MV_BINDINGS 16

/* An empty map slot, and the words of a map pixel: its depth as an
   order-preserving pattern, the least node at that depth (inherited from
   the parent's map or drawn; NONE: none yet), and the node. */
#define MLOD_IF_MV_NONE 0xffffffffu
#define MLOD_IF_MV_WORDS 3u

/* The cut's control block (std430): indirect dispatch arguments (a slot
   per round parity, then cut_finish's, then the exact pass's: x the
   workgroups it runs, w the entries cut_step or cut_finish deferred to
   it, listed in status_out or acts: defer_entry), the entries each
   slot's round reads, the splits and merges of the running round,
   whether the last round needed more than capacity entries, converged,
   rounds that changed the list, whether the current list is in buffer
   B, the entries the overflowing round needed, the entries of the
   current list, the entries deferred to the exact pass in all rounds and
   cut_finish (the float filter unsure of a status they need), and the
   criterion evaluations and the steps of the call (64-bit counts: low
   word, high word). */
#define MLOD_IF_CONTROL(MEMBER, ARRAY)                                                                                 \
    ARRAY(MLOD_IF_UVEC4, args, 4)                                                                                      \
    ARRAY(MLOD_IF_U32, count, 2)                                                                                       \
    MEMBER(MLOD_IF_U32, changed)                                                                                       \
    MEMBER(MLOD_IF_U32, overflow)                                                                                      \
    MEMBER(MLOD_IF_U32, done)                                                                                          \
    MEMBER(MLOD_IF_U32, rounds)                                                                                        \
    MEMBER(MLOD_IF_U32, input_is_b)                                                                                    \
    MEMBER(MLOD_IF_U32, needed)                                                                                        \
    MEMBER(MLOD_IF_U32, current)                                                                                       \
    MEMBER(MLOD_IF_U32, deferred)                                                                                      \
    ARRAY(MLOD_IF_U32, evaluated, 2)                                                                                   \
    ARRAY(MLOD_IF_U32, steps, 2)
#define MLOD_IF_CONTROL_BYTES 120

/* The cut shaders' push constants: epsilon (pixels), the tree's leaves,
   the views, whether the tree has cones, whether the input's statuses are
   current (not a call's first round), whether to look for sibling pairs
   to merge, the round parity (args[slot], count[slot]), the entries the
   output list holds, the device's maxComputeWorkGroupCount[0], and for
   cut_exact whether it settles cut_finish's pending entries (1) or takes
   a round's deferred ones (0). */
#define MLOD_IF_CUT_PUSH(MEMBER)                                                                                       \
    MEMBER(float, epsilon)                                                                                             \
    MEMBER(MLOD_IF_U32, leaf_count)                                                                                    \
    MEMBER(MLOD_IF_U32, view_count)                                                                                    \
    MEMBER(MLOD_IF_U32, has_cones)                                                                                     \
    MEMBER(MLOD_IF_U32, trust)                                                                                         \
    MEMBER(MLOD_IF_U32, merge)                                                                                         \
    MEMBER(MLOD_IF_U32, slot)                                                                                          \
    MEMBER(MLOD_IF_U32, capacity)                                                                                      \
    MEMBER(MLOD_IF_U32, max_groups_x)                                                                                  \
    MEMBER(MLOD_IF_U32, settle)
#define MLOD_IF_CUT_PUSH_BYTES 40

/* The splat shaders' push constants: the atlas's width and pixels, whether
   the tree has cones, whether the atlas has normals and colours, the
   device's maxComputeWorkGroupCount[0], the drawn radius over the image
   radius (in (0, 1]; below 1, no pixel-holding-the-centre fallback),
   splat_draw's pass (splat_layout.glsl), and whether nodes draw as tangent
   discs (the atlas's splat setting with the tree: mlod__splat_tangent). */
#define MLOD_IF_SPLAT_PUSH(MEMBER)                                                                                     \
    MEMBER(MLOD_IF_U32, atlas_width)                                                                                   \
    MEMBER(MLOD_IF_U32, pixel_count)                                                                                   \
    MEMBER(MLOD_IF_U32, has_cones)                                                                                     \
    MEMBER(MLOD_IF_U32, want_normal)                                                                                   \
    MEMBER(MLOD_IF_U32, want_color)                                                                                    \
    MEMBER(MLOD_IF_U32, max_groups_x)                                                                                  \
    MEMBER(float, disc_scale)                                                                                          \
    MEMBER(MLOD_IF_U32, pass)                                                                                          \
    MEMBER(MLOD_IF_U32, tangent)
#define MLOD_IF_SPLAT_PUSH_BYTES 36

/* The refit shaders' push constants: the tree's area_unit and
   radius_scale, its leaves, the items of this dispatch (vertices for the
   check, leaves, or the nodes of one depth), the depth's first node (merge)
   or the triangles (check), the floats between consecutive vertices'
   positions, normals (0: none) and colours (0: none), whether the tree has
   cones and colours, the device's maxComputeWorkGroupCount[0], and the
   check's pass (0: the vertices and the high words of the growths, 1: the
   low words of the growths whose high word is the largest). */
#define MLOD_IF_REFIT_PUSH(MEMBER)                                                                                     \
    MEMBER(MLOD_IF_F64, area_unit)                                                                                     \
    MEMBER(float, radius_scale)                                                                                        \
    MEMBER(MLOD_IF_U32, leaf_count)                                                                                    \
    MEMBER(MLOD_IF_U32, count)                                                                                         \
    MEMBER(MLOD_IF_U32, first)                                                                                         \
    MEMBER(MLOD_IF_U32, position_stride)                                                                               \
    MEMBER(MLOD_IF_U32, normal_stride)                                                                                 \
    MEMBER(MLOD_IF_U32, color_stride)                                                                                  \
    MEMBER(MLOD_IF_U32, has_cones)                                                                                     \
    MEMBER(MLOD_IF_U32, has_colors)                                                                                    \
    MEMBER(MLOD_IF_U32, max_groups_x)                                                                                  \
    MEMBER(MLOD_IF_U32, pass)
#define MLOD_IF_REFIT_PUSH_BYTES 56

/* The MegaViews control block (std430), host-visible: the parameters
   (epsilon, delta, the maps' scale S = resolution / 2, the group radius;
   the disc scale, whether nodes draw as tangent discs), the level (its
   first view node and count, the previous level's first), the trees
   (scene leaves, view leaves, whether the scene has cones, the view tree
   cones, half fields of view), the map (resolution, pixels per map,
   flags, atlas width, channels wanted), the level block's offsets in
   words (tiles, leaf sources, half fields of view and the view tree's
   floors as float bits, this level's pair counts, drawn flags and slots,
   the previous level's slots, each slot's node), the lists' counts (the
   round's input and output pairs, the next level's pairs, the level's
   draws; the draws stand after next_capacity pairs), the slots given out,
   the most pairs at one view node, the counts of what the pairs did
   (shared views: a 64-bit count, low word first), and a word that pads
   the block to a multiple of 8 bytes. */
#define MLOD_IF_MV_CONTROL_BLOCK(MEMBER)                                                                               \
    MEMBER(MLOD_IF_F64, epsilon)                                                                                       \
    MEMBER(MLOD_IF_F64, delta)                                                                                         \
    MEMBER(MLOD_IF_F64, scale)                                                                                         \
    MEMBER(MLOD_IF_F64, group_radius)                                                                                  \
    MEMBER(float, disc_scale)                                                                                          \
    MEMBER(MLOD_IF_U32, tangent)                                                                                       \
    MEMBER(MLOD_IF_U32, first)                                                                                         \
    MEMBER(MLOD_IF_U32, count)                                                                                         \
    MEMBER(MLOD_IF_U32, prev_first)                                                                                    \
    MEMBER(MLOD_IF_U32, scene_leaves)                                                                                  \
    MEMBER(MLOD_IF_U32, eye_leaves)                                                                                    \
    MEMBER(MLOD_IF_U32, has_cones)                                                                                     \
    MEMBER(MLOD_IF_U32, has_view_cones)                                                                                \
    MEMBER(MLOD_IF_U32, has_fovs)                                                                                      \
    MEMBER(MLOD_IF_U32, resolution)                                                                                    \
    MEMBER(MLOD_IF_U32, pixels)                                                                                        \
    MEMBER(MLOD_IF_U32, flags)                                                                                         \
    MEMBER(MLOD_IF_U32, atlas_width)                                                                                   \
    MEMBER(MLOD_IF_U32, want_normal)                                                                                   \
    MEMBER(MLOD_IF_U32, want_color)                                                                                    \
    MEMBER(MLOD_IF_U32, off_tiles)                                                                                     \
    MEMBER(MLOD_IF_U32, off_sources)                                                                                   \
    MEMBER(MLOD_IF_U32, off_fovs)                                                                                      \
    MEMBER(MLOD_IF_U32, off_floors)                                                                                    \
    MEMBER(MLOD_IF_U32, off_pairs)                                                                                     \
    MEMBER(MLOD_IF_U32, off_drawn)                                                                                     \
    MEMBER(MLOD_IF_U32, off_slots)                                                                                     \
    MEMBER(MLOD_IF_U32, off_prev_slots)                                                                                \
    MEMBER(MLOD_IF_U32, off_slot_nodes)                                                                                \
    MEMBER(MLOD_IF_U32, in_count)                                                                                      \
    MEMBER(MLOD_IF_U32, out_count)                                                                                     \
    MEMBER(MLOD_IF_U32, next_count)                                                                                    \
    MEMBER(MLOD_IF_U32, next_capacity)                                                                                 \
    MEMBER(MLOD_IF_U32, draw_count)                                                                                    \
    MEMBER(MLOD_IF_U32, slots)                                                                                         \
    MEMBER(MLOD_IF_U32, node_pairs)                                                                                    \
    MEMBER(MLOD_IF_U32, pairs)                                                                                         \
    MEMBER(MLOD_IF_U32, culled)                                                                                        \
    MEMBER(MLOD_IF_U32, shared_draws)                                                                                  \
    MEMBER(MLOD_IF_U32, leaf_draws)                                                                                    \
    MEMBER(MLOD_IF_U32, shared_leaves)                                                                                 \
    MEMBER(MLOD_IF_U32, shared_views_low)                                                                              \
    MEMBER(MLOD_IF_U32, shared_views_high)                                                                             \
    MEMBER(MLOD_IF_U32, pad)
#define MLOD_IF_MV_CONTROL_BYTES 192

/* The MegaViews shaders' push constants: the items of the dispatch (pairs,
   draws, slots, or map pixels) and the draw's pass (mv_draw.comp). */
#define MLOD_IF_MV_PUSH(MEMBER)                                                                                        \
    MEMBER(MLOD_IF_U32, items)                                                                                         \
    MEMBER(MLOD_IF_U32, pass)
#define MLOD_IF_MV_PUSH_BYTES 8

/* The refit check's findings: flags (1 a non-finite position, 2 a position
   beyond 1e36, 4 a non-finite normal, 8 a non-finite colour), the first
   vertex flagged (atomicMin), the largest growth of a triangle's area (a
   non-negative double, whose bits order as the doubles do: the largest
   high word, by atomicMax in pass 0, then the largest low word among the
   growths with that high word, in pass 1). */
#define MLOD_IF_FINDINGS(MEMBER)                                                                                       \
    MEMBER(MLOD_IF_U32, flags)                                                                                         \
    MEMBER(MLOD_IF_U32, first_vertex)                                                                                  \
    MEMBER(MLOD_IF_U32, growth_low)                                                                                    \
    MEMBER(MLOD_IF_U32, growth_high)
#define MLOD_IF_FINDINGS_BYTES 16

/* Spelling a member list out as declarations, in either language. */
#define MLOD_IF_DECLARE(type, name) type name;
#define MLOD_IF_DECLARE_ARRAY(type, name, count) type name[count];

#endif
