#!/usr/bin/env python3
# Writes the minimized inputs of the open defects the `layered` fuzz target found
# (fuzz/regressions/layered/open_*/, besides the fuzzer's own crash files), with the scene
# encoder of layered.py: `python3 fuzz/corpus_gen/open_defects.py fuzz/regressions/layered`.
import os, sys
here = os.path.dirname(os.path.abspath(__file__))
out = sys.argv[1]
src = open(os.path.join(here, 'layered.py')).read().split('seeds = {')[0]
exec(src.replace('out = sys.argv[1]', ''))
cube = lambda m: (0, 0.75, 0, 1, 0, TR(), m)
far_light = dict(ef=0x10 | 1, points=(((1000.0, 1, 0), (255, 255, 255), (1.0, 1.0, 1.0)),))
ortho_fog = lambda far: dict(opts=1, proj=(6.0, 0.5, far), ef=0x10 | 4, fog=(4.0, 9.0, (150, 170, 200)))
# lm=1 with receiver index 9 (lists=0): a layered frame refuses the layering, so only render draws.
plain = dict(lm=1, lists=0, bad=9)
inputs = {
    'open_phong_point_attenuation/phong_cube_point_light_1000_att_111': scene(caster=cube(MAT(2)), **far_light),
    'open_phong_point_attenuation/phong_cube_point_light_plain_render': scene(caster=cube(MAT(2)), **far_light, **plain),
    'open_fog_ortho_far/phong_fog_ortho_far_1e15': scene(caster=cube(MAT(2)), **ortho_fog(1e15)),
    'open_fog_ortho_far/phong_fog_ortho_far_1e30': scene(caster=cube(MAT(2)), **ortho_fog(1e30)),
    'open_fog_ortho_far/phong_fog_ortho_far_1e30_plain_render': scene(caster=cube(MAT(2)), **ortho_fog(1e30), **plain),
}
for name, data in inputs.items():
    os.makedirs(os.path.dirname(os.path.join(out, name)), exist_ok=True)
    open(os.path.join(out, name), 'wb').write(data)
print(len(inputs), 'inputs')
