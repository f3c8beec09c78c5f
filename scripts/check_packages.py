#!/usr/bin/python3
"""Checks that the build, the tests and the scripts use nothing beyond scripts/setup.sh.

A fresh Debian machine has the packages of a base system plus what scripts/setup.sh installs
(its package lists and their dependencies). A file that the configure, the build or a test
touches but that belongs to any other package is a missing install step: it works on a machine
that happens to have the package and fails on a new one. This script finds such files.

    check_packages.py run [--trace FILE] -- COMMAND...
        Runs COMMAND under strace, recording every file opened, stat'ed or executed by it and
        its children, then reports as `report` does. Exit status: COMMAND's if it failed, else
        1 if the report found a problem, else 0.
    check_packages.py report TRACE
        Reports on a trace written by `run` (or by strace -f -o with the same syscalls).
    check_packages.py files FILE...
        Reports on the given paths as if a traced command had opened them (the self-test).

The report names every package outside the allowed set that owns a touched file (with example
files), and every executed program outside the repository and temporary directories that no
Debian package owns (a tool on PATH that a new machine would not have, e.g. another python3).

Allowed: the packages named in scripts/setup.sh's package lists (or in --packages FILE, one
per line, for the self-test), the installed packages they depend on (Depends and Pre-Depends,
recursively; for an alternative `a | b`, the first one that is installed), and the packages a
base system always has (Essential, priority required or important). Ownership comes from dpkg's
database (/var/lib/dpkg/info/*.list), read once.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
DPKG = Path("/var/lib/dpkg")
TRACED_SYSCALLS = "execve,open,openat,stat,lstat,newfstatat,statx,access,faccessat,faccessat2,readlink"
# The first quoted absolute path of a traced call, and its result (a number or -1 ERRNO).
CALL = re.compile(r'^(?:\d+\s+)?(?P<call>\w+)\((?:AT_FDCWD, |-?\d+, )?"(?P<path>/[^"]*)"')
RESUMED = re.compile(r'^(?:\d+\s+)?<\.\.\. (?P<call>\w+) resumed>')
RESULT = re.compile(r'\)\s+=\s+(?P<ret>-?\d+)(?:\s+(?P<errno>E[A-Z0-9]+))?')
UNFINISHED = "<unfinished ...>"
# Files that programs read only if present and work the same without: not a dependency. Each
# is a directory or file that a program scans whatever packages put there.
OPTIONAL_FILES = [
    (r"^/usr/share/locale/locale\.alias$", "glibc reads it when the locales package is installed"),
    (r"^/etc/ld\.so\.conf\.d/", "ldconfig reads every file other packages put there"),
    (r"/bfd-plugins/", "binutils (ar, nm, ld) loads every linker plugin installed there"),
    (r"^/usr/lib/ssl/openssl\.cnf$", "OpenSSL reads its configuration file when openssl is installed"),
    (r"^/usr/lib/python3/dist-packages/[^/]+\.pth$", "Python's site module runs every .pth file installed"),
    (r"^/usr/lib/python3/dist-packages/_distutils_hack/", "imported by setuptools' .pth file, when installed"),
    (r"^/usr/lib/python3/dist-packages/[^/]+\.(?:dist|egg)-info/entry_points\.txt$",
     "importlib.metadata reads every installed distribution's entry points (Dask looks up its plugins)"),
    (r"^/usr/lib/debug/", "symbolizers read separate debug information when it is installed"),
    (r"^/usr/share/fonts/", "fontconfig offers every installed font; Chromium opens faces that happen to be there "
                            "(DejaVu Sans Oblique of fonts-dejavu-extra at start-up) and draws without them"),
]
OPTIONAL = re.compile("|".join(f"(?:{p})" for p, _ in OPTIONAL_FILES))


def setup_packages():
    """The packages of scripts/setup.sh (its DEFAULT_PACKAGES=( ... ) and FULL_PACKAGES=( ... )
    lists: the default job's and the rest), comments removed."""
    text = (REPO / "scripts" / "setup.sh").read_text()
    lists = re.findall(r"^(?:DEFAULT|FULL)_PACKAGES=\((.*?)^\)", text, re.S | re.M)
    if len(lists) != 2:
        sys.exit("check_packages: scripts/setup.sh has no DEFAULT_PACKAGES=( ... ) and FULL_PACKAGES=( ... ) lists")
    names = []
    for body in lists:
        for line in body.splitlines():
            names += line.split("#", 1)[0].split()
    return names


def installed_packages():
    """name -> fields of every installed package in dpkg's status file."""
    pkgs = {}
    for block in (DPKG / "status").read_text(errors="replace").split("\n\n"):
        fields, key = {}, None
        for line in block.splitlines():
            if line[:1] in (" ", "\t") and key:
                fields[key] += " " + line.strip()
            elif ":" in line:
                key, value = line.split(":", 1)
                fields[key] = value.strip()
        if fields.get("Status", "").endswith(" installed") and "Package" in fields:
            pkgs[fields["Package"]] = fields
    return pkgs


def dep_groups(field):
    """'a (>= 1) | b:any, c' -> [['a', 'b'], ['c']]."""
    groups = []
    for group in field.split(","):
        alts = [re.sub(r"[\s(\[].*", "", a.strip()).split(":")[0] for a in group.split("|")]
        alts = [a for a in alts if a]
        if alts:
            groups.append(alts)
    return groups


def allowed_packages(roots, pkgs):
    providers = {}
    for name, f in pkgs.items():
        for group in dep_groups(f.get("Provides", "")):
            providers.setdefault(group[0], []).append(name)
    base = [n for n, f in pkgs.items()
            if f.get("Essential") == "yes" or f.get("Priority") in ("required", "important")]
    missing = [r for r in roots if r not in pkgs]
    allowed = set()
    todo = [r for r in roots if r in pkgs] + base
    while todo:
        name = todo.pop()
        if name in allowed:
            continue
        allowed.add(name)
        f = pkgs[name]
        for group in dep_groups(f.get("Depends", "") + "," + f.get("Pre-Depends", "")):
            for alt in group:  # the first alternative that is installed, as apt would pick
                chosen = [alt] if alt in pkgs else providers.get(alt, [])
                if chosen:
                    todo += [c for c in chosen if c not in allowed]
                    break
    return allowed, missing


def file_owners():
    """path -> [package] from dpkg's file lists (symlinks and files; directories are shared)."""
    owners = {}
    for lst in (DPKG / "info").glob("*.list"):
        pkg = lst.name[:-5].split(":")[0]
        for path in lst.read_text(errors="replace").splitlines():
            owners.setdefault(path, []).append(pkg)
    return owners


def owner_of(path, owners):
    """Owners of a path as dpkg names it: normalised, resolved, with or without the /usr merge."""
    candidates = [os.path.normpath(path), os.path.realpath(path)]
    for c in list(candidates):
        for top in ("/bin/", "/sbin/", "/lib/", "/lib64/"):
            if c.startswith(top):
                candidates.append("/usr" + c)
            elif c.startswith("/usr" + top):
                candidates.append(c[4:])
    for c in candidates:
        if c in owners:
            return owners[c]
    return []


def parse_trace(trace):
    """(touched, executed, optional): absolute paths of files the traced processes used
    successfully; `optional` holds those matching OPTIONAL_FILES (kept out of `touched`)."""
    touched, executed, optional = set(), set(), set()
    pending = {}  # pid -> (call, path) of an unfinished call
    with open(trace, errors="replace") as f:
        for line in f:
            pid = line.split(None, 1)[0] if line[:1].isdigit() else ""
            m = CALL.match(line)
            if m:
                call, path = m.group("call"), m.group("path")
                if UNFINISHED in line:
                    pending[pid] = (call, path)
                    continue
            else:
                r = RESUMED.match(line)
                if not r or pid not in pending:
                    continue
                call, path = pending.pop(pid)
            res = RESULT.search(line)
            if not res or int(res.group("ret")) < 0:
                continue  # failed look-ups (ENOENT and the like) touch nothing
            if os.path.isdir(path) or not os.path.lexists(path):
                continue
            if OPTIONAL.search(os.path.normpath(path)):
                optional.add(path)
                continue
            touched.add(path)
            if call == "execve":
                executed.add(path)
    return touched, executed, optional


def report(touched, executed, package_list, optional=()):
    pkgs = installed_packages()
    roots = package_list if package_list is not None else setup_packages()
    allowed, missing = allowed_packages(roots, pkgs)
    owners = file_owners()
    # An optional file that is a plugin loads its own dependencies (binutils' LLVM plugin loads
    # libLLVM): the packages of optional files and their dependencies are exempt too.
    optional_owners = sorted({o for p in optional for o in owner_of(p, owners)})
    exempt, _ = allowed_packages(optional_owners, pkgs) if optional_owners else (set(), [])
    outside = {}
    for path in sorted(touched):
        for pkg in owner_of(path, owners):
            if pkg not in allowed and pkg not in exempt:
                outside.setdefault(pkg, []).append(path)
    scratch = [str(REPO), tempfile.gettempdir(), "/tmp", "/proc", "/dev"]
    foreign = sorted(p for p in executed
                     if not owner_of(p, owners)
                     and not any(os.path.realpath(p).startswith(s.rstrip("/") + "/") for s in scratch))
    ok = True
    if missing:
        print(f"check_packages: not installed although listed in setup.sh: {' '.join(missing)}")
        ok = False
    for pkg, paths in sorted(outside.items()):
        examples = ", ".join(paths[:3]) + (f" (+{len(paths) - 3} more)" if len(paths) > 3 else "")
        print(f"check_packages: package '{pkg}' is used but not installed by scripts/setup.sh: {examples}")
        ok = False
    for path in foreign:
        print(f"check_packages: program '{path}' was run but belongs to no Debian package")
        ok = False
    n_pkgs = len({o for p in touched for o in owner_of(p, owners)})
    print(f"check_packages: {len(touched)} files touched, {len(executed)} programs run, from "
          f"{n_pkgs} packages; {len(allowed)} packages allowed (setup.sh's {len(roots)} with dependencies "
          f"and the base system): {'OK' if ok else 'FAILED'}")
    return ok


def run(args):
    cmd = args.command[1:] if args.command[:1] == ["--"] else args.command
    if not cmd:
        sys.exit("check_packages: run: no command given")
    strace = shutil.which("strace")
    works = strace and subprocess.run([strace, "-f", "-qq", "-o", "/dev/null", "true"],
                                      stderr=subprocess.DEVNULL).returncode == 0
    if not works:
        # Without ptrace (some containers forbid it) nothing can be recorded: the command still
        # runs, but CI (CI=true) must not pass without the check.
        msg = "check_packages: strace cannot trace here (not installed or ptrace not permitted)"
        if os.environ.get("CI") or os.environ.get("TESSIM_REQUIRE_PACKAGE_CHECK"):
            sys.exit(msg)
        print(msg + "; running without the package check", file=sys.stderr)
        return subprocess.run(cmd).returncode
    trace = Path(args.trace) if args.trace else Path(tempfile.mkstemp(prefix="tessim-trace-")[1])
    trace.parent.mkdir(parents=True, exist_ok=True)
    # --seccomp-bpf stops the traced processes only at the traced calls: the build and the tests
    # run at nearly full speed.
    status = subprocess.run([strace, "-f", "--seccomp-bpf", "-qq", "-s", "4096", "-e", f"trace={TRACED_SYSCALLS}",
                             "-e", "signal=none", "-o", str(trace), "--", *cmd]).returncode
    touched, executed, optional = parse_trace(trace)
    if not args.trace:
        trace.unlink()
    ok = report(touched, executed, None, optional)
    if status != 0:
        print(f"check_packages: the command failed with exit status {status}", file=sys.stderr)
        return status
    return 0 if ok else 1


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="mode", required=True)
    r = sub.add_parser("run", help="run a command under strace and report")
    r.add_argument("--trace", help="keep the trace in this file")
    r.add_argument("command", nargs=argparse.REMAINDER)
    p = sub.add_parser("report", help="report on an existing trace")
    p.add_argument("trace")
    p.add_argument("--packages", help="allowed packages, one per line (default: setup.sh's list)")
    f = sub.add_parser("files", help="report on the given paths as if they had been opened")
    f.add_argument("--packages", help="allowed packages, one per line (default: setup.sh's list)")
    f.add_argument("--executed", action="append", default=[], help="a path that was executed")
    f.add_argument("paths", nargs="*")
    args = ap.parse_args()

    if args.mode == "run":
        return run(args)
    package_list = None
    if args.packages:
        package_list = [w for line in Path(args.packages).read_text().splitlines()
                        for w in line.split("#", 1)[0].split()]
    if args.mode == "report":
        touched, executed, optional = parse_trace(args.trace)
    else:
        touched, executed, optional = set(args.paths) | set(args.executed), set(args.executed), set()
    return 0 if report(touched, executed, package_list, optional) else 1


if __name__ == "__main__":
    sys.exit(main())
