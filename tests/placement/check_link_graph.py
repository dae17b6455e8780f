#!/usr/bin/env python3
"""Fails when a target (library or program) of dds/ or components/ depends,
directly or through others, on the deploy-file reader (wbi_placement, or
wbi_launch which links it) or on a controller (any target of controllers/):
components never depend on controllers; the programs that assemble both live
in apps/.

Input: lines "TARGET|FOLDER|DEP;DEP;..." written by tests/placement/CMakeLists.txt
at generate time; aliases wbi::x name wbi_x.
"""
import re
import sys

DEPLOY_READER = {"wbi_placement", "wbi_launch"}


def name_of(dependency):
    dependency = re.sub(r"^\$<LINK_ONLY:(.*)>$", r"\1", dependency.strip())
    return "wbi_" + dependency[len("wbi::"):] if dependency.startswith("wbi::") else dependency


def main(path):
    edges, folder_of = {}, {}
    with open(path) as graph:
        for line in graph:
            if not line.strip():
                continue
            target, folder, dependencies = line.rstrip("\n").split("|", 2)
            folder_of[target] = folder
            edges[target] = {name_of(d) for d in dependencies.split(";") if d.strip()}
    forbidden = DEPLOY_READER | {t for t, f in folder_of.items() if f.startswith("controllers")}
    checked, failures = 0, []
    for target, folder in sorted(folder_of.items()):
        if not (folder == "dds" or folder.startswith("dds/") or folder.startswith("components")):
            continue
        checked += 1
        # Depth-first, remembering the path for the message.
        stack, seen = [(target, [target])], {target}
        while stack:
            node, path_to = stack.pop()
            for dependency in edges.get(node, ()):
                if dependency in forbidden:
                    failures.append(f"{target} ({folder}) reaches {dependency}: " +
                                    " -> ".join(path_to + [dependency]))
                elif dependency not in seen:
                    seen.add(dependency)
                    stack.append((dependency, path_to + [dependency]))
    for failure in failures:
        print("FAIL:", failure)
    if checked == 0:
        print(f"FAIL: no target of dds/ or components/ in {path}")
        return 1
    print(f"{checked} targets of dds/ and components/ checked; "
          f"{len(failures)} reach the deploy-file reader or a controller")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
