"""Deck generators of the exic benchmarks (input language of /work/shared/spec/input-language.md).

Every function returns the text of one deck. Units are those of the seed's examples: the solids
of sections 7.1-7.4 have lambda = 33333, mu = 5000 (E = 14348, nu = 0.4348) and density 0.1.
"""
import math
import random

LAMBDA, MU, RHO = 33333.0, 5000.0, 0.1


def _material(ma, young="young", nu="nu", rho="rho", quad=2, rigid=False):
    if rigid:
        return f"MATErial,{ma}\n  RIGId\n    DENSity {rho}\n\n"
    return (f"MATErial,{ma}\n  SOLId\n    ELAStic NEOHookean {young} {nu}\n    DENSity {rho}\n"
            f"    QUADrature {quad}\n\n")


def _lame_parameters(rho=RHO):
    return ("PARAmeters\n  lam = 33333\n  mu = 5000\n  young = mu*(3*lam+2*mu)/(lam+mu)\n"
            f"  nu = lam/(2*(lam+mu))\n  rho = {rho!r}\n\n")


def _block(nx, ny, mat, corners, node1=0, elmt1=0):
    s = f"BLOCk\n  CARTesian,{nx},{ny},{node1},{elmt1},{mat}\n"
    for k, (x, y) in enumerate(corners, start=1):
        s += f"    {k},{x!r},{y!r}\n"
    return s + "\n"


def _program(steps=None, tmax=None, tplot=100, dt="DT,CFL,0.9", hdf5=None, requests=()):
    s = "END\nBATCh\n  TRANsient,EXPLicit\n  " + dt + "\n"
    if tplot:
        s += f"  TPLOt,,{tplot}\n"
    if hdf5:
        s += f"  OUTPut,HDF5,{hdf5!r}\n"
    if tmax is not None:
        s += f"  LOOP,,100000000\n    TIME,,{tmax!r}\n    FORM,EXPLicit\n  NEXT\nEND\n"
    else:
        s += f"  LOOP,,{steps}\n    TIME\n    FORM,EXPLicit\n  NEXT\nEND\n"
    if tplot:
        s += "".join(f"  {r}\n" for r in requests) + "\n"
    return s + "STOP\n"


def cantilever(nx=120, ny=24, quad=2, steps=1500, tplot=100, hdf5=None, dt="DT,CFL,0.9"):
    """A 30 x 6 bar (nx x ny elements), clamped at x = 0, given a uniform transverse velocity 5:
    a bending and shear wave problem without contact (the throughput benchmark)."""
    return ("FEAP * * benchmark bar 30 x 6, clamped, transverse velocity\n0 0 0 2 2 4\n"
            + _lame_parameters() + _material(1, quad=quad)
            + _block(nx, ny, 1, [(0.0, 0.0), (30.0, 0.0), (30.0, 6.0), (0.0, 6.0)])
            + "EBOUndary\n  1,0,1,1\n\n"
            + "INITial,VELOcity\n  MATErial,1,0,5\n\n"
            + _program(steps=steps, tplot=tplot, hdf5=hdf5, dt=dt,
                       requests=["disp,,2,30,6", "velo,,2,30,6"]))


def distorted_bar(nx=60, ny=12, amp=0.0, seed=1, steps=4000, dt="DT,CFL,0.9", tplot=20):
    """The clamped bar of `cantilever` with every interior node moved at random by up to
    amp x the element size in x and in y (explicit COORdinates and ELEMents)."""
    rnd = random.Random(seed)
    hx, hy = 30.0/nx, 6.0/ny
    lines = []
    for j in range(ny + 1):
        for i in range(nx + 1):
            x, y = i*hx, j*hy
            if 0 < i < nx and 0 < j < ny:
                x += amp*hx*(2.0*rnd.random() - 1.0)
                y += amp*hy*(2.0*rnd.random() - 1.0)
            lines.append(f"  {1 + j*(nx + 1) + i},0,{x!r},{y!r}")
    elems = []
    for j in range(ny):
        for i in range(nx):
            n1 = 1 + j*(nx + 1) + i
            elems.append(f"  {1 + j*nx + i},0,1,{n1},{n1 + 1},{n1 + nx + 2},{n1 + nx + 1}")
    return (f"FEAP * * bar 30 x 6, interior nodes moved by up to {amp} h\n0 0 0 2 2 4\n"
            + _lame_parameters() + _material(1)
            + "COORdinates\n" + "\n".join(lines) + "\n\n"
            + "ELEMents\n" + "\n".join(elems) + "\n\n"
            + "EBOUndary\n  1,0,1,1\n\n"
            + "INITial,VELOcity\n  MATErial,1,0,5\n\n"
            + _program(steps=steps, tplot=tplot, dt=dt, requests=["disp,,2,30,6"]))


