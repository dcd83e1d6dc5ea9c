"""doc/stability.md and its figures from the JSON results of the stress suite (doc/stability/)."""
import collections
import os
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GROWTH_WARN, GROWTH_BAD, DEPTH_LIMIT = 0.01, 0.05, 1e-3


def _git():
    try:
        return subprocess.run(["git", "-C", ROOT, "log", "-1", "--format=%h %cs"], capture_output=True,
                              text=True, timeout=10).stdout.strip()
    except Exception:  # noqa: BLE001
        return "?"


def pct(a, b):
    return f"{100.0 * a / b:.1f} %" if b else "-"


def fmt(v, spec=".3g"):
    if v is None:
        return "-"
    try:
        if v != v:
            return "nan"
    except TypeError:
        return str(v)
    return format(v, spec)


def write(load, figdir, doc, log):
    """doc/stability.md: what the stress suite measures and its latest result of each family,
    each with the command that repeats it and the commit it ran on (the history of the
    campaigns is in the commit log). Sections 1a-1c and 1f keep the measurements that
    doc/decisions.md and doc/hourglass.md cite as the reasons of their rules."""
    os.makedirs(figdir, exist_ok=True)
    sc, fz, cfl, lg, lg6 = (load(n) for n in ("scenes", "fuzz", "cfl", "long", "long_1e6"))
    kl = load("kills")
    inv = load("inversions_20261123")
    inv24 = load("inversions_20261124")
    hg24 = load("hourglass_20261124")
    sc25 = load("scenes_20261125")
    out = []
    w = out.append
    w("# Numerical stability: the stress suite\n")
    w("Written by `make stress` (`tools/stress/stress.py`; results in `doc/stability/*.json`, "
      f"figures `doc/stability/*.png`; this text at commit {_git()}). Each section gives the command "
      "that repeats its campaign and the commit it ran on. Re-run one family with "
      "`tools/stress/stress.py --only scenes|fuzz|cfl|long|kills`; `make stress STRESS_ARGS=--long` runs "
      "the long cases for 10^6 steps. The sections written by hand are in `doc/stability/by_hand.md`.\n")
    w("What is measured, and the limits used to call something a failure:\n")
    w("- **Energy growth** of a run: the largest over its rows of (E - E_in) / (|E(0)| + |W_ext| + |W_pm|), "
      "E = kinetic + strain (with hourglass) + plastic work from `<stem>.ene`, E_in = E(0) + W_ext + W_pm the energy "
      "put in by the initial state, the external forces and prescribed motion (the measure of exic's energy guard). Above 1 % (and 5 %) a finished run is a failure "
      "unless exic warned (a `warning: ... energy` line in `<stem>.out`). Impact losses make it negative.")
    w("- **Penetration**, measured by the harness itself: at every field output of `<stem>.h5` every "
      "node of every body is tested against the deformed boundary polygon of every other body "
      "(even-odd rule, so holes of rings count); its depth is the distance to that boundary, relative "
      "to the length of the nearest boundary edge. Deeper than 1e-3 of an edge in a finished run is a "
      "failure unless exic warned (a `warning: ... penetrat` line: exic's own geometric check, "
      "src/exic/contact/inside.f90, at the same output times). `<stem>.out`'s largest penetration is "
      "that geometric depth, shown beside it.")
    w("- **Stops** (exit 1) must give a physical reason that names a node, element or pair; the reason "
      "is read from the message (inversion, non-finite, energy, time step, ...). A crash is a signal "
      "or an exit code other than 0-2; a hang is a run killed at the timeout.\n")
    if sc:
        _scenes(sc, w, figdir)
    if inv:
        _inversions(inv, w)
    if inv24 and hg24:
        _hourglass(inv24, hg24, w, sc25)
    if sc25:
        _barrier_rerun(w)
    _self_contact(w)
    _by_hand(w)
    if fz:
        _fuzz(fz, w)
    if cfl:
        _cfl(cfl, w, figdir)
    for data in (lg, lg6):
        if data:
            _long(data, w, figdir)
    if kl:
        _kills(kl, w)
    with open(doc, "w") as f:
        f.write("\n".join(out) + "\n")
    _saved_readme()
    log(f"report: {os.path.relpath(doc, ROOT)}")


# --- kills -------------------------------------------------------------------------------

