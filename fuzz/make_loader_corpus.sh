#!/bin/sh
# fuzz/make_loader_corpus.sh - write the seeds of fuzz/fuzz_loader.c into
# fuzz/corpus/loader/ (run from anywhere; rewrites the seed-* files).  Each
# seed is fuzz_loader's input: a flags byte (bits 0-1 the name: 0 in.obj,
# 1 in.ply, 2 in, 3 IN.PLY; bit 2 a small error buffer, whose size is the
# next byte; bit 3 a failing allocation, the next byte says which; bit 4
# also through a file), then a file's bytes: small valid and invalid OBJ,
# ASCII PLY and binary PLY (both byte orders).
set -eu
cd "$(dirname "$0")/corpus" && mkdir -p loader && cd loader
rm -f seed-*
seed() { name=$1; shift; printf "$@" > "seed-$name"; }

tri='v 0 0 0\nv 1 0 0\nv 0 1 0\n'
seed obj-triangle "\000${tri}f 1 2 3\n"
seed obj-forms "\020# a square in every form\r\no square\r\nv 0 0 0\r\nv\t1 0 0\r\nv 1 1 0 1.0\r\n  v 0 1 0\r\nvt 0 0\r\nvn 0 0 1\r\nf 1/1/1 2/2/1 3/2/1 4/1/1\r\nf 1//1 2//1 3//1  # c\r\nf\t1/1 2/2 3/2\r\nl 1 2\r\nf -4 -3 -2 -1"
seed obj-hexagon "\002v 1 0 0\nv 0.5 0.8 0\nv -0.5 0.8 0\nv -1 0 0\nv -0.5 -0.8 0\nv 0.5 -0.8 0\nf 1 2 3 4 5 6\n"
seed obj-floats "\000v 1e30 -1.00000002e30 0x1p-3\nv 1.40129846e-45 -0 1e-40\nv 0 1 0\nf 1 2 3\n"
seed obj-bigindex "\000${tri}f 1 2 99999999999999999999\n"
seed obj-relative "\000${tri}f -5 -6 -7\n"
seed obj-zero "\004\030${tri}f 0 1 2\n"
seed obj-nul "\010\003v 0 0 0\nv 1 0\000 0\nf 1 2 3\n"
seed obj-junk "\000${tri}f 1/x 2 3\nv 1 2 3x\n"
seed obj-alloc "\010\002${tri}${tri}f 1 2 3 4 5 6\nf -1 -2 -3\n"

head='ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n'
seed ply-ascii "\001ply\nformat ascii 1.0\ncomment four corners\nobj_info by hand\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty uchar red\nelement face 1\nproperty list uchar int vertex_indices\nelement edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n0 0 0 0 255\n1 0 0 0 0\n1 1 0 0 7\n0 1 0 0 9\n4 0 1 2 3\n0 2\n"
seed ply-ascii-crlf "\023${head}element face 2\r\nproperty list uint uint vertex_index\r\nend_header\r\n0 0 0\r\n1 0 0\r\n1 1 0\r\n0 1 0\r\n3 0 1 2\r\n3 0 2 3\r\n"
seed ply-version "\001ply\nformat ascii 2.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n"
seed ply-cut "\001${head}element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1\n"
seed ply-badindex "\005\040${head}element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1.5 4\n"
seed ply-facefirst "\001ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n3 0 1 2\n0 0 0\n1 0 0\n0 1 0\n"
seed ply-empty-element "\001ply\nformat ascii 1.0\nelement nothing 1000000000000000000\n${head#ply\\nformat ascii 1.0\\n}element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n"

# binary: the square (float x y z, a uchar list of uint) in either byte order
le_body='\000\000\000\000\000\000\000\000\000\000\000\000\000\000\200\077\000\000\000\000\000\000\000\000\000\000\200\077\000\000\200\077\000\000\000\000\000\000\000\000\000\000\200\077\000\000\000\000\004\000\000\000\000\001\000\000\000\002\000\000\000\003\000\000\000'
be_body='\000\000\000\000\000\000\000\000\000\000\000\000\077\200\000\000\000\000\000\000\000\000\000\000\077\200\000\000\077\200\000\000\000\000\000\000\000\000\000\000\077\200\000\000\000\000\000\000\004\000\000\000\000\000\000\000\001\000\000\000\002\000\000\000\003'
bhead='element vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n'
seed ply-little "\002ply\nformat binary_little_endian 1.0\n${bhead}${le_body}"
seed ply-big "\021ply\nformat binary_big_endian 1.0\n${bhead}${be_body}"
seed ply-little-alloc "\012\003ply\nformat binary_little_endian 1.0\n${bhead}${le_body}"
seed ply-little-cut "\001ply\nformat binary_little_endian 1.0\n${bhead}\000\000\000\000\000\000\000\000\000\000\000\000\000\000\200\077"
# binary: double coordinates, a short list of int8 indices, an extra element
seed ply-double "\003ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\nelement face 1\nproperty list ushort char vertex_indices\nelement extra 2\nproperty int16 a\nend_header\n\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\360\077\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\360\077\000\000\000\000\000\000\000\000\003\000\000\001\002\001\000\002\000"
# binary big-endian: signed types (short, int, char coordinates; a char count of int16 indices)
seed ply-signed "\001ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty short x\nproperty int y\nproperty char z\nelement face 1\nproperty list char int16 vertex_indices\nend_header\n\000\000\377\376\356\220\377\377\376\000\000\000\005\000\000\003\000\000\000\000\002\003\000\000\000\001\000\002"