def bar_on_bar(k=1, tmax=0.1, pair="SYMMetric", tplot=1, dt="DT,CFL,0.9", rigid=False):
    """The seed's example 7.2 (7.1 with `rigid`): a horizontal bar 30 x 4 (30k x 6k elements)
    moving at 50 strikes a free vertical bar 4 x 30 (6k x 30k elements) at rest; they touch at
    t = 0, the vertical bar centred on the horizontal bar's axis."""
    req = ["disp,,1,0,0", "velo,,1,0,0", "acce,,1,0,0", "cont,1,1", "cont,1,4", "cont,1,5"]
    return ("FEAP * * seed example 7.2, bar striking a compliant bar\n0 0 0 2 2 4\n"
            + _lame_parameters() + _material(1) + _material(2, rigid=rigid)
            + "REGIon,1\n" + _block(30*k, 6*k, 1, [(-30.0, -2.0), (0.0, -2.0), (0.0, 2.0), (-30.0, 2.0)])
            + "REGIon,2\n" + _block(6*k, 30*k, 2, [(0.0, -15.0), (4.0, -15.0), (4.0, 15.0), (0.0, 15.0)])
            + "INITial,VELOcity\n  REGIon,1,50,0\n\n"
            + f"CONTact\n  SURFace,1\n    REGIon,1\n  SURFace,2\n    REGIon,2\n  PAIR,1,{pair},1,2\n"
            + "END CONTact\n\n"
            + _program(tmax=tmax, tplot=tplot, dt=dt, requests=req))


def striking_strips(nx=100, ny=16, v0=1.0, tmax=None, tplot=0):
    """A long contact line: two free strips of height H = ny/2 (elements 0.5 x 0.5) meet at
    y = 0 with velocities +-v0, the lower one nx x ny elements, the upper (nx+1) x ny, so the
    meshes do not match; the upper bottom nodes are slaves of the lower top surface (NTOS).
    In 1-D the strips stay in contact for 2 H/c; the run stops at 0.9 of that (default), so
    the whole contact line (about nx+2 constraints) is active in every step."""
    h = 0.5
    w = nx*h
    H = ny*h
    if tmax is None:
        tmax = 0.9*2.0*H/math.sqrt((LAMBDA + 2.0*MU)/RHO)
    return (f"FEAP * * two strips meeting along {w} ({nx} elements along the contact line)\n0 0 0 2 2 4\n"
            + _lame_parameters() + _material(1) + _material(2)
            + "REGIon,1\n" + _block(nx, ny, 1, [(0.0, -H), (w, -H), (w, 0.0), (0.0, 0.0)])
            + "REGIon,2\n" + _block(nx + 1, ny, 2, [(0.0, 0.0), (w, 0.0), (w, H), (0.0, H)])
            + f"INITial,VELOcity\n  REGIon,1,0,{v0!r}\n  REGIon,2,0,{-v0!r}\n\n"
            + "CONTact\n  SURFace,1\n    REGIon,1\n  SURFace,2\n    REGIon,2\n  PAIR,1,NTOS,2,1\n"
            + "END CONTact\n\n"
            + _program(tmax=tmax, tplot=tplot, requests=["cont,1,4"]))


# the 1-D bar against a rigid wall of doc/contact-verification.md (test_contact's bar_deck)
WALL_E, WALL_RHO, WALL_V0, WALL_L, WALL_H = 1.0e4, 0.1, 0.1, 30.0, 4.0


