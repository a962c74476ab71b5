#!/usr/bin/python3
"""Runs the README's shell blocks as a reader pastes them, and checks every
figure the README quotes against the command printed beside it.

Which blocks count. Every fenced block of README.md holds commands a reader
pastes, except a block whose info string names something else than a shell
(```toml, ```text, ...) and the plain blocks listed in NOT_COMMANDS (the
Layout tree), named by their first line. A new plain block is therefore run
unless it is listed here.

How they run. The blocks run in README order, each as one bash script
(errexit and pipefail, and a check after every top-level command, so a
failing `cd X && ...` counts too), in a temporary copy of the repository:
cases/ and scripts/ copied, build/bin a link to BUILD_DIR/bin (and
build/python to BUILD_DIR/python, the Python module) and nothing else, so
that a command writing into the tree (docs/images/...) fails here instead of
overwriting a committed file. HOME and XDG_DATA_HOME point into
the temporary directory and LAMINA_LIBRARY and LAMINA_FFTW_WISDOM are
unset: the library is the README's default ~/.local/share/lamina/library.toml,
a fresh one, and the user's library is never touched. State carries from
block to block as it does for a reader (the library, out/, files written).
Any non-zero exit fails the test, naming the README line and the command.

SKIP: the commands not run, each with its reason (make demo, make test and
the other test-suite commands). SMALL: size overrides, each a text of one
README command replaced, to keep the whole run short.

Figures. FIGURES binds each figure the README quotes to the commands printed
beside it (in the quote's paragraph or table row, or in the fenced block just
before or after that paragraph) and to a reader of their output. The numbers
of the quoted text are the figures; each must equal what the commands give to
the quoted digits: |value - quoted| <= half a unit of the last quoted digit.
The commands that are in a block ran with it (their files are read); the
others are run here, in the same tree, after the blocks. A reader of a
program's JSON runs the command again with --json appended (only the output
format changes) to read full precision.

LAMINA_README_FULL=1 drops the SMALL overrides (the README verbatim) and
also checks the figures marked full: the reduced-order cell's accuracy
(scripts/plot_rom.py: nine full-field nonlinear cells, about 70 s of CPU,
as much as all the rest). Every other figure's commands are cheap enough to
run always.

Cost: about 40 s of CPU (user + system; the blast-roof pair, 13 s, is the
largest, the sheet impacts, blasts, convergence studies and cells a few
seconds each), measured on the 2-core machine under load 13-16, where it
took 2 min 15 s of wall time alone (5 min beside a second such job). The
figures marked full add about 70 s of CPU.

Usage: readme_commands.py SOURCE_DIR BUILD_DIR [--keep]   (--keep: leave the
       temporary tree and print its path)
       readme_commands.py --self-test   (plants two failing commands, a wrong
       figure and a stale override in a temporary tree and exits 1 unless each
       is reported, and nothing else)
Prints one line per failure and exits 1 if there is any. Standard library only.
"""
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

from check_links import compare_planted  # the docs self-tests' verdict (same folder)

# Plain blocks that are not commands, by their first line.
NOT_COMMANDS = ["core/ "]
SHELLS = {"", "sh", "bash", "shell", "console"}

# Commands not run (a README command, exactly): why.
SKIP = {
    # make demo and make test (the README's first block) install packages
    # with apt-get and build; the demo then runs every stage (the other
    # blocks run those one by one) for about half a minute more, writing
    # demo-out/ into the tree; make test runs the suite, this test included.
    "make demo": "apt-get, the build and the whole demo: too long, and its stages are the other"
                 " blocks",
    "make test": "apt-get, the build and the test suite, this test included",
    "ctest --test-dir build -L unit": "the test suite itself (make test runs it)",
    "ctest --test-dir build -L 'unit|malformed'": "the test suite itself (make test runs it)",
    "ctest --test-dir build -L verification": "the test suite itself, this test included",
    "make test-sanitize": "a second build and the suite under sanitizers: tens of minutes",
    "make fuzz": "a third build and 8 x 60 s of fuzzing",
    "/usr/bin/python3 -m venv --system-site-packages .venv && .venv/bin/pip install"
    " --no-build-isolation .": "a build of the module in build-pip/ (minutes); CI's stage"
                              " pip-install runs it, reusing build/",
}

