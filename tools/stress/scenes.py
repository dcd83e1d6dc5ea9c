"""Random scenes for the stress suite: decks of 2-6 bodies in the deck language of exic.

    scene = make_scene(seed, index)      # a Scene: .deck (text), .info (dict), .bodies

Every scene is a pure function of (seed, index), so a failing scene is reproduced by its pair.
Bodies are blocks (CARTesian, rotated: corner impacts), disks (a centre square and four
CARTesian sectors joined by TIE, as in the seed's example 7.5), rings (one POLAr block about a
SHIFt centre, its seam closed by TIE) and rigid blocks (fixed walls or moving). Materials are
neo-Hookean with E in 300..3000, nu in 0..0.45 and densities 10^-1.5..10^1.5 (ratios up to
1e3), QUADrature 2 or 1 (+ HOURglass); element sizes differ by up to 10x between bodies. The
bodies start apart (a gap of 0.1-1 of the smaller element size) and meet under AUTOmatic
contact at speeds of 0.02-0.3 of the slower wave speed of the two, head on, oblique, grazing
(1-10 degrees) or corner first. The run stops at a time that covers the approach and the
first contact, bounded to about MAX_STEPS steps at the estimated stable step.

Metals (METALS, from the campaigns after seed 20261210 on): each deformable body is, with
probability 1/2, elastic-plastic (`PLAStic MISEs Y0` with Y0 = E 10^(-3..-2), and
`PLAStic HARDening H 0` with H = E (0..0.05)), and a plastic or elastic body of QUADrature 2 is,
with probability 1/2, MIXEd (mean dilatation). These choices come from a random stream of
their own, so the geometry, speeds and elastic constants of a scene are those of the
generator without metals (`stress.py --elastic-only` reproduces the earlier campaigns).

Erosion (EROSION, off by default): the record(s) written into every deformable body's material,
e.g. "EROSion INVErted" (`stress.py --erosion 'EROSion INVErted'`, doc/erosion.md); the scene is
otherwise the same deck.
"""
import math
import random
from dataclasses import dataclass, field

import numpy as np

#: bound on the estimated number of steps of a scene
MAX_STEPS = 6000
#: bound on the elements of a scene
MAX_ELEMENTS = 1500
PATTERNS = ("impact", "grazing", "corner", "cluster", "walls")
#: plastic and mean-dilatation bodies in the scenes (module header); False: the generator of the
#: campaigns up to seed 20261210
METALS = True


@dataclass
class Material:
    young: float
    nu: float
    rho: float
    quad: int = 2
    rigid: bool = False
    y0: float = 0.0              # PLAStic MISEs (0: elastic)
    hiso: float = 0.0            # PLAStic HARDening (linear isotropic)
    mixed: bool = False          # MIXEd (QUADrature 2 only)

    @property
    def wave_speed(self):
        """Dilatational wave speed sqrt((lambda + 2 mu)/rho) (a rigid body: 0)."""
        if self.rigid:
            return 0.0
        lam = self.young * self.nu / ((1 + self.nu) * (1 - 2 * self.nu))
        mu = self.young / (2 * (1 + self.nu))
        return math.sqrt((lam + 2 * mu) / self.rho)


