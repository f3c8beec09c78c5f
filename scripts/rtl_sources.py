#!/usr/bin/python3
"""The sources an RTL list file names (rtl/tess.f, rtl/system.f, rtl/ge/ge.f): the one reader of
those lists for scripts, as cmake/rtl_sources.cmake's tessim_rtl_list is for CMake.

    rtl_sources.py LIST.f [LIST.f ...]    the sources of each list in turn, one path a line

A list names one source a line, relative to the list's directory; lines are stripped, and blank
lines and lines starting with // are skipped. Paths are joined to the list's directory as given
(not resolved), so a shell script reads them with
    mapfile -t srcs < <(/usr/bin/python3 scripts/rtl_sources.py "$root/rtl/tess.f")
"""
import sys
from pathlib import Path


def read(listing):
    """The sources of list file `listing`, in its order, as paths under its directory."""
    listing = Path(listing)
    lines = [line.strip() for line in listing.read_text().splitlines()]
    return [listing.parent / line for line in lines if line and not line.startswith("//")]


def main(argv):
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__.strip(), file=sys.stdout if argv else sys.stderr)
        return 0 if argv else 2
    try:
        for listing in argv:
            for path in read(listing):
                print(path)
    except OSError as e:
        print(f"rtl_sources.py: error: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