# Size overrides: (README text, replacement, why). Each text must occur in
# exactly one README command. Dropped with LAMINA_README_FULL=1.
SMALL = [
    ("cases/cells/polyurea-two-scale.toml --name pu-rom-8 --reduced-order --partitions 8",
     "cases/cells/polyurea-two-scale.toml --name pu-rom-8 --reduced-order --partitions 8"
     " --resolution 16",
     "16 partitions' influence functions at 32^3: 7 s; at 16^3 under 1 s"),
    ("sphere-plain.toml --resolution 128", "sphere-plain.toml --resolution 16",
     "the benchmark's 128^3 cell: 3 s idle and 337 MiB; 16^3 is instant"),
]

# Files the README's prose says how to make, made before the blocks run:
# (file, made from, lines dropped). The Benchmarks block uses sphere-plain.toml,
# "cases/cells/sphere.toml without its size line".
SETUP = [("sphere-plain.toml", "cases/cells/sphere.toml", r"^size\s*=")]


# Readers: each takes (root, outputs) -- the temporary tree and a dict
# command -> its output (parsed JSON for the figure's json commands, text for
# its stdout commands) -- and returns the figures in the quote's order.

def _json_of(outputs, command):
    return outputs[command]


def _summary(root, out):
    with open(os.path.join(root, out, "summary.json")) as f:
        return json.load(f)


def _last_row(root, out, name="probes.csv"):
    with open(os.path.join(root, out, name)) as f:
        return list(csv.DictReader(f))[-1]


def converge_rates(command):
    def read(root, outputs):
        r = _json_of(outputs, command)["rates"]["displacement"]
        return [r["L1"], r["L2"], r["Linf"]]
    return read


def voxel_fraction(command, phase):
    """A phase's voxel fraction (%) from micro's report."""
    def read(root, outputs):
        m = re.search(r"phase \d+ %s\s+voxel fraction ([0-9.eE+-]+)" % phase, outputs[command])
        return [100 * float(m.group(1))]
    return read


def framed_panel(out, bag):
    """Terminal velocity of the centre (m/s, at the end) and, with bag, the
    depth of the centre below the frame (corner) at the end (m)."""
    def read(root, _):
        row = _last_row(root, out)
        values = [-float(row["centre_vz"])]
        if bag:
            values.append(float(row["corner_uz"]) - float(row["centre_uz"]))
        return values
    return read


def polyurea_blast(root, _):
    gvbo, elastic = _summary(root, "out/blast-gvbo"), _summary(root, "out/blast-elastic")
    return [gvbo["max_abs_w"], elastic["max_abs_w"],
            gvbo["energy"]["inelastic_dissipation"] / 1e3, gvbo["energy"]["external_work"] / 1e3]


def sheet_impact(root, _):
    runs = {m: _summary(root, "out/impact-" + m)
            for m in ("polyurea-elastic-rest", "polyurea-gvbo", "pu-rom")}
    deeper = runs["polyurea-gvbo"]["max_abs_w"] / runs["polyurea-elastic-rest"]["max_abs_w"] - 1
    return [100 * deeper, runs["polyurea-gvbo"]["energy"]["inelastic_dissipation"],
            runs["polyurea-gvbo"]["energy"]["initial"],
            runs["pu-rom"]["energy"]["inelastic_dissipation"]]


def blast_roof(root, _):
    d = _summary(root, "out/roof")["drag_comparison"]
    return [d["with_drag"]["max_abs_w"], d["with_drag"]["peak_support_reaction"] / 1e3,
            d["without_drag"]["max_abs_w"], d["without_drag"]["peak_support_reaction"] / 1e3]


MICRO_WEAVE = "build/bin/micro cases/cells/plain-weave.toml --out weave.h5"
def reduced_order_accuracy(root, _):
    """plot_rom.py's table (rom-study/table.md, one scheme, one partition per phase):
    the smallest and largest disagreement where the soft domains flow
    (uniaxial stress; shear below 1e5 /s), then the same elsewhere (%)."""
    with open(os.path.join(root, "rom-study", "table.md")) as f:
        rows = [line.strip("| \n").split(" | ") for line in f if line.startswith("| ")][1:]
    flow, rest = [], []
    for path, rate, value in rows:
        flows = path == "uniaxial-stress" or (path == "shear" and rate != "1e5")
        (flow if flows else rest).append(float(value.rstrip(" %")))
    return [min(flow), max(flow), min(rest), max(rest)]


