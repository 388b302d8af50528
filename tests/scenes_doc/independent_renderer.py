# An independent renderer's front end, written from docs/SCENES.md alone (not from gbump's
# source): every scene's top records (each stimulus column, their order, tri_start and the
# groups), computed here and compared with `gbump.Config.from_scene(S).vectors("scene:S")`.
# tests/scenes_doc.rs runs it on every built-in scene and on mixed.toml under several
# configurations; a line `S OK N records` per scene, `S DIFFERS ...` where a column differs.
# Usage: python3 independent_renderer.py NAME|FILE.toml ...
import math, sys, tomllib, collections
import numpy as np

TAU = 2 * math.pi
PI = math.pi

def add(a, b): return (a[0] + b[0], a[1] + b[1], a[2] + b[2])
def sub(a, b): return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
def mul(a, s): return (a[0] * s, a[1] * s, a[2] * s)
def neg(a): return (-a[0], -a[1], -a[2])
def dot(a, b): return (a[0] * b[0]) + (a[1] * b[1]) + (a[2] * b[2])
def cross(a, b): return (a[1] * b[2] - b[1] * a[2], a[2] * b[0] - b[2] * a[0], a[0] * b[1] - b[0] * a[1])
def length(a): return math.sqrt(dot(a, a))
def recip(x):
    try:
        return 1.0 / x
    except ZeroDivisionError:
        return math.inf
def normalize(a): return mul(a, recip(length(a)))
def try_normalize(a):
    r = recip(length(a))
    if math.isfinite(r) and r > 0.0:
        return mul(a, r)
    return None
