#!/usr/bin/env python3
"""Fails when a target (library or program) of dds/ or components/ depends,
directly or through others, on the deploy-file reader (wbi_placement, or
wbi_launch which links it) or on a controller (any target of controllers/):
components never depend on controllers; the programs that assemble both live
in apps/. Also when a bottom layer reaches a project target above it (the
vocabulary links none, the IDL only the vocabulary, dds/ only those two, the
model libraries of model_service/ only the vocabulary), when a simulation
engine reaches another (they share wbi_sim_models), and when a target outside
cli/ reaches one of cli/ (the command line is a thin layer on top: its verbs
call the libraries, never the other way round).

Input: lines "TARGET|FOLDER|DEP;DEP;..." written by tests/placement/CMakeLists.txt
at generate time; aliases wbi::x name wbi_x.
"""
import re
import sys

DEPLOY_READER = {"wbi_placement", "wbi_launch"}

# Simulation engines: none reaches another (what they share is wbi_sim_models).
ENGINES = {"components/sim": "wbi_sim", "components/mujoco_sim": "wbi_mujoco_sim"}

# The project targets each bottom layer may reach (its own folder's aside).
BELOW = {
    "vocabulary": set(),
    "idl": {"wbi_vocabulary"},
    "dds": {"wbi_vocabulary", "wbi_idl"},
    "model_service": {"wbi_vocabulary"},
}


def name_of(dependency):
    dependency = re.sub(r"^\$<LINK_ONLY:(.*)>$", r"\1", dependency.strip())
    return "wbi_" + dependency[len("wbi::"):] if dependency.startswith("wbi::") else dependency


def reachable(edges, target):
    """Every target reached from `target`, each with the path that reaches it."""
    stack, paths = [(target, [target])], {}
    while stack:
        node, path_to = stack.pop()
        for dependency in edges.get(node, ()):
            if dependency not in paths:
                paths[dependency] = path_to + [dependency]
                stack.append((dependency, path_to + [dependency]))
    return paths


def layer_failures(edges, folder_of):
    """A bottom layer's targets that reach a project target above the layer."""
    failures, checked = [], 0
    for target, folder in sorted(folder_of.items()):
        layer = folder.split("/")[0]
        if layer not in BELOW:
            continue
        checked += 1
        for dependency, path_to in sorted(reachable(edges, target).items()):
            above = dependency.startswith("wbi_") and dependency not in BELOW[layer]
            if above and folder_of.get(dependency, "").split("/")[0] != layer:
                failures.append(f"{target} ({folder}) reaches {dependency}, above its layer: " +
                                " -> ".join(path_to))
    return failures, checked


def engine_failures(edges, folder_of):
    """An engine's targets that reach another engine's library."""
    failures = []
    for target, folder in sorted(folder_of.items()):
        if folder not in ENGINES:
            continue
        others = {library for engine, library in ENGINES.items() if engine != folder}
        for dependency, path_to in sorted(reachable(edges, target).items()):
            if dependency in others:
                failures.append(f"{target} ({folder}) reaches the engine {dependency}: " +
                                " -> ".join(path_to))
    return failures


def cli_failures(edges, folder_of):
    """A target outside cli/ that reaches a target of cli/."""
    cli_targets = {t for t, f in folder_of.items() if f == "cli" or f.startswith("cli/")}
    failures = []
    for target, folder in sorted(folder_of.items()):
        if target in cli_targets:
            continue
        for dependency, path_to in sorted(reachable(edges, target).items()):
            if dependency in cli_targets:
                failures.append(f"{target} ({folder}) reaches {dependency} of cli/: " +
                                " -> ".join(path_to))
    return failures


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
    layer_failed, layer_checked = layer_failures(edges, folder_of)
    failures += layer_failed
    engine_failed = engine_failures(edges, folder_of)
    failures += engine_failed
    cli_failed = cli_failures(edges, folder_of)
    failures += cli_failed
    for failure in failures:
        print("FAIL:", failure)
    if checked == 0:
        print(f"FAIL: no target of dds/ or components/ in {path}")
        return 1
    if layer_checked == 0:
        print(f"FAIL: no target of vocabulary/, idl/, dds/ or model_service/ in {path}")
        return 1
    print(f"{checked} targets of dds/ and components/ checked; "
          f"{len(failures) - len(layer_failed) - len(engine_failed) - len(cli_failed)} reach the "
          f"deploy-file reader or a controller; {layer_checked} targets of vocabulary/, idl/, "
          f"dds/ and model_service/: {len(layer_failed)} reach above their layer; "
          f"{len(engine_failed)} engine targets reach another engine; {len(cli_failed)} targets "
          f"outside cli/ reach cli/")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