ROM_STUDY = "/usr/bin/python3 scripts/plot_rom.py --partitions 1 --schemes clustering --out rom.png"
CONVERGE_5 = ("build/bin/membrane converge cases/membrane/case5.toml --levels 4"
              " --set mesh.nx=10 --set time.dt=2e-5")
CONVERGE_3 = ("build/bin/membrane converge cases/membrane/case3.toml --levels 4"
              " --set mesh.nx=10 --set time.dt=2e-5")
CONVERGE_PATCH = "build/bin/membrane converge cases/membrane/case3-patch.toml --levels 4"
FRAMED = "build/bin/membrane run cases/membrane/framed-panel-large-deflection.toml"

# Each figure: quote (README text; its numbers are the figures), commands
# (README text printed beside the quote), read (a reader above), json and
# stdout (the commands whose JSON output or text the reader takes), full
# (checked only with LAMINA_README_FULL=1).
FIGURES = [
    dict(quote="in epoxy, 41 %", commands=[MICRO_WEAVE], stdout=[MICRO_WEAVE],
         read=voxel_fraction(MICRO_WEAVE, "yarn")),
    dict(quote="gives 1.78 / 1.67 / 1.33", commands=[CONVERGE_5], json=[CONVERGE_5],
         read=converge_rates(CONVERGE_5)),
    dict(quote="converges only at 0.92 / 0.72 / 0.59", commands=[CONVERGE_3], json=[CONVERGE_3],
         read=converge_rates(CONVERGE_3)),
    dict(quote="converges at 1.60 / 1.50 / 1.70", commands=[CONVERGE_PATCH],
         json=[CONVERGE_PATCH], read=converge_rates(CONVERGE_PATCH)),
    dict(quote="lets it in 39 % deeper and dissipates 34 of the 72 J, the\ntwo-scale cell 23 J",
         commands=["build/bin/homogenize cases/cells/polyurea-two-scale.toml --name pu-rom"
                   " --reduced-order --scheme clustering",
                   "build/bin/membrane run cases/membrane/polyurea-sheet-impact.toml"
                   " --out out/impact-$m --set \"section[0].material=$m\""],
         read=sheet_impact),
    dict(quote="falls at 23.4 m/s, the bag 0.47 m deep",
         commands=[FRAMED + " --out out/framed"], read=framed_panel("out/framed", True)),
    dict(quote="at 21.6 m/s",
         commands=[FRAMED + " --out out/framed-resultant --set 'drag[0].velocity=\"resultant\"'"],
         read=framed_panel("out/framed-resultant", False)),
    dict(quote="peak deflection 0.304 / 0.196 m, GVBO dissipates 13.3 of 13.8 kJ",
         commands=["build/bin/membrane run cases/membrane/polyurea-blast.toml --out out/blast-gvbo",
                   "build/bin/membrane run cases/membrane/polyurea-blast.toml --out"
                   " out/blast-elastic --set section[0].material=polyurea-elastic-rest"],
         read=polyurea_blast),
    dict(quote="at 1.01 m and the supports take 178 kN (without: 1.90 m, 332 kN",
         commands=["build/bin/membrane run cases/membrane/blast-roof.toml --out out/roof"],
         read=blast_roof),
    # full: nine 60-step full-field nonlinear cells at 32^3, about 70 s of CPU
    # (as much as all the rest), for a figure of a study, not of a command the
    # pipeline needs
    dict(quote="within 2.8-4.3 % of the full-field cell in\nuniaxial stress and shear (0.2-3.6 %",
         commands=[ROM_STUDY], read=reduced_order_accuracy, full=True),
]

NUMBER = re.compile(r"(?<![\w.\[])-?\d+(?:\.\d+)?(?![\w\]])")
FENCE = re.compile(r"^\s*(```|~~~)\s*([\w+-]*)")


def squash(text):
    return " ".join(text.split())