@dataclass
class Body:
    kind: str                    # block | disk | ring
    mat: Material
    h: float                     # element size
    center: tuple = (0.0, 0.0)
    angle: float = 0.0           # degrees (blocks)
    a: float = 1.0               # block half width / disk radius / ring outer radius
    b: float = 1.0               # block half height / ring inner radius
    velocity: tuple = (0.0, 0.0)
    fixed: bool = False          # rigid and still
    outline: np.ndarray = field(default=None, repr=False)

    def make_outline(self):
        """Boundary polygon (counter-clockwise) of the body as meshed, for placement checks."""
        cx, cy = self.center
        if self.kind == "block":
            c, s = math.cos(math.radians(self.angle)), math.sin(math.radians(self.angle))
            pts = [(-self.a, -self.b), (self.a, -self.b), (self.a, self.b), (-self.a, self.b)]
            self.outline = np.array([(cx + c * x - s * y, cy + s * x + c * y) for x, y in pts])
        else:
            t = np.linspace(0.0, 2 * math.pi, 72, endpoint=False)
            self.outline = np.column_stack([cx + self.a * np.cos(t), cy + self.a * np.sin(t)])
        return self.outline

    @property
    def radius(self):
        return math.hypot(self.a, self.b) if self.kind == "block" else self.a

    @property
    def elements(self):
        return sum(n1 * n2 for n1, n2 in self.divisions())

    def divisions(self):
        """Element counts of the blocks of this body."""
        if self.kind == "block":
            return [(_n(2 * self.a, self.h), _n(2 * self.b, self.h))]
        if self.kind == "disk":
            n = _even(_n(self.a, self.h))
            m = max(2, _n(0.6 * self.a, self.h))
            return [(n, n)] + [(m, n)] * 4
        nr = max(1, _n(self.a - self.b, self.h))
        ns = max(12, _n(math.pi * (self.a + self.b), self.h))
        return [(nr, ns)]

    def smallest_edge(self):
        """Rough smallest element edge (for the stable-step estimate)."""
        if self.kind == "block":
            n1, n2 = self.divisions()[0]
            return min(2 * self.a / n1, 2 * self.b / n2)
        if self.kind == "disk":
            n, _ = self.divisions()[0]
            m = self.divisions()[1][0]
            return min(0.8 * self.a / n, 0.6 * self.a / m)
        nr, ns = self.divisions()[0]
        return min((self.a - self.b) / nr, 2 * math.pi * self.b / ns)


def _n(length, h):
    return int(min(40, max(2, round(length / h))))


def _even(n):
    return n + (n % 2)


@dataclass
class Scene:
    seed: int
    index: int
    pattern: str
    bodies: list
    t_end: float
    dt_est: float
    deck: str = ""
    info: dict = field(default_factory=dict)


# --- geometry ----------------------------------------------------------------------------

def _inside(p, poly):
    """Even-odd point in polygon."""
    x, y = p
    inside = False
    n = len(poly)
    for i in range(n):
        x1, y1 = poly[i]
        x2, y2 = poly[(i + 1) % n]
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside


def _seg_dist(p, a, b):
    d = b - a
    t = max(0.0, min(1.0, float(np.dot(p - a, d) / max(np.dot(d, d), 1e-300))))
    return float(np.linalg.norm(p - (a + t * d)))


def _cross(a, b, c, d):
    """Segments ab and cd cross."""
    def orient(p, q, r):
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
    return (orient(a, b, c) * orient(a, b, d) < 0) and (orient(c, d, a) * orient(c, d, b) < 0)


def distance(p1, p2):
    """Distance between two polygons, 0 when they touch or overlap."""
    for p in p1:
        if _inside(p, p2):
            return 0.0
    for p in p2:
        if _inside(p, p1):
            return 0.0
    n1, n2 = len(p1), len(p2)
    for i in range(n1):
        for j in range(n2):
            if _cross(p1[i], p1[(i + 1) % n1], p2[j], p2[(j + 1) % n2]):
                return 0.0
    d = min(_seg_dist(p, p2[j], p2[(j + 1) % n2]) for p in p1 for j in range(n2))
    return min(d, min(_seg_dist(p, p1[i], p1[(i + 1) % n1]) for p in p2 for i in range(n1)))


# --- random parts ------------------------------------------------------------------------

def _material(rng, rigid=False):
    m = Material(young=10 ** rng.uniform(2.5, 3.5), nu=rng.uniform(0.0, 0.45),
                 rho=10 ** rng.uniform(-1.5, 1.5), quad=rng.choice((1, 2)), rigid=rigid)
    return m