def _kills(data, w):
    res = data["kills"]
    n = len(res)
    w(f"## 5. Runs killed at random moments ({n} kills, seed {data['seed']})\n")
    w(f"`tools/stress/stress.py --only kills --kills {n} --seed {data['seed']}` ({data['seconds']:.0f} s "
      "on two cores; `tools/stress/kills.py`). The seed's example 7.2 with fields every 0.002 "
      f"({data['reference_times']} output times) and a restart file every 0.05 (SAVE,,0.05) runs once "
      f"to the end ({data['reference_seconds']:.2f} s from the creation of its .out to its end), then is "
      "killed by SIGKILL, SIGTERM and SIGINT in turn at a random point of its progress: when its .his "
      "reaches a fraction of the reference's .his length drawn uniformly, plus a random delay uniform "
      "over the reference's wall time of one output interval (runs that end before the signal are "
      "counted apart). Since the field output is written in batches (doc/fields.md), a SIGKILL loses the "
      "output times not yet flushed, at most 1 s or 4 MB of them. Checked after each kill: the .h5 opens with h5dump and h5py; a file left open "
      "(SIGKILL) has its count /n_times, /time finite in that many slots, then at most an interrupted "
      "batch of increasing times (written, not yet counted), then 0 (unwritten slots, doc/fields.md), "
      "every series as many slots as /time, and a closed file the count of all its slots and no NaN (*count right*; files finished before the count was kept: no count); "
      "its complete output times are the reference's first ones (a SIGTERM or SIGINT run adds the "
      "state it stopped in); both XDMF files parse and name only times the .h5 holds; the .his "
      "reaches the last time of the .h5; every restart file present opens, and the run continued "
      "from the newest ends with the reference's .his byte for byte.\n")
    w("A signal that comes while the program is still being loaded (its shared libraries, before "
      "its first statement; over a second on the loaded test machine) ends it by the signal's "
      "default action before it has written anything: counted apart as *before start*.\n")
    w("| signal | kills | before start | ended before the signal | exit as documented | .h5 readable "
      "| .h5 left open | count right | .h5 times right "
      "| XDMF right | .his not behind | restart files present | continued runs identical | failures |")
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name in ("SIGKILL", "SIGTERM", "SIGINT"):
        rs = [r for r in res if r["signal"] == name]
        if not rs:
            continue

        def count(word):
            return sum(1 for r in rs if not any(word in f for f in r["failures"]))
        present = sum(1 for r in rs if r.get("restart_files", 0) > 0)
        cont = sum(1 for r in rs if r.get("restart_files", 0) > 0
                   and not any(("restart" in f or "continued" in f) for f in r["failures"]))
        bad = sum(1 for r in rs if r["failures"])
        w(f"| {name} | {len(rs)} | {sum(1 for r in rs if r.get('before_start'))} | "
          f"{sum(1 for r in rs if r['finished_before'])} | {count('exit code')} | "
          f"{count('h5 unreadable')} | {sum(1 for r in rs if r.get('h5_open_file'))} | {count('h5 count')} | "
          f"{count('/time is not the')} | {count('xdmf')} | {count('.his behind')} | "
          f"{present} | {cont} of {present} | {bad} |")
    w("")
    reached = sorted(r.get("h5_times") or 0 for r in res if not r["finished_before"])
    if reached:
        w(f"Output times in the .h5 at the signal (of {data['reference_times']}): smallest {reached[0]}, "
          f"median {reached[len(reached) // 2]}, largest {reached[-1]}.\n")
    fails = [r for r in res if r["failures"]]
    if fails:
        w("Failures:\n")
        for r in fails[:20]:
            w(f"- kill {r['index']} ({r['signal']} at {r.get('progress')} of the .his + {r['delay']} s): "
              f"{'; '.join(r['failures'])}")
        w("")


# --- scenes ------------------------------------------------------------------------------

def _inversions(data, w):
    res = [r for r in data["scenes"] if r.get("kind")]
    if not res:
        return
    n = len(res)
    w(f"## 1a. The stops by inversion of seed {data['seed']}, classified\n")
    w(f"`tools/stress/inversions.py --scenes doc/stability/scenes_{data['seed']}.json` reruns each of the "
      f"{len(data['scenes'])} scenes of that campaign that stopped on an inverted element (with the exic "
      "of that campaign, before the flat-corner tolerance of doc/decisions.md) and reads the state at the failure from its <stem>.h5: the "
      "folded corner, whether its node and its neighbours are on a contact surface and in contact, "
      "the spread of the element's nodal velocities over its size. It also reruns each with "
      "QUADrature 2 in every solid (no one-point element, no hourglass control). "
      f"{len(data['scenes']) - n} of them finished on the rerun's build.\n")
    kinds = collections.Counter(r["kind"] for r in res)
    w("| folded corner | stops | one-point element | finishes with QUADrature 2 | median spread of nodal velocities over size |")
    w("|---|---:|---:|---:|---:|")
    for k, v in kinds.most_common():
        rr = [r for r in res if r["kind"] == k]
        one = sum(1 for r in rr if r.get("quad") == 1)
        q2 = sum(1 for r in rr if r.get("q2_class") == "finished")
        w(f"| {k} | {v} | {one} | {q2} | {fmt(float(np.median([r['dv_over_h'] for r in rr])))} |")
    one = sum(1 for r in res if r.get("quad") == 1)
    q2 = sum(1 for r in res if r.get("q2_class") == "finished")
    w(f"| all | {n} | {one} | {q2} | {fmt(float(np.median([r['dv_over_h'] for r in res])))} |")
    w("")
    flat = [r for r in res if r["kind"] == "flat corner"]
    w(f"- **flat corner** ({len(flat)}): a corner node pressed onto a rigid face together with both its "
      "neighbours, all three in contact; the corner's det J is within 1e-6 of its reference value of "
      "zero, in 7 of them within round-off: the element is a triangle, not folded, and was stopped by "
      "the sign of a rounding error. A corner triangle within 1e-10 of the element's area is "
      "flat (src/exic/element/q4_stable.f90, `stable_block`; doc/decisions.md); with that rule 7 of these "
      "scenes run to the end (60, 101, 131, 151, 293, 319, 363), 3 stop later when the node slides on "
      "past its neighbour and the corner folds for real (29, 52, 303) and 2 at the same step (253, "
      "323: folded by more than 1e-10); scene 101 is a regression test (test/session/test_stress_decks.f90).")
    w("- **contact node**: the folded corner's node is in contact. Scene 76, followed step by step (a "
      "rigid block's corner pressing the top of a one-point block at about 0.1 c): the corner's det J falls "
      "from 0.43 to 0 of its reference value over 50 steps while the node stays on the rigid face and "
      "its contact force flips between the two faces of the rigid corner; no node is pushed through "
      "its element by the corrector in one step. The other stops of this class were not followed one "
      "by one; "
      f"{sum(1 for r in res if r['kind'] == 'contact node' and r.get('q2_class') == 'finished')} of the "
      f"{sum(1 for r in res if r['kind'] == 'contact node')} run to the end with 2x2 Gauss points and "
      "the same contact, which puts the cause in the element, not in the contact.")
    w("- **free surface / interior**: the fold is at a node that is not in contact: the impact wave "
      "folds an element of the body's free edge (or inside it, or next to the edge).")
    w(f"- {one} of the {n} folded elements are one-point elements (QUADrature 1 with HOURglass 0.1, the "
      f"generator's choice for half of the bodies); with 2x2 Gauss points in every solid {q2} of the "
      f"{n} scenes run to the end. The one-point element resists a corner fold only through its "
      "hourglass stiffness, and an impact at 0.1-0.3 of the wave speed concentrated on a corner or "
      "reflected at a free edge drives that mode: these stops are folds of the one-point element by "
      "its hourglass mode, not crushes (section 1b measures it for seed 20261124: the centroid J stays "
      "far from 0) (the last column: the spread of the element's nodal velocities over its size, "
      "1/time; times the step, the strain of one step). The remedy is in the element's hourglass "
      "control (section 1b), not in the contact.\n")


