"""Final energy, drift, rebound and momentum of the three 1-D impacts (decks.impact_bars) with
the seed's scheme and LAGRange,ENERgy at 30 x 6 and 120 x 24, measured with the kinetic
correction of the energy balance (doc/decisions.md, "Energy balance"): the energy the
central-difference step conserves, K + U + kinetic_correction, at the last step against its
initial value; the uncorrected K + U beside it.

    .venv/bin/python bench/impact_energy.py EXIC [workdir]

Prints one line per run (doc/impact.md, section 4)."""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import decks  # noqa: E402
from run_bench import read_table  # noqa: E402


def main():
    exic = os.path.abspath(sys.argv[1])
    work = sys.argv[2] if len(sys.argv) > 2 else "build/impact_energy"
    os.makedirs(work, exist_ok=True)
    print("| problem | mesh | scheme | final energy | uncorrected K + U | drift | rebound | momentum change |")
    print("|---|---|---|---|---|---|---|---|")
    for prob in decks.IMPACT_PROBLEMS:
        ex = decks.impact_exact(prob)
        for nx in (30, 120):
            for method in ("LAGRange", "LAGRange,ENERgy"):
                name = f"impact_{prob}_{nx}_{method.replace(',', '_')}"
                deck = os.path.join(work, name + ".inp")
                with open(deck, "w") as f:
                    f.write(decks.impact_bars(prob, nx, method))
                out = os.path.join(work, name)
                r = subprocess.run([exic, deck, "-o", out, "-q"], capture_output=True, text=True)
                if r.returncode:
                    print(f"| {prob} | {nx} x {nx // 5} | {method} | failed: {r.stderr.strip()[-200:]} |")
                    continue
                e = read_table(os.path.join(out, name + ".ene"))
                h = read_table(os.path.join(out, name + ".his"))
                ec = [k + u + c for k, u, c in zip(e["kinetic"], e["strain"], e["kinetic_correction"])]
                eu = [k + u for k, u in zip(e["kinetic"], e["strain"])]
                reb = (h["mome(r1,1)"][-1] - ex["p1"])/abs(ex["p1"])
                dp = e["momentum_x"][-1] - e["momentum_x"][0]
                moving = "" if prob == "wall" else f"{dp:+.1e}"
                print(f"| {prob} | {nx} x {nx // 5} | {method} | {ec[-1]/ec[0] - 1:+.4%} | "
                      f"{eu[-1]/eu[0] - 1:+.4%} | {e['drift'][-1]:+.2e} | {reb:+.3%} | {moving} |")


if __name__ == "__main__":
    main()
