#!/usr/bin/env python3
"""No function of the library over 80 lines, unless it says why.

A function a reader can hold in view does one thing.
This check lists every function defined in the library folders (core,
materials, micro, homogenize, membrane; the programs' mains included) and
fails on each one longer than the limit, naming its file, name, first line
and length, unless the line just above its first line (above its
`template <...>` line, if any) is a one-line comment

    // long: <why it must be longer>

Functions are found by universal-ctags (Debian package universal-ctags):

    ctags --fields=+ne --c++-kinds=f -f - FILES

which gives each definition's first line (the line of its name) and last
line. A lambda inside a function counts in that function's length and is not
checked apart; a lambda at namespace scope is checked like a function.

Usage:
    function_length.py [--max N] ROOT      check ROOT's library folders
    function_length.py --self-test         show that the check can fail

Exit status: 0 all short (or justified), 1 a long function, 2 the check
could not run (no universal-ctags, no sources).
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

FOLDERS = ("core", "materials", "micro", "homogenize", "membrane")
SUFFIXES = (".cpp", ".hpp", ".h", ".cc")
DEFAULT_MAX = 80
JUSTIFICATION = re.compile(r"^\s*//\s*long:\s*\S")
TEMPLATE_LINE = re.compile(r"^\s*template\s*<")


class CheckError(Exception):
    """The check could not run (exit status 2)."""


def find_ctags():
    """The path of universal-ctags, or CheckError saying how to get it."""
    for name in ("ctags", "ctags-universal", "universal-ctags"):
        path = shutil.which(name)
        if not path:
            continue
        try:
            version = subprocess.run([path, "--version"], capture_output=True, text=True,
                                     check=False).stdout
        except OSError:
            continue
        if "Universal Ctags" in version:
            return path
    raise CheckError("universal-ctags is not installed (it lists the functions this check "
                     "measures): install the Debian package universal-ctags "
                     "(scripts/install-deps.sh, run by `make test`, installs it)")


def source_files(root, folders=FOLDERS):
    """Every C++ source and header under root/<folder>, sorted."""
    files = []
    for folder in folders:
        top = os.path.join(root, folder)
        for dirpath, dirnames, filenames in os.walk(top):
            dirnames.sort()
            files += [os.path.join(dirpath, f) for f in sorted(filenames)
                      if f.endswith(SUFFIXES)]
    return files


def functions(ctags, files):
    """(file, name, scope kind, first line, last line) of every function in files."""
    out = subprocess.run([ctags, "--fields=+ne", "--c++-kinds=f", "--language-force=C++",
                          "-f", "-"] + files, capture_output=True, text=True, check=False)
    if out.returncode != 0:
        raise CheckError("ctags failed (status %d): %s" % (out.returncode, out.stderr.strip()))
    found = []
    for row in out.stdout.splitlines():
        if row.startswith("!_"):
            continue
        cols = row.split("\t")
        fields = dict(c.split(":", 1) for c in cols[3:] if ":" in c)
        if "line" not in fields or "end" not in fields:
            continue
        scope_kind = next((k for k in ("function", "class", "struct", "namespace")
                           if k in fields), "")
        name = cols[0]
        if name.startswith("__anon"):
            name = "<lambda>"
        # the innermost named scope: Class::method, namespace::function
        scopes = [s for s in fields.get(scope_kind, "").split("::")
                  if s and not s.startswith("__anon")]
        if scope_kind in ("class", "struct", "namespace") and scopes:
            name = scopes[-1] + "::" + name
        found.append((cols[1], name, scope_kind, int(fields["line"]), int(fields["end"])))
    return found


def justified(lines, first):
    """Whether the line above line `first` (1-based; above its template line) says `// long:`."""
    i = first - 2
    while i >= 0 and TEMPLATE_LINE.match(lines[i]):
        i -= 1
    return i >= 0 and bool(JUSTIFICATION.match(lines[i]))


def long_functions(ctags, files, limit, root):
    """Messages naming every function over `limit` lines without a `// long:` comment."""
    texts = {}
    failures = []
    for path, name, scope_kind, first, last in sorted(functions(ctags, files),
                                                      key=lambda f: (f[0], f[3])):
        length = last - first + 1
        if length <= limit:
            continue
        if name == "<lambda>" and scope_kind == "function":
            continue  # a lambda's lines count in its enclosing function
        if path not in texts:
            with open(path, encoding="utf-8", errors="replace") as f:
                texts[path] = f.read().splitlines()
        if justified(texts[path], first):
            continue
        failures.append("%s:%d: %s is %d lines (at most %d; or a `// long: why` comment on "
                        "the line above it)" % (os.path.relpath(path, root), first, name,
                                                length, limit))
    return failures


def check(root, limit):
    """Runs the check on root's library folders; returns the exit status."""
    files = source_files(root)
    if not files:
        raise CheckError("no C++ sources under %s (folders %s)" % (root, ", ".join(FOLDERS)))
    failures = long_functions(find_ctags(), files, limit, root)
    for message in failures:
        print(message)
    if failures:
        print("function_length: %d function(s) over %d lines" % (len(failures), limit))
        return 1
    print("function_length: %d files, every function at most %d lines (or justified)"
          % (len(files), limit))
    return 0


