#!/usr/bin/env python3
"""make_seeds.py SRC_A SRC_B HALF_KTX - regenerate the committed seed corpora from real files.

SRC_A, SRC_B: two small baked table sets, e.g.
    swell-bake --size 16 --size-geo 8 --frames 4 --patterns 1 --out A
    swell-bake --size 16 --size-geo 8 --frames 4 --patterns 2 --spectrum tma --depth 20 \
               --wind 25 --budget tiny --out B
HALF_KTX: a small RGBA16F table written by ktx_write_memory (the bake writes RGBA8 only).
Names carry the expectation test_fuzz_replay.c enforces: ok_* accepted, bad_* refused.
Every hand-made bad_ case breaks exactly one rule of the format, so the loader must notice
that rule in particular (a seed that broke several could be refused for the wrong reason).
"""
import os, struct, sys, zlib

a, b, half = sys.argv[1:4]
here = os.path.dirname(os.path.abspath(__file__))

def out(target, name, data):
    d = os.path.join(here, 'corpus', target)
    os.makedirs(d, exist_ok=True)
    assert len(data) < 65536, name
    with open(os.path.join(d, name), 'wb') as f:
        f.write(data)

def rd(p):
    with open(p, 'rb') as f:
        return f.read()

# ---- KTX ----------------------------------------------------------------------------------
for d, tag in ((a, 'a'), (b, 'b')):
    for fn in sorted(os.listdir(d)):
        if fn.endswith('.ktx'):
            out('fuzz_ktx', 'ok_%s_%s' % (tag, fn), rd(os.path.join(d, fn)))
out('fuzz_ktx', 'ok_half_rgba16f.ktx', rd(half))

base = rd(os.path.join(a, 'disp_p0.ktx'))
fields = ['endianness', 'gltype', 'gltypesize', 'glformat', 'glinternalformat',
          'glbaseinternalformat', 'pixelwidth', 'pixelheight', 'pixeldepth',
          'arrayelements', 'faces', 'miplevels', 'kvbytes']
def set_u32(buf, off, v):
    return buf[:off] + struct.pack('<I', v & 0xffffffff) + buf[off + 4:]
# each header field in turn: a plausible-but-wrong value and an extreme one
for i, name in enumerate(fields):
    off = 12 + 4 * i
    old = struct.unpack_from('<I', base, off)[0]
    out('fuzz_ktx', 'bad_hdr_%s_plus1' % name, set_u32(base, off, old + 1))
    out('fuzz_ktx', 'bad_hdr_%s_max' % name, set_u32(base, off, 0xffffffff))
out('fuzz_ktx', 'bad_hdr_endianness_swapped', set_u32(base, 12, 0x01020304))
out('fuzz_ktx', 'bad_identifier', b'\xabKTX 20\xbb' + base[8:])
out('fuzz_ktx', 'bad_empty', b'')
out('fuzz_ktx', 'bad_identifier_only', base[:12])
out('fuzz_ktx', 'bad_header_only', base[:64])
out('fuzz_ktx', 'bad_truncated_last_byte', base[:-1])
out('fuzz_ktx', 'bad_trailing_byte', base + b'\0')
flip = bytearray(base); flip[-5] ^= 0x01
out('fuzz_ktx', 'bad_texel_flipped', bytes(flip))
kv = bytearray(base); i = kv.find(b'swell.kind\0'); kv[i + 9] ^= 0x20   # "swell.kinD": missing
out('fuzz_ktx', 'bad_kv_key_changed', bytes(kv))
ori = bytearray(base); ori[0x4C] ^= 0x20   # "KTXorienTation": KTX allows unknown keys
out('fuzz_ktx', 'ok_kv_unknown_key', bytes(ori))
crc = bytearray(base); i = crc.find(b'0x'); crc[i + 2] = ord('X')
out('fuzz_ktx', 'bad_crc_not_hex', bytes(crc))
ver = bytearray(base); i = ver.find(b'swell.version\0') + 14; ver[i] = ord('3')
out('fuzz_ktx', 'bad_version_3', bytes(ver))
# a key/value length pointing past the block
kvl = set_u32(base, 64, 0x7fffffff)
out('fuzz_ktx', 'bad_kv_length_huge', kvl)

# ---- manifest -----------------------------------------------------------------------------
ma = rd(os.path.join(a, 'manifest.swell'))
mb = rd(os.path.join(b, 'manifest.swell'))
out('fuzz_manifest', 'ok_a', ma)
out('fuzz_manifest', 'ok_b', mb)
lines = ma.split(b'\n')
def edit(key, value):
    res = []
    hit = False
    for l in lines:
        if l.startswith(key + b' = '):
            l = key + b' = ' + value; hit = True
        res.append(l)
    assert hit, key
    return b'\n'.join(res)
