#!/usr/bin/env python3
"""Fails when a project target (library or program) reaches, directly or through
others, a target of a layer it may not use (LAYERS below, the table of
docs/layers.md), when a simulation engine reaches another engine, or when a
target outside cli/ reaches one of cli/.

The layer of a target is the top folder it is declared in. Among what this
enforces: the controller host and wbi_host link no concrete controller (they
come from plugins); components never depend on controllers or on the deploy-file reader
(deploy/); the runtime reads no deploy format; the robot side (and so a real
robot's driver interface) uses no DDS; dds/ uses only the IDL and the vocabulary.

Input: lines "TARGET|FOLDER|DEP;DEP;..." written by tests/placement/CMakeLists.txt
at generate time; aliases wbi::x name wbi_x.
"""
import re
import sys

# The layers each layer may reach (its own aside), bottom to top.
BOTTOM = {"vocabulary", "idl", "dds"}
LIBRARIES = {"vocabulary", "model_service", "estimation", "mcap"}  # no DDS
LAYERS = {
    "vocabulary": set(),
    "mcap": set(),  # the recording file format: bytes and channels, no DDS
    "idl": {"vocabulary"},
    "dds": {"vocabulary", "idl"},
    "model_service": {"vocabulary"},
    "estimation": {"vocabulary", "model_service"},  # F/T estimation runs through the model
    "robot_side": LIBRARIES,
    "runtime": BOTTOM,
    "components": BOTTOM | LIBRARIES | {"robot_side", "runtime"},
    "tools": BOTTOM | LIBRARIES | {"robot_side"},
    "wbi_proxy": BOTTOM | {"model_service"},
    "controllers": BOTTOM | LIBRARIES | {"runtime", "wbi_proxy"},
    "deploy": BOTTOM | {"runtime"},
    "testing": BOTTOM | LIBRARIES | {"robot_side", "runtime", "components", "tools", "wbi_proxy"},
}
# The programs on top may use every layer.
TOP = {"apps", "cli", "python"}

# Concrete controllers come from plugins (wbi/plugin.hpp): the controller host
# and the programs that host controllers load them by name, never link them.
CONCRETE_CONTROLLERS = {"wbi_pd_gravity", "wbi_momentum_balance", "wbi_reference_generators"}
CONTROLLER_HOSTS = {"wbi_controller_host", "wbi_host"}

# Simulation engines: none reaches another (what they share is wbi_sim_models).
ENGINES = {"robot_side/sim": "wbi_sim", "robot_side/mujoco_sim": "wbi_mujoco_sim"}


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


def layer_of(folder):
    return folder.split("/")[0]


def layer_failures(edges, folder_of):
    """Targets that reach a project target of a layer theirs may not use."""
    failures, checked = [], 0
    for target, folder in sorted(folder_of.items()):
        layer = layer_of(folder)
        if layer in TOP:
            continue
        if layer not in LAYERS:
            failures.append(f"{target} ({folder}): the folder '{layer}' is in no layer of "
                            "check_link_graph.py: add it to LAYERS (and to the table of docs/layers.md)")
            continue
        checked += 1
        for dependency, path_to in sorted(reachable(edges, target).items()):
            other = layer_of(folder_of.get(dependency, layer))
            if other != layer and other not in LAYERS[layer]:
                failures.append(f"{target} ({folder}) reaches {dependency} ({other}/), a layer "
                                f"{layer}/ may not use: " + " -> ".join(path_to))
    return failures, checked


def cli_failures(edges, folder_of):
    """Targets outside cli/ that reach a target of cli/ (the verbs are the top)."""
    failures = []
    for target, folder in sorted(folder_of.items()):
        if layer_of(folder) == "cli":
            continue
        for dependency, path_to in sorted(reachable(edges, target).items()):
            if layer_of(folder_of.get(dependency, "")) == "cli":
                failures.append(f"{target} ({folder}) reaches {dependency} of cli/: " +
                                " -> ".join(path_to))
    return failures


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


def concrete_failures(edges, folder_of):
    """The controller host, or a program hosting controllers, that links a concrete one."""
    failures = []
    for target in sorted(CONTROLLER_HOSTS & set(folder_of)):
        for dependency, path_to in sorted(reachable(edges, target).items()):
            if dependency in CONCRETE_CONTROLLERS:
                failures.append(f"{target} ({folder_of[target]}) links the concrete controller "
                                f"{dependency} (it comes from a plugin): " + " -> ".join(path_to))
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
    layer_failed, checked = layer_failures(edges, folder_of)
    engine_failed = (engine_failures(edges, folder_of) + cli_failures(edges, folder_of) +
                     concrete_failures(edges, folder_of))
    missing = [f"no target in {layer}/" for layer in ("vocabulary", "dds", "components",
                                                       "robot_side", "runtime")
               if not any(layer_of(f) == layer for f in folder_of.values())]
    for failure in layer_failed + engine_failed + missing:
        print("FAIL:", failure)
    print(f"{checked} targets in {len(LAYERS)} layers checked: {len(layer_failed)} reach a layer "
          f"theirs may not use; {len(engine_failed)} reach another engine, cli/ or link a "
          "concrete controller")
    return 1 if layer_failed or engine_failed or missing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