def bar_on_wall(nx, method="LAGRange", tplot=1, tmax=None):
    """Bar L x H = 30 x 4 (nx x nx/5 elements), E = 1e4, nu = 0, rho = 0.1, moving at v0 = 0.1
    onto a fixed rigid wall it touches at t = 0; runs to 3 L/c (default). `method` is the pair's
    method record (LAGRange or PENAlty,k)."""
    ny = max(1, nx//5)
    c = math.sqrt(WALL_E/WALL_RHO)
    if tmax is None:
        tmax = 3.0*WALL_L/c
    L, H = WALL_L, WALL_H
    return ("FEAP * * bar on a rigid wall\n0 0 0 2 2 4\n"
            + _material(1, young=repr(WALL_E), nu="0", rho=repr(WALL_RHO))
            + _material(2, rho=repr(WALL_RHO), rigid=True)
            + "REGIon,1\n" + _block(nx, ny, 1, [(0.0, 0.0), (L, 0.0), (L, H), (0.0, H)])
            + "REGIon,2\n" + _block(2, 4, 2, [(L, -H), (L + H, -H), (L + H, 2*H), (L, 2*H)])
            + f"INITial,VELOcity\n  REGIon,1,{WALL_V0!r},0\n\n"
            + "CONTact\n  SURFace,1\n    REGIon,1\n  SURFace,2\n    REGIon,2\n  PAIR,1,NTOS,1,2\n"
            + f"    {method}\nEND CONTact\n\n"
            + _program(tmax=tmax, tplot=tplot, requests=["cont,1,1", "cont,1,4", "cont,1,5", "mome,1,1"]))


def deforming_block(n, quad=2, steps=300, tplot=100, a=0.5, b=0.5):
    """A free square block of n x n unit elements in which every element deforms at every step:
    the initial velocity varies linearly along each row from +a to -a in x (a uniform
    compression rate) and varies as b sin(2 pi (j + 1/2)/16) from row j to row j in y (a shear wave
    16 elements long), so no element moves rigidly. With a, b = 0.5 against a wave speed of 658
    the strains stay below about 1e-3 and the run is stable for any number of steps.
    The throughput benchmark of element rates at 10^3..10^6 elements (section rate_sizes)."""
    init = []
    for j in range(n + 1):
        first = 1 + j*(n + 1)
        vy = b*math.sin(2.0*math.pi*(j + 0.5)/16.0)
        init.append(f"  {first},1,{a!r},{vy!r}")
        init.append(f"  {first + n},0,{-a!r},{vy!r}")
    return (f"FEAP * * block {n} x {n}, every element deforming\n0 0 0 2 2 4\n"
            + _lame_parameters() + _material(1, quad=quad)
            + _block(n, n, 1, [(0.0, 0.0), (float(n), 0.0), (float(n), float(n)), (0.0, float(n))])
            + "INITial,VELOcity\n" + "\n".join(init) + "\n\n"
            + _program(steps=steps, tplot=tplot, requests=["disp,,1,0,0", "velo,,1,0,0"]))


def body_grid(nside, ne=4, gap=0.05, v=5.0, steps=300, tplot=100, auto=True, far=False):
    """nside x nside free square bodies (REGIons) of ne x ne elements 0.25 wide, gap apart, with
    AUTOmatic contact: the columns move at +v and -v in x alternately, so columns 1-2, 3-4, ...
    close their gap after gap / (2 v) and collide, while the gaps between columns 2-3, 4-5, ...
    open and bodies above each other slide side by side without touching. `far`: only two
    bodies, the second 100 widths away (a pair that never comes near). Without `auto` the
    same bodies run without a CONTact block."""
    h = 0.25*ne
    pitch = h + gap
    s = (f"FEAP * * {nside} x {nside} bodies of {ne} x {ne} elements, AUTOmatic contact\n0 0 0 2 2 4\n"
         + _lame_parameters() + _material(1))
    places = [(ix, iy) for iy in range(nside) for ix in range(nside)]
    if far:
        places = [(0, 0), (100, 0)]
    init = []
    for r, (ix, iy) in enumerate(places, start=1):
        x0, y0 = ix*pitch, iy*pitch
        s += f"REGIon,{r}\n" + _block(ne, ne, 1, [(x0, y0), (x0 + h, y0), (x0 + h, y0 + h), (x0, y0 + h)])
        init.append(f"  REGIon,{r},{(v if ix % 2 == 0 else -v)!r},0")
    s += "INITial,VELOcity\n" + "\n".join(init) + "\n\n"
    if auto:
        s += "CONTact\n  AUTOmatic\nEND CONTact\n\n"
    return s + _program(steps=steps, tplot=tplot, requests=["disp,,1,0,0"])


# The three 1-D impacts of the work-precision study (doc/performance.md section 4, exact values
# in doc/contact-verification.md "Two bars"): E = 1e4, nu = 0, bars L x H = 30 x 4, v0 = 0.1.
IMPACT_E, IMPACT_V0, IMPACT_L, IMPACT_H = 1.0e4, 0.1, 30.0, 4.0
IMPACT_PROBLEMS = {"wall": (0.1, None), "equal": (0.1, 0.1), "unequal": (0.5, 1.0)}


def impact_exact(problem):
    """Exact 1-D answers of `impact_bars(problem)`: contact force, duration, momentum of bar 1
    after separation, initial energy (doc/contact-verification.md, "Two bars")."""
    rho1, rho2 = IMPACT_PROBLEMS[problem]
    E, v0, L, H = IMPACT_E, IMPACT_V0, IMPACT_L, IMPACT_H
    c1, z1 = math.sqrt(E/rho1), math.sqrt(E*rho1)
    m1 = rho1*L*H
    if rho2 is None:                                  # rigid wall: Z2 -> infinity
        force, p1, e0 = z1*v0*H, -m1*v0, 0.5*m1*v0**2
    else:
        z2 = math.sqrt(E*rho2)
        force = 2.0*v0*z1*z2/(z1 + z2)*H
        p1 = m1*v0*(z1 - 3.0*z2)/(z1 + z2)
        e0 = 0.5*(m1 + rho2*L*H)*v0**2
    # bar 1 is the faster one (rho1 <= rho2): the bars part when its release wave returns
    return {"force": force, "duration": 2.0*L/c1, "p1": p1, "energy": e0, "m1": m1}


def impact_bars(problem, nx, method="LAGRange", tmax=None, tplot=1):
    """Bar 1 (nx x nx/5 elements, density rho1) at +v0 strikes a fixed rigid wall ("wall") or
    bar 2 (the same mesh, density rho2) moving at -v0 ("equal": 0.1 and 0.1, "unequal": 0.5 and
    1.0); the bodies touch at t = 0. The contact surfaces are the struck ends only (FACEts), the
    same for every `method` (the pair's method record: LAGRange, LAGRange,ENERgy, PENAlty,k).
    Runs to 1.5 x the exact contact duration."""
    rho1, rho2 = IMPACT_PROBLEMS[problem]
    ny = max(1, nx//5)
    L, H, v0 = IMPACT_L, IMPACT_H, IMPACT_V0
    if tmax is None:
        tmax = 1.5*impact_exact(problem)["duration"]
    nb = (nx + 1)*(ny + 1)                            # nodes of bar 1: node(i, j) = 1 + (nx+1) j + i
    end1 = "".join(f"      {j + 1},0,{(nx + 1)*(j + 1)},{(nx + 1)*(j + 2)}\n" for j in range(ny))
    s = (f"FEAP * * {problem} impact, {nx} x {ny}\n0 0 0 2 2 4\n"
         + _material(1, young=repr(IMPACT_E), nu="0", rho=repr(rho1))
         + "REGIon,1\n" + _block(nx, ny, 1, [(0.0, 0.0), (L, 0.0), (L, H), (0.0, H)]))
    if rho2 is None:
        s += (_material(2, rho="0.1", rigid=True)
              + "REGIon,2\n" + _block(2, 4, 2, [(L, -H), (L + H, -H), (L + H, 2*H), (L, 2*H)])
              + f"INITial,VELOcity\n  REGIon,1,{v0!r},0\n\n")
        surf2 = "    REGIon,2\n"
    else:
        s += (_material(2, young=repr(IMPACT_E), nu="0", rho=repr(rho2))
              + "REGIon,2\n" + _block(nx, ny, 2, [(L, 0.0), (2*L, 0.0), (2*L, H), (L, H)], node1=nb + 1, elmt1=nx*ny + 1)
              + f"INITial,VELOcity\n  REGIon,1,{v0!r},0\n  REGIon,2,{-v0!r},0\n\n")
        surf2 = "    FACEts\n" + "".join(f"      {j + 1},0,{nb + 1 + (nx + 1)*(j + 1)},{nb + 1 + (nx + 1)*j}\n"
                                      for j in range(ny))
    s += ("CONTact\n  SURFace,1\n    FACEts\n" + end1 + "\n  SURFace,2\n" + surf2
          + f"\n  PAIR,1,NTOS,1,2\n    {method}\nEND CONTact\n\n")
    return s + _program(tmax=tmax, tplot=tplot, requests=["cont,1,1", "cont,1,4", "cont,1,5", "mome,1,1"])