def _hourglass(inv, hg, w, new=None):
    """Section 1b: the stops of seed 20261124 classified by the one-point element's hourglass
    displacement and centroid J at the fold (inv: tools/stress/inversions.py with the campaign's
    exic), and the same scenes with the assumed-strain control (hg: the scenes rerun and judged
    by the suite, and the remaining stops classified)."""
    res = [r for r in inv["scenes"] if r.get("kind")]
    seed = inv["seed"]
    w(f"## 1b. The stops of seed {seed}: hourglass modes, and the assumed-strain control\n")
    w(f"`tools/stress/inversions.py --scenes doc/stability/scenes_{seed}.json --out "
      f"doc/stability/inversions_{seed}.json` reran the {len(inv['scenes'])} inversion stops of the campaign "
      f"of seed {seed} with HOURglass 0.1 (doc/stability/scenes_{seed}.json) with that campaign's exic and measured, at the failure, the folded element's centroid J (det of "
      "its mean deformation gradient: the one-point element's J) and its hourglass displacement |q| "
      "(doc/hourglass.md, (H2)) over its size sqrt(A0). A crush takes the centroid J to 0; an "
      "hourglass fold keeps it near 1 while |q| grows to a good fraction of the size (a square of side "
      "L folds at a corner when the pure hourglass mode reaches |q| = L/2, less with a mean compression "
      "or shear).\n")
    w("| folded corner | stops | one-point element | centroid J (min, median) | abs(q)/size (min, median, max) | finish with QUADrature 2 |")
    w("|---|---:|---:|---:|---:|---:|")

    def row(name, rr):
        jc = [r["j_centroid"] for r in rr]
        qh = [r["q_over_h"] for r in rr]
        one = sum(1 for r in rr if r.get("quad") == 1)
        q2 = sum(1 for r in rr if r.get("q2_class") == "finished")
        w(f"| {name} | {len(rr)} | {one} | {min(jc):.2f}, {np.median(jc):.2f} | "
          f"{min(qh):.2f}, {np.median(qh):.2f}, {max(qh):.2f} | {q2} |")
    for k, v in collections.Counter(r["kind"] for r in res).most_common():
        row(k, [r for r in res if r["kind"] == k])
    row("all", res)
    w("")
    one = [r for r in res if r.get("quad") == 1]
    w(f"- No stop is a crush: the smallest centroid J at a fold is {min(r['j_centroid'] for r in res):.2f}. "
      f"{len(one)} of the {len(res)} folded elements are one-point elements, folded by their hourglass "
      f"mode: abs(q) at the fold is {min(r['q_over_h'] for r in one):.2f} to "
      f"{max(r['q_over_h'] for r in one):.2f} of the element's size with the centroid J at "
      f"{min(r['j_centroid'] for r in one):.2f} to {max(r['j_centroid'] for r in one):.2f}: the mode that "
      "the one-point element resists only through its hourglass control (HOURglass 0.1) grows from the "
      "impact until a corner folds.")
    nc = sum(1 for r in one if r["kind"] in ("contact node", "flat corner"))
    w(f"- Of these, {nc} fold at a node in contact (a corner under the concentrated contact force of the "
      f"impact) and {len(one) - nc} at a free-surface or interior node (the impact wave reflected at a free "
      "edge): the same hourglass mode, driven from a contact node or by the wave.")
    two = [r for r in res if r.get("quad") != 1]
    if two:
        w(f"- {len(two)} folded elements are 2x2 elements (scenes {', '.join(str(r['index']) for r in two)}): "
          "crushed corners of fully integrated elements, not an hourglass mode of the one-point element.")
    sc = hg["scenes"]
    fin = [r for r in sc if r["class"] == "finished"]
    stop = [r for r in sc if r["class"] == "stopped"]
    w("")
    w(f"The remedy (doc/hourglass.md): `{hg['hourglass']}`, the assumed-strain stabilization of "
      "Belytschko & Bindeman in the element's turning frame, stiffness from mu and nu, no coefficient. "
      f"The stress generator writes it for every one-point body (`scenes.HOURGLASS`; `stress.py "
      "--hourglass 'HOURglass 0.1'` writes the linear control instead), which changes nothing else of a scene. "
      f"The {len(sc)} scenes of seed {seed} that stopped with HOURglass 0.1, rerun with it and judged "
      "like section 1 (`tools/stress/hourglass_rerun.py`):\n")
    grow = [r for r in fin if ((r.get("energy") or {}).get("max") or 0.0) > GROWTH_WARN]
    deep = [r for r in fin if ((r.get("penetration") or {}).get("relative") or 0.0) > DEPTH_LIMIT]
    w("| outcome | scenes |")
    w("|---|---:|")
    w(f"| finished | {len(fin)} |")
    w(f"| ... energy growth > 1 % (warned) | {len(grow)} ({sum(1 for r in grow if r.get('energy_warned'))}) |")
    w(f"| ... a node deeper than 1e-3 edge inside another body (warned) | {len(deep)} "
      f"({sum(1 for r in deep if r.get('penetration_warned'))}) |")
    reasons = collections.Counter(r.get("reason", "?") for r in stop)
    for k, v in reasons.most_common():
        w(f"| stopped: {k} | {v} |")
    w(f"| crash or hang | {sum(1 for r in sc if r['class'] in ('crash', 'hang'))} |")
    w("")
    left = hg.get("stops", [])
    if left:
        import re
        lone = [r for r in left if r.get("quad") == 1]

        def step(msg):
            m = re.search(r"step (\d+)", msg or "")
            return int(m.group(1)) if m else None
        before = {r["index"]: step(r.get("message")) for r in inv["scenes"]}
        later = sum(1 for r in left if step(r.get("message")) and before.get(r["index"]) and
                    step(r["message"]) > before[r["index"]])
        w(f"Still stopped: {len(left)} scenes ({', '.join(str(r['index']) for r in left)}), "
          f"{len(lone)} with a one-point element folded, {later} of the {len(left)} at a later step than "
          "with HOURglass 0.1; at the "
          f"fold the centroid J is {min(r['j_centroid'] for r in lone):.2f} to "
          f"{max(r['j_centroid'] for r in lone):.2f} and abs(q) {min(r['q_over_h'] for r in lone):.2f} to "
          f"{max(r['q_over_h'] for r in lone):.2f} of the size: the same hourglass folds, under impacts "
          "stronger than the linear control resists. The 2x2 element resists them "
          f"({sum(1 for r in res if r.get('q2_class') == 'finished')} of the {len(res)} run to the end "
          "with QUADrature 2) through its Gauss points, where the neo-Hookean law's volumetric "
          "term grows without bound as a corner's J goes to 0; a linear (quadratic-energy) hourglass "
          "control has no such barrier. Those scenes need QUADrature 2 for the crushed body or a finer "
          "mesh.\n")
    if new:
        res2 = new["scenes"]
        n = len(res2)
        fin2 = [r for r in res2 if r["class"] == "finished"]
        stop2 = [r for r in res2 if r["class"] == "stopped"]
        reasons = ", ".join(f"{k} {v}" for k, v in
                            collections.Counter(r.get("reason", "?") for r in stop2).most_common())
        one2 = sum(1 for r in stop2 if any(b["quad"] == 1 and not b["rigid"] for b in r["bodies"]))
        g2 = [r for r in fin2 if ((r.get("energy") or {}).get("max") or 0.0) > GROWTH_WARN]
        p2 = [r for r in fin2 if ((r.get("penetration") or {}).get("relative") or 0.0) > DEPTH_LIMIT]
        w(f"A new campaign with the generator writing `{hg['hourglass']}` "
          f"(`tools/stress/stress.py --only scenes --seed {new['seed']} --scenes {n}`, "
          f"{new['seconds']:.0f} s; results in `doc/stability/scenes_{new['seed']}.json`): "
          f"{len(fin2)} of {n} scenes run to the end ({pct(len(fin2), n)}), {len(stop2)} stop ({reasons}; "
          f"{sum(1 for r in stop2 if r.get('named'))} naming their element or pair, {one2} in scenes with a "
          f"one-point body), {sum(1 for r in res2 if r['class'] in ('crash', 'hang'))} crash or hang; of the "
          f"finished, {len(g2)} grow in energy by more than 1 % ({sum(1 for r in g2 if r.get('energy_warned'))} "
          f"warned) and {len(p2)} hold a node deeper than 1e-3 edge inside another body "
          f"({sum(1 for r in p2 if r.get('penetration_warned'))} warned); section 1c reruns its stops "
          "with the corner barrier.\n")