def _metals(rng, bodies):
    """Make some deformable bodies elastic-plastic and some of QUADrature 2 MIXEd (module
    header); three draws per body, rigid or not, so that each body's draws do not depend on the
    others'."""
    for b in bodies:
        plastic, y_exp, h_frac, mixed = (rng.random() < 0.5, rng.uniform(-3.0, -2.0),
                                         rng.uniform(0.0, 0.05), rng.random() < 0.5)
        m = b.mat
        if m.rigid:
            continue
        if plastic:
            m.y0 = m.young * 10 ** y_exp
            m.hiso = m.young * h_frac
        m.mixed = mixed and m.quad == 2


def _body(rng, h0, kind=None, size=None, rigid=False):
    kind = kind or rng.choice(("block", "block", "disk", "ring"))
    h = h0 * 10 ** rng.uniform(-0.5, 0.5)
    size = size or rng.uniform(1.0, 3.0)
    if kind == "block":
        b = Body("block", _material(rng, rigid), h, a=size * rng.uniform(0.5, 1.5),
                 b=size * rng.uniform(0.3, 1.0))
    elif kind == "disk":
        b = Body("disk", _material(rng, rigid), h, a=size)
    else:
        b = Body("ring", _material(rng, rigid), h, a=size, b=size * rng.uniform(0.45, 0.8))
    # keep the element count of one body reasonable
    while b.elements > MAX_ELEMENTS // 2 and b.h < 10 * size:
        b.h *= 1.25
    return b


def _place_against(rng, target, body, direction, gap):
    """Put `body` on the ray from target's centre in `direction` (radians), `gap` from it."""
    u = np.array([math.cos(direction), math.sin(direction)])
    tc = np.array(target.center)
    s = target.radius + body.radius + gap
    lo, hi = 0.0, s
    # bisection on the centre distance for the wanted gap
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        body.center = tuple(tc + mid * u)
        body.make_outline()
        d = distance(body.outline, target.outline)
        if d > gap:
            hi = mid
        else:
            lo = mid
    body.center = tuple(tc + hi * u)
    body.make_outline()


def _fits(bodies, body, gap):
    return all(distance(body.outline, o.outline) >= gap for o in bodies)


def _aim(rng, body, point, speed, off_deg):
    """Velocity of `body` toward `point`, turned by off_deg."""
    d = np.array(point) - np.array(body.center)
    ang = math.atan2(d[1], d[0]) + math.radians(off_deg)
    body.velocity = (speed * math.cos(ang), speed * math.sin(ang))


def _speed(rng, a, b):
    cs = [m.wave_speed for m in (a.mat, b.mat) if not m.rigid]
    c = min(cs) if cs else 1.0
    return rng.uniform(0.02, 0.3) * c


# --- patterns ----------------------------------------------------------------------------

def _impact(rng, h0):
    target = _body(rng, h0, size=rng.uniform(1.5, 3.0), rigid=rng.random() < 0.25)
    target.fixed = target.mat.rigid
    target.angle = rng.uniform(0, 90) if target.kind == "block" else 0.0
    target.make_outline()
    bodies = [target]
    for _ in range(rng.randint(1, 3)):
        p = _body(rng, h0, rigid=not target.mat.rigid and rng.random() < 0.1)
        if p.kind == "block":
            p.angle = rng.uniform(0, 90)
        gap = rng.uniform(0.1, 1.0) * min(p.h, target.h)
        for _try in range(20):
            _place_against(rng, target, p, rng.uniform(0, 2 * math.pi), gap)
            if _fits(bodies, p, gap):
                break
        else:
            continue
        speed = _speed(rng, p, target) * (0.33 if p.mat.rigid else 1.0)
        _aim(rng, p, target.center, speed, rng.choice((0.0, rng.uniform(-30, 30))))
        bodies.append(p)
    return bodies


