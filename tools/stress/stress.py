#!/usr/bin/env python3
"""The stress suite of exic (issue 10): random scenes, a fuzzer over the decks of inputs/, CFL
sweeps on the seed's examples 7.2 and 7.3, long runs, and runs killed at random moments
(SIGKILL, SIGTERM, SIGINT: tools/stress/kills.py); writes doc/stability.md, its figures
and JSON results under doc/stability/.

    tools/stress/stress.py [--exic PATH] [--seed N] [--scenes N] [--fuzz N] [--kills N] [--long]
                           [--only scenes,fuzz,cfl,long,kills] [--jobs 2] [--keep]
                           [--erosion 'EROSion INVErted'] [--save-as NAME]

`make stress` builds the release binary and runs this with the defaults (500 scenes of seed
20240610, 2,000 fuzzed decks, CFL 0.1-1.0, long runs of 2e4-5e4 steps; about 20 minutes on
two cores); `make stress STRESS_ARGS=--long` runs the long cases for 10^6 steps. Each section
saves its JSON as it ends, so `--only` reruns one section and the report is rebuilt from
every saved result. Exit code 0 when the suite ran (whatever it found), 2 on a usage error.
`--erosion` writes the given EROSion records (";" between several) into every deformable body of
the random scenes (doc/erosion.md; the scenes are otherwise the same decks), keeps their results
as doc/stability/<NAME>.json (default scenes_erosion) and saves no deck into test/data/stress.
`tools/stress/inversions.py` classifies the scenes of a campaign that stopped on an inverted
element (its JSON, doc/stability/inversions_<seed>.json, is section 1a of the report).
"""
import argparse
import concurrent.futures as cf
import glob
import json
import os
import shutil
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)

import analyse  # noqa: E402
import scenes  # noqa: E402

RESULTS = os.path.join(ROOT, "doc", "stability")
WORK = os.path.join(ROOT, "build", "stress")
SAVED = os.path.join(ROOT, "test", "data", "stress")


def find_exic():
    cands = glob.glob(os.path.join(ROOT, "build", "*", "app", "exic"))
    if not cands:
        sys.exit("stress: no exic binary under build/; build it first (make build)")
    return max(cands, key=os.path.getmtime)


def save(name, data):
    os.makedirs(RESULTS, exist_ok=True)
    with open(os.path.join(RESULTS, name + ".json"), "w") as f:
        json.dump(data, f, indent=1, default=float)


def load(name):
    p = os.path.join(RESULTS, name + ".json")
    if not os.path.exists(p):
        return None
    with open(p) as f:
        return json.load(f)


def log(msg):
    print(msg, flush=True)


# --- random scenes -----------------------------------------------------------------------

#: a finished scene is a failure past these
GROWTH_WARN, GROWTH_BAD = 0.01, 0.05
#: deepest node, in edges of the body it is in, counted as a penetration
DEPTH_LIMIT = 1e-3


def one_scene(exic, seed, index, timeout):
    sc = scenes.make_scene(seed, index)
    d = os.path.join(WORK, "scenes_erosion" if scenes.EROSION else "scenes")
    os.makedirs(d, exist_ok=True)
    name = f"scene_{seed}_{index:04d}"
    deck = os.path.join(d, name + ".inp")
    with open(deck, "w") as f:
        f.write(sc.deck)
    r = analyse.run(exic, deck, d, timeout)
    stem = os.path.join(d, name)
    r.update(sc.info)
    r["name"] = name
    if r["class"] in ("finished", "stopped"):
        r["energy"] = analyse.energy_growth(stem + ".ene")
        r["penetration"] = analyse.penetration(stem + ".h5")
        rep, warned = analyse.reported_penetration(stem + ".out")
        r["reported_penetration"] = analyse.finite_or_none(rep)
        r["penetration_warned"] = warned
        r["energy_warned"] = analyse.energy_warned(stem + ".out")
        r["nonfinite"] = analyse.nonfinite_in_outputs(stem)
    analyse.clean(stem)
    return r, sc.deck


def judge_scene(r):
    """The failures of one scene (empty when it is sound)."""
    f = []
    if r["class"] in ("hang", "crash", "input"):
        f.append(r["class"])
    if r["class"] == "stopped":
        if r.get("reason") in ("other", "start overlap"):
            f.append("stop: " + r.get("reason"))
        elif not r.get("named"):
            f.append("stop names no node or element")
    e = r.get("energy") or {}
    if r["class"] == "finished" and e:
        g = e.get("max", 0.0)
        if g == g and g > GROWTH_BAD:
            f.append("energy > 5 %" + ("" if r.get("energy_warned") else " unwarned"))
        elif g == g and g > GROWTH_WARN:
            f.append("energy > 1 %" + ("" if r.get("energy_warned") else " unwarned"))
    p = r.get("penetration") or {}
    if r["class"] == "finished" and p.get("relative", 0.0) > DEPTH_LIMIT:
        f.append("penetration" + ("" if r.get("penetration_warned") else " unwarned"))
    if r.get("nonfinite"):
        f.append("non-finite output")
    return f


def report_commit():
    """The commit the campaign runs on (its results name it: doc/stability.md)."""
    import subprocess
    try:
        return subprocess.run(["git", "-C", ROOT, "log", "-1", "--format=%h"], capture_output=True,
                              text=True, timeout=10).stdout.strip() or "?"
    except Exception:  # noqa: BLE001
        return "?"