class Readme:
    """The README's units: paragraphs (and table rows) and fenced blocks, in
    order, each with its first line number and its text."""

    def __init__(self, path):
        with open(path, encoding="utf-8") as f:
            self.lines = f.read().split("\n")
        self.units = []  # dicts: kind (text/block), line, text, info, lines
        fence, block, para = None, None, None
        for number, line in enumerate(self.lines, 1):
            if fence:
                if line.strip().startswith(fence):
                    self.units.append(block)
                    fence, block = None, None
                else:
                    block["lines"].append((number, line))
                continue
            m = FENCE.match(line)
            if m:
                para = None
                fence = m.group(1)
                block = dict(kind="block", line=number, info=m.group(2).lower(), lines=[])
                continue
            if not line.strip():
                para = None
                continue
            if line.lstrip().startswith("|"):
                self.units.append(dict(kind="text", line=number, text=line))
                para = None
                continue
            if para is None:
                para = dict(kind="text", line=number, text=line)
                self.units.append(para)
            else:
                para["text"] += "\n" + line
        for u in self.units:
            if u["kind"] == "block":
                u["commands"] = logical_commands(u["lines"])
                u["text"] = "\n".join(c for _, c in u["commands"])

    def command_blocks(self):
        blocks = []
        for u in self.units:
            if u["kind"] != "block" or u["info"] not in SHELLS:
                continue
            first = next((t for _, t in u["lines"] if t.strip()), "")
            if u["info"] == "" and any(first.startswith(n) for n in NOT_COMMANDS):
                continue
            blocks.append(u)
        return blocks


def logical_commands(lines):
    """(README line, command) per logical line: continuations joined, blank
    lines and whole-line comments dropped."""
    out, pending, start = [], "", None
    for number, line in lines:
        if not pending and (not line.strip() or line.strip().startswith("#")):
            continue
        if start is None:
            start = number
        if line.rstrip().endswith("\\"):
            pending += line.rstrip()[:-1].rstrip() + " "
            continue
        out.append((start, (pending + line.strip()).strip()))
        pending, start = "", None
    return out


def strip_comment(command):
    """A command without a trailing ' # comment' outside quotes."""
    quote = None
    for i, ch in enumerate(command):
        if quote:
            if ch == quote:
                quote = None
        elif ch in "'\"":
            quote = ch
        elif ch == "#" and i > 0 and command[i - 1] in " \t":
            return command[:i].rstrip()
    return command


NESTING = re.compile(r"(?:^|[;&|]\s*|\bdo\s+|\bthen\s+)(for|while|until|if|case)\b")
CLOSING = re.compile(r"(?:^|[;&|]\s*)(done|fi|esac)\b")


def block_script(block, skip, small):
    """The bash text of a block and, per script line, its README line."""
    body = ["set -eo pipefail",
            "trap 'rc=$?; echo \"@@failed $LINENO $rc\" >&2' ERR"]
    where = [None, None]
    depth = 0
    for number, command in block["commands"]:
        bare = strip_comment(command)
        if bare in skip:
            body.append(": skipped")
            where.append(number)
            continue
        for old, new, _ in small:
            if old in bare:
                bare = bare.replace(old, new)
        depth += len(NESTING.findall(bare)) - len(CLOSING.findall(bare))
        body.append(bare)
        where.append(number)
        if depth == 0:
            body.append('st=$?; [ "$st" = 0 ] || { echo "@@failed $((LINENO - 1)) $st" >&2; exit "$st"; }')
            where.append(number)
    return "\n".join(body) + "\n", where


def make_tree(source, build, root):
    for d in ("cases", "scripts"):
        shutil.copytree(os.path.join(source, d), os.path.join(root, d), symlinks=True)
    os.makedirs(os.path.join(root, "build"))
    os.symlink(os.path.join(os.path.abspath(build), "bin"), os.path.join(root, "build", "bin"))
    if os.path.isdir(os.path.join(build, "python")):  # the Python module (README, "Python")
        os.symlink(os.path.join(os.path.abspath(build), "python"),
                   os.path.join(root, "build", "python"))
    for name, origin, drop in SETUP:
        if os.path.exists(os.path.join(root, origin)):
            with open(os.path.join(root, origin)) as f:
                kept = [line for line in f if not re.match(drop, line)]
            with open(os.path.join(root, name), "w") as f:
                f.writelines(kept)


def environment(home):
    env = dict(os.environ)
    for key in ("LAMINA_LIBRARY", "LAMINA_FFTW_WISDOM"):
        env.pop(key, None)
    env.update(HOME=home, XDG_DATA_HOME=os.path.join(home, ".local", "share"),
               MPLCONFIGDIR=os.path.join(home, "mpl"), MPLBACKEND="Agg")
    return env