def _grazing(rng, h0):
    length = rng.uniform(6, 14)
    target = Body("block", _material(rng, rigid=rng.random() < 0.4), h0 * 10 ** rng.uniform(-0.5, 0.5),
                  a=length / 2, b=rng.uniform(0.5, 1.5))
    target.fixed = target.mat.rigid
    while target.elements > MAX_ELEMENTS // 2:
        target.h *= 1.25
    target.make_outline()
    p = _body(rng, h0, kind=rng.choice(("block", "disk", "ring")), size=rng.uniform(0.6, 1.5))
    gap = rng.uniform(0.05, 0.5) * min(p.h, target.h)
    p.center = (-length / 2 + p.radius, 0.0)
    p.make_outline()
    lo, hi = 0.0, 10.0
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        p.center = (-length / 2 + p.radius, target.b + mid)
        p.make_outline()
        if distance(p.outline, target.outline) > gap:
            hi = mid
        else:
            lo = mid
    p.center = (-length / 2 + p.radius, target.b + hi)
    p.make_outline()
    alpha = math.radians(rng.uniform(1.0, 10.0))
    speed = _speed(rng, p, target)
    p.velocity = (speed * math.cos(alpha), -speed * math.sin(alpha))
    return [target, p]


def _corner(rng, h0):
    target = Body("block", _material(rng, rigid=rng.random() < 0.3), h0 * 10 ** rng.uniform(-0.5, 0.5),
                  a=rng.uniform(3, 6), b=rng.uniform(0.8, 2.0))
    target.fixed = target.mat.rigid
    while target.elements > MAX_ELEMENTS // 2:
        target.h *= 1.25
    target.make_outline()
    side = rng.uniform(0.6, 1.5)
    p = Body("block", _material(rng), h0 * 10 ** rng.uniform(-0.5, 0.5), a=side, b=side * rng.uniform(0.6, 1.0),
             angle=rng.uniform(20, 70))
    while p.elements > MAX_ELEMENTS // 2:
        p.h *= 1.25
    gap = rng.uniform(0.1, 1.0) * min(p.h, target.h)
    _place_against(rng, target, p, math.pi / 2 + math.radians(rng.uniform(-10, 10)), gap)
    speed = _speed(rng, p, target)
    tilt = math.radians(rng.uniform(-20, 20))
    p.velocity = (speed * math.sin(tilt), -speed * math.cos(tilt))
    return [target, p]


def _cluster(rng, h0):
    n = rng.randint(3, 6)
    bodies = []
    box = 6.0 + 1.5 * n
    tries = 0
    while len(bodies) < n and tries < 400:
        tries += 1
        b = _body(rng, h0, size=rng.uniform(0.7, 1.8), rigid=rng.random() < 0.15)
        b.fixed = b.mat.rigid          # rigid bodies of a cluster stay still
        if b.kind == "block":
            b.angle = rng.uniform(0, 90)
        b.center = (rng.uniform(-box / 2, box / 2), rng.uniform(-box / 2, box / 2))
        b.make_outline()
        gap = 0.1 * b.h
        if _fits(bodies, b, max(gap, 0.2)):
            bodies.append(b)
    if len(bodies) < 2:
        return _impact(rng, h0)
    centre = np.mean([b.center for b in bodies], axis=0)
    for b in bodies:
        if b.fixed:
            continue
        other = min((o for o in bodies if o is not b), key=lambda o: np.hypot(*np.subtract(o.center, b.center)))
        speed = _speed(rng, b, other) * (0.33 if b.mat.rigid else 1.0)
        _aim(rng, b, centre, speed, rng.uniform(-20, 20))
    return bodies


def _walls(rng, h0):
    width = rng.uniform(4, 8)
    height = rng.uniform(4, 8)
    walls = []
    for x in (-width / 2 - 0.5, width / 2 + 0.5):
        w = Body("block", _material(rng, rigid=True), h0, center=(x, 0.0), a=0.5, b=height / 2)
        w.fixed = True
        w.make_outline()
        walls.append(w)
    p = _body(rng, h0, kind=rng.choice(("block", "disk", "ring")), size=rng.uniform(0.6, 1.2))
    p.center = (rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5))
    p.make_outline()
    if not _fits(walls, p, 0.05 * p.h):
        p.center = (0.0, 0.0)
        p.make_outline()
    ang = math.radians(rng.uniform(-40, 40)) + (math.pi if rng.random() < 0.5 else 0.0)
    speed = rng.uniform(0.02, 0.3) * p.mat.wave_speed
    p.velocity = (speed * math.cos(ang), speed * math.sin(ang))
    return walls + [p]


