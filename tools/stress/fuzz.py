"""The fuzzer of the stress suite: mutations of every deck of inputs/, each run under a timeout.

A mutant is written next to its original in a copy of inputs/ (so that its INCLude files are
found) and run with `exic -q -o DIR`. Every mutant must end with exit code 0, 1 or 2 (no signal,
no other code), before the timeout or still advancing in time when it strikes (a mutant may ask
for a much longer run: that is a long run, not a hang), with no non-finite number in its .his,
.ene, .out or .h5, and with a message naming file:line when it exits with 2.

Operators (one or two per mutant): field deletion and duplication, numeric extremes (1e308,
-0, nan, inf, huge integers, 1/0, 2^1024 ...), truncation, keyword case, binary junk, control
characters, long records, line deletion/duplication/swap, blank records added or removed, CRLF
and tabs, UTF-8 text, separators, undefined parameters, INCLude chains up to 12 deep, INCLude of
/dev/zero, a directory, a missing file or the deck itself, a mutated include file, an empty deck.
"""
import glob
import os
import random
import re
import shutil
import time
import concurrent.futures as cf

import analyse

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXTREMES = ["1e308", "-1e308", "1e-308", "4e-320", "-0", "0", "-0.0", "nan", "NaN", "inf",
            "-inf", "Infinity", "1e400", "-1e400", "99999999999", "-99999999999", "2147483648",
            "-2147483649", "-1", "1e20", "-1e20", "1/0", "sqrt(-1)", "2^1024", "log(0)", "0.5",
            "1e-12", "1e12", "", "1e", "1.2.3", "--1", "((1)", "1)", "exp(800)", "-(2^-1075)"]
NUMBER = re.compile(r"(?<![A-Za-z_0-9.])[-+]?(\d+\.?\d*|\.\d+)([eEdD][-+]?\d+)?")


def _records(lines):
    """Indices of lines that hold something other than blanks and comments."""
    return [i for i, l in enumerate(lines) if l.strip() and not l.strip().startswith("!")]


def _split(line):
    body, _, comment = line.partition("!")
    return [f for f in re.split(r"\s*[, =]\s*|\s+", body.strip())], comment


def op_delete_field(rng, lines, ctx):
    i = rng.choice(_records(lines))
    f, _ = _split(lines[i])
    if len(f) > 1:
        del f[rng.randrange(len(f))]
    lines[i] = "  " + ",".join(f)


def op_duplicate_field(rng, lines, ctx):
    i = rng.choice(_records(lines))
    f, _ = _split(lines[i])
    k = rng.randrange(len(f))
    f.insert(k, f[k])
    lines[i] = "  " + ",".join(f)


def op_extreme(rng, lines, ctx):
    recs = [i for i in _records(lines) if NUMBER.search(lines[i].split("!")[0])]
    if not recs:
        return op_delete_field(rng, lines, ctx)
    i = rng.choice(recs)
    body, sep, comment = lines[i].partition("!")
    ms = list(NUMBER.finditer(body))
    m = rng.choice(ms)
    body = body[:m.start()] + rng.choice(EXTREMES) + body[m.end():]
    lines[i] = body + sep + comment


def op_truncate(rng, lines, ctx):
    text = "\n".join(lines)
    cut = rng.randrange(len(text) + 1)
    lines[:] = text[:cut].split("\n")


def op_case(rng, lines, ctx):
    i = rng.choice(_records(lines))
    lines[i] = "".join(c.upper() if rng.random() < 0.5 else c.lower() for c in lines[i])


def op_junk(rng, lines, ctx):
    i = rng.randrange(len(lines) + 1)
    junk = bytes(rng.randrange(256) for _ in range(rng.randint(1, 64)))
    lines.insert(i, junk.decode("latin-1").replace("\n", " "))


def op_control(rng, lines, ctx):
    i = rng.randrange(len(lines))
    k = rng.randrange(len(lines[i]) + 1)
    lines[i] = lines[i][:k] + chr(rng.choice([0, 1, 7, 8, 11, 12, 27, 127])) + lines[i][k:]