def _barrier_rerun(w):
    """Section 1c: the 22 stops of seed 20261125 rerun with the corner barrier (measured once with
    the release build of the barrier's branch; the runs are not kept as JSON)."""
    w("## 1c. The stops of seed 20261125 and the corner barrier\n")
    w("The 22 stops of the campaign of seed 20261125 (section 1b) are folds the quadratic control cannot resist. The\n"
      "corner barrier (doc/hourglass.md section 5: an energy of the corner volume ratios that is zero\n"
      "above 1/2 and infinite at a fold, its bound on the stable step and a kinematic step limit), on\n"
      "with `HOURglass,PHYSical`, reran on the same 22 decks (the release build of the branch,\n"
      "`scenes.make_scene(20261125, k)`, judged as in section 1, two at a time):\n")
    w("| outcome | scenes |\n|---|---:|")
    w("| finished | 15 (74, 86, 156, 180, 199, 263, 279, 280, 285, 316, 325, 355, 439, 444, 462) |")
    w("| ... energy growth > 1 % | 0 |")
    w("| ... a node deeper than 1e-3 edge inside another body (warned) | 4 (4: 199, 279, 316, 439) |")
    w("| stopped: inversion | 6 (73, 96, 159, 244, 303, 381) |")
    w("| stopped: energy guard | 1 (229: past its fold now, stopped at step 3247 by the energy guard at "
      "52 % growth, the largest contributor contact pair 1 with 2465 of work: a contact defect, not the "
      "element) |")
    w("| crash or hang | 0 |\n")
    w("Of 60 finished scenes of the campaign (every eighth), rerun with the barrier: 60 finish, with the\n"
      "same failures (none new), largest energy growth 2.2 %. Scene 86 is saved as\n"
      "test/data/stress/barrier_20261125_0086.inp (a regression test, suite `stress_decks`).\n")