def numbered_function(name, body_lines, comment=None):
    """C++ text of a function `name` of exactly 2 + body_lines lines, after an optional line."""
    text = ([comment] if comment else []) + ["int %s(int x) {" % name]
    text += ["  x += %d;" % i for i in range(body_lines)] + ["}"]
    return "\n".join(text) + "\n"


def self_test():
    """Shows the check fails on an 81-line function and passes the others."""
    ctags = find_ctags()
    with tempfile.TemporaryDirectory() as root:
        os.makedirs(os.path.join(root, "core"))
        path = os.path.join(root, "core", "sample.cpp")
        with open(path, "w", encoding="utf-8") as f:
            f.write(numbered_function("eighty", DEFAULT_MAX - 2))
            f.write(numbered_function("eighty_one", DEFAULT_MAX - 1))
            f.write(numbered_function("justified", DEFAULT_MAX + 20, "// long: a table"))
            f.write(numbered_function("bare", DEFAULT_MAX + 20, "// long:"))
            f.write("template <int N>\n" + numbered_function("templated", DEFAULT_MAX + 20))
            f.write("// long: a table of N\ntemplate <int N>\n"
                    + numbered_function("templated_justified", DEFAULT_MAX + 20))
        failures = long_functions(ctags, source_files(root), DEFAULT_MAX, root)
    expected = ["core/sample.cpp:%d: %s is %d lines" % (line, name, length)
                for line, name, length in ((81, "eighty_one", 81), (266, "bare", 102),
                                           (369, "templated", 102))]
    ok = len(failures) == len(expected) and all(
        message.startswith(prefix) for message, prefix in zip(failures, expected))
    if not ok:
        print("function_length self-test: expected failures starting with\n  %s\ngot\n  %s"
              % ("\n  ".join(expected), "\n  ".join(failures) or "(none)"))
        return 1
    print("function_length self-test: the check names the 81-line function, an empty "
          "`// long:` and an unjustified template; passes the 80-line and justified ones")
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("root", nargs="?", help="the source tree (its library folders)")
    parser.add_argument("--max", type=int, default=DEFAULT_MAX, help="longest allowed function")
    parser.add_argument("--self-test", action="store_true",
                        help="check a generated file with functions of known lengths")
    args = parser.parse_args()
    try:
        if args.self_test:
            return self_test()
        if not args.root:
            parser.error("ROOT is required unless --self-test")
        return check(os.path.abspath(args.root), args.max)
    except CheckError as e:
        print("function_length: error: %s" % e)
        return 2


if __name__ == "__main__":
    sys.exit(main())
