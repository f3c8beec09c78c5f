#!/usr/bin/python3
"""The include layers of model/ and sim/ (docs/architecture.md, Layers).

Reads the layer lists from the header comments of model/CMakeLists.txt and sim/CMakeLists.txt
("# Layers of DIR/, lowest first" followed by "#   name: component ..." lines) and checks every
project include (#include "model/..." or "sim/...") of the .hpp/.cpp files under model/ and
sim/ and their folders (a component is named by its path below the library: "run/simulate"):
  - model/ includes nothing of sim/, and neither includes render/, app/, cosim/ or rtl/;
  - every file belongs to a component named in a layer (a new file must be placed);
  - a file includes only components of its own layer or of lower ones (no upward include);
  - the components form no cycle (a component is a header with its .cpp; "a+b" in a layer makes
    a and b one component);
  - a file in a folder of sim/ includes only its own folder and those before it, in the order of
    the "# Folders of sim/, lowest first: ..." line (a new folder must be placed there too).
Before it checks the tree, it checks itself: an upward include, a cycle and an include of a later
folder added to the parsed tree must all be reported, so that a checker which reports nothing
cannot pass.

Usage: include_layers_test.py [SOURCE_DIR]   (default: the repository holding this script)
"""

import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)
# Directories in dependency order: each may include itself and those before it.
LIBRARIES = ["model", "sim"]
FOREIGN = ("render/", "app/", "cosim/", "rtl/", "python/", "bench/", "fuzz/", "tests/")


def parse_layers(cmake_file, directory):
    """[(layer, [component patterns])] from the header comment of `cmake_file`."""
    lines = cmake_file.read_text().splitlines()
    marker = f"# Layers of {directory}/, lowest first"
    start = next((i for i, line in enumerate(lines) if line.startswith(marker)), None)
    if start is None:
        raise SystemExit(f"include_layers_test: {cmake_file}: no line starting with {marker!r}")
    layers = []
    for line in lines[start + 1:]:
        if not line.startswith("#"):
            break
        m = re.match(r"#   ([a-z_]+):\s+(.*)$", line)
        if m:
            layers.append((m.group(1), m.group(2).split()))
        elif layers and re.match(r"#\s{6,}\S", line):
            layers[-1][1].extend(line[1:].split())  # a continued list
        elif layers:
            break  # the list ends at the first other line
    if not layers:
        raise SystemExit(f"include_layers_test: {cmake_file}: no layers after {marker!r}")
    return layers


def parse_folders(cmake_file, directory):
    """The folders of `directory`, lowest first, from the "# Folders of DIR/, lowest first: ..." line."""
    marker = f"# Folders of {directory}/, lowest first:"
    for line in cmake_file.read_text().splitlines():
        if line.startswith(marker):
            return line[len(marker):].split()
    raise SystemExit(f"include_layers_test: {cmake_file}: no line starting with {marker!r}")


def folder_of(path):
    """The folder of a path below its library ("sim/run/simulate.hpp" -> "run"); None at the top."""
    parts = path.split("/")
    return parts[1] if len(parts) > 2 else None


def component_of(stem, layers):
    """(layer index, component name) of a file stem such as "blocks/te", or None.

    A name wins over a "dir/*" pattern, so that one file of a folder may sit in another layer than
    the folder's others.
    """
    for index, (_, patterns) in enumerate(layers):
        for pattern in patterns:
            if stem in pattern.split("+"):
                return index, pattern
    for index, (_, patterns) in enumerate(layers):
        for pattern in patterns:
            if pattern.endswith("/*") and stem.startswith(pattern[:-1]):
                return index, stem
    return None


def scan(root):
    """{path: [included paths]} of every .hpp/.cpp/.inc under the libraries."""
    files = {}
    for library in LIBRARIES:
        for path in sorted((root / library).rglob("*")):
            if path.suffix in (".hpp", ".cpp", ".inc", ".h") and path.is_file():
                rel = path.relative_to(root).as_posix()
                files[rel] = INCLUDE.findall(path.read_text(errors="replace"))
    return files


def library_of(path):
    return path.split("/", 1)[0]


