#!/usr/bin/env python3
# Writes the seed corpus of the `layered` fuzz target (fuzz/corpus/layered), in the byte layout
# fuzz_targets/layered_input.rs decodes: run once as `python3 fuzz/corpus_gen/layered.py fuzz/corpus/layered`
# and again (after clearing the folder) whenever that layout changes.
import struct, os, sys, math
out = sys.argv[1]
SPECIAL = {0.0:0, 'nan':2, 'inf':3, '-inf':4, 1e30:5, -1e30:6, 19000.0:7, 24000.0:8, 32767.99:9,
           -32768.0:10, 181.0:11, 1e-6:12, 65536.0:15, 'max':16, 16.0:18, 255.0:19}
def R(v):
    if isinstance(v, str) or v in SPECIAL and v not in (0.0,):
        return bytes([3, SPECIAL[v]])
    if v == 0.0:
        return bytes([0, 0])
    if abs(v*16) < 128 and float(int(round(v*16))) == v*16:
        return bytes([0, int(round(v*16)) & 0xff])
    if abs(v*256) < 32768 and float(int(round(v*256))) == v*256:
        return bytes([1]) + struct.pack('<h', int(round(v*256)))
    return bytes([2]) + struct.pack('<f', v)
def V3(v): return b''.join(R(x) for x in v)
def RGB(c): return bytes(c)
def MAT(f=1, color=(200,120,60), amb=0.125, dif=0.875, spec=0.0, shin=8, tex=0, key=0, alpha=255):
    return bytes([f]) + RGB(color) + R(amb) + R(dif) + R(spec) + bytes([shin, tex]) + struct.pack('<H', key) + bytes([alpha])
def TR(t=(0,1.25,0), rot=0.25, k=1.0): return V3(t) + R(rot) + R(k)

def scene(opts=0, vw=40, vh=32, bg=(20,30,40), eye=(0,3,6), target=(0,0,0), up=(0,1,0),
          proj=(0.75, 0.5, 30.0), lights=(((-1,2,1),(255,255,255)),((1,1,-1),(60,60,90))),
          ground=(4.0, 0.0, MAT(1,(200,200,200))),
          caster=(0, 0.75, 0.375, 1, 6, TR(), MAT()),
          free=None,
          ef=0, points=(), fog=(4.0, 9.0, (150,170,200)), curve=0, exposure=1.0, intensity=1.0,
          lm=0, lists=0x0e, bad=200, plane_mode=0, plane=(0,1,0,0), slight=(-1,2,1), scol=(0,0,0), salpha=160,
          reach=8.0, vcol=(0,0,0), valpha=140, adj=(0,0,0), seed=1234, angle=30.0, cshort=0, ocol=(255,255,0)):
    b = bytes([opts, vw, vh]) + RGB(bg)
    b += V3(eye) + V3(target) + V3(up) + R(proj[0]) + R(proj[1]) + R(proj[2])
    for d, c in lights: b += V3(d) + RGB(c)
    g, y, m = ground
    b += R(g) + R(y) + m
    kind, x, yy, c, d, tr, m = caster
    b += bytes([kind]) + R(x) + R(yy) + bytes([c, d]) + tr + m
    if opts & 0x20:
        f, pos, nor, uvs, idx, tr, m = free
        b += bytes([f, len(pos)-1, len(idx)-1])
        for p in pos: b += V3(p)
        if f & 1:
            for n in nor: b += V3(n)
        if f & 2:
            for uv in uvs: b += R(uv[0]) + R(uv[1])
        for t in idx: b += bytes(t)
        b += tr + m
    b += bytes([ef])
    assert len(points) == ef % 4
    for p, c, att in points: b += V3(p) + RGB(c) + V3(att)
    b += R(fog[0]) + R(fog[1]) + RGB(fog[2]) + bytes([curve]) + R(exposure) + R(intensity)
    b += bytes([lm, lists, bad, plane_mode]) + b''.join(R(v) for v in plane) + V3(slight) + RGB(scol) + bytes([salpha])
    b += R(reach) + RGB(vcol) + bytes([valpha]) + bytes(adj) + struct.pack('<H', seed) + R(angle) + bytes([cshort]) + RGB(ocol)
    return b