out('fuzz_manifest', 'bad_empty', b'')
out('fuzz_manifest', 'bad_no_final_newline', ma[:-1])
out('fuzz_manifest', 'bad_magic', b'swell-manifext' + ma[14:])
out('fuzz_manifest', 'bad_version_4', ma.replace(b'swell-manifest 5', b'swell-manifest 4', 1))
out('fuzz_manifest', 'bad_truncated_half', ma[:len(ma) // 2].rsplit(b'\n', 1)[0] + b'\n')
out('fuzz_manifest', 'bad_count_33', edit(b'set.count', b'33'))
out('fuzz_manifest', 'bad_count_negative', edit(b'set.count', b'-1'))
out('fuzz_manifest', 'bad_patterns_5', edit(b'set.patterns', b'5'))
out('fuzz_manifest', 'bad_wind_nan', edit(b'state.wind_speed_mps', b'nan'))
out('fuzz_manifest', 'bad_hs_inf', edit(b'set.hs_m', b'inf'))
out('fuzz_manifest', 'bad_spectrum_name', edit(b'state.spectrum', b'jonswapp'))
out('fuzz_manifest', 'bad_table_name_slash', edit(b'table.0.name', b'../etc'))
out('fuzz_manifest', 'bad_table_width_0', edit(b'table.0.width', b'0'))
out('fuzz_manifest', 'bad_table_width_huge', edit(b'table.0.width', b'4294967312'))
out('fuzz_manifest', 'bad_table_crc_short', edit(b'table.0.file_crc32', b'0x1'))
out('fuzz_manifest', 'bad_duplicate_key', ma + lines[3] + b'\n')
out('fuzz_manifest', 'bad_unknown_key', ma + b'set.colour = blue\n')
out('fuzz_manifest', 'bad_nul_byte', ma.replace(b'\n', b'\0\n', 5))
out('fuzz_manifest', 'ok_crlf', ma.replace(b'\n', b'\r\n'))
# fuzz_set: manifests whose accepted values go on into the CPU side of the renderer
out('fuzz_set', 'ok_a', ma)
out('fuzz_set', 'ok_b', mb)
out('fuzz_set', 'ok_a_unresolved_max', edit(b'set.mss_unresolved_x', b'1'))
out('fuzz_set', 'bad_frames_0', edit(b'set.frames', b'0'))
# values that parse but lie (src/tables/set_check.h); the target reseals them
out('fuzz_manifest', 'bad_frames_0', edit(b'set.frames', b'0'))
out('fuzz_manifest', 'bad_size_m_0', edit(b'pattern.0.size_m', b'0'))
out('fuzz_manifest', 'bad_size_m_huge', edit(b'pattern.0.size_m', b'3e38'))
out('fuzz_manifest', 'bad_mss_50', edit(b'set.mss_unresolved_x', b'50'))
out('fuzz_manifest', 'bad_hs_other', edit(b'set.hs_m', b'3'))
out('fuzz_manifest', 'bad_period_not_divisor', edit(b'pattern.0.period_s', b'1.7'))
out('fuzz_manifest', 'bad_table_layers', edit(b'table.0.layers', b'2'))
out('fuzz_manifest', 'bad_state_frames_0', edit(b'state.frames', b'0'))

# ---- preset -------------------------------------------------------------------------------
tables = os.path.join(here, '..', '..', 'tables')
for fn in sorted(os.listdir(tables)):
    if fn.endswith('.preset'):
        out('fuzz_preset', 'ok_' + fn, rd(os.path.join(tables, fn)))
out('fuzz_preset', 'ok_empty', b'')
out('fuzz_preset', 'ok_comments_only', b'# nothing\n\n#\n')
out('fuzz_preset', 'ok_every_field',
    b'wind_speed_mps = 12.5\nwind_dir_deg = -30\nfetch_km = 0.5\ndepth_m = 20\n'
    b'spectrum = tma\nspread = 8\nseed = 4294967295\npatterns = 2\nloop_period_s = 32\n'
    b'frames = 16\nsize_fs = 64\nsize_geo = 32\nchoppiness = 0.5\nwhitecap_model = wu88\n'
    b'foam_half_life_s = 0.25\nbudget_bytes = 8388608\n')
out('fuzz_preset', 'ok_no_final_newline', b'wind_speed_mps = 7')
for name, text in [
        ('nan', b'wind_speed_mps = nan\n'), ('inf', b'fetch_km = inf\n'),
        ('neg_inf', b'depth_m = -inf\n'), ('hex_float', b'spread = 0x1p3junk\n'),
        ('empty_value', b'wind_speed_mps =\n'), ('trailing_junk', b'wind_speed_mps = 5m/s\n'),
        ('float_overflow', b'wind_speed_mps = 1e39\n'), ('int_overflow', b'frames = 2147483648\n'),
        ('seed_overflow', b'seed = 4294967296\n'), ('seed_negative', b'seed = -1\n'),
        ('budget_overflow', b'budget_bytes = 18446744073709551616\n'),
        ('unknown_key', b'wind = 5\n'), ('duplicate', b'frames = 8\nframes = 8\n'),
        ('enum', b'spectrum = jonswapp\n'), ('no_equals', b'wind_speed_mps 5\n'),
        ('nul_byte', b'wind_speed_mps = 5\0\n'), ('key_only', b'=\n'),
        ('magic_line', b'swell-manifest 1\nwind_speed_mps = 5\n')]:
    out('fuzz_preset', 'bad_' + name, text)
