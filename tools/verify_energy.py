"""The seed's 2-D examples with `LAGRange,ENERgy` (massless contact faces, doc/impact.md section 3)
next to the default scheme for doc/verification.md: energy histories, final energy, contact work
and drift. Decks inputs/paper/<example>_energy.inp are the seed's decks with `LAGRange,ENERgy`
under every pair (their REGIon surfaces kept, so the bodies' whole boundaries are massless).
Called by verify_report.report."""
import numpy as np

import exic_results as xr
from verify_text import g, pct, table
import verify_figures as vf

#: (label, default deck, ENERgy deck) of inputs/paper
EXAMPLES = (("7.1", "ex71_rigid", "ex71_rigid_energy"),
            ("7.2", "ex72_compliant", "ex72_compliant_energy"),
            ("7.2b", "ex72b_compliant_6x31", "ex72b_compliant_6x31_energy"),
            ("7.3", "ex73_like_bars", "ex73_like_bars_energy"),
            ("7.4", "ex74_unlike_bars", "ex74_unlike_bars_energy"),
            ("7.5", "ex75_disk", "ex75_disk_energy"))


def figures(run):
    """Final (K + U - external and prescribed work) / E0 - 1, contact work / E0, largest |drift|,
    steps and the face stiffness refreshes (ENERgy runs) of a run."""
    e = run.energy()
    ene = run.ene
    return dict(final=e[-1] / e[0] - 1.0, wcon=ene["contact_work"][-1] / e[0],
                drift=float(np.max(np.abs(ene["drift"]))), steps=len(e) - 1,
                refresh=run.out_number(r"stiffness rows formed again at large strain (\d+)"))


def section_energy(ctx):
    out = ["## The seed's examples with LAGRange,ENERgy (massless contact faces)\n",
           "Decks `inputs/paper/<example>_energy.inp`: each seed deck with `LAGRange,ENERgy` under "
           "its pairs (doc/impact.md, section 3), the seed's REGIon surfaces kept, so that the whole "
           "boundary of every body in contact is placed by the static face problem, massless along "
           "its normals where it meets a deformable body and along both dofs against a rigid one "
           "(doc/impact.md, section 3.1); the face stiffness is formed again at large strain (doc/impact.md, section "
           "3.2, 'Refresh at large strain'). Energy = kinetic + strain (- external and prescribed "
           "work) over its initial value; the default scheme's curve loses the capture of the "
           "struck nodes at every first contact, which its `contact_work` column books.\n"]
    panels, rows, ran = [], [], []
    for label, base, energy in EXAMPLES:
        r0, r1 = ctx.run("paper", base), ctx.run("paper", energy)
        ran.append(r1 is not None)
        curves = []
        cells = [label]
        for run, name, style in ((r0, "default (LAGRange)", {"lw": 1.2}),
                                 (r1, "LAGRange,ENERgy", {"lw": 1.0, "ls": "--"})):
            if run is None:
                cells += ["failed", "-", "-"]
                continue
            e = run.energy()
            curves.append((name, run.ene["t"], e / e[0], style))
            f = figures(run)
            cells += [pct(f["final"]), pct(f["wcon"]), pct(f["drift"])]
        f1 = figures(r1) if r1 is not None else None
        cells.append(g(f1["refresh"]) if f1 else "-")
        rows.append(cells)
        panels.append((f"{label}: E / E0", curves))
    fig = vf.lines(ctx.fig("energy_option.png"), panels,
                   "the seed's examples: default scheme and LAGRange,ENERgy")
    out.append(table(["example", "default: final energy", "default: contact work / E0",
                      "default: largest |drift|", "ENERgy: final energy",
                      "ENERgy: contact work / E0", "ENERgy: largest |drift|",
                      "ENERgy: stiffness refreshes"], rows))
    out.append("\n" + ctx.img(fig, "energy histories of the seed's examples with both schemes"))
    ctx.claim(90, "beyond the seed: its 2-D examples run with LAGRange,ENERgy (issue 16, done-when 4)",
              "inputs/paper/*_energy.inp", f"{sum(ran)} of {len(ran)} ran to the end", all(ran))
    return "\n".join(out)