# A translucent (or any) quad-ish free mesh: a tetrahedron, closed and consistently wound.
TET = [(0,0.5,0),(1,0.5,0),(0,1.5,0),(0,0.5,1)]
TET_IDX = [(0,2,1),(0,1,3),(0,3,2),(1,2,3)]
TET_NOR = [(-0.5,-0.5,-0.5),(1,0,0),(0,1,0),(0,0,1)]
TET_UV = [(0,0),(1,0),(0,1),(1,1)]
def free(f=3, mat=None, idx=TET_IDX, pos=TET, tr=None):
    return (f, pos, TET_NOR, TET_UV, idx, tr or TR((1.5,0,0.5),0,1.0), mat or MAT(0x41,(90,160,255),alpha=128))
PHONG, FASTPHONG = 2, 3
TEXTURED = 4
seeds = {
  'projected_directional': scene(lm=1),
  'projected_point_light': scene(lm=1|8, slight=(1,6,2)),
  'blob_shadow': scene(lm=3, salpha=200),
  'blob_point_light': scene(lm=3|8, slight=(0,5,0), caster=(1, 0.75, 0, 1, 0, TR(), MAT())),
  'volumes_icosphere': scene(lm=4, caster=(1, 0.75, 0, 1, 0, TR(), MAT()), reach=8.0),
  'volumes_box_point_light': scene(lm=4|8, slight=(1,5,1), caster=(7, 0.5, 0, 0, 0, TR(), MAT(0))),
  'volumes_garbage_adjacency': scene(lm=4, caster=(1, 0.75, 0, 1, 0, TR(), MAT()), adj=(0,3,0)),
  'volumes_short_table': scene(lm=4, caster=(7, 0.5, 0, 0, 0, TR(), MAT()), adj=(0,4,0)),
  'volumes_other_mesh_table': scene(lm=4, caster=(7, 0.5, 0, 0, 0, TR(), MAT()), adj=(0,6,0)),
  'volumes_missing_table': scene(lm=4, caster=(7, 0.5, 0, 0, 0, TR(), MAT()), lists=0x40|0xe),
  'volumes_q16_reach_24000': scene(lm=4, caster=(1, 0.75, 0, 1, 0, TR(), MAT()), reach=24000.0),
  'volumes_reach_nan': scene(lm=4, caster=(7, 0.5, 0, 0, 0, TR(), MAT()), reach='nan'),
  'volumes_bad_index_mesh': scene(opts=0x20, lm=4, lists=0xf, free=free(f=1, mat=MAT(1), idx=[(0,2,1),(0,1,5),(0,3,2),(1,2,3)])),
  'two_shadows': scene(lm=7, caster=(7, 0.5, 0, 0, 0, TR(), MAT())),
  'outline_silhouette': scene(lm=0x10, caster=(1, 0.75, 0, 1, 0, TR(), MAT())),
  'outline_crease': scene(lm=0x10|(1<<5), caster=(7, 0.5, 0, 0, 0, TR(), MAT()), angle=30.0),
  'outline_crease_short_table': scene(lm=0x10|(1<<5), caster=(7, 0.5, 0, 0, 0, TR(), MAT()), cshort=1),
  'outline_all_see_through': scene(lm=0x10|(2<<5)|0x80|4, caster=(2, 1.0, 0.375, 8, 6, TR(), MAT())),
  'outline_ground_and_garbage': scene(lm=0x10, lists=0x6, caster=(7, 0.5, 0, 0, 0, TR(), MAT()), adj=(5,3,0)),
  'outline_bad_index_mesh': scene(opts=0x20, lm=0x10, lists=0xf, free=free(f=1, mat=MAT(1), idx=[(0,2,1),(0,1,5),(0,3,2),(1,2,3)])),
  'translucent': scene(opts=0x20, lm=0, free=free()),
  'translucent_over_projected': scene(opts=0x20, lm=1, lists=0xf, free=free()),
  'translucent_phong_refused': scene(opts=0x20, lm=0, free=free(mat=MAT(0x40|PHONG, alpha=100))),
  'textured_torus_phong_ground': scene(ground=(4.0, 0.0, MAT(TEXTURED|1, (255,255,255), tex=2)),
        caster=(4, 1.0, 0.375, 10, 8, TR(), MAT(TEXTURED|1|(2<<3), (255,255,255), tex=6))),
  'textured_cube_keyed': scene(lm=1, caster=(3, 0.75, 0, 0, 0, TR(), MAT(TEXTURED|0x20|(0<<3), (255,255,255), tex=1, key=0xffff))),
  'textured_icosphere_affine': scene(lm=3, caster=(5, 0.75, 0, 1, 0, TR(), MAT(TEXTURED|1|(3<<3), (255,255,255), tex=4))),
  'textured_terrain_wide_texture': scene(caster=(6, 3.0, 0.5, 8, 0, TR((0,0.5,0)), MAT(TEXTURED|0|(1<<3), (255,255,255), tex=5))),
  'textured_free_mesh_hostile_uvs': scene(opts=0x20, free=free(f=3, mat=MAT(TEXTURED|1, tex=3)), lm=0),
  'phong_point_lights_fog_tone': scene(ef=0x10|4|8|2, points=(((1,2,1),(255,200,150),(1.0,0.25,0.125)),((-2,1,0),(100,100,255),(1.0,0,0))),
        curve=1, exposure=1.5, intensity=2.0, lm=1,
        caster=(1, 0.75, 0, 1, 0, TR(), MAT(PHONG, spec=0.5, shin=16))),
  'fast_phong_textured_fog': scene(ef=0x10|4, caster=(3, 0.75, 0, 0, 0, TR(), MAT(FASTPHONG|TEXTURED, tex=0))),
  'point_light_nan': scene(ef=0x10|1, points=((('nan',2,1),(255,255,255),(1.0,0,0)),), lm=1),
  'point_light_1e30_phong': scene(ef=0x10|1, points=(((1e30,1,1),(255,255,255),(1.0,0,0)),), caster=(1,0.75,0,1,0,TR(),MAT(PHONG))),
  'point_light_hostile_attenuation': scene(ef=0x10|1, points=(((0,1.5,0),(255,255,255),('inf',-1.0,1e30)),)),
  'fog_inverted': scene(ef=0x10|4, fog=(9.0, 4.0, (150,170,200))),
  'fog_nan_textured': scene(ef=0x10|4, fog=('nan', 9.0, (1,2,3)), caster=(3, 0.75, 0, 0, 0, TR(), MAT(TEXTURED, tex=1))),
  'tone_filmic_hostile': scene(ef=0x10|8, curve=2, exposure=255.0, intensity=16.0, caster=(1,0.75,0,1,0,TR(),MAT(PHONG))),
  'tone_reinhard_zero_exposure': scene(ef=0x10|8, curve=1, exposure=0.0),
  'receiver_off_plane': scene(lm=1, ground=(4.0, 0.5, MAT(1)), plane_mode=0),
  'receiver_bad_index': scene(lm=1, lists=0x0, bad=7),
  'caster_bad_index': scene(lm=4, lists=0x2, bad=250),
  'shadow_plane_nan': scene(lm=1, plane=('nan', 1, 0, 0)),
  'shadow_light_parallel': scene(lm=1, slight=(1, 0, 0)),
  'draw_what_fits_viewport': scene(opts=0x10|0x40|0x20, vw=17, vh=9, lm=4, lists=0xf,
        caster=(2, 1.0, 0.375, 11, 11, TR(), MAT()), free=free()),
  'ortho_dither_volumes_outline': scene(opts=1|2|(1<<2), proj=(6.0, 0.5, 30.0), lm=4|0x10,
        caster=(1, 0.75, 0, 1, 0, TR(), MAT())),
}
os.makedirs(out, exist_ok=True)
for name, data in seeds.items():
    assert len(data) <= 1024, (name, len(data))
    open(os.path.join(out, name), 'wb').write(data)
print(len(seeds), 'seeds, max', max(len(d) for d in seeds.values()), 'bytes')