def run_blocks(readme, root, env, skip, small, errors):
    """Runs every command block; returns the set of commands that ran as
    written (no override)."""
    ran = set()
    for block in readme.command_blocks():
        text, where = block_script(block, skip, small)
        p = subprocess.run(["bash", "-c", text], cwd=root, env=env, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
        failed = re.findall(r"^@@failed (\d+) (\d+)$", p.stderr, re.M)
        if p.returncode != 0 or failed:
            line, rc = (int(failed[0][0]), failed[0][1]) if failed else (None, str(p.returncode))
            number = where[line - 1] if line and line - 1 < len(where) else block["line"]
            command = next((c for n, c in block["commands"] if n == number), "(the block)")
            tail = [t for t in p.stderr.strip().split("\n") if not t.startswith("@@failed")][-3:]
            errors.append(f"README.md:{number}: `{command}` exited {rc}: " + " | ".join(tail))
            continue
        for _, command in block["commands"]:
            bare = strip_comment(command)
            if not any(old in bare for old, _, _ in small):
                ran.add(squash(bare))
    return ran


def beside(readme, quote, command):
    """True if command is printed in the unit holding quote, or in a fenced
    block adjacent to it."""
    units = readme.units
    for i, u in enumerate(units):
        if u["kind"] != "text" or squash(quote) not in squash(u["text"]):
            continue
        near = [u] + [units[j] for j in (i - 1, i + 1)
                      if 0 <= j < len(units) and units[j]["kind"] == "block"]
        return any(squash(command) in squash(n["text"]) for n in near)
    return False


def quote_line(readme, quote):
    for u in readme.units:
        if u["kind"] == "text" and squash(quote) in squash(u["text"]):
            return u["line"]
    return None


def figure_outputs(readme, root, env, ran, fig, where):
    """Runs the figure's commands that no block ran as written (and those
    whose output the reader takes); returns their outputs, or a failure."""
    outputs = {}
    for command in fig["commands"]:
        as_json = command in fig.get("json", [])
        wanted = as_json or command in fig.get("stdout", [])
        if squash(command) in ran and not wanted:
            continue
        if not wanted and any(squash(command) in squash(b["text"])
                              for b in readme.command_blocks()):
            return None, (f"{where}: `{command}` did not run as written (its block failed, or"
                          " SMALL shrinks it: mark the figure full)")
        p = subprocess.run(["bash", "-c", command + (" --json" if as_json else "")], cwd=root,
                           env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if p.returncode != 0:
            return None, (f"{where}: `{command}` exited {p.returncode}: "
                          + " | ".join(p.stderr.strip().split("\n")[-2:]))
        if wanted:
            outputs[command] = json.loads(p.stdout) if as_json else p.stdout
        ran.add(squash(command))
    return outputs, None


def compare(quote, values, where):
    """Failures of the figures read against the numbers quoted: each must
    be within half a unit of its last quoted digit."""
    quoted = NUMBER.findall(squash(quote))
    if len(quoted) != len(values):
        return [f"{where}: {len(quoted)} numbers quoted, {len(values)} read (update FIGURES)"]
    failures = []
    for q, v in zip(quoted, values):
        decimals = len(q.split(".")[1]) if "." in q else 0
        if not math.isfinite(v) or abs(v - float(q)) > 0.5 * 10 ** -decimals * (1 + 1e-9):
            failures.append(f"{where}: {q} quoted, the command gives {v:.6g}")
    return failures


def check_figures(readme, root, env, ran, figures, full, errors):
    """Checks every figure of the table; returns how many were checked."""
    checked = 0
    for fig in figures:
        quote = fig["quote"]
        line = quote_line(readme, quote)
        if line is None:
            errors.append(f"README.md: the figure '{squash(quote)}' is not in the README"
                          " (update FIGURES)")
            continue
        if fig.get("full") and not full:
            continue
        where = f"README.md:{line}: '{squash(quote)}'"
        missing = [c for c in fig["commands"] if not beside(readme, quote, c)]
        if missing:
            errors.append(f"{where}: the command `{missing[0]}` is not printed beside it")
            continue
        outputs, failure = figure_outputs(readme, root, env, ran, fig, where)
        if failure:
            errors.append(failure)
            continue
        try:
            values = fig["read"](root, outputs)
        except (OSError, KeyError, ValueError, IndexError, AttributeError) as e:
            errors.append(f"{where}: could not read the figures: {e!r}")
            continue
        errors += compare(quote, values, where)
        checked += 1
    return checked


def check(source, build, skip=SKIP, small=SMALL, figures=FIGURES, full=False, keep=False):
    """Returns (errors, number of commands run, number of figures checked)."""
    readme = Readme(os.path.join(source, "README.md"))
    errors = []
    small = [] if full else small
    commands = [strip_comment(c) for b in readme.command_blocks() for _, c in b["commands"]]
    for name in skip:
        if name not in commands:
            errors.append(f"SKIP: '{name}' is no README command (update the table)")
    for old, _, _ in small:
        hits = sum(old in c for c in commands)
        if hits != 1:
            errors.append(f"SMALL: '{old}' matches {hits} README commands, not 1"
                          " (update the table)")
    temp = tempfile.mkdtemp(prefix="lamina-readme-")
    try:
        root = os.path.join(temp, "repo")
        home = os.path.join(temp, "home")
        os.makedirs(root)
        os.makedirs(home)
        make_tree(source, build, root)
        env = environment(home)
        ran = run_blocks(readme, root, env, skip, small, errors)
        checked = check_figures(readme, root, env, ran, figures, full, errors)
    finally:
        if keep:
            print(f"kept {temp}")
        else:
            shutil.rmtree(temp, ignore_errors=True)
    return errors, len(commands), checked


PLANTED_README = """# Tree

```sh
make demo    # skipped
build/bin/tool hello > hello.txt
build/bin/tool fail
```

```
core/        not a command
```

```sh
cd nowhere && build/bin/tool hello
```

The tool (`build/bin/tool answer`) answers 42; `build/bin/tool answer --out x` answers 41.
"""
PLANTED_TOOL = """#!/bin/sh
case "$1" in
  hello) echo hello ;;
  fail) echo "tool: failing on purpose" >&2; exit 3 ;;
  answer) case "$*" in *--json*) echo '{"answer": 42}' ;; *) echo 42 ;; esac ;;
  *) echo "{\\"answer\\": 42}" ;;
esac
"""
PLANTED_FIGURES = [
    dict(quote="answers 42", commands=["build/bin/tool answer"], json=["build/bin/tool answer"],
         read=lambda root, out: [out["build/bin/tool answer"]["answer"]]),
    dict(quote="answers 41", commands=["build/bin/tool answer --out x"],
         json=["build/bin/tool answer --out x"],
         read=lambda root, out: [out["build/bin/tool answer --out x"]["answer"]]),
]
EXPECTED = [
    "README.md:6: `build/bin/tool fail` exited 3",
    "README.md:14: `cd nowhere && build/bin/tool hello` exited 1",
    "README.md:17: 'answers 41': 41 quoted, the command gives 42",
    "SMALL: 'no such text' matches 0 README commands",
]


def self_test():
    """Plants a failing command, a failing `cd X && ...` (which errexit
    alone lets pass), a wrong figure (beside a right one) and a stale
    override; fails unless each is reported and nothing else."""
    with tempfile.TemporaryDirectory() as source:
        os.makedirs(os.path.join(source, "cases"))
        os.makedirs(os.path.join(source, "scripts"))
        os.makedirs(os.path.join(source, "build", "bin"))
        with open(os.path.join(source, "README.md"), "w") as f:
            f.write(PLANTED_README)
        tool = os.path.join(source, "build", "bin", "tool")
        with open(tool, "w") as f:
            f.write(PLANTED_TOOL)
        os.chmod(tool, 0o755)
        errors, _, _ = check(source, os.path.join(source, "build"), skip={"make demo": "planted"},
                             small=[("no such text", "x", "planted")], figures=PLANTED_FIGURES)
    return compare_planted(errors, EXPECTED)


def main():
    args = sys.argv[1:]
    if args == ["--self-test"]:
        return self_test()
    keep = "--keep" in args
    args = [a for a in args if a != "--keep"]
    if len(args) != 2:
        print(__doc__)
        return 2
    full = os.environ.get("LAMINA_README_FULL") == "1"
    errors, commands, figures = check(os.path.abspath(args[0]), os.path.abspath(args[1]),
                                      full=full, keep=keep)
    for e in errors:
        print(e)
    if errors:
        print(f"{len(errors)} failures ({commands} README commands, {figures} figures checked)")
        return 1
    print(f"{commands} README commands run or skipped as listed, {figures} figures reproduced"
          + (" (full size)" if full else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