def op_long(rng, lines, ctx):
    n = rng.choice([257, 300, 4096, 100000, 2000000])
    i = rng.randrange(len(lines) + 1)
    if rng.random() < 0.5 and lines:
        i = min(i, len(lines) - 1)
        lines[i] = lines[i] + "1" * n
    else:
        lines.insert(i, "  " + ",".join(["1"] * (n // 2)))


def op_delete_line(rng, lines, ctx):
    if lines:
        del lines[rng.randrange(len(lines))]


def op_duplicate_line(rng, lines, ctx):
    i = rng.randrange(len(lines))
    lines.insert(i, lines[i])


def op_swap(rng, lines, ctx):
    i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
    lines[i], lines[j] = lines[j], lines[i]


def op_blank(rng, lines, ctx):
    blanks = [i for i, l in enumerate(lines) if not l.strip()]
    if blanks and rng.random() < 0.5:
        del lines[rng.choice(blanks)]
    else:
        lines.insert(rng.randrange(len(lines) + 1), rng.choice(["", "! a comment", "   "]))


def op_crlf(rng, lines, ctx):
    lines[:] = [l.replace(" ", "\t") + "\r" if rng.random() < 0.5 else l + "\r" for l in lines]


def op_utf8(rng, lines, ctx):
    i = rng.choice(_records(lines))
    lines[i] = lines[i] + rng.choice([" é", ",ü", " ∞", ",😀", " µ=1"])


def op_separators(rng, lines, ctx):
    i = rng.choice(_records(lines))
    lines[i] = lines[i].replace(",", rng.choice(["  ", "=", ",,", " , "]))


def op_undefined(rng, lines, ctx):
    recs = [i for i in _records(lines) if NUMBER.search(lines[i].split("!")[0])]
    if not recs:
        return
    i = rng.choice(recs)
    body, sep, comment = lines[i].partition("!")
    m = rng.choice(list(NUMBER.finditer(body)))
    lines[i] = body[:m.start()] + rng.choice(["undefinedname", "x_1", "a" * 17, "sin(", "2*"]) + \
        body[m.end():] + sep + comment


def op_include_chain(rng, lines, ctx):
    """The deck's body moved to the end of a chain of INCLude files."""
    depth = rng.choice([1, 2, 8, 9, 10, 12])
    d, tag = ctx["dir"], ctx["tag"]
    # the title and control record stay; the rest goes to the last file of the chain
    head, rest = lines[:2], lines[2:]
    names = [f"{tag}_chain{j}.inc" for j in range(depth)]
    for j, name in enumerate(names):
        with open(os.path.join(d, name), "w") as f:
            if j + 1 < depth:
                f.write(f"INCLude,{names[j + 1]}\n")
            else:
                f.write("\n".join(rest) + "\n")
        ctx["files"].append(os.path.join(d, name))
    lines[:] = head + [f"INCLude,{names[0]}"]


def op_include_target(rng, lines, ctx):
    target = rng.choice(["/dev/zero", "/dev/null", "/dev/urandom", ".", "/", "nothere.inc",
                         ctx["name"], "/proc/self/status", '"' + "x" * 200 + '"'])
    inc = [i for i, l in enumerate(lines) if l.strip().lower().startswith("incl")]
    if inc and rng.random() < 0.6:
        lines[rng.choice(inc)] = f"INCLude,{target}"
    else:
        lines.insert(rng.randrange(min(2, len(lines)), len(lines) + 1), f"INCLude,{target}")


def op_mutate_include(rng, lines, ctx):
    """An included file replaced by a mutated copy."""
    inc = [i for i, l in enumerate(lines) if l.strip().lower().startswith("incl")]
    if not inc:
        return op_extreme(rng, lines, ctx)
    i = rng.choice(inc)
    name = _split(lines[i])[0][1]
    src = os.path.join(ctx["dir"], name)
    try:
        sub = open(src, errors="replace").read().split("\n")
    except OSError:
        return
    for _ in range(rng.randint(1, 3)):
        if not sub or not _records(sub):
            break
        rng.choice(SIMPLE)(rng, sub, ctx)
    new = os.path.join(os.path.dirname(name), f"{ctx['tag']}_mut.inc") if os.path.dirname(name) else f"{ctx['tag']}_mut.inc"
    with open(os.path.join(ctx["dir"], new), "w", errors="replace") as f:
        f.write("\n".join(sub))
    ctx["files"].append(os.path.join(ctx["dir"], new))
    lines[i] = f"INCLude,{new}"


def op_empty(rng, lines, ctx):
    lines[:] = rng.choice([[], [""], ["FEAP * * empty"], ["STOP"]])


SIMPLE = [op_delete_field, op_duplicate_field, op_extreme, op_extreme, op_extreme, op_truncate,
          op_case, op_junk, op_control, op_delete_line, op_duplicate_line, op_swap, op_blank,
          op_utf8, op_separators, op_undefined]
OPERATORS = SIMPLE + [op_long, op_crlf, op_include_chain, op_include_target, op_mutate_include,
                      op_extreme, op_extreme, op_delete_line, op_blank]
RARE = [op_empty]


def decks():
    return sorted(glob.glob(os.path.join(ROOT, "inputs", "*", "*.inp")))


def make_mutant(seed, k, tree):
    """Mutant number k: (path of the deck, names of the operators, extra files)."""
    rng = random.Random(seed * 7919 + k)
    origs = decks()
    orig = origs[k % len(origs)]
    rel = os.path.relpath(orig, os.path.join(ROOT, "inputs"))
    d = os.path.join(tree, os.path.dirname(rel))
    tag = f"fuzz{k:05d}"
    name = f"{tag}.inp"
    text = open(orig).read()
    lines = text.split("\n")
    ctx = {"dir": d, "tag": tag, "name": name, "files": []}
    ops = []
    if rng.random() < 0.005:
        op = rng.choice(RARE)
        op(rng, lines, ctx)
        ops.append(op.__name__[3:])
    else:
        for _ in range(1 if rng.random() < 0.7 else 2):
            if not lines or not _records(lines):
                break
            op = rng.choice(OPERATORS)
            op(rng, lines, ctx)
            ops.append(op.__name__[3:])
    path = os.path.join(d, name)
    with open(path, "w", encoding="latin-1", errors="replace", newline="\n") as f:
        f.write("\n".join(lines))
    return path, os.path.relpath(orig, ROOT), ops, ctx["files"]


def one_mutant(exic, seed, k, tree, outdir, timeout):
    """One mutant made, run and checked; a failure of the checker itself (it once ran out of
    memory) is a failure of that mutant, named, not the end of the campaign."""
    try:
        return _one_mutant(exic, seed, k, tree, outdir, timeout)
    except (MemoryError, OSError, ValueError) as e:
        r = {"k": k, "deck": "?", "ops": [], "class": "checker", "failures": [f"checker error: {e!r}"[:200]],
             "message": ""}
        try:
            path = make_mutant(seed, k, tree)[0]
            keep = open(path, encoding="latin-1").read()
        except (OSError, MemoryError):
            keep = None
        return r, keep


def _one_mutant(exic, seed, k, tree, outdir, timeout):
    path, orig, ops, files = make_mutant(seed, k, tree)
    r = analyse.run(exic, path, outdir, timeout)
    stem = os.path.join(outdir, f"fuzz{k:05d}")
    r.update({"k": k, "deck": orig, "ops": ops})
    if r["class"] == "hang":
        r["advancing"] = r.get("advancing") or advancing(stem + ".ene")
        if r["advancing"]:
            r["class"] = "long run"
    r["nonfinite"] = analyse.nonfinite_in_outputs(stem)
    failures = []
    if r["class"] in ("crash", "hang"):
        failures.append(r["class"])
    if r["nonfinite"]:
        failures.append("non-finite output")
    if r["class"] == "input" and not r.get("file_line"):
        failures.append("exit 2 without file:line")
    r["failures"] = failures
    keep = None
    if failures:
        try:
            keep = open(path, encoding="latin-1").read()
        except OSError:
            keep = None
    analyse.clean(stem)
    for p in [path] + files:
        try:
            os.remove(p)
        except OSError:
            pass
    return r, keep


def advancing(ene):
    """True when the last rows of a killed run's <stem>.ene show the time still advancing (only
    the file's last 64 kB are read)."""
    try:
        with open(ene, "rb") as f:
            f.seek(0, os.SEEK_END)
            size = f.tell()
            f.seek(max(0, size - 65536))
            tail = f.read().decode(errors="replace")
    except OSError:
        return False
    rows = [l.split() for l in tail.splitlines()[1:] if l.strip() and not l.startswith("#")]
    if len(rows) < 3:
        return False
    try:
        t = [float(r[0]) for r in rows[-50:]]
    except (ValueError, IndexError):
        return False
    return t[-1] > t[0]


def run_fuzz(exic, seed, n, jobs, work, save, log):
    tree = os.path.join(work, "fuzz", "inputs")
    outdir = os.path.join(work, "fuzz", "out")
    if os.path.exists(os.path.join(work, "fuzz")):
        shutil.rmtree(os.path.join(work, "fuzz"))
    shutil.copytree(os.path.join(ROOT, "inputs"), tree)
    os.makedirs(outdir, exist_ok=True)
    timeout = 20.0
    analyse.limit_memory()
    log(f"fuzz: {n} mutants of the {len(decks())} decks of inputs/, seed {seed}, timeout {timeout:.0f} s")
    t0 = time.time()
    results, kept = [], {}
    with cf.ThreadPoolExecutor(max_workers=jobs) as ex:
        futs = [ex.submit(one_mutant, exic, seed, k, tree, outdir, timeout) for k in range(n)]
        for j, fut in enumerate(cf.as_completed(futs), 1):
            r, text = fut.result()
            results.append(r)
            if r["failures"]:
                kept[r["k"]] = text
                log(f"  fuzz{r['k']:05d} ({r['deck']}, {'+'.join(r['ops'])}): {', '.join(r['failures'])} "
                    f"{r.get('message', '')[:100]}")
            if j % 250 == 0:
                log(f"  {j}/{n} mutants, {time.time() - t0:.0f} s")
    results.sort(key=lambda r: r["k"])
    data = {"seed": seed, "count": n, "decks": len(decks()), "timeout": timeout, "seconds": round(time.time() - t0, 1),
            "mutants": results}
    save("fuzz", data)
    saved = os.path.join(ROOT, "test", "data", "stress")
    os.makedirs(saved, exist_ok=True)
    for old in glob.glob(os.path.join(saved, f"fuzz_{seed}_*.inp")):
        os.remove(old)
    for r in results:
        text = kept.get(r["k"])
        if text is not None and len(text) < 20000:
            with open(os.path.join(saved, f"fuzz_{seed}_{r['k']:05d}.inp"), "w", encoding="latin-1") as f:
                f.write(f"! stress fuzz: mutant of {r['deck']} ({'+'.join(r['ops'])}): "
                        f"{', '.join(r['failures'])}; {r.get('message', '')[:160]}\n" + text)
    return data
