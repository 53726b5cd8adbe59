#!/usr/bin/env python3
# Writes the textured-shape seeds of the `shapes` fuzz target (fuzz/corpus/shapes/textured_*), in
# the byte layout fuzz_targets/shapes_input.rs decodes (selector 5 or 13, then the shape: 0 cube,
# 1 torus, 2 icosphere, 3 terrain): `python3 fuzz/corpus_gen/textured_shapes.py fuzz/corpus/shapes`.
import os, struct, sys
out = sys.argv[1]
def sp(i): return bytes([3, i])  # a special value: 10 is 1.0, 11 is 0.4, 2 NaN, 7 32767.99999
def f64(v): return bytes([0]) + struct.pack('<d', v)
def small(n): return bytes([0, n])
def big(n): return bytes([1]) + struct.pack('<Q', n)
seeds = {
 'textured_cube_one': bytes([5, 0]) + sp(10),
 'textured_cube_nan': bytes([5, 0]) + sp(2),
 'textured_torus_default': bytes([5, 1]) + sp(10) + sp(11) + small(12) + small(8),
 'textured_torus_max_nu': bytes([5, 1]) + sp(10) + sp(11) + big(2**64-1) + small(3),
 'textured_torus_max_nv': bytes([13, 1]) + sp(10) + sp(11) + small(3) + big(2**64-1),
 'textured_torus_max_both': bytes([5, 1]) + sp(10) + sp(11) + big(2**64-1) + big(2**64-1),
 'textured_torus_too_many': bytes([5, 1]) + sp(10) + sp(11) + small(17) + small(16),
 'textured_torus_spindle': bytes([5, 1]) + sp(11) + sp(10) + small(8) + small(8),
 'textured_icosphere_one': bytes([5, 2]) + sp(10) + bytes([1, 0]),
 'textured_icosphere_two': bytes([5, 2]) + sp(10) + bytes([2, 0]),
 'textured_icosphere_zero': bytes([5, 2]) + sp(10) + bytes([0, 0]),
 'textured_icosphere_q16_rail': bytes([5, 2]) + sp(7) + bytes([1, 0]),
 'textured_terrain_hills': bytes([5, 3]) + f64(4.0) + small(12) + f64(0.5),
 'textured_terrain_max_cells': bytes([5, 3]) + f64(4.0) + big(2**64-1) + f64(0.5),
 'textured_terrain_zero_cells': bytes([5, 3]) + f64(4.0) + small(0) + f64(0.5),
}
for k, v in seeds.items():
    open(os.path.join(out, k), 'wb').write(v)
print(len(seeds), 'seeds')
