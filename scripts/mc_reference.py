#!/usr/bin/env python3
"""Independent reference decoder for the Minecraft worlds in ../shared/data/minecraft.

It shares no code with lua/minecraft/*.lua or lua/bind_data.cc (Python's zlib + struct only) and prints, per
world: chunk count, full-chunk count, DataVersion(s), statuses, non-air blocks in full chunks, and the block at a
few positions. tests/io/test_minecraft.cc hard-codes its output; rerun it if the data changes:

    python3 scripts/mc_reference.py [<minecraft data dir> [<world> x,y,z ...]]

With a world name and positions, only that world is decoded and the raw block at each position is printed
("minecraft:<name>" for palette formats, "<id>:<data>" before 1.13).
"""
import os, struct, sys, zlib, gzip, collections

def nbt(buf, pos=0):
    def rd(t, p):
        if t == 1: return struct.unpack_from('>b', buf, p)[0], p + 1
        if t == 2: return struct.unpack_from('>h', buf, p)[0], p + 2
        if t == 3: return struct.unpack_from('>i', buf, p)[0], p + 4
        if t == 4: return struct.unpack_from('>q', buf, p)[0], p + 8
        if t == 5: return struct.unpack_from('>f', buf, p)[0], p + 4
        if t == 6: return struct.unpack_from('>d', buf, p)[0], p + 8
        if t == 7:
            n = struct.unpack_from('>i', buf, p)[0]; p += 4
            return bytes(buf[p:p + n]), p + n
        if t == 8:
            n = struct.unpack_from('>H', buf, p)[0]; p += 2
            return buf[p:p + n].decode('utf-8', 'replace'), p + n
        if t == 9:
            et = buf[p]; n = struct.unpack_from('>i', buf, p + 1)[0]; p += 5
            out = []
            for _ in range(n):
                v, p = rd(et, p); out.append(v)
            return out, p
        if t == 10:
            out = {}
            while True:
                tt = buf[p]; p += 1
                if tt == 0: return out, p
                n = struct.unpack_from('>H', buf, p)[0]; p += 2
                name = buf[p:p + n].decode('utf-8', 'replace'); p += n
                out[name], p = rd(tt, p)
        if t == 11:
            n = struct.unpack_from('>i', buf, p)[0]; p += 4
            return list(struct.unpack_from('>%di' % n, buf, p)), p + 4 * n
        if t == 12:
            n = struct.unpack_from('>i', buf, p)[0]; p += 4
            return list(struct.unpack_from('>%dq' % n, buf, p)), p + 8 * n
        raise ValueError('bad tag %d' % t)
    t = buf[pos]
    n = struct.unpack_from('>H', buf, pos + 1)[0]
    v, p = rd(t, pos + 3 + n)
    return v

def chunks(path):
    data = open(path, 'rb').read()
    for i in range(1024):
        off = struct.unpack_from('>I', data, 4 * i)[0]
        sector, count = off >> 8, off & 255
        if sector == 0: continue
        length, comp = struct.unpack_from('>IB', data, sector * 4096)
        raw = data[sector * 4096 + 5: sector * 4096 + 4 + length]
        if comp == 2: raw = zlib.decompress(raw)
        elif comp == 1: raw = gzip.decompress(raw)
        yield i, nbt(raw)

FULL = {'full', 'minecraft:full', 'postprocessed', 'fullchunk'}

def unpack(longs, bits, spanning):
    out = []
    mask = (1 << bits) - 1
    if spanning:
        big = 0
        for j, l in enumerate(longs): big |= (l & 0xFFFFFFFFFFFFFFFF) << (64 * j)
        for k in range(4096): out.append((big >> (k * bits)) & mask)
    else:
        per = 64 // bits
        for k in range(4096):
            l = longs[k // per] & 0xFFFFFFFFFFFFFFFF
            out.append((l >> ((k % per) * bits)) & mask)
    return out

def section_blocks(sec, dv, root):
    """Yields (section_y, list of 4096 block keys); keys are names or 'id:data' before 1.13."""
    if 'Blocks' in sec:
        b = sec['Blocks']; d = sec.get('Data', bytes(2048)); a = sec.get('Add')
        keys = []
        for k in range(4096):
            i = b[k] & 255
            if a: i |= ((a[k >> 1] >> (4 * (k & 1))) & 15) << 8
            keys.append('%d:%d' % (i, (d[k >> 1] >> (4 * (k & 1))) & 15))
        return keys
    if 'block_states' in sec:
        pal = sec['block_states']['palette']; data = sec['block_states'].get('data')
    elif 'Palette' in sec:
        pal = sec['Palette']; data = sec.get('BlockStates')
    else:
        return None
    names = [p['Name'] for p in pal]
    if not data: return [names[0]] * 4096
    bits = max(4, (len(names) - 1).bit_length())
    idx = unpack(data, bits, dv < 2529)  # 20w17a (2529): entries stop spanning longs
    return [names[i] for i in idx]

AIR = {'0:%d' % i for i in range(16)} | {'minecraft:air', 'minecraft:cave_air', 'minecraft:void_air'}

def world(path, probes=()):
    chunks_n = full_n = nonair = 0
    dvs = collections.Counter(); statuses = collections.Counter(); blocks = {}
    for i, root in chunks(path):
        chunks_n += 1
        dv = root.get('DataVersion', 0)
        dvs[dv] += 1
        level = root.get('Level', root)
        status = level.get('Status', 'full') if 'Level' in root else root.get('Status')
        statuses[status] += 1
        if status not in FULL: continue
        full_n += 1
        cx, cz = level['xPos'], level['zPos']
        for sec in level.get('Sections', level.get('sections', [])):
            keys = section_blocks(sec, dv, root)
            if keys is None: continue
            sy = sec['Y']
            for k, key in enumerate(keys):
                if key not in AIR:
                    nonair += 1
            for (x, y, z) in probes:
                if x >> 4 == cx and z >> 4 == cz and y >> 4 == sy:
                    blocks[(x, y, z)] = keys[((y & 15) << 8) | ((z & 15) << 4) | (x & 15)]
    return dict(chunks=chunks_n, full=full_n, dv=dict(dvs), status=dict(statuses), nonair=nonair, blocks=blocks)

if __name__ == '__main__':
    base = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), '../../shared/data/minecraft')
    only = sys.argv[2] if len(sys.argv) > 2 else None
    for w in sorted(os.listdir(base)):
        if only and w != only: continue
        for f in sorted(os.listdir(os.path.join(base, w))):
            if f.endswith('.mca'):
                probes = [tuple(int(v) for v in p.split(',')) for p in sys.argv[3:]]
                r = world(os.path.join(base, w, f), probes)
                print(w, f, r)