def run_scenes(exic, seed, n, jobs, timeout, save_as="scenes", keep_decks=True):
    log(f"scenes: {n} random scenes of seed {seed}, timeout {timeout} s, {jobs} at a time")
    t0 = time.time()
    results = []
    decks = {}
    with cf.ThreadPoolExecutor(max_workers=jobs) as ex:
        futs = {ex.submit(one_scene, exic, seed, i, timeout): i for i in range(n)}
        for k, fut in enumerate(cf.as_completed(futs), 1):
            r, deck = fut.result()
            r["failures"] = judge_scene(r)
            results.append(r)
            if r["failures"]:
                decks[r["name"]] = deck
                log(f"  {r['name']}: {r['pattern']}: {r['class']} {', '.join(r['failures'])} "
                    f"{r.get('message', '')[:100]}")
            if k % 50 == 0:
                log(f"  {k}/{n} scenes, {time.time() - t0:.0f} s")
    results.sort(key=lambda r: r["index"])
    data = {"seed": seed, "count": n, "timeout": timeout, "seconds": round(time.time() - t0, 1),
            "commit": report_commit(), "metals": scenes.METALS, "scenes": results}
    if scenes.EROSION:
        data["erosion"] = scenes.EROSION
    save(save_as, data)
    if keep_decks:
        save_failing_scenes(results, decks, seed)
    return data


def save_failing_scenes(results, decks, seed):
    """The decks of the worst failing scenes into test/data/stress/ (with a note each)."""
    os.makedirs(SAVED, exist_ok=True)
    for old in glob.glob(os.path.join(SAVED, f"scene_{seed}_*.inp")):
        os.remove(old)
    picked = []
    order = ("hang", "crash", "input", "non-finite output", "energy > 5 % unwarned",
             "penetration unwarned", "energy > 1 % unwarned", "stop names no node or element",
             "stop: other", "stop: start overlap", "energy > 5 %", "energy > 1 %", "penetration")
    for kind in order:
        hits = [r for r in results if kind in r["failures"]]
        hits.sort(key=lambda r: -(((r.get("energy") or {}).get("max") or 0.0)
                                  + ((r.get("penetration") or {}).get("relative") or 0.0)))
        for r in hits[:3]:
            if r["name"] not in [p["name"] for p in picked]:
                picked.append(r)
    for r in picked:
        note = describe(r)
        with open(os.path.join(SAVED, r["name"] + ".inp"), "w") as f:
            f.write(f"! stress: {note}\n" + decks[r["name"]])


def describe(r):
    e = r.get("energy") or {}
    p = r.get("penetration") or {}
    s = f"{r['class']}; {', '.join(r['failures'])}"
    if e:
        s += f"; energy growth {100 * (e.get('max') or 0.0):.2f} % at t = {e.get('t_max', 0.0):.4g}"
    if p and p.get("relative", 0) > 0:
        s += (f"; node {p['node']} of region {p['of_body']} {p['relative']:.3g} edges inside region "
              f"{p['in_body']} at t = {p['t']:.4g} (reported {r.get('reported_penetration')})")
    if r.get("message"):
        s += f"; message: {r['message'][:160]}"
    return s


# --- main --------------------------------------------------------------------------------

def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exic", default=None)
    ap.add_argument("--seed", type=int, default=20240610)
    ap.add_argument("--scenes", type=int, default=500)
    ap.add_argument("--fuzz", type=int, default=2000)
    ap.add_argument("--kills", type=int, default=300)
    ap.add_argument("--long", action="store_true", help="long runs of 10^6 steps")
    ap.add_argument("--only", default="scenes,fuzz,cfl,long,kills")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=120.0)
    ap.add_argument("--no-report", action="store_true")
    ap.add_argument("--hourglass", default=None,
                    help='the hourglass record of one-point bodies (default: scenes.HOURGLASS; '
                         '"HOURglass 0.1" as in the campaigns up to seed 20261124)')
    ap.add_argument("--erosion", default=None,
                    help='EROSion records for every deformable body, separated by ";" (e.g. '
                         '"EROSion INVErted"; doc/erosion.md); the scenes results go to '
                         'doc/stability/scenes_erosion.json, no deck is saved into test/data/stress')
    ap.add_argument("--save-as", default="scenes",
                    help="the name of the scenes results under doc/stability (default scenes)")
    ap.add_argument("--elastic-only", action="store_true",
                    help="scenes without plastic and MIXEd bodies, as in the campaigns up to seed 20261210")
    args = ap.parse_args()
    if args.hourglass:
        scenes.HOURGLASS = args.hourglass
    if args.elastic_only:
        scenes.METALS = False
    if args.erosion:
        scenes.EROSION = args.erosion
        if args.save_as == "scenes":
            args.save_as = "scenes_erosion"
    exic = os.path.abspath(args.exic or find_exic())
    if not os.path.exists(exic):
        sys.exit(f"stress: no exic at {exic}")
    jobs = max(1, min(args.jobs, 2))
    only = set(args.only.split(","))
    os.makedirs(WORK, exist_ok=True)
    if "scenes" in only:
        run_scenes(exic, args.seed, args.scenes, jobs, args.timeout, args.save_as, not args.erosion)
    if "fuzz" in only:
        import fuzz
        fuzz.run_fuzz(exic, args.seed, args.fuzz, jobs, WORK, save, log)
    if "cfl" in only:
        import sweeps
        sweeps.run_cfl(exic, jobs, WORK, save, log)
    if "long" in only:
        import sweeps
        sweeps.run_long(exic, args.long, jobs, WORK, save, log)
    if "kills" in only:
        import kills
        kills.run_kills(exic, args.seed, args.kills, jobs, WORK, save, log)
    if not args.no_report:
        import report
        report.write(load, RESULTS, os.path.join(ROOT, "doc", "stability.md"), log)
    return 0


if __name__ == "__main__":
    sys.exit(main())