def _self_contact(w):
    """Section 1f: the scene of seed 20261201 that showed a body passing through itself (cited by
    doc/decisions.md, "Geometric penetration check")."""
    w("## 1f. A body through itself: scene 454 of seed 20261201\n")
    w("Scene 454 (`test/data/stress/scene_20261201_0454.inp`: a hollow POLAr ring thrown at an "
      "immovable rigid block; `tools/stress/stress.py --only scenes --seed 20261201 --scenes 500 --jobs 1 "
      "--elastic-only` on 4c0f744, results in `doc/stability/scenes_20261201.json`) ends with ring node "
      "232 0.125 edges inside the block at t = 0.5626 by the suite's check, which tests every node. The "
      "ring closes on itself: AUTOmatic contact is between bodies, not within one (self contact is "
      "`PAIR,id,SELF,s`), and by t = 0.42 52 of the ring's nodes lie inside its own elements. The "
      "block's corner node 7 then sits in two overlapping layers of the ring, where its distance to the "
      "ring's boundary, the depth the geometric check measures, is small, and node 232 is an interior "
      "node, which the geometric check does not test (a body enters another through its boundary, "
      "unless it has passed through itself first). The geometric check therefore also tests a body's "
      "boundary nodes against its own elements (doc/decisions.md, \"Geometric penetration check\"): "
      "on this deck it warns at t = 0.4233 that 25 nodes of region 2 are inside other elements of "
      "region 2 (`test/data/stress/ring_self_20261201_0454.inp`, suite `stress_decks`).\n")


def _by_hand(w):
    """The sections written by hand (doc/stability/by_hand.md, without its leading comment): the
    campaigns run again on later commits, which have no generator of their own."""
    path = os.path.join(ROOT, "doc", "stability", "by_hand.md")
    if not os.path.exists(path):
        return
    text = open(path, encoding="utf-8").read()
    if text.startswith("<!--"):
        text = text[text.index("-->") + 3:].lstrip("\n")
    w(text)