X, Y, Z, ZERO = (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (0.0, 0.0, 0.0)

def frame(n, pu, pv):
    nn = try_normalize(n)
    if nn is None:
        nn = try_normalize(cross(pu, pv)) or Z
    n = nn
    t = try_normalize(sub(pu, mul(n, dot(n, pu)))) or ZERO
    if t == ZERO:
        t = try_normalize(cross(pv, n))
        assert t is not None
    b = cross(n, t)
    if dot(pv, pv) > 0.0 and dot(b, pv) < 0.0:
        b = neg(b)
    return n, t, b

def grid(segs, uvs, f, verts, tris):
    su, sv = segs
    base = len(verts)
    for j in range(sv + 1):
        for i in range(su + 1):
            u, v = i / su, j / sv
            p, pu, pv = f(u, v)
            n, t, b = frame(cross(pu, pv), pu, pv)
            verts.append(dict(p=p, n=n, t=t, b=b, uv=(u * uvs[0], v * uvs[1])))
    row = su + 1
    for j in range(sv):
        for i in range(su):
            a = base + j * row + i
            tris.append((a, a + 1, a + row + 1))
            tris.append((a, a + row + 1, a + row))

def teapot_patches():
    vs, idx = [], []
    for line in open('/work/main/src/scene/teapot.dat'):
        w = line.split()
        if not w: continue
        if w[0] == 'v': vs.append(tuple(float(x) for x in w[1:4]))
        elif w[0] == 'p': idx.append([int(x) for x in w[1:]])
    return [[sub(vs[k], (0.0, 0.0, 1.575)) for k in p] for p in idx]

def bern(t):
    s = 1.0 - t
    return ([s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t],
            [-3.0 * s * s, 3.0 * s * s - 6.0 * t * s, 6.0 * t * s - 3.0 * t * t, 3.0 * t * t])

def teapot_eval(patch, u, v):
    bu, du = bern(u); bv, dv = bern(v)
    p = pu = pv = ZERO
    for i in range(4):
        for j in range(4):
            c = patch[i * 4 + j]
            p = add(p, mul(mul(c, bv[i]), bu[j]))
            pu = add(pu, mul(mul(c, bv[i]), du[j]))
            pv = add(pv, mul(mul(c, dv[i]), bu[j]))
    if dot(pu, pu) < 1e-16 or dot(pv, pv) < 1e-16:
        u2, v2 = min(max(u, 1e-4), 1 - 1e-4), min(max(v, 1e-4), 1 - 1e-4)
        if (u2, v2) != (u, v):
            _, a, b = teapot_eval(patch, u2, v2)
            return p, a, b
    return p, pu, pv

def mat_rz(a):
    s, c = math.sin(a), math.cos(a)
    return [(c, s, 0.0), (-s, c, 0.0), Z]  # columns
def mat_ry(a):
    s, c = math.sin(a), math.cos(a)
    return [(c, 0.0, -s), Y, (s, 0.0, c)]
def mat_rx(a):
    s, c = math.sin(a), math.cos(a)
    return [X, (0.0, c, s), (0.0, -s, c)]
def mv(m, v):
    r = mul(m[0], v[0]); r = add(r, mul(m[1], v[1])); return add(r, mul(m[2], v[2]))
def mm(a, b): return [mv(a, b[0]), mv(a, b[1]), mv(a, b[2])]

def tessellate(o):
    verts, tris = [], []
    s = o['segments']; uvs = o['uv_scale']; sh = o['shape']; k = sh['kind']
    if k == 'plane':
        w, h = sh['size']
        grid(s, uvs, lambda u, v: (((u - 0.5) * w, (v - 0.5) * h, 0.0), mul(X, w), mul(Y, h)), verts, tris)
    elif k == 'sphere':
        r = sh['radius']
        def f(u, v):
            th, ph = u * TAU, (v - 0.5) * PI
            p = mul((math.cos(ph) * math.cos(th), math.cos(ph) * math.sin(th), math.sin(ph)), r)
            pu = mul(mul((-math.cos(ph) * math.sin(th), math.cos(ph) * math.cos(th), 0.0), r), TAU)
            pv = mul(mul((-math.sin(ph) * math.cos(th), -math.sin(ph) * math.sin(th), math.cos(ph)), r), PI)
            n = normalize(p)
            return p, (cross(pv, n) if length(pu) < 1e-9 else pu), pv
        grid(s, uvs, f, verts, tris)
    elif k == 'torus':
        big, small = sh['major'], sh['minor']
        def f(u, v):
            a, b = u * TAU, v * TAU
            ring = big + small * math.cos(b)
            p = (ring * math.cos(a), ring * math.sin(a), small * math.sin(b))
            pu = mul((-ring * math.sin(a), ring * math.cos(a), 0.0), TAU)
            pv = mul((-small * math.sin(b) * math.cos(a), -small * math.sin(b) * math.sin(a), small * math.cos(b)), TAU)
            return p, pu, pv
        grid(s, uvs, f, verts, tris)
    elif k == 'cylinder':
        r, h, sides = sh['radius'], sh['height'], sh.get('sides', 0)
        segs = [sides, s[1]] if sides > 0 else s
        def f(u, v):
            th = u * TAU
            return (r * math.cos(th), r * math.sin(th), (v - 0.5) * h), mul(mul((-math.sin(th), math.cos(th), 0.0), r), TAU), mul(Z, h)
        grid(segs, uvs, f, verts, tris)
        if sides > 0:
            old, rows = verts, s[1]
            verts, tris = [], []
            row = sides + 1
            for i in range(sides):
                v00, v10 = old[i], old[i + 1]
                n = normalize(mul(add(v00['n'], v10['n']), 0.5))
                t = normalize(sub(v10['p'], v00['p']))
                base = len(verts)
                for j in range(rows + 1):
                    for kk in (i, i + 1):
                        src = old[j * row + kk]
                        verts.append(dict(p=src['p'], n=n, t=t, b=cross(n, t), uv=(0.0 if kk == i else 1.0, src['uv'][1])))
                for j in range(rows):
                    a = base + 2 * j
                    tris.append((a, a + 1, a + 3)); tris.append((a, a + 3, a + 2))
    elif k == 'teapot':
        for patch in teapot_patches():
            grid(s, uvs, lambda u, v: teapot_eval(patch, u, v), verts, tris)
    r = [math.radians(x) for x in o['rotate_deg']]
    rot = mm(mm(mat_rz(r[2]), mat_ry(r[1])), mat_rx(r[0]))
    tr = tuple(o['translate'])
    for v in verts:
        v['p'] = add(mv(rot, mul(v['p'], o['scale'])), tr)
        for key in 'ntb':
            v[key] = mv(rot, v[key])
    return verts, tris

def hash01(a, b):
    M = 0xFFFFFFFF
    x = ((a * 0x9E3779B1) & M) ^ ((b * 0x85EBCA77) & M) ^ 0x27D4EB2F
    x ^= x >> 15
    x = (x * 0x2C1B3C6D) & M
    x ^= x >> 12
    return (x & 0xFFFF) / 65536.0

def fract(x): return x - math.trunc(x)

def height_field(src, size):
    k = src['kind']
    def fn(u, v):
        if k == 'flat': return 0.5
        if k == 'bricks':
            rows, cols, m = float(src['rows']), float(src['cols']), src['mortar']
            row = math.floor(v * rows)
            shift = 0.5 if int(row) % 2 == 1 else 0.0
            col = math.floor(u * cols + shift)
            fu = fract(u * cols + shift); fv = fract(v * rows)
            d = min(min(fu, 1.0 - fu) * (1.0 / cols) * rows, min(fv, 1.0 - fv))
            if d < m: return 0.0
            bevel = min((d - m) / m, 1.0)
            return 0.7 + 0.3 * hash01(int(row), int(col) % int(cols)) * bevel
        if k == 'sphere_caps':
            c, r = float(src['cells']), src['radius']
            x, y = fract(u * c) - 0.5, fract(v * c) - 0.5
            d2 = x * x + y * y
            return math.sqrt(r * r - d2) / r if d2 < r * r else 0.0
        if k == 'mexican_hat':
            c, s = float(src['cells']), src['sigma']
            x, y = fract(u * c) - 0.5, fract(v * c) - 0.5
            q = (x * x + y * y) / (s * s)
            return 0.5 + 0.5 * (1.0 - q) * math.exp(-q / 2.0)
        raise ValueError(k)
    return [[fn((x + 0.5) / size, (y + 0.5) / size) for x in range(size)] for y in range(size)]

def normal_map(b):
    size = b.get('size', 128); strength = b.get('strength', 4.0); method = b.get('method', 'eq2')
    hf = height_field(b['source'], size)
    at = lambda x, y: hf[y % size][x % size]
    data = []
    for y in range(size):
        for x in range(size):
            if method == 'eq2':
                fu = (at(x + 1, y) - at(x - 1, y)) / 2.0; fv = (at(x, y + 1) - at(x, y - 1)) / 2.0
            else:
                fu = at(x + 1, y) - at(x, y); fv = at(x, y + 1) - at(x, y)
            data.append(normalize((-strength * fu, -strength * fv, 1.0)))
    clamp_u = False
    sides = b.get('cylinder_sides', 0)
    if sides > 0:
        span = TAU / sides; clamp_u = True
        for y in range(size):
            for x in range(size):
                th = ((x + 0.5) / size - 0.5) * span
                n = data[y * size + x]; s, c = math.sin(th), math.cos(th)
                data[y * size + x] = normalize((c * n[0] + s * n[2], n[1], -s * n[0] + c * n[2]))
    return size, data, clamp_u

NB = 8; NS = 1.0; LHW = 16; CMAX = 255
def encode(n):
    half = 1 << (NB - 1)
    return tuple(min(max(math.floor((c / NS) * 2.0 ** (NB - 1) + 0.5), -half), half - 1) + half for c in n)

def sample(codes, w, h, clamp_u, uv, filt):
    addr = lambda i: min(max(i, 0), w - 1) if clamp_u else i % w
    if filt == 'nearest':
        return codes[(math.floor(uv[1] * h) % h) * w + addr(math.floor(uv[0] * w))]
    x = uv[0] * w - 0.5; y = uv[1] * h - 0.5
    x0, y0 = math.floor(x), math.floor(y)
    fx, fy = x - x0, y - y0
    acc = [0.0, 0.0, 0.0]
    for (xx, yy, wt) in ((x0, y0, (1.0 - fx) * (1.0 - fy)), (x0 + 1, y0, fx * (1.0 - fy)), (x0, y0 + 1, (1.0 - fx) * fy), (x0 + 1, y0 + 1, fx * fy)):
        c = codes[(yy % h) * w + addr(xx)]
        for i in range(3): acc[i] += wt * c[i]
    return tuple(math.floor(a + 0.5) for a in acc)

def rnd(x):  # Rust f64::round: half away from zero
    return math.floor(x + 0.5) if x >= 0 else -math.floor(-x + 0.5)
def colour_codes(c, mx=None):
    mx = CMAX if mx is None else mx
    out = []
    for x in c:
        x = min(max(x, 0.0), 1.0) * mx
        # exact half-away-from-zero of the f64 product
        f = math.floor(x); out.append(int(f + 1 if x - f >= 0.5 else f))
    return tuple(out)

def light_dir(l, p, fallback):
    if l['kind'] == 'directional': return normalize(tuple(l['direction']))
    return try_normalize(sub(tuple(l['position']), p)) or fallback
def spot_factor(l, p):
    if l['kind'] != 'spot': return 1.0
    axis = normalize(tuple(l['direction']))
    to_p = try_normalize(sub(p, tuple(l['position'])))
    if to_p is None: return 1.0
    c = dot(axis, to_p)
    if c < math.cos(math.radians(l.get('cutoff_deg', 30.0))): return 0.0
    return max(c, 0.0) ** l.get('exponent', 0.0)
def half_vector(l, v): return try_normalize(add(l, v)) or l
def gouraud(scene, p, n):
    c = tuple(scene.get('ambient', [0.0] * 3))
    for l in scene['lights']:
        if l.get('bump', True): continue
        d = light_dir(l, p, n)
        c = add(c, mul(tuple(l['colour']), max(dot(n, d), 0.0) * spot_factor(l, p) * l.get('k', 1.0)))
    return c

def q_lh(x):
    width = LHW; frac = LHW - 2
    r = math.floor((x * NS) * 2.0 ** frac + 0.5)
    return min(max(r, -(1 << (width - 1))), (1 << (width - 1)) - 1)
def q_k(x, kf):
    r = math.floor(x * 2.0 ** kf + 0.5)
    return min(max(r, 0), (1 << (kf + 1)) - 1)

def run(name):
    import gbump
    import os
    path = name if name.endswith('.toml') else os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'scenes', f'{name}.toml')
    text = open(path, 'rb').read()
    sc = tomllib.loads(text.decode())
    cfg = gbump.Config.from_scene(name)
    cd = cfg.as_dict(); kf = cd['k_frac_bits']; nlights = cd['lights']
    global NB, NS, LHW, CMAX
    NB = cd['normal_bits']; LHW = cd['lh_bits']; CMAX = (1 << cd['colour_bits']) - 1
    NS = (2.0 ** (NB - 1)) / (2.0 ** (NB - 1) - 1.0) if cd['normal_range'] == 'symmetric' else 1.0
    W, H = sc.get('size', [256, 256])
    cam = sc['camera']
    eye, target = tuple(cam['eye']), tuple(cam['target'])
    fwd = normalize(sub(target, eye))
    right = normalize(cross(fwd, tuple(cam.get('up', [0.0, 0.0, 1.0]))))
    up = cross(right, fwd); to_viewer = neg(fwd)
    half_h = cam['height'] / 2.0; half_w = half_h * W / H
    def project(p):
        d = sub(p, target)
        x = (dot(d, right) / half_w + 1.0) * 0.5 * W
        y = (1.0 - dot(d, up) / half_h) * 0.5 * H
        return (x, y), -dot(sub(p, eye), to_viewer)
    lights = sc.get('lights', [])
    blights = [l for l in lights if l.get('bump', True)]
    objs = []
    for o in sc['objects']:
        o.setdefault('segments', [32, 16]); o.setdefault('translate', [0.0] * 3); o.setdefault('rotate_deg', [0.0] * 3)
        o.setdefault('scale', 1.0); o.setdefault('uv_scale', [1.0, 1.0])
        verts, tris = tessellate(o)
        size, nm, clamp_u = normal_map(o['bump'])
        codes = [encode(n) for n in nm]
        states = []
        for t in tris:
            v = [verts[i] for i in t]
            centroid = mul(add(add(v[0]['p'], v[1]['p']), v[2]['p']), 1.0)  # placeholder, replaced below
            centroid = tuple(c / 3.0 for c in add(add(v[0]['p'], v[1]['p']), v[2]['p']))
            n, tg, bn = frame(add(add(v[0]['n'], v[1]['n']), v[2]['n']), add(add(v[0]['t'], v[1]['t']), v[2]['t']), add(add(v[0]['b'], v[1]['b']), v[2]['b']))
            tb = lambda w: (dot(w, tg), dot(w, bn), dot(w, n))
            st = []
            for l in blights:
                ld = light_dir(l, centroid, n); hd = half_vector(ld, to_viewer)
                L, Hh = tb(ld), tb(hd)
                k = l.get('k', 1.0) * spot_factor(l, centroid)
                st.append(([q_lh(c) for c in L], [q_lh(c) for c in Hh], [int(rnd(c * CMAX)) for c in l['colour']], q_k(k, kf)))
            while len(st) < nlights:
                st.append(([0] * 3, [0] * 3, [0] * 3, 0))
            states.append(st)
        objs.append((o, verts, tris, size, codes, clamp_u, states))
    # rasterise
    hits = [None] * (W * H); depth = [math.inf] * (W * H)
    edge = lambda a, b, p: (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
    for oi, (o, verts, tris, *_r) in enumerate(objs):
        proj = [project(v['p']) for v in verts]
        for ti, t in enumerate(tris):
            a, b, c = (proj[i] for i in t)
            area = edge(a[0], b[0], c[0])
            if abs(area) < 1e-12 or not math.isfinite(area): continue
            x0 = int(max(math.floor(min(a[0][0], b[0][0], c[0][0])), 0.0))
            x1 = min(max(math.ceil(max(a[0][0], b[0][0], c[0][0])), 0), W)
            y0 = int(max(math.floor(min(a[0][1], b[0][1], c[0][1])), 0.0))
            y1 = min(max(math.ceil(max(a[0][1], b[0][1], c[0][1])), 0), H)
            for y in range(y0, y1):
                for x in range(x0, x1):
                    q = (x + 0.5, y + 0.5)
                    wa = edge(b[0], c[0], q) / area; wb = edge(c[0], a[0], q) / area; wc = edge(a[0], b[0], q) / area
                    if wa < 0.0 or wb < 0.0 or wc < 0.0: continue
                    z = wa * a[1] + wb * b[1] + wc * c[1]
                    i = y * W + x
                    if z >= 0.0 and z < depth[i]:
                        depth[i] = z; hits[i] = (oi, ti, (wa, wb, wc))
    frags = []
    for i, hh in enumerate(hits):
        if hh is None: continue
        oi, ti, w = hh
        o, verts, tris, size, codes, clamp_u, states = objs[oi]
        v = [verts[k] for k in tris[ti]]
        mix = lambda key: add(add(mul(v[0][key], w[0]), mul(v[1][key], w[1])), mul(v[2][key], w[2]))
        uv = (v[0]['uv'][0] * w[0] + v[1]['uv'][0] * w[1] + v[2]['uv'][0] * w[2], v[0]['uv'][1] * w[0] + v[1]['uv'][1] * w[1] + v[2]['uv'][1] * w[2])
        cs = [gouraud(sc, vv['p'], vv['n']) for vv in v]
        c_src = add(add(mul(cs[0], w[0]), mul(cs[1], w[1])), mul(cs[2], w[2]))
        tex = o.get('texture', {'kind': 'constant', 'colour': [1.0, 1.0, 1.0]})
        if tex['kind'] == 'constant': tc = tex['colour']
        else:
            cc = float(tex['cells'])
            kk = (math.floor(uv[0] * cc) + math.floor(uv[1] * cc)) % 2
            tc = tex['a'] if kk == 0 else tex['b']
        bump = sample(codes, size, size, clamp_u, uv, o['bump'].get('filter', 'bilinear'))
        st = states[ti]
        interp = cd.get('interpolate', 'none'); ik = cd.get('interpolate_k', False)
        if interp != 'none' or ik:
            st = [list(x) for x in st]
            for li, l in enumerate(blights):
                vv = []
                for vx in v:
                    n_, t_, b_ = frame(vx['n'], vx['t'], vx['b'])
                    tb_ = lambda w_: (dot(w_, t_), dot(w_, b_), dot(w_, n_))
                    ld = light_dir(l, vx['p'], n_)
                    vv.append((tb_(ld), tb_(half_vector(ld, to_viewer)), l.get('k', 1.0) * spot_factor(l, vx['p'])))
                m3 = lambda k_: add(add(mul(vv[0][k_], w[0]), mul(vv[1][k_], w[1])), mul(vv[2][k_], w[2]))
                if interp == 'h': st[li][1] = [q_lh(c) for c in m3(1)]
                if interp == 'hl': st[li][0] = [q_lh(c) for c in m3(0)]; st[li][1] = [q_lh(c) for c in m3(1)]
                if ik: st[li][3] = q_k(vv[0][2] * w[0] + vv[1][2] * w[1] + vv[2][2] * w[2], kf)
        frags.append((oi, ti, i % W, i // W, bump, colour_codes(c_src), colour_codes(tc), o.get('diffuse', True), o.get('specular', True), st))
    frags.sort(key=lambda f: (f[0], f[1]))
    groups = collections.OrderedDict()
    prev = {}
    for f in frags:
        o = objs[f[0]][0]
        key = o.get('shininess', 0)
        start = prev.get(key) != (f[0], f[1]); prev[key] = (f[0], f[1])
        groups.setdefault(key, []).append((f, start))
    got = cfg.vectors(f'scene:{name}')
    ok = True
    if len(got) != len(groups):
        print(name, 'sets differ: gbump wrote', len(got), 'here', len(groups)); ok = False
    stimulus = [c['name'] for c in cfg.columns('top') if c['role'] == 'stimulus']
    for (key, recs), gs in zip(sorted(groups.items()), got):
        u = cfg.unpack('top', gs['records'])
        assert gs['shininess'] == key, (gs['shininess'], key)
        n = len(recs)
        if n != len(u['in_bump']):
            print(name, 'count differs', n, len(u['in_bump'])); ok = False; continue
        mine = {
            'in_bump': np.array([r[0][4] for r in recs]), 'in_c_src': np.array([r[0][5] for r in recs]),
            'in_tex': np.array([r[0][6] for r in recs]), 'in_diffuse_en': np.array([[int(r[0][7])] for r in recs]),
            'in_specular_en': np.array([[int(r[0][8])] for r in recs]), 'tri_start': np.array([[int(r[1])] for r in recs]),
            'tri_l': np.array([sum((s[0] for s in r[0][9]), []) for r in recs]),
            'tri_h': np.array([sum((s[1] for s in r[0][9]), []) for r in recs]),
            'tri_lc': np.array([sum((s[2] for s in r[0][9]), []) for r in recs]),
            'tri_k': np.array([[s[3] for s in r[0][9]] for r in recs]),
        }
        # Each record's pixel, as the set's `pixels` gives it.
        px = np.array([r[0][2:4] for r in recs])
        if not np.array_equal(gs['pixels'], px):
            ok = False
            print(name, key, 'pixels differ')
        compared = set()
        for col, arr in mine.items():
            if col.startswith('tri_') and col != 'tri_start' and col not in u: col = 'in_' + col[4:]
            if col not in u: continue
            compared.add(col)
            bad = np.nonzero((u[col] != arr).any(axis=1))[0]
            if len(bad):
                ok = False
                j = bad[0]
                print(name, key, col, f'{len(bad)}/{n} differ; first at record {j} pixel {recs[j][0][2:4]}: gbump {u[col][j].tolist()} mine {arr[j].tolist()}')
        # Every stimulus column of the records is one rebuilt here (a column this front end
        # does not make, a frame's or EMBM's, is not a pass).
        missing = [c for c in stimulus if c not in compared]
        if missing:
            ok = False
            print(name, key, 'stimulus columns not rebuilt here:', missing)
    print(name, 'OK' if ok else 'DIFFERS', sum(len(r) for r in groups.values()), 'records')

if __name__ == '__main__':
    for n in sys.argv[1:]:
        run(n)