# --- the deck ----------------------------------------------------------------------------

def _fmt(x):
    return repr(float(x))


def _block_text(region, mat, nr, ns, corners, mids=None):
    s = f"BLOCk\n  CARTesian,{nr},{ns},0,0,{mat}\n"
    for k, (x, y) in enumerate(corners, start=1):
        s += f"    {k},{_fmt(x)},{_fmt(y)}\n"
    for k, (x, y) in (mids or {}).items():
        s += f"    {k},{_fmt(x)},{_fmt(y)}\n"
    return s + "\n"


#: the hourglass record of the one-point (QUADrature 1) bodies: the assumed-strain control
#: (doc/hourglass.md); campaigns up to seed 20261124 wrote "HOURglass 0.1" (stress.py --hourglass)
HOURGLASS = "HOURglass,PHYSical"
#: the EROSion records of every deformable body, one per line (empty: none, the default)
EROSION = ""


def _body_text(k, b):
    """MATErial and mesh of body k (region k, material k)."""
    m = b.mat
    if m.rigid:
        mat = f"MATErial,{k}\n  RIGId\n    DENSity {_fmt(m.rho)}\n\n"
    else:
        mat = (f"MATErial,{k}\n  SOLId\n    ELAStic NEOHookean {_fmt(m.young)} {_fmt(m.nu)}\n"
               f"    DENSity {_fmt(m.rho)}\n    QUADrature {m.quad}\n")
        if m.y0 > 0.0:
            mat += f"    PLAStic MISEs {_fmt(m.y0)}\n    PLAStic HARDening {_fmt(m.hiso)} 0\n"
        if m.mixed:
            mat += "    MIXEd\n"
        if m.quad == 1:
            mat += f"    {HOURGLASS}\n"
        for rec in EROSION.split(";"):
            if rec.strip():
                mat += f"    {rec.strip()}\n"
        mat += "\n"
    cx, cy = b.center
    mesh = f"REGIon,{k}\n"
    if b.kind == "block":
        (nr, ns), = b.divisions()
        corners = [(p[0], p[1]) for p in b.make_outline()]
        mesh += _block_text(k, k, nr, ns, corners)
    elif b.kind == "disk":
        (n, _), (m_, _) = b.divisions()[0], b.divisions()[1]
        a = 0.4 * b.a
        r = b.a
        sq = [(cx - a, cy - a), (cx + a, cy - a), (cx + a, cy + a), (cx - a, cy + a)]
        mesh += _block_text(k, k, n, n, sq)
        for j in range(4):
            t0 = math.radians(-45 + 90 * j)
            t1 = t0 + math.pi / 2
            tm = 0.5 * (t0 + t1)
            c0, c1 = sq[(j + 1) % 4], sq[(j + 2) % 4]
            corners = [c0, (cx + r * math.cos(t0), cy + r * math.sin(t0)),
                       (cx + r * math.cos(t1), cy + r * math.sin(t1)), c1]
            mesh += _block_text(k, k, m_, n, corners, {6: (cx + r * math.cos(tm), cy + r * math.sin(tm))})
    else:
        (nr, ns), = b.divisions()
        mesh += f"SHIFt,{_fmt(cx)},{_fmt(cy)}\nBLOCk\n  POLAr,{nr},{ns},0,0,{k}\n"
        mesh += f"    1,{_fmt(b.b)},0\n    2,{_fmt(b.a)},0\n    3,{_fmt(b.a)},360\n    4,{_fmt(b.b)},360\n\n"
    return mat, mesh