def _scenes(data, w, figdir):
    res = data["scenes"]
    n = len(res)
    cls = collections.Counter(r["class"] for r in res)
    fin = [r for r in res if r["class"] == "finished"]
    stop = [r for r in res if r["class"] == "stopped"]
    w(f"## 1. Random scenes (seed {data['seed']}, {n} scenes)\n")
    only_elastic = " --elastic-only" if data.get("metals") is False else ""
    w(f"`tools/stress/stress.py --only scenes --seed {data['seed']} --scenes {n} --jobs 2{only_elastic}` "
      f"on {data.get('commit', '?')} ({data['seconds']:.0f} s on two cores, timeout {data['timeout']:.0f} s "
      "per scene; `--elastic-only`: neo-Hookean bodies only, section 1k adds metals). Scene k of "
      "seed s is `scenes.make_scene(s, k)`: 2-6 bodies (blocks, rotated blocks, disks of five blocks + "
      "TIE, POLAr rings + TIE, rigid walls and rigid projectiles), QUADrature 1 and 2, AUTOmatic "
      "contact, speeds 0.02-0.3 of the slower wave speed of the two bodies, density ratios up to "
      "1e3, element sizes differing up to 10x, head-on, oblique, grazing (1-10 degrees) and "
      "corner-first impacts, each run to a time that covers the approach and the first contact "
      "(at most about 6000 steps).\n")
    pats = collections.Counter(r["pattern"] for r in res)
    kinds = collections.Counter(b["kind"] + (" (rigid)" if b["rigid"] else "") for r in res for b in r["bodies"])
    quads = collections.Counter(b["quad"] for r in res for b in r["bodies"] if not b["rigid"])
    contact = sum(1 for r in res if ((r.get("energy") or {}).get("max_active") or 0) > 0)
    w("Scenes by pattern: " + ", ".join(f"{k} {v}" for k, v in sorted(pats.items())) + ". Bodies: " +
      ", ".join(f"{k} {v}" for k, v in sorted(kinds.items())) + "; solid bodies with QUADrature 1: "
      f"{quads.get(1, 0)}, 2: {quads.get(2, 0)}. Scenes with contact (active constraints in some row): "
      f"{contact}. Density ratios up to {max(r['density_ratio'] for r in res):.3g}, element size ratios "
      f"up to {max(r['size_ratio'] for r in res):.3g}, elements per scene "
      f"{min(r['elements'] for r in res)}-{max(r['elements'] for r in res)}.\n")
    w("| outcome | scenes | share |")
    w("|---|---:|---:|")
    for k in ("finished", "stopped", "crash", "hang", "input"):
        w(f"| {k} | {cls.get(k, 0)} | {pct(cls.get(k, 0), n)} |")
    reasons = collections.Counter(r.get("reason", "?") for r in stop)
    named = sum(1 for r in stop if r.get("named"))
    w("")
    if stop:
        w("Stops by reason: " + ", ".join(f"{k} {v}" for k, v in reasons.most_common()) +
          f"; {named} of {len(stop)} messages name a node, element or pair.\n")
    if stop:
        w("Stops against the impact speed (the largest body speed of the scene over the smallest wave "
          "speed of its solid bodies) and the quadrature:\n")
        w("| speed / c | scenes | stopped | inversion | energy |")
        w("|---|---:|---:|---:|---:|")
        for lo, hi in ((0.0, 0.1), (0.1, 0.2), (0.2, 10.0)):
            rs = [r for r in res if lo <= max(b["speed_over_c"] for b in r["bodies"]) < hi]
            st = [r for r in rs if r["class"] == "stopped"]
            w(f"| {lo:g}-{hi if hi < 10 else 'max'} | {len(rs)} | {len(st)} ({pct(len(st), len(rs))}) | "
              f"{sum(1 for r in st if r.get('reason') == 'inversion')} | "
              f"{sum(1 for r in st if r.get('reason') == 'energy')} |")
        one = [r for r in res if any(b["quad"] == 1 and not b["rigid"] for b in r["bodies"])]
        w(f"\nScenes with a one-point (QUADrature 1) body: {len(one)}, of which stopped "
          f"{sum(1 for r in one if r['class'] == 'stopped')}; scenes with 2x2 bodies only: "
          f"{n - len(one)}, stopped {sum(1 for r in res if r not in one and r['class'] == 'stopped')}.\n")
    g = [((r.get("energy") or {}).get("max") or 0.0) for r in fin]
    pen = [((r.get("penetration") or {}).get("relative") or 0.0) for r in fin]
    ew = [r.get("energy_warned") for r in fin]
    pw = [r.get("penetration_warned") for r in fin]
    w("Finished scenes:\n")
    w("| finished scenes with | count | of which exic warned |")
    w("|---|---:|---:|")
    for lim in (GROWTH_WARN, GROWTH_BAD):
        hit = [i for i, x in enumerate(g) if x > lim]
        w(f"| energy growth > {100 * lim:.0f} % | {len(hit)} | {sum(1 for i in hit if ew[i])} |")
    for lim in (DEPTH_LIMIT, 0.1, 1.0):
        hit = [i for i, x in enumerate(pen) if x > lim]
        w(f"| a node deeper than {lim:g} edge inside another body | {len(hit)} | {sum(1 for i in hit if pw[i])} |")
    nf = sum(1 for r in res if r.get("nonfinite"))
    w(f"| non-finite numbers in an output file | {nf} | - |")
    w("")
    if fin:
        w(f"Largest energy growth of a finished scene {100 * max(g):.3g} %; median {100 * float(np.median(g)):.3g} %. "
          f"Deepest node of a finished scene {max(pen):.3g} edges.\n")
    # figures
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
    gg = np.array(g)
    ax[0].hist(np.clip(gg, -1, 1), bins=60, color="tab:blue")
    ax[0].axvline(GROWTH_WARN, color="tab:orange", ls="--", label="1 %")
    ax[0].axvline(GROWTH_BAD, color="tab:red", ls="--", label="5 %")
    ax[0].set_yscale("log")
    ax[0].set_xlabel("largest energy growth (E - E_in)/(|E0| + |W_ext|)")
    ax[0].set_ylabel("finished scenes")
    ax[0].legend()
    pp = np.array(pen)
    ax[1].hist(np.log10(np.maximum(pp, 1e-18)), bins=60, color="tab:green")
    ax[1].axvline(-3, color="tab:red", ls="--", label="1e-3 edge")
    ax[1].set_xlabel("log10 deepest node inside another body (edges)")
    ax[1].set_ylabel("finished scenes")
    ax[1].legend()
    rep = np.array([r.get("reported_penetration") or 0.0 for r in fin])
    dep = np.array([((r.get("penetration") or {}).get("depth") or 0.0) for r in fin])
    ax[2].loglog(np.maximum(dep, 1e-18), np.maximum(rep, 1e-18), ".", ms=4)
    lim = [1e-18, max(1.0, dep.max() if len(dep) else 1.0)]
    ax[2].plot(lim, lim, "k:", lw=0.8)
    ax[2].set_xlabel("deepest node, measured (length)")
    ax[2].set_ylabel("largest penetration reported in <stem>.out")
    fig.tight_layout()
    fig.savefig(os.path.join(figdir, "scenes.png"), dpi=90)
    plt.close(fig)
    w("![energy growth and penetration of the finished scenes](stability/scenes.png)\n")
    w("Per pattern:\n")
    w("| pattern | scenes | finished | stopped | crash | hang | energy > 1 % | penetration > 1e-3 edge |")
    w("|---|---:|---:|---:|---:|---:|---:|---:|")
    for p in sorted(pats):
        rs = [r for r in res if r["pattern"] == p]
        c = collections.Counter(r["class"] for r in rs)
        e1 = sum(1 for r in rs if r["class"] == "finished" and ((r.get("energy") or {}).get("max") or 0) > GROWTH_WARN)
        p1 = sum(1 for r in rs if r["class"] == "finished" and ((r.get("penetration") or {}).get("relative") or 0) > DEPTH_LIMIT)
        w(f"| {p} | {len(rs)} | {c.get('finished', 0)} | {c.get('stopped', 0)} | {c.get('crash', 0)} | "
          f"{c.get('hang', 0)} | {e1} | {p1} |")
    w("")
    bad = [r for r in res if r.get("failures")]
    w(f"### Failing scenes ({len(bad)})\n")
    w("Reproduce one with `python3 -c 'import sys; sys.path.insert(0, \"tools/stress\"); import scenes; "
      f"print(scenes.make_scene({data['seed']}, K).deck)' > scene.inp`; the worst of each kind are saved in "
      "`test/data/stress/` (the first comment line of each says what it shows).\n")
    if bad:
        w("| scene | pattern | outcome | failures | energy growth | deepest node (edges) | reported | message |")
        w("|---|---|---|---|---:|---:|---:|---|")
        for r in sorted(bad, key=lambda r: r["index"])[:80]:
            e = r.get("energy") or {}
            p = r.get("penetration") or {}
            saved = os.path.exists(os.path.join(ROOT, "test", "data", "stress", r["name"] + ".inp"))
            w(f"| {r['index']}{' (saved)' if saved else ''} | {r['pattern']} | {r['class']} | "
              f"{', '.join(r['failures'])} | {fmt(100 * (e.get('max') or 0), '.3g')} % | "
              f"{fmt(p.get('relative'))} | {fmt(r.get('reported_penetration'))} | "
              f"{(r.get('message') or '')[:90]} |")
        if len(bad) > 80:
            w(f"\n({len(bad) - 80} more in doc/stability/scenes.json.)")
    w("")
    if stop:
        w("Stopped scenes:\n")
        w("| scene | pattern | reason | names | message |")
        w("|---|---|---|---|---|")
        for r in stop:
            w(f"| {r['index']} | {r['pattern']} | {r.get('reason')} | {'yes' if r.get('named') else 'no'} | "
              f"{r['message'][:120]} |")
        w("")


