#!/usr/bin/env python3
"""Rerun the scenes of a campaign that stopped, with the generator's hourglass record of today
(doc/stability.md, section 1b).

    tools/stress/hourglass_rerun.py --scenes doc/stability/scenes_20261124.json [--exic PATH]
                                    [--hourglass 'HOURglass,PHYSical']
                                    [--out doc/stability/hourglass_<seed>.json]

Each scene of the campaign that stopped is made again (`scenes.make_scene`, the same draw: only
the HOURglass record of its one-point bodies differs when the record differs) and judged like
the campaign's scenes (stress.one_scene, stress.judge_scene: energy growth, penetration, the
stop's reason); a scene that stops again on an inverted element is classified by
`inversions.classify` (the folded corner, the centroid J and |q|/size at the fold, and the run
with QUADrature 2).
"""
import argparse
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)

import inversions  # noqa: E402
import scenes  # noqa: E402
import stress  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", required=True, help="a scenes JSON of the stress suite")
    ap.add_argument("--exic", default=None)
    ap.add_argument("--hourglass", default=None, help="default: scenes.HOURGLASS")
    ap.add_argument("--out", default=None)
    ap.add_argument("--timeout", type=float, default=120.0)
    args = ap.parse_args()
    if args.hourglass:
        scenes.HOURGLASS = args.hourglass
    exic = os.path.abspath(args.exic or stress.find_exic())
    with open(args.scenes) as f:
        data = json.load(f)
    seed = data["seed"]
    out = args.out or os.path.join(ROOT, "doc", "stability", f"hourglass_{seed}.json")
    picks = [r["index"] for r in data["scenes"] if r["class"] == "stopped"]
    work = os.path.join(ROOT, "build", "stress", "hourglass")
    os.makedirs(work, exist_ok=True)
    res, stops = [], []
    for k in picks:
        r, _ = stress.one_scene(exic, seed, k, args.timeout)
        r["failures"] = stress.judge_scene(r)
        res.append(r)
        print(f"{k}: {r['class']} {r.get('reason', '')} {', '.join(r['failures'])}", flush=True)
        if r["class"] == "stopped" and r.get("reason") == "inversion":
            stops.append(inversions.classify(exic, seed, k, work))
    with open(out, "w") as f:
        json.dump({"seed": seed, "exic": exic, "hourglass": scenes.HOURGLASS, "scenes": res,
                   "stops": stops}, f, indent=1, default=str)
    return 0


if __name__ == "__main__":
    sys.exit(main())