def scene_deck(sc):
    mats, meshes, inits, ties = [], [], [], []
    for k, b in enumerate(sc.bodies, start=1):
        mat, mesh = _body_text(k, b)
        mats.append(mat)
        meshes.append(mesh)
        if b.velocity != (0.0, 0.0):
            inits.append(f"  REGIon,{k},{_fmt(b.velocity[0])},{_fmt(b.velocity[1])}\n")
        if b.kind in ("disk", "ring"):
            ties.append(f"TIE,REGIon,{k},{k}\n")
    fixed = []
    for k, b in enumerate(sc.bodies, start=1):
        if b.fixed:
            fixed.append(k)
    title = f"FEAP * * stress scene seed {sc.seed} index {sc.index}: {sc.pattern}, " + \
        ", ".join(f"{b.kind}{'(rigid)' if b.mat.rigid else ''}" for b in sc.bodies)
    deck = title + "\n0 0 0 2 2 4\n" + "".join(mats) + "".join(meshes)
    deck += "SHIFt,0,0\n" if any(b.kind == "ring" for b in sc.bodies) else ""
    if inits:
        deck += "INITial,VELOcity\n" + "".join(inits) + "\n"
    deck += "CONTact\n  AUTOmatic\nEND CONTact\n\nEND\n" + "".join(ties)
    deck += ("BATCh\n  DT,CFL,0.9\n  TPLOt,,1\n"
             f"  OUTPut,HDF5,{_fmt(sc.t_end / 8)}\n  LOOP,,100000000\n"
             f"    TIME,,{_fmt(sc.t_end)}\n    FORM,EXPLicit\n  NEXT\nEND\n"
             "  cont,1,1\n  cont,1,5\n\nSTOP\n")
    return deck


def make_scene(seed, index):
    """Scene number `index` of the campaign `seed`."""
    rng = random.Random(seed * 1000003 + index)
    pattern = PATTERNS[rng.randrange(len(PATTERNS))]
    h0 = rng.uniform(0.15, 0.4)
    bodies = {"impact": _impact, "grazing": _grazing, "corner": _corner, "cluster": _cluster,
              "walls": _walls}[pattern](rng, h0)
    for b in bodies:
        b.make_outline()
    if METALS:
        _metals(random.Random(seed * 1000003 + index + 7919 * 10**9), bodies)
    # time: approach over the largest gap at the body's speed, then contact (a few wave transits)
    cmax = max(b.mat.wave_speed for b in bodies)
    cmin = min((b.mat.wave_speed for b in bodies if not b.mat.rigid), default=cmax)
    hmin = min(b.smallest_edge() for b in bodies if not b.mat.rigid) if any(
        not b.mat.rigid for b in bodies) else 1.0
    dt_est = 0.9 * 0.7 * hmin / cmax
    speeds = [math.hypot(*b.velocity) for b in bodies if b.velocity != (0.0, 0.0)]
    vmax = max(speeds) if speeds else cmin * 0.1
    size = max(2 * b.radius for b in bodies)
    t_approach = 2.0 * size / max(vmax, 1e-12) * 0.5
    t_contact = 3.0 * size / cmin
    t_end = min(t_approach + t_contact, MAX_STEPS * dt_est)
    sc = Scene(seed, index, pattern, bodies, t_end, dt_est)
    sc.deck = scene_deck(sc)
    sc.info = {
        "seed": seed, "index": index, "pattern": pattern, "t_end": t_end,
        "bodies": [{"kind": b.kind, "rigid": b.mat.rigid, "fixed": b.fixed, "quad": b.mat.quad,
                    "plastic": b.mat.y0 > 0.0, "mixed": b.mat.mixed,
                    "rho": b.mat.rho, "young": b.mat.young, "nu": b.mat.nu, "h": b.h,
                    "elements": b.elements,
                    "speed_over_c": (math.hypot(*b.velocity) / cmin) if cmin > 0 else 0.0}
                   for b in bodies],
        "elements": sum(b.elements for b in bodies),
        "density_ratio": max(b.mat.rho for b in bodies) / min(b.mat.rho for b in bodies),
        "size_ratio": max(b.h for b in bodies) / min(b.h for b in bodies),
    }
    return sc