# --- fuzz --------------------------------------------------------------------------------

def _fuzz(data, w):
    res = data["mutants"]
    n = len(res)
    cls = collections.Counter(r["class"] for r in res)
    w(f"## 2. Fuzzed decks (seed {data['seed']}, {n} mutants)\n")
    w(f"`tools/stress/stress.py --only fuzz --seed {data['seed']} --fuzz {n}` ({data['seconds']:.0f} s, "
      f"timeout {data['timeout']:.0f} s). Mutant k mutates deck k mod {data.get('decks', 38)} of inputs/ "
      "(every deck in turn) with one or two operators; see `tools/stress/fuzz.py`. A run still going at "
      "the timeout is asked for its time twice by SIGUSR2 (its status line, 1 s apart) and counted as a "
      "long run when the time advances (a mutant that lost its TIME record steps a LOOP of 10^7 steps "
      "without writing a row; exic warns about such a LOOP at its line). Non-finite numbers are looked "
      "for in every number of .his, .ene, the datasets of .h5 and .out outside the echo of the deck, "
      "its title and the error and warning lines (a title \"seed nan\" is the user's text).\n")
    w("| outcome | mutants |")
    w("|---|---:|")
    for k in ("finished", "stopped", "input", "long run", "crash", "hang", "checker"):
        w(f"| {k} | {cls.get(k, 0)} |")
    fl = sum(1 for r in res if r["class"] == "input" and r.get("file_line"))
    nf = sum(1 for r in res if r.get("nonfinite"))
    w("")
    w(f"- exit 2 with a message naming file:line: {fl} of {cls.get('input', 0)};")
    w(f"- signals or other exit codes: {cls.get('crash', 0)}; hangs (killed at the timeout without the "
      f"time advancing): {cls.get('hang', 0)}; long runs (still advancing at the timeout, a mutant asking "
      f"for a much longer run): {cls.get('long run', 0)};")
    w(f"- mutants with a non-finite number in an output file: {nf}.\n")
    w(f"The campaign ran on {data.get('commit', 'f332b83')}. Each defect an earlier campaign found has a "
      "regression test in `make test` (suites `hostile`, `run_output` and `stress_decks`, decks in "
      "test/data/stress/).\n")
    ops = collections.Counter(op for r in res for op in r["ops"])
    w("Operators used: " + ", ".join(f"{k} {v}" for k, v in ops.most_common()) + ".\n")
    bad = [r for r in res if r["failures"]]
    if bad:
        w("| mutant | deck | operators | failures | message |")
        w("|---|---|---|---|---|")
        for r in bad[:60]:
            w(f"| {r['k']} | {r['deck']} | {'+'.join(r['ops'])} | {', '.join(r['failures'])} | "
              f"{(r.get('message') or r.get('stderr_tail', '')[-80:]).strip()[:100]} |")
        w("")
    stops = [r for r in res if r["class"] == "stopped"]
    if stops:
        w("Mutants that stopped (exit 1):\n")
        c = collections.Counter(_short(r["message"]) for r in stops)
        for m, k in c.most_common(15):
            w(f"- {k} x {m}")
        w("")


def _short(msg):
    import re
    return re.sub(r"[-+]?\d[\d.E+-]*", "#", msg)[:110]


# --- cfl ---------------------------------------------------------------------------------