def check(files, layers_by_library, folders=()):
    """Every violation, as text; empty when the tree keeps its layers (and `folders`, the order of
    sim/'s folders)."""
    errors = []
    for path in files:
        folder = folder_of(path)
        if library_of(path) == "sim" and folder is not None and folder not in folders:
            errors.append(f"{path}: in no folder of the folder line of sim/CMakeLists.txt")
    place = {}  # path -> (library, layer index, component)
    for path in files:
        library = library_of(path)
        stem = path[len(library) + 1:].rsplit(".", 1)[0]
        found = component_of(stem, layers_by_library[library])
        if found is None:
            errors.append(f"{path}: in no layer of {library}/CMakeLists.txt")
            continue
        place[path] = (library, found[0], found[1])
    edges = {}
    for path, includes in files.items():
        if path not in place:
            continue
        library, layer, component = place[path]
        for inc in includes:
            if inc.startswith(FOREIGN):
                errors.append(f"{path}: includes {inc} (a layer above {library}/)")
                continue
            target_library = library_of(inc)
            if target_library not in LIBRARIES:
                continue  # a header found beside the file or a third-party one
            if LIBRARIES.index(target_library) > LIBRARIES.index(library):
                errors.append(f"{path}: includes {inc}: {target_library}/ is above {library}/")
                continue
            if target_library != library:
                continue
            if inc not in files:
                errors.append(f"{path}: includes {inc}, which does not exist")
                continue
            source_folder, target_folder = folder_of(path), folder_of(inc)
            if (library == "sim" and source_folder in folders and target_folder in folders
                    and folders.index(target_folder) > folders.index(source_folder)):
                errors.append(f"{path}: includes {inc}: folder {target_folder}/ comes after {source_folder}/")
            if inc not in place:
                continue  # reported above
            _, target_layer, target_component = place[inc]
            names = [name for name, _ in layers_by_library[library]]
            if target_layer > layer:
                errors.append(f"{path}: includes {inc}: layer {names[target_layer]} is above {names[layer]}")
            key = (library, component)
            target = (library, target_component)
            if target != key:
                edges.setdefault(key, set()).add(target)
    for cycle in cycles(edges):
        errors.append("include cycle: " + " -> ".join(f"{lib}/{c}" for lib, c in cycle + [cycle[0]]))
    return errors


def cycles(edges):
    """One cycle through each strongly connected component of more than one node (Tarjan)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            scc = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                scc.append(w)
                if w == v:
                    break
            if len(scc) > 1:
                found.append(path_within(sorted(scc)[0], set(scc), edges))

    nodes = set(edges) | {w for ws in edges.values() for w in ws}
    sys.setrecursionlimit(10000)
    for v in sorted(nodes):
        if v not in index:
            visit(v)
    return found


def path_within(start, scc, edges):
    """A shortest cycle from `start` back to it inside the strongly connected component `scc`."""
    previous, frontier = {}, [start]
    while frontier:
        following = []
        for v in frontier:
            for w in sorted(edges.get(v, ())):
                if w in scc and w not in previous:
                    previous[w] = v
                    following.append(w)
        if start in previous:
            break
        frontier = following
    cycle, v = [], previous[start]
    while v != start:
        cycle.append(v)
        v = previous[v]
    return [start] + cycle[::-1]


def main():
    root = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2]
    layers = {library: parse_layers(root / library / "CMakeLists.txt", library) for library in LIBRARIES}
    folders = parse_folders(root / "sim" / "CMakeLists.txt", "sim")
    files = scan(root)

    # Self-check on the parsed tree: an include from the lowest layer of sim/ to its highest, and
    # a pair of components of one layer that include each other, must both be reported.
    def first_file(library, layer):
        for path in files:
            if library_of(path) == library and path.endswith(".hpp"):
                stem = path[len(library) + 1:].rsplit(".", 1)[0]
                found = component_of(stem, layers[library])
                if found and found[0] == layer:
                    return path
        raise SystemExit(f"include_layers_test: no header in layer {layer} of {library}/")

    low, high = first_file("sim", 0), first_file("sim", len(layers["sim"]) - 1)
    upward = dict(files)
    upward[low] = files[low] + [high]
    if not any(e.startswith(f"{low}: includes {high}: layer") for e in check(upward, layers)):
        raise SystemExit(f"include_layers_test: self-check: {low} including {high} was not reported")
    a = first_file("sim", len(layers["sim"]) - 1)
    top = [p for p in files if p.endswith(".hpp") and library_of(p) == "sim"
           and component_of(p[4:-4], layers["sim"]) is not None
           and component_of(p[4:-4], layers["sim"])[0] == len(layers["sim"]) - 1]
    b = next(p for p in top if component_of(p[4:-4], layers["sim"])[1] != component_of(a[4:-4], layers["sim"])[1])
    cyclic = dict(files)
    cyclic[a] = files[a] + [b]
    cyclic[b] = files[b] + [a]
    if not any(e.startswith("include cycle:") for e in check(cyclic, layers)):
        raise SystemExit(f"include_layers_test: self-check: {a} and {b} including each other was not reported")
    # A header of the first folder including one of the last: the folder order must catch it.
    sim_headers = [p for p in files if library_of(p) == "sim" and p.endswith(".hpp")]
    first = next(p for p in sim_headers if folder_of(p) == folders[0])
    last = next(p for p in sim_headers if folder_of(p) == folders[-1])
    later = dict(files)
    later[first] = files[first] + [last]
    if not any(e.startswith(f"{first}: includes {last}: folder") for e in check(later, layers, folders)):
        raise SystemExit(f"include_layers_test: self-check: {first} including {last} was not reported")

    errors = check(files, layers, folders)
    for e in errors:
        print("include_layers_test: " + e, file=sys.stderr)
    if errors:
        return 1
    print(f"include_layers_test: {len(files)} files of {', '.join(LIBRARIES)} keep their layers "
          f"({', '.join(f'{lib}: ' + ' < '.join(n for n, _ in layers[lib]) for lib in LIBRARIES)}) "
          f"and sim/ its folders ({' < '.join(folders)})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