def _cfl(data, w, figdir):
    runs = data["runs"]
    w("## 3. CFL sweeps on the seed's examples 7.2 and 7.3\n")
    w("`inputs/paper/ex72_compliant.inp` and `ex73_like_bars.inp` with `cfl` = 0.1 ... 1.0 "
      f"({data['seconds']:.0f} s). Energy growth is the largest of the run (negative: the run only "
      "lost energy); drift is `<stem>.ene`'s drift column at the end; peak force the largest "
      "resultant normal contact force (`cont,1,1`); penetration the deepest node inside the other "
      "bar at the field outputs, measured, and the largest `cont,1,5` exic reported.\n")
    w("| example | CFL | outcome | steps | energy growth | final drift | peak force | deepest node (length) | (edges) | reported |")
    w("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|")
    for r in runs:
        e = r.get("energy") or {}
        p = r.get("penetration") or {}
        w(f"| {r['example']} | {r['cfl']:.1f} | {r['class']} | {r.get('steps', '-')} | {fmt(e.get('max'))} | "
          f"{fmt(r.get('drift_final'))} | {fmt(r.get('peak_force'), '.5g')} | {fmt(p.get('depth'))} | "
          f"{fmt(p.get('relative'))} | {fmt(r.get('reported_penetration'))} |")
    w("")
    fig, ax = plt.subplots(1, 3, figsize=(15, 4))
    for ex, mk in (("7.2", "o-"), ("7.3", "s-")):
        rs = [r for r in runs if r["example"] == ex]
        c = [r["cfl"] for r in rs]
        ax[0].plot(c, [r.get("drift_final") or np.nan for r in rs], mk, label=f"{ex} final drift")
        ax[0].plot(c, [((r.get("energy") or {}).get("max") or np.nan) for r in rs], mk.replace("-", ":"),
                   label=f"{ex} largest growth")
        ax[1].plot(c, [r.get("peak_force") or np.nan for r in rs], mk, label=ex)
        ax[2].semilogy(c, [max(((r.get("penetration") or {}).get("depth") or 0.0), 1e-18) for r in rs], mk,
                       label=f"{ex} measured")
        ax[2].semilogy(c, [max(r.get("reported_penetration") or 0.0, 1e-18) for r in rs], mk.replace("-", ":"),
                       label=f"{ex} reported")
    ax[0].set_ylabel("energy (relative)")
    ax[1].set_ylabel("peak contact force")
    ax[2].set_ylabel("deepest penetration")
    for a in ax:
        a.set_xlabel("CFL number")
        a.legend(fontsize=8)
        a.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(figdir, "cfl.png"), dpi=90)
    plt.close(fig)
    w("![energy, peak force and penetration against the CFL number](stability/cfl.png)\n")


# --- long runs ---------------------------------------------------------------------------

def _long(data, w, figdir):
    runs = data["runs"]
    tag = "10^6 steps" if data["long"] else "default length"
    w(f"## 4. Long runs ({tag})\n")
    w(f"({data['seconds']:.0f} s.) Energy growth as above; |p_y| is the largest transverse momentum "
      "of the whole model over the run (the bounce's frictionless walls must keep it at round-off), "
      "against the initial momentum p_x(0); pass-limit steps are the corrector steps that reached "
      "their pass limit (`<stem>.out`), and whether a warning was written.\n")
    w("| run | outcome | steps | energy growth (largest) | (final) | |p_y| max | p_x(0) | pass-limit steps | warned | deepest node (edges) | steps/s |")
    w("|---|---|---:|---:|---:|---:|---:|---:|---|---:|---:|")
    for r in runs:
        e = r.get("energy") or {}
        p = r.get("penetration") or {}
        w(f"| {r['kind']} | {r['class']} | {r.get('steps', '-')} | {fmt(e.get('max'))} | {fmt(e.get('final'))} | "
          f"{fmt(r.get('momentum_y_max'))} | {fmt(r.get('momentum_x0'))} | {r.get('pass_limit_steps')} | "
          f"{'yes' if r.get('pass_limit_warned') else 'no'} | {fmt(p.get('relative'))} | "
          f"{fmt(r.get('steps_per_second'), '.4g')} |")
    w("")
    for r in runs:
        w(f"- **{r['kind']}**: {r['what']}." + (f" Stopped: {r['message']}" if r.get("message") else ""))
    w("")
    name = "long_1e6.png" if data["long"] else "long.png"
    fig, ax = plt.subplots(1, 3, figsize=(15, 4))
    for r in runs:
        s = r.get("series")
        if not s:
            continue
        ax[0].plot(s["step"], s["growth"], label=r["kind"])
        ax[1].plot(s["step"], s["momentum_y"], label=r["kind"])
        ax[2].plot(s["step"], s["active"], label=r["kind"], lw=0.6)
    ax[0].set_ylabel("energy growth (E - E_in)/(|E0| + |W_ext|)")
    ax[1].set_ylabel("momentum y")
    ax[2].set_ylabel("active constraints")
    for a in ax:
        a.set_xlabel("step")
        a.legend(fontsize=8)
        a.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(figdir, name), dpi=90)
    plt.close(fig)
    w(f"![energy, transverse momentum and active constraints over the long runs](stability/{name})\n")


# --- what part 2 must fix ----------------------------------------------------------------

def _saved_readme():
    """test/data/stress/README.md: every saved deck with the note of its first comment line."""
    import glob
    d = os.path.join(ROOT, "test", "data", "stress")
    files = sorted(glob.glob(os.path.join(d, "*.inp")))
    if not files:
        return
    lines = ["# Decks saved by the stress suite", "",
             "Written by `make stress` (tools/stress/, doc/stability.md): the worst random scenes of each "
             "kind of failure, the fuzzed decks that failed, and the decks of the long runs (flat_corner_*.inp, hourglass_*.inp, barrier_*.inp, plastic1pt_*.inp, impulse_*.inp, rest_on_wall_*.inp, ring_self_*.inp, facing_side_*.inp, nearest_face_*.inp, corner_pass_*.inp, guard_first_contact_*.inp and mirror_corner_*.inp are kept by hand: regression decks). Each deck's "
             "first comment line (`! stress...`) says what it showed when it was saved. Scenes and long "
             "runs are self-contained (`exic test/data/stress/NAME.inp -o out`); a fuzzed deck is a "
             "mutant of a deck of inputs/ and may INCLude that deck's `common/` files: copy it next to "
             "its original to run it.", ""]
    for f in files:
        note = ""
        with open(f, encoding="latin-1") as fh:
            for line in fh:
                if line.startswith("! stress"):
                    note = line.split(":", 1)[1].strip() if ":" in line else line[2:].strip()
                    break
        lines.append(f"- `{os.path.basename(f)}`: {note or 'long run of the stress suite (section 4)'}")
    with open(os.path.join(d, "README.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
